#!/usr/bin/python3
"""Stages 3, 4 and 5 against Blender's Cycles under an environment map (issue 49, "Measures", item 1).
Not part of the article: bench machinery (BENCH_CYCLES-style; no unit test needs it).

A real glTF file (bench/gltf_real/files.json's entry --file, made ready with its bench camera by
gltf_prepare.prepare) under a blender-data world (CC0, /usr/share/blender/datafiles/studiolights/world),
rendered by Cycles (bench/cycles/render_cycles_env.py: Environment Texture on Generated coordinates
through a Mapping node, the fair settings of render_cycles.py) and by the stages (--env, --backend cpu).
  efficiency   1 / (relative MSE x CPU s), relative MSE against the renderer's converged reference
               (Cycles against its own; the stages against stage5's, all three being unbiased
               estimates of one image), averaged over --seeds seeds; CPU s = user + sys of the
               stage's whole process, of Cycles' render call (as bench/cycles/compare.py)
  marginal     the same without each renderer's fixed cost (its CPU s at 1 spp taken off), which
               under a map holds Cycles' world importance map and the stages' table build
  means        the references' image means (Rec. 709 luminance), stage5 / Cycles, and the same for
               the Lambert control (every material Lambert in both renderers, render_cycles_imported's)
Writes OUT/efficiency.csv, OUT/means.csv and OUT/FILE_principled.png, OUT/FILE_lambert.png (the
converged images, Cycles left, stage5 right); --glossy renders a glossier copy of the file
(glossy_copy) and names them *_glossy. Needs blender (Debian 12's 3.4.1), oiiotool, python3-numpy.

  /usr/bin/python3 bench/cycles/compare_env.py --bin-dir build-h3/bin --out-dir docs/results/env
"""
import argparse
import csv
import json
import os
import re
import shutil
import sys
import time

import numpy as np

from compare_images import luminance, read_rgb, rel_mse
from compare_gltf import picture
from compare_renderers import run_timed
from gltf_prepare import REPO, lambert_copy, prepare

HERE = os.path.dirname(os.path.abspath(__file__))
WORLDS = "/usr/share/blender/datafiles/studiolights/world"


def log(message):
    print(f"compare_env.py: {message}", file=sys.stderr, flush=True)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bin-dir", default="build/bin")
    p.add_argument("--out-dir", default="out/env")
    p.add_argument("--work-dir", default="out/env_work", help="renders and references (cached)")
    p.add_argument("--file", default="04_common_materials", help="an id of bench/gltf_real/files.json")
    p.add_argument("--world", default="forest.exr", help="a blender-data world, or a path")
    p.add_argument("--strength", type=float, default=1.0)
    p.add_argument("--rotate", type=float, default=30.0)
    p.add_argument("--size", default="160x120")
    p.add_argument("--spp", type=int, default=128)
    p.add_argument("--seeds", type=int, default=4)
    p.add_argument("--ref-spp", type=int, default=4096)
    p.add_argument("--control-spp", type=int, default=1024)
    p.add_argument("--stages", default="stage3_importance,stage4_direct_indirect,stage5_mis")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--blender", default="blender")
    p.add_argument("--means-only", action="store_true", help="only the references' means (means.csv)")
    p.add_argument("--glossy", action="store_true",
                   help="a glossy copy of the file (glossy_copy): outputs named *_glossy.csv/png")
    return p.parse_args()


class Env:
    """Renders one scene under one map with either renderer; returns the CPU seconds."""

    def __init__(self, args, scene, world):
        self.args, self.scene, self.world = args, scene, world
        self.w, self.h = (int(v) for v in args.size.split("x"))

    def cycles(self, spp, seed, out, lambert=False, scene=None, flags=()):
        cmd = ["nice", self.args.blender, "--factory-startup", "-b", "--python",
               os.path.join(HERE, "render_cycles_env.py"), "--", "--scene", scene or self.scene,
               "--env", self.world, "--env-strength", str(self.args.strength), "--env-rotate",
               str(self.args.rotate), "--width", str(self.w), "--height", str(self.h), "--spp", str(spp),
               "--seed", str(seed), "--threads", str(self.args.threads), "--out", out]
        output, _, _ = run_timed(cmd + (["--lambert"] if lambert else []) + list(flags))
        return float(re.search(r"CYCLES_RENDER cpu_s=(\S+)", output).group(1))

    def stage(self, name, spp, seed, out, scene=None):
        cmd = ["nice", os.path.join(self.args.bin_dir, name), "--scene", scene or self.scene, "--env", self.world,
               "--env-strength", str(self.args.strength), "--env-rotate", str(self.args.rotate),
               "--width", str(self.w), "--height", str(self.h), "--spp", str(spp), "--seed", str(seed),
               "--backend", "cpu", "--threads", str(self.args.threads), "--out", out]
        _, cpu, _ = run_timed(cmd)
        return cpu


