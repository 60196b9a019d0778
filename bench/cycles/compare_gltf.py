#!/usr/bin/python3
"""Real glTF files rendered by Blender's Cycles through Blender's own glTF importer and by stage5,
same camera, size and sky (issue 46, "Against Blender"). Not part of the article: bench machinery.

Per file (bench/gltf_real/files.json; licences in bench/gltf_real/LICENSES.md): the file made ready
(a shipped .blend exported by Blender's glTF exporter at run time, or a shipped .gltf, with a camera
added where it has none), then each renderer renders it twice (seeds 1 and 2, spp/2 each, 2 threads,
under nice): Cycles by bench/cycles/render_cycles_imported.py (Principled BSDF and lights as the
importer makes them), stage5 by `stage5_mis --sky`. The two halves average to the image compared:

  mean ratio      stage5 / Cycles of the image mean (Rec. 709 luminance; also R, G, B)
  worst region    of the 4x4 grid of region luminance means, the ratio farthest from 1, over the
                  regions where either renderer's mean is at least 1% of Cycles' image mean
  noise           the standard error of a ratio, from the two halves: per pixel (a - b)^2 / 4 is the
                  variance of the average, summed over a region's pixels / n^2, for both renderers
  Lambert control the same for both renderers with every material Lambert (textures, vertex colours,
                  emission, lights, camera and sky kept): what differs then is not the BSDF
  split           (files with "split": true) Cycles' Principled with Specular 0 over its Lambert control,
                  Cycles' Principled over that, stage5 over its Lambert control
Target (issue 46): every mean within 3% and every region within 8%.

Writes OUT/gltf_real.csv, OUT/gltf_real.md and OUT/pictures/ID.png (Cycles left, stage5 right,
sRGB, one exposure for both); --publish DIR copies those there (docs/results/gltf_real).
Needs: blender (Debian 12's 3.4.1), oiiotool, python3-numpy. Without blender: one line, exit 0.

  /usr/bin/python3 bench/cycles/compare_gltf.py --bin-dir build/bin --out-dir out/gltf_real \\
      --publish docs/results/gltf_real   # all files, 25 min on 2 busy cores
  /usr/bin/python3 bench/cycles/compare_gltf.py --only 04_lights --spp-scale 0.25   # a quick look
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import time

import numpy as np

from compare_images import luminance, read_rgb
from gltf_prepare import REPO, lambert_copy, prepare

TARGET_MEAN, TARGET_REGION = 0.03, 0.08
GRID = 4


def log(message):
    print(f"compare_gltf.py: {message}", file=sys.stderr, flush=True)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bin-dir", default="build/bin")
    p.add_argument("--out-dir", default="out/gltf_real")
    p.add_argument("--publish", default=None, help="also copy the CSV, table and pictures to this folder")
    p.add_argument("--files", default="bench/gltf_real/files.json")
    p.add_argument("--only", default="", help="comma-separated ids of the files to run")
    p.add_argument("--spp-scale", type=float, default=1.0, help="multiply every file's spp (quick looks)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--blender", default="blender")
    p.add_argument("--no-control", action="store_true", help="leave out the Lambert control renders")
    return p.parse_args()


def repo_path(path):
    return path if os.path.isabs(path) else os.path.join(REPO, path)


def run(cmd, what):
    t0 = time.time()
    r = subprocess.run(["nice"] + cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{what} failed ({r.returncode}): {(r.stderr or r.stdout).strip()[-600:]}")
    return time.time() - t0, r.stdout + r.stderr


def regions(y):
    h, w = y.shape
    return [(slice(i * h // GRID, (i + 1) * h // GRID), slice(j * w // GRID, (j + 1) * w // GRID))
            for i in range(GRID) for j in range(GRID)]


def region_stats(a, b):
    """Means and standard errors of the average of two half images (luminance), per region."""
    y = (luminance(a) + luminance(b)) / 2
    var = (luminance(a) - luminance(b)) ** 2 / 4
    out = []
    for rs in regions(y) + [(slice(None), slice(None))]:
        n = y[rs].size
        out.append((float(y[rs].mean()), float(np.sqrt(var[rs].sum()) / n)))
    return out  # the 16 regions, then the whole image


def compare(entry, cyc, st5):
    c, s = region_stats(*cyc), region_stats(*st5)
    (cm, cse), (sm, sse) = c[-1], s[-1]
    rgb_c = (cyc[0] + cyc[1]).mean(axis=(0, 1)) / 2
    rgb_s = (st5[0] + st5[1]).mean(axis=(0, 1)) / 2
    row = {"id": entry["id"], "mean_cycles": cm, "mean_stage5": sm, "mean_ratio": sm / cm,
           "mean_noise": (sm / cm) * np.hypot(cse / cm, sse / sm),
           "ratio_r": rgb_s[0] / rgb_c[0] if rgb_c[0] > 0 else float("nan"),
           "ratio_g": rgb_s[1] / rgb_c[1] if rgb_c[1] > 0 else float("nan"),
           "ratio_b": rgb_s[2] / rgb_c[2] if rgb_c[2] > 0 else float("nan")}
    ratios, noises, skipped = [], [], 0
    for (rc, ec), (rs_, es) in zip(c[:-1], s[:-1]):
        if max(rc, rs_) < 0.01 * cm:
            ratios.append(float("nan"))
            skipped += 1
            continue
        r = rs_ / rc if rc > 0 else float("inf")
        ratios.append(r)
        noises.append(r * np.hypot(ec / rc, es / rs_) if rc > 0 and rs_ > 0 else float("inf"))
    finite = [(abs(r - 1), i) for i, r in enumerate(ratios) if not np.isnan(r)]
    worst = max(finite)[1] if finite else None
    row.update({"worst_region": ratios[worst] if worst is not None else float("nan"),
                "worst_region_index": worst if worst is not None else -1,
                "worst_region_noise": noises[[i for i, r in enumerate(ratios) if not np.isnan(r)].index(worst)]
                if worst is not None else float("nan"),
                "max_region_noise": max(noises) if noises else float("nan"),
                "regions_dark": skipped,
                "regions": " ".join("nan" if np.isnan(r) else f"{r:.4f}" for r in ratios)})
    row["mean_ok"] = abs(row["mean_ratio"] - 1) <= TARGET_MEAN
    row["regions_ok"] = worst is None or abs(row["worst_region"] - 1) <= TARGET_REGION
    return row


def picture(entry, cyc, st5, path):
    """Cycles | stage5, sRGB PNG, exposed so that Cycles' image mean luminance is 0.18."""
    tmp = path + ".tmp"
    os.makedirs(tmp, exist_ok=True)
    mean = float(luminance((cyc[0] + cyc[1]) / 2).mean())
    k = 0.18 / mean if mean > 0 else 1.0
    halves = []
    for name, (a, b) in (("c", cyc), ("s", st5)):
        img = ((a + b) / 2 * k).astype(np.float32)
        h, w, _ = img.shape
        pfm = os.path.join(tmp, name + ".pfm")  # portable float map: bottom row first
        with open(pfm, "wb") as f:
            f.write(f"PF\n{w} {h}\n-1.0\n".encode())
            f.write(np.ascontiguousarray(img[::-1]).tobytes())
        halves.append(pfm)
    subprocess.run(["oiiotool", halves[0], halves[1], "--mosaic", "2x1", "--clamp:min=0:max=1",
                    "--colorconvert", "linear", "sRGB", "-d", "uint8", "-o", path],
                   check=True, stdout=subprocess.DEVNULL)
    shutil.rmtree(tmp)
    return k


