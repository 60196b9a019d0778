#!/usr/bin/python3
"""What explains each residual of the Blender comparison (issue 46; bench/cycles/compare_gltf.py):
one change at a time, to Cycles, to stage5's file or to both. Not part of the article: bench machinery.

Each experiment renders a file as compare_gltf.py does (seeds 1 and 2, half the samples each; the
same mean ratio, worst of the 4x4 regions and their noise) with one thing changed: a Principled
BSDF input or its distribution, the image textures' interpolation, the spots' blend, a default
material for material-less meshes (bench/cycles/render_cycles_imported.py's diagnosis options), or
the glTF file that stage5 reads (a sampler, an extension, a spot cone). Its row sits beside the
file's baseline (compare_gltf.py's row in docs/results/gltf_real/gltf_real.csv, at 4 times the
samples by default), so the change's effect is the difference of the two.

  /usr/bin/python3 bench/cycles/gltf_residuals.py --bin-dir build/bin --out-dir out/gltf_residuals \\
      --publish docs/results/gltf_real [--only 14_transmission]
Writes OUT/residuals.csv (one row per file and experiment) and OUT/residual_splits.csv (splits());
--publish copies them there.
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys

from compare_gltf import compare, log, region_stats, render_pair, repo_path
from gltf_prepare import lambert_copy, prepare


def edited(path, suffix, edit):
    """A copy of the glTF file at `path` changed by edit(doc), next to it (its buffers and images)."""
    with open(path) as f:
        doc = json.load(f)
    edit(doc)
    out = path[:-len(".gltf")] + "_" + suffix + ".gltf"
    with open(out, "w") as f:
        json.dump(doc, f)
    return out


def nearest_samplers(doc):
    doc["samplers"] = doc.get("samplers", []) + [{"magFilter": 9728, "minFilter": 9728}]
    for t in doc.get("textures", []):
        t["sampler"] = len(doc["samplers"]) - 1


def nearest_no_normal_map(doc):
    nearest_samplers(doc)
    for m in doc.get("materials", []):
        m.pop("normalTexture", None)


def no_transmission(doc):
    for m in doc.get("materials", []):
        m.get("extensions", {}).pop("KHR_materials_transmission", None)


def hard_spots(doc):
    for light in doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", []):
        if light.get("type") == "spot":
            light.setdefault("spot", {})["innerConeAngle"] = light["spot"].get("outerConeAngle", 0.7853981633974483)


# (file, experiment, what it changes, Cycles options, stage5's file: None = as is, "lambert" = the
# Lambert control, else an edit of the file, and the control on top when the name ends in +lambert).
# The baselines (no change) are compare_gltf.py's rows in docs/results/gltf_real/gltf_real.csv.
EXPERIMENTS = [  # in the order run, the most telling first
    ("01_principled_material", "control_cycles_closest", "Lambert control, Cycles' textures Closest (stage5 LINEAR)",
     ["--lambert", "--interpolation", "Closest"], "lambert"),
    ("14_transmission", "no_transmission", "transmission 0 in both (the plastic alone)",
     ["--set-input", "Transmission=0"], ("notransmission", no_transmission)),
    ("05_metallic_sphere_light", "control_hard_spots", "Lambert control, hard cones in both (blend 0, inner = outer)",
     ["--lambert", "--spot-blend", "0"], ("hardspots+lambert", hard_spots)),
    ("22_vertex_color", "cycles_default_material", "Cycles: glTF's default material x COLOR_0 on bare meshes",
     ["--bare-default-material"], None),
    ("14_transmission", "cycles_multi_ggx", "Cycles' Principled Multiscatter GGX", ["--distribution", "MULTI_GGX"],
     None),
    ("01_principled_material", "cycles_closest", "Cycles' textures Closest (stage5 LINEAR)",
     ["--interpolation", "Closest"], None),
    ("spheres", "cycles_multi_ggx", "Cycles' Principled Multiscatter GGX", ["--distribution", "MULTI_GGX"], None),
    ("05_metallic_sphere_light", "cycles_multi_ggx", "Cycles' Principled Multiscatter GGX",
     ["--distribution", "MULTI_GGX"], None),
    ("01_principled_material", "control_both_nearest", "Lambert control, both NEAREST",
     ["--lambert", "--interpolation", "Closest"], ("nearest+lambert", nearest_samplers)),
    ("01_principled_material", "control_both_nearest_no_normal_map",
     "Lambert control, both NEAREST, no normal map in either",
     ["--lambert", "--interpolation", "Closest", "--no-normal-map"], ("nonormal+lambert", nearest_no_normal_map)),
    ("04_common_materials", "cycles_specular0", "Cycles' Principled Specular 0", ["--set-input", "Specular=0"], None),
    ("04_common_materials", "control", "the Lambert control", ["--lambert"], "lambert"),
    ("spheres", "cycles_specular0", "Cycles' Principled Specular 0", ["--set-input", "Specular=0"], None),
    ("14_transmission", "cycles_specular0", "Cycles' Principled Specular 0", ["--set-input", "Specular=0"], None),
    ("14_transmission", "control", "the Lambert control", ["--lambert"], "lambert"),
    ("04_lights", "cycles_specular0", "Cycles' Principled Specular 0", ["--set-input", "Specular=0"], None),
    ("04_lights", "control", "the Lambert control", ["--lambert"], "lambert"),
    ("14_transmission", "no_transmission_specular0", "transmission 0 in both, Cycles' Principled Specular 0",
     ["--set-input", "Transmission=0", "--set-input", "Specular=0"], ("notransmission", no_transmission)),
    ("spheres", "control", "the Lambert control", ["--lambert"], "lambert"),
    ("05_metallic_sphere_light", "stage5_separable_masking",
     "stage5 built with Cycles 3.4's separable masking G1(wo) G1(wi) (bench build, PT_BENCH_SEPARABLE_MASKING)",
     [], None, "separable_masking"),
    ("01_principled_material", "control_both_nearest_mikktspace",
     "Lambert control, both NEAREST, stage5 reads Blender's MikkTSpace tangents (TANGENT exported)",
     ["--lambert", "--interpolation", "Closest"], ("tangents:nearest+lambert", nearest_samplers)),
    ("01_principled_material", "control_both_nearest_no_fold",
     "Lambert control, both NEAREST, stage5 built without the shading normals' fold (bench build, PT_BENCH_NO_FOLD)",
     ["--lambert", "--interpolation", "Closest"], ("nearest+lambert", nearest_samplers), "no_fold"),
]
# The stage5 file of an experiment whose suffix starts with "tangents:" is the file Blender exports
# with its MikkTSpace tangents (export_tangents=True) instead of the baseline's export.

# Experiments with a sixth field render with a bench-only build of stage5 (stage5_variant()): the
# compile definition PT_BENCH_<NAME> switches one formula in common/kernel; the default build never
# sets it.

COLUMNS = ["id", "experiment", "what", "size", "spp", "mean_cycles", "mean_stage5", "mean_ratio", "mean_noise",
           "worst_region", "worst_region_index", "worst_region_noise", "regions", "cycles_regions"]


def stage5_variant(args, name):
    """stage5_mis built with -DPT_BENCH_<NAME> (CPU kernel, one variant) in build-bench-<name>."""
    build = repo_path(f"build-bench-{name}")
    flag = f"-DPT_BENCH_{name.upper()}=1"
    for cmd in (["cmake", "-S", repo_path("."), "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DPT_CPU_GENERAL_ONLY=ON",
                 f"-DCMAKE_CXX_FLAGS={flag}"] + (["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []),
                ["nice", "cmake", "--build", build, f"-j{args.threads}", "--target", "stage5_mis"]):
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"building stage5 with {flag} failed: {r.stderr.strip()[-400:]}")
    return os.path.join(build, "bin", "stage5_mis")


SPLITS = [("file", "cycles_specular0", None), ("no_transmission", "no_transmission_specular0", "no_transmission")]


def splits(rows, baseline_csv):
    """Where a file has both a cycles_specular0 and a control row: for its image and for the worst
    region of its baseline (compare_gltf.py's row), the three factors whose product is the
    baseline's ratio: Principled's diffuse over Lambert (Cycles, Specular 0 / Cycles' control),
    Principled's specular layer (Cycles / Cycles with Specular 0, from the ratios of stage5 as is to
    each) and stage5's 1 - F weight with its metals (stage5 / stage5's control). The control takes
    transmission out too, so a transmissive file's factors hold its transmission as well; where the
    file also has no_transmission rows, a second split (baseline no_transmission) leaves it out."""
    with open(baseline_csv) as f:
        baselines = {r["id"]: r for r in csv.DictReader(f)}
    out = []
    for file_id, (variant, spec0, base) in [(f, v) for f in sorted({r["id"] for r in rows}) for v in SPLITS]:
        mine = {r["experiment"]: r for r in rows if r["id"] == file_id}
        b = baselines.get(file_id) if base is None else mine.get(base)
        if spec0 not in mine or "control" not in mine or b is None:
            continue
        s0, c = mine[spec0], mine["control"]
        worst = int(b["worst_region_index"])
        for region in ("image", worst):
            if region == "image":
                cs0, cc, rs0, rc, rb = (float(s0["mean_cycles"]), float(c["mean_cycles"]), float(s0["mean_ratio"]),
                                        float(c["mean_ratio"]), float(b["mean_ratio"]))
            else:
                cs0, cc = (float(x[worst]) for x in (s0["cycles_regions"].split(), c["cycles_regions"].split()))
                rs0, rc, rb = (float(x[worst]) for x in (s0["regions"].split(), c["regions"].split(),
                                                         b["regions"].split()))
            out.append({"id": file_id, "baseline": variant, "region": region, "baseline_ratio": f"{rb:.4f}",
                        "principled_diffuse": f"{cs0 / cc:.4f}", "principled_specular": f"{rs0 / rb:.4f}",
                        "stage5_fresnel": f"{rs0 * cs0 / (rc * cc):.4f}"})
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bin-dir", default="build/bin")
    p.add_argument("--out-dir", default="out/gltf_residuals")
    p.add_argument("--publish", default=None)
    p.add_argument("--files", default="bench/gltf_real/files.json")
    p.add_argument("--only", default="", help="comma-separated file ids")
    p.add_argument("--experiments", default="", help="comma-separated experiment names (default: all)")
    p.add_argument("--spp-scale", type=float, default=0.25)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--blender", default="blender")
    args = p.parse_args()
    if shutil.which(args.blender) is None:
        print(f"gltf_residuals.py: skipped: '{args.blender}' not found; the Blender comparison is bench-only")
        return 0
    stage5 = os.path.join(repo_path(args.bin_dir), "stage5_mis")
    with open(repo_path(args.files)) as f:
        manifest = {e["id"]: e for e in json.load(f)["files"]}
    only = [s for s in args.only.split(",") if s]
    out_dir = repo_path(args.out_dir)
    os.makedirs(out_dir, exist_ok=True)
    prepared, rows = {}, []
    csv_path = os.path.join(out_dir, "residuals.csv")
    if os.path.exists(csv_path):  # an earlier run's rows stay unless an experiment runs again
        with open(csv_path) as f:
            rows = list(csv.DictReader(f))
    for file_id, name, what, flags, stage5_file, *variant in EXPERIMENTS:
        if (only and file_id not in only) or (args.experiments and name not in args.experiments.split(",")):
            continue
        entry = manifest[file_id]
        if file_id not in prepared:
            prepared[file_id] = prepare(entry, os.path.join(out_dir, "files"), args.blender, log)
        scene = prepared[file_id]
        if isinstance(stage5_file, tuple) and stage5_file[0].startswith("tangents:"):
            tangents = dict(entry, id=file_id + "_tangents", export_tangents=True)
            scene = prepare(tangents, os.path.join(out_dir, "files"), args.blender, log)
            stage5_file = (stage5_file[0][len("tangents:"):], stage5_file[1])
        if stage5_file == "lambert":
            st5_scene = lambert_copy(scene)
        elif stage5_file is None:
            st5_scene = scene
        else:
            suffix, edit = stage5_file
            st5_scene = edited(scene, suffix.split("+")[0], edit)
            if suffix.endswith("+lambert"):
                st5_scene = lambert_copy(st5_scene)
        half = max(1, int(round(entry["spp"] * args.spp_scale / 2)))
        binary = stage5_variant(args, variant[0]) if variant else stage5
        cyc, st5, _ = render_pair(args, entry, scene, st5_scene, half, "_" + name, binary, flags)
        row = compare(entry, cyc, st5)
        c_regions = [m for m, _ in region_stats(*cyc)[:-1]]
        row.update({"experiment": name, "what": what, "size": f"{entry['width']}x{entry['height']}",
                    "spp": 2 * half, "cycles_regions": " ".join(f"{m:.5g}" for m in c_regions)})
        rows = [r for r in rows if (r["id"], r["experiment"]) != (file_id, name)] + [row]
        log(f"{file_id} {name}: mean ratio {row['mean_ratio']:.4f} (±{row['mean_noise']:.4f}), worst region "
            f"{row['worst_region']:.4f} (±{row['worst_region_noise']:.4f}) [{row['worst_region_index']}]")
        with open(csv_path, "w", newline="") as f:  # after every experiment: a partial run keeps its rows
            writer = csv.DictWriter(f, fieldnames=COLUMNS, extrasaction="ignore")
            writer.writeheader()
            for r in rows:
                writer.writerow({k: (f"{v:.5g}" if isinstance(v, float) else v) for k, v in r.items()})
    split_rows = splits(rows, repo_path("docs/results/gltf_real/gltf_real.csv"))
    split_path = os.path.join(out_dir, "residual_splits.csv")
    if split_rows:
        with open(split_path, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(split_rows[0]))
            writer.writeheader()
            writer.writerows(split_rows)
    if args.publish and rows:
        os.makedirs(repo_path(args.publish), exist_ok=True)
        for path in (csv_path, split_path):
            if os.path.exists(path):
                shutil.copy(path, repo_path(args.publish))
    return 0


if __name__ == "__main__":
    sys.exit(main())
