#!/usr/bin/python3
"""What an environment map costs (issue 49, "Measures", items 3 to 5). Not part of the article:
bench machinery. All CPU seconds are user + sys of the whole process (os.wait4), --backend cpu.

  sampling   stage4 on a real glTF file (bench/gltf_real's --file, its bench camera) lit by a map
             against a uniform --sky of the map's solid-angle mean: CPU s per sample, from the
             difference of a --spp-hi and a --spp-lo render (start-up and loading cancel)
  sun        stage4 against stage3 on maps with a sun (a synthetic 2-texel sun of 1e4 over a dim
             sky, and blender-data's sunrise.exr): efficiency 1 / (relative MSE x CPU s) against
             a stage5 reference of --ref-spp, over --seeds seeds
  load       a 4096 x 2048 map (a blender-data world upsampled by oiiotool) and the 1024 x 512
             original: stage1, builtin:cornell, 1x1, 1 spp, with and without --env, --repeats
             times; the median difference is the map's read + table build (wall and CPU), with
             and without the image module's (OpenImageIO's) first loading, which a 1x1 .png
             output without a map measures; with --table-time, make_environment alone
Writes OUT/sampling_cost.csv, OUT/sun.csv, OUT/load.csv.

  /usr/bin/python3 bench/env/costs.py --bin-dir build-h3/bin --out-dir docs/results/env
"""
import argparse
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "cycles"))
import env_scenes  # noqa: E402
from compare_images import read_rgb, rel_mse  # noqa: E402
from compare_env import write  # noqa: E402 (the CSV writer of the Cycles comparison)
from compare_renderers import run_timed  # noqa: E402
from gltf_prepare import REPO, prepare  # noqa: E402


def log(message):
    print(f"costs.py: {message}", file=sys.stderr, flush=True)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bin-dir", default="build/bin")
    p.add_argument("--out-dir", default="out/env")
    p.add_argument("--work-dir", default="out/env_work")
    p.add_argument("--only", default="sampling,sun,load")
    p.add_argument("--file", default="04_common_materials")
    p.add_argument("--world", default="forest.exr")
    p.add_argument("--size", default="160x120")
    p.add_argument("--spp-lo", type=int, default=16)
    p.add_argument("--spp-hi", type=int, default=256)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seeds", type=int, default=4)
    p.add_argument("--ref-spp", type=int, default=4096)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--blender", default="blender")
    p.add_argument("--table-time", default="", help="the built bench/env/table_time.cpp (README.md)")
    return p.parse_args()


def stage(args, name, scene, spp, seed, out, extra, size=None):
    w, h = (size or args.size).split("x")
    cmd = ["nice", os.path.join(args.bin_dir, name), "--scene", scene, "--width", w, "--height", h,
           "--spp", str(spp), "--seed", str(seed), "--backend", "cpu", "--threads", str(args.threads),
           "--out", out] + extra
    _, cpu, wall = run_timed(cmd)
    return cpu, wall


def solid_angle_mean(path):
    """The map's mean radiance over the sphere (rows weighted by sin theta), negative texels as 0."""
    img = np.maximum(read_rgb(path), 0.0)
    h = img.shape[0]
    weight = np.sin((np.arange(h) + 0.5) / h * np.pi)[:, None, None]
    return (img * weight).sum(axis=(0, 1)) / (weight.sum() * img.shape[1])


def sampling(args, scene, world, work):
    mean = solid_angle_mean(world)
    sky = ",".join(f"{c:.6g}" for c in mean)
    w, h = (int(v) for v in args.size.split("x"))
    rows = []
    for light, extra in (("map", ["--env", world]), ("sky", ["--sky", sky])):
        cpu = {}
        for spp in (args.spp_lo, args.spp_hi):
            cpu[spp] = min(stage(args, "stage4_direct_indirect", scene, spp, 1,
                                 os.path.join(work, f"cost_{light}_{spp}.exr"), extra)[0] for _ in range(2))
        us = (cpu[args.spp_hi] - cpu[args.spp_lo]) / (w * h * (args.spp_hi - args.spp_lo)) * 1e6
        rows.append({"light": light, "scene": args.file, "world": os.path.basename(world), "sky": sky,
                     "size": args.size, "spp_lo": args.spp_lo, "spp_hi": args.spp_hi,
                     "cpu_s_lo": cpu[args.spp_lo], "cpu_s_hi": cpu[args.spp_hi], "cpu_us_per_sample": us})
        log(f"sampling: stage4 lit by the {light}: {us:.4g} CPU µs per sample")
    for r in rows:
        r["ratio_to_sky"] = r["cpu_us_per_sample"] / rows[1]["cpu_us_per_sample"]
    return rows