def render_pair(args, entry, cycles_scene, stage5_scene, half, tag, stage5, cycles_flags=()):
    """Both renderers, seeds 1 and 2 at `half` spp each: ([Cycles halves], [stage5 halves], seconds)."""
    w, h, sky = entry["width"], entry["height"], entry["sky"]
    here = os.path.dirname(os.path.abspath(__file__))
    cyc, st5, secs = [], [], {"cycles": 0.0, "stage5": 0.0}
    for seed in (1, 2):
        base = os.path.join(repo_path(args.out_dir), "renders", f"{entry['id']}{tag}_{w}x{h}_{half}spp_seed{seed}")
        os.makedirs(os.path.dirname(base), exist_ok=True)
        t, _ = run([args.blender, "--factory-startup", "-b", "--python",
                    os.path.join(here, "render_cycles_imported.py"), "--", "--scene", cycles_scene,
                    "--width", str(w), "--height", str(h), "--spp", str(half), "--seed", str(seed),
                    "--threads", str(args.threads), "--sky", sky, "--out", base + "_cycles.exr"]
                   + list(cycles_flags), f"Cycles on {entry['id']}{tag}")
        secs["cycles"] += t
        cyc.append(read_rgb(base + "_cycles.exr"))
        if stage5 is None:
            continue
        t, _ = run([stage5, "--scene", stage5_scene, "--width", str(w), "--height", str(h), "--spp", str(half),
                    "--seed", str(seed), "--threads", str(args.threads), "--sky", sky, "--backend", "cpu",
                    "--out", base + "_stage5.exr"], f"stage5 on {entry['id']}{tag}")
        secs["stage5"] += t
        st5.append(read_rgb(base + "_stage5.exr"))
    return cyc, st5, secs