def glossy_copy(path):
    """The file with glossier materials, textures kept: the crate's dielectric at roughness 0.3, the
    plane's at 0.4, the red sphere a metal of roughness 0.25. Written beside PATH."""
    with open(path) as f:
        doc = json.load(f)
    for m in doc.get("materials", []):
        pbr = m.setdefault("pbrMetallicRoughness", {})
        glossy = {"Crate": (0.0, 0.3), "Plane": (0.0, 0.4), "Sphere": (1.0, 0.25)}
        metallic, roughness = glossy.get(m["name"], (0.0, 0.3))
        pbr["metallicFactor"], pbr["roughnessFactor"] = metallic, roughness
    out = path[:-len(".gltf")] + "_glossy.gltf"
    with open(out, "w") as f:
        json.dump(doc, f)
    return out


def cached(path, render):
    """A reference rendered once: (image, CPU s), the seconds kept beside it in PATH.json."""
    meta = path[:-4] + ".json"
    if not (os.path.exists(path) and os.path.exists(meta)):
        t0 = time.time()
        cpu = render(path)
        with open(meta, "w") as f:
            json.dump({"cpu_s": cpu, "wall_s": time.time() - t0}, f)
        log(f"{os.path.basename(path)}: {cpu:.1f} CPU s")
    with open(meta) as f:
        return read_rgb(path), json.load(f)["cpu_s"]


def main():
    args = parse_args()
    if shutil.which(args.blender) is None:
        print(f"compare_env.py: skipped: '{args.blender}' not found (Debian: apt-get install blender)")
        return 0
    with open(os.path.join(REPO, "bench", "gltf_real", "files.json")) as f:
        entry = next(e for e in json.load(f)["files"] if e["id"] == args.file)
    work = os.path.abspath(args.work_dir)
    os.makedirs(work, exist_ok=True)
    os.makedirs(args.out_dir, exist_ok=True)
    scene = prepare(entry, os.path.join(work, "files"), args.blender, log)
    suffix = "_glossy" if args.glossy else ""
    if args.glossy:
        scene = glossy_copy(scene)
    world = args.world if os.path.sep in args.world else os.path.join(WORLDS, args.world)
    env = Env(args, scene, world)
    tag = f"{args.file}{suffix}_{os.path.basename(world)[:-4]}_{args.size}"
    ref = lambda name: os.path.join(work, f"{tag}_{name}_{args.ref_spp}spp.exr")  # noqa: E731
    stages = [s for s in args.stages.split(",") if s]
    ref_cycles, ref_cycles_cpu = cached(ref("cycles"), lambda p: env.cycles(args.ref_spp, 1000, p))
    ref_stage5, ref_stage5_cpu = cached(ref("stage5_mis"), lambda p: env.stage("stage5_mis", args.ref_spp, 1000, p))
    if not args.means_only:
        efficiency(args, env, work, tag, stages, ref_cycles, ref_stage5, world, suffix)
    means(args, env, scene, ref, world, ref_cycles, ref_stage5, ref_cycles_cpu, ref_stage5_cpu, suffix)
    return 0