def sun(args, scene, work):
    synthetic = env_scenes.sun_map(os.path.join(work, "sun_2texel.exr"))
    rows = []
    for label, world in (("sun_2texel", synthetic), ("sunrise", os.path.join(env_scenes.WORLDS, "sunrise.exr"))):
        ref_path = os.path.join(work, f"sun_{label}_ref_{args.ref_spp}.exr")
        if not os.path.exists(ref_path):
            cpu, _ = stage(args, "stage5_mis", scene, args.ref_spp, 1000, ref_path, ["--env", world])
            log(f"sun: {label} reference, {cpu:.1f} CPU s")
        ref = read_rgb(ref_path)
        for name in ("stage3_importance", "stage4_direct_indirect", "stage5_mis"):
            errs, cpus = [], []
            for seed in range(1, args.seeds + 1):
                out = os.path.join(work, f"sun_{label}_{name}_{seed}.exr")
                cpus.append(stage(args, name, scene, args.spp, seed, out, ["--env", world])[0])
                errs.append(rel_mse(read_rgb(out), ref))
            mse, cpu = float(np.mean(errs)), float(np.mean(cpus))
            rows.append({"map": label, "renderer": name, "scene": args.file, "size": args.size,
                         "spp": args.spp, "seeds": args.seeds, "ref_spp": args.ref_spp, "rel_mse": mse,
                         "rel_mse_min": float(min(errs)), "rel_mse_max": float(max(errs)), "cpu_s": cpu,
                         "efficiency": 1.0 / (mse * cpu)})
            log(f"sun: {label} {name}: relMSE {mse:.4g} ({min(errs):.3g}-{max(errs):.3g}), {cpu:.2f} CPU s")
        s3 = next(r for r in rows if r["map"] == label and r["renderer"] == "stage3_importance")
        for r in rows:
            if r["map"] == label:
                r["vs_stage3"] = r["efficiency"] / s3["efficiency"]
    return rows


def load(args, world, work):
    big = os.path.join(work, "world_4096x2048.exr")
    if not os.path.exists(big):
        env_scenes.upsampled(world, big)
    rows = []
    out = os.path.join(work, "load.exr")
    base = [stage(args, "stage1_raycast", "builtin:cornell", 1, 0, out, [], size="1x1") for _ in range(args.repeats)]
    # The image module (OpenImageIO) is loaded on first use: a 1x1 .png output loads it without a map.
    module = [stage(args, "stage1_raycast", "builtin:cornell", 1, 0, out[:-4] + ".png", [], size="1x1")
              for _ in range(args.repeats)]
    for label, path in (("4096x2048", big), ("1024x512", world)):
        runs = [stage(args, "stage1_raycast", "builtin:cornell", 1, 0, out, ["--env", path], size="1x1")
                for _ in range(args.repeats)]
        row = {"map": label, "source": os.path.basename(world), "repeats": args.repeats,
               "file_mb": os.path.getsize(path) / 1e6,
               "wall_s_without": float(np.median([b[1] for b in base])),
               "cpu_s_without": float(np.median([b[0] for b in base])),
               "wall_s_with": float(np.median([r[1] for r in runs])),
               "cpu_s_with": float(np.median([r[0] for r in runs]))}
        row["wall_s_module_only"] = float(np.median([m[1] for m in module]))
        row["cpu_s_module_only"] = float(np.median([m[0] for m in module]))
        row["load_wall_s"] = row["wall_s_with"] - row["wall_s_without"]
        row["load_cpu_s"] = row["cpu_s_with"] - row["cpu_s_without"]
        row["map_wall_s"] = row["wall_s_with"] - row["wall_s_module_only"]
        row["map_cpu_s"] = row["cpu_s_with"] - row["cpu_s_module_only"]
        if args.table_time:   # make_environment alone (bench/env/table_time.cpp), best of --repeats
            w, h = label.split("x")
            text, _, _ = run_timed([args.table_time, w, h, str(args.repeats)])
            row["table_wall_s"] = float(text.split("wall_s=")[1].split()[0])
            row["table_cpu_s"] = float(text.split("cpu_s=")[1].split()[0])
        rows.append(row)
        log(f"load: {label}: {row['load_wall_s']:.3f} s wall, {row['load_cpu_s']:.3f} CPU s; without the image "
            f"module's loading {row['map_wall_s']:.3f} s wall, {row['map_cpu_s']:.3f} CPU s")
    return rows



def main():
    args = parse_args()
    only = args.only.split(",")
    work = os.path.abspath(args.work_dir)
    os.makedirs(work, exist_ok=True)
    os.makedirs(args.out_dir, exist_ok=True)
    world = args.world if os.path.sep in args.world else os.path.join(env_scenes.WORLDS, args.world)
    scene = None
    if "sampling" in only or "sun" in only:
        with open(os.path.join(REPO, "bench", "gltf_real", "files.json")) as f:
            entry = next(e for e in json.load(f)["files"] if e["id"] == args.file)
        scene = prepare(entry, os.path.join(work, "files"), args.blender, log)
    if "load" in only:
        write(os.path.join(args.out_dir, "load.csv"), load(args, world, work))
    if "sampling" in only:
        write(os.path.join(args.out_dir, "sampling_cost.csv"), sampling(args, scene, world, work))
    if "sun" in only:
        write(os.path.join(args.out_dir, "sun.csv"), sun(args, scene, work))
    return 0


if __name__ == "__main__":
    sys.exit(main())