def main():
    args = parse_args()
    if shutil.which(args.blender) is None:
        print(f"compare_gltf.py: skipped: '{args.blender}' not found (Debian: apt-get install blender); "
              "the Blender comparison is bench-only")
        return 0
    stage5 = os.path.join(repo_path(args.bin_dir), "stage5_mis")
    if not os.access(stage5, os.X_OK):
        log(f"{stage5} not found; build first (cmake --build build)")
        return 1
    with open(repo_path(args.files)) as f:
        manifest = json.load(f)["files"]
    only = [s for s in args.only.split(",") if s]
    manifest = [e for e in manifest if not only or e["id"] in only]
    out_dir = repo_path(args.out_dir)
    pictures = os.path.join(out_dir, "pictures")
    os.makedirs(pictures, exist_ok=True)
    rows = []
    started = time.time()
    for entry in manifest:
        scene = prepare(entry, os.path.join(out_dir, "files"), args.blender, log)
        w, h = entry["width"], entry["height"]
        half = max(1, int(round(entry["spp"] * args.spp_scale / 2)))
        cyc, st5, secs = render_pair(args, entry, scene, scene, half, "", stage5)
        row = compare(entry, cyc, st5)
        row["exposure_scale"] = picture(entry, cyc, st5, os.path.join(pictures, entry["id"] + ".png"))
        row.update({"size": f"{w}x{h}", "spp": 2 * half, "sky": entry["sky"],
                    "cycles_wall_s": round(secs["cycles"], 1), "stage5_wall_s": round(secs["stage5"], 1),
                    "features": entry.get("features", ""), "needs": entry.get("needs", "")})
        if not args.no_control:
            # The control: both renderers with every material Lambert (textures, vertex colours,
            # normals, emission, lights, camera and sky unchanged), so what differs is the BSDF.
            c2, s2, _ = render_pair(args, entry, scene, lambert_copy(scene), half, "_lambert", stage5, ["--lambert"])
            control = compare(entry, c2, s2)
            row.update({"control_mean_ratio": control["mean_ratio"], "control_mean_noise": control["mean_noise"],
                        "control_worst_region": control["worst_region"],
                        "control_worst_region_noise": control["worst_region_noise"]})
            picture(entry, c2, s2, os.path.join(pictures, entry["id"] + "_lambert.png"))
            if entry.get("split"):
                # Where a dielectric's difference comes from, on Cycles' side: Principled's diffuse
                # alone (Specular 0) against Lambert, and what its specular layer adds on top.
                c0, _, _ = render_pair(args, entry, scene, None, half, "_specular0", None, ["--specular-zero"])
                mean = lambda halves: float(luminance((halves[0] + halves[1]) / 2).mean())  # noqa: E731
                row.update({"split_principled_diffuse": mean(c0) / mean(c2),
                            "split_principled_specular": mean(cyc) / mean(c0),
                            "split_stage5_fresnel": mean(st5) / mean(s2)})
        rows.append(row)
        log(f"{entry['id']}: mean ratio {row['mean_ratio']:.4f} (±{row['mean_noise']:.4f}), worst region "
            f"{row['worst_region']:.4f} (±{row['worst_region_noise']:.4f}); Lambert control "
            f"{row.get('control_mean_ratio', float('nan')):.4f}, {row.get('control_worst_region', float('nan')):.4f}; "
            f"Cycles {secs['cycles']:.0f} s, stage5 {secs['stage5']:.0f} s")
    write_tables(rows, out_dir, time.time() - started)
    if args.publish:
        dest = repo_path(args.publish)
        os.makedirs(os.path.join(dest, "pictures"), exist_ok=True)
        for name in ("gltf_real.csv", "gltf_real.md"):
            shutil.copy(os.path.join(out_dir, name), dest)
        for row in rows:
            for suffix in (".png", "_lambert.png"):
                if os.path.exists(os.path.join(pictures, row["id"] + suffix)):
                    shutil.copy(os.path.join(pictures, row["id"] + suffix), os.path.join(dest, "pictures"))
    return 0