def efficiency(args, env, work, tag, stages, ref_cycles, ref_stage5, world, suffix):
    names = ["cycles"] + stages
    render = lambda name, spp, seed, out: (env.cycles(spp, seed, out) if name == "cycles"  # noqa: E731
                                           else env.stage(name, spp, seed, out))
    errs, cpus = {n: [] for n in names}, {n: [] for n in names}
    for seed in range(1, args.seeds + 1):   # interleaved seed by seed, so a change of load falls on all
        for name in names:
            out = os.path.join(work, f"{tag}_{name}_{args.spp}spp_seed{seed}.exr")
            cpus[name].append(render(name, args.spp, seed, out))
            errs[name].append(rel_mse(read_rgb(out), ref_cycles if name == "cycles" else ref_stage5))
    # The fixed cost (start-up, scene and map loading, Cycles' world importance map): one 1-spp run.
    cpu1 = {name: render(name, 1, 1, os.path.join(work, f"{tag}_{name}_1spp.exr")) for name in names}
    rows = []
    for name in names:
        mse, cpu = float(np.mean(errs[name])), float(np.mean(cpus[name]))
        rows.append({"renderer": name, "scene": args.file, "world": os.path.basename(world),
                     "size": args.size, "spp": args.spp, "seeds": args.seeds, "rel_mse": mse,
                     "rel_mse_min": float(np.min(errs[name])), "rel_mse_max": float(np.max(errs[name])),
                     "cpu_s": cpu, "cpu_us_per_sample": cpu / (env.w * env.h * args.spp) * 1e6,
                     "efficiency": 1.0 / (mse * cpu), "cpu_s_1spp": cpu1[name],
                     "marginal_us_per_sample": (cpu - cpu1[name]) / (env.w * env.h * (args.spp - 1)) * 1e6,
                     "efficiency_marginal": 1.0 / (mse * (cpu - cpu1[name]) * args.spp / (args.spp - 1))})
        log(f"{name}: relMSE {mse:.4g} ({np.min(errs[name]):.3g}-{np.max(errs[name]):.3g}), {cpu:.2f} CPU s, "
            f"efficiency {rows[-1]['efficiency']:.4g}")
    for r in rows:
        r["vs_cycles"] = r["efficiency"] / rows[0]["efficiency"]
        r["vs_cycles_marginal"] = r["efficiency_marginal"] / rows[0]["efficiency_marginal"]
    write(os.path.join(args.out_dir, f"efficiency{suffix}.csv"), rows)


def means(args, env, scene, ref, world, ref_cycles, ref_stage5, ref_cycles_cpu, ref_stage5_cpu, suffix):
    # The converged means, and the Lambert control's (the BSDFs taken out of the comparison).
    lam = lambert_copy(scene)
    cl, _ = cached(ref("cycles_lambert").replace(f"_{args.ref_spp}spp", f"_{args.control_spp}spp"),
                   lambda p: env.cycles(args.control_spp, 1000, p, lambert=True))
    sl, _ = cached(ref("stage5_lambert").replace(f"_{args.ref_spp}spp", f"_{args.control_spp}spp"),
                   lambda p: env.stage("stage5_mis", args.control_spp, 1000, p, scene=lam))
    rows = []
    for what, c, s, spp in (("principled", ref_cycles, ref_stage5, args.ref_spp),
                            ("lambert_control", cl, sl, args.control_spp)):
        mc, ms = float(luminance(c).mean()), float(luminance(s).mean())
        ratio_rgb = [float(s[..., k].mean() / c[..., k].mean()) for k in range(3)]
        rows.append({"what": what, "scene": args.file, "world": os.path.basename(world), "size": args.size,
                     "spp": spp, "mean_cycles": mc, "mean_stage5": ms, "ratio": ms / mc,
                     "ratio_r": ratio_rgb[0], "ratio_g": ratio_rgb[1], "ratio_b": ratio_rgb[2]})
        log(f"means ({what}): Cycles {mc:.5g}, stage5 {ms:.5g}, ratio {ms / mc:.4f}")
    rows[0]["ref_cpu_s_cycles"], rows[0]["ref_cpu_s_stage5"] = ref_cycles_cpu, ref_stage5_cpu
    # Each renderer's own BSDF against its own Lambert: where the principled ratio comes from.
    rows[0]["cycles_over_own_lambert"] = rows[0]["mean_cycles"] / rows[1]["mean_cycles"]
    rows[0]["stage5_over_own_lambert"] = rows[0]["mean_stage5"] / rows[1]["mean_stage5"]
    # Cycles' Principled with Specular 0 (its diffuse alone) over its Lambert: what Burley's diffuse adds.
    c0, _ = cached(ref("cycles_specular0").replace(f"_{args.ref_spp}spp", f"_{args.control_spp}spp"),
                   lambda p: env.cycles(args.control_spp, 1000, p, flags=["--specular-zero"]))
    rows[0]["cycles_specular0_over_own_lambert"] = float(luminance(c0).mean()) / rows[1]["mean_cycles"]
    write(os.path.join(args.out_dir, f"means{suffix}.csv"), rows)
    # The converged images side by side (Cycles left, stage5 right; one exposure, Cycles' mean at 0.18).
    for what, c, s in (("principled", ref_cycles, ref_stage5), ("lambert", cl, sl)):
        picture(None, [c, c], [s, s], os.path.join(args.out_dir, f"{args.file}{suffix}_{what}.png"))


def write(path, rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.5g}" if isinstance(v, float) else v) for k, v in r.items()})


if __name__ == "__main__":
    sys.exit(main())