COLUMNS = ["id", "size", "spp", "sky", "mean_cycles", "mean_stage5", "mean_ratio", "mean_noise", "ratio_r",
           "ratio_g", "ratio_b", "worst_region", "worst_region_index", "worst_region_noise", "max_region_noise",
           "regions_dark", "mean_ok", "regions_ok", "regions", "exposure_scale", "cycles_wall_s",
           "stage5_wall_s", "control_mean_ratio", "control_mean_noise", "control_worst_region",
           "control_worst_region_noise", "split_principled_diffuse", "split_principled_specular",
           "split_stage5_fresnel", "features", "needs"]


def write_tables(rows, out_dir, seconds):
    with open(os.path.join(out_dir, "gltf_real.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        for row in rows:  # the split columns only where a file asks for them
            writer.writerow({k: (f"{v:.5g}" if isinstance(v, float) else v) for k, v in row.items()})
    lines = ["| file | features | mean ratio (±noise) | R, G, B | worst of 4×4 regions (±noise) | target "
             "| Lambert control: mean, worst region | needs |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        ok = ("met" if r["mean_ok"] and r["regions_ok"] else
              "mean missed" if not r["mean_ok"] and r["regions_ok"] else
              "regions missed" if r["mean_ok"] else "both missed")
        lines.append(f"| {r['id']} | {r['features']} | {r['mean_ratio']:.3f} (±{r['mean_noise']:.4f}) | "
                     f"{r['ratio_r']:.3f}, {r['ratio_g']:.3f}, {r['ratio_b']:.3f} | "
                     f"{r['worst_region']:.3f} (±{r['worst_region_noise']:.4f}) | {ok} | "
                     f"{r.get('control_mean_ratio', float('nan')):.3f}, "
                     f"{r.get('control_worst_region', float('nan')):.3f} | "
                     f"{r['needs'] or '-'} |")
    lines.append("")
    lines.append(f"stage5 / Cycles 3.4.1 through Blender's glTF importer; {len(rows)} files, "
                 f"{seconds / 60:.1f} min. Target: mean within 3%, every region within 8%.")
    with open(os.path.join(out_dir, "gltf_real.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    sys.exit(main())
