#!/usr/bin/python3
"""Efficiency of the stages against Blender's Cycles on one glTF scene (issue 23, "the bench's anchor").

For each image size: a reference per renderer (default 16384 spp, cached in the output folder,
keyed by renderer, the references' stage arguments, size and spp; --ref-dir shares them), then, interleaved in one run (Cycles, stage4,
stage3, Cycles, ... for each seed), renders at --spp with --threads threads, each measured against
its own renderer's reference:

  relative RMSE   = sqrt(mean over pixels and R,G,B of (x - ref)^2) / mean over pixels and R,G,B of ref
  relative MSE    = relative RMSE^2, averaged over the seeds
  efficiency      = 1 / (relative MSE * CPU s), CPU s averaged over the seeds
  CPU s           Cycles: the bpy.ops.render.render call alone (CYCLES_RENDER line of render_cycles.py,
                  time.process_time: user + sys of all its threads; it includes Cycles' scene sync and
                  BVH build, not Blender's start-up or the glTF import); a stage: the whole process,
                  user + sys from os.wait4 (start-up, glTF load, BVH build, render, EXR write).
  away from lights the same, over the pixels whose reference luminance (Rec. 709 Y) is below half the
                  smallest emitted luminance of the scene's emissive materials, in every renderer's
                  reference, and that are not next to such a pixel (the light's image plus a 1-pixel ring,
                  8-neighbourhood); its relative RMSE divides by the mean of ref over those pixels.

The references' noise adds to each measured MSE (about spp/ref_spp of it for equal samplers: 1.6% at
256 against 16384); it is not subtracted. The references are also compared with each other (image
means, per-row means, and the row means of an upside-down image, to catch a flipped image).

Needs: Debian 12's python3 with python3-numpy, openimageio-tools (oiiotool reads the EXR files) and,
for the Cycles rows, blender (3.4.1). Without blender it says so in one line and exits 0 (skipped).
Writes OUT/runs.csv (every render), OUT/summary.csv and OUT/summary.md (the table).

  /usr/bin/python3 bench/cycles/compare.py                      # 64x64 and 128x128, refs 16384 spp
  /usr/bin/python3 bench/cycles/compare.py --sizes 64x64 --ref-spp 256 --spp 16 --seeds 2   # quick
  /usr/bin/python3 bench/cycles/compare.py --stage-args "--sampler independent"
"""
import argparse
import os
import shlex
import shutil
import sys
import time

import numpy as np

# bench/cycles, beside this script; bench/smallpt_compare.py and bench/sampler_study.py import
# read_rgb, run_timed and slug from this module (compare), so it names them all.
from compare_images import away_mask, emitted_luminances, read_rgb, rel_mse
from compare_renderers import REPO, Cycles, Stage, log, reference, run_timed, slug  # noqa: F401
from compare_report import reference_agreement, write_report


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default="scenes/cornell.gltf", help="glTF scene (relative to the repository)")
    p.add_argument("--sizes", default="64x64,128x128", help="comma-separated WxH list")
    p.add_argument("--spp", type=int, default=256, help="samples per pixel of the measured renders")
    p.add_argument("--ref-spp", type=int, default=16384, help="samples per pixel of the references")
    p.add_argument("--ref-spp-for", action="append", default=[], metavar="WxH=N",
                   help="a different reference spp for one size (e.g. 128x128=4096); repeatable")
    p.add_argument("--seeds", type=int, default=4, help="measured renders per renderer and size (seeds 1..N)")
    p.add_argument("--ref-seed", type=int, default=1000003, help="seed of the references (not among 1..N)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--bin-dir", default="build/bin", help="where the stage programs are (relative to the repository)")
    p.add_argument("--stages", default="stage4_direct_indirect,stage3_importance",
                   help="comma-separated stage programs, in the interleaving order after Cycles")
    p.add_argument("--stage-args", default="",
                   help="extra arguments for every stage render (e.g. \"--sampler independent\"); they label the rows")
    p.add_argument("--ref-stage-args", default=None,
                   help="extra arguments for the stages' references (default: the same as --stage-args)")
    p.add_argument("--blender", default="blender", help="the blender program")
    p.add_argument("--no-cycles", action="store_true", help="leave Cycles out (the stages alone, no ratio)")
    p.add_argument("--out-dir", default="out/bench_cycles",
                   help="references, renders and tables (relative to the repository; /out/ is git-ignored)")
    p.add_argument("--ref-dir", default=None,
                   help="the reference cache (default OUT-DIR/refs); share it between runs with other --stage-args")
    p.add_argument("--fresh-refs", action="store_true", help="render the references again even if cached")
    p.add_argument("--light-threshold", type=float, default=None,
                   help="reference luminance above which a pixel counts as the light's image "
                        "(default: half the smallest emitted luminance in the glTF)")
    return p.parse_args()


def repo_path(path):
    return path if os.path.isabs(path) else os.path.join(REPO, path)


def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def main():
    args = parse_args()
    scene = repo_path(args.scene)
    out_dir = repo_path(args.out_dir)
    ref_dir = repo_path(args.ref_dir) if args.ref_dir else os.path.join(out_dir, "refs")
    bin_dir = repo_path(args.bin_dir)
    stage_args = shlex.split(args.stage_args)
    ref_stage_args = stage_args if args.ref_stage_args is None else shlex.split(args.ref_stage_args)
    sizes = [tuple(int(v) for v in s.lower().split("x")) for s in args.sizes.split(",") if s]
    ref_spp = {f"{w}x{h}": args.ref_spp for w, h in sizes}
    for item in args.ref_spp_for:
        size, n = item.split("=")
        ref_spp[size.lower()] = int(n)

    renderers = []
    if not args.no_cycles:
        if shutil.which(args.blender) is None:
            print(f"compare.py: skipped: '{args.blender}' not found (Debian: apt-get install blender); "
                  "the Cycles comparison is bench-only")
            return 0
        renderers.append(Cycles(args.blender, scene, args.threads))
    for name in [s for s in args.stages.split(",") if s]:
        binary = os.path.join(bin_dir, name)
        if not os.access(binary, os.X_OK):
            log(f"{binary} not found; build first (cmake --build build)")
            return 1
        renderers.append(Stage(binary, scene, args.threads, stage_args, ref_stage_args))
    if shutil.which("oiiotool") is None:
        log("oiiotool not found (Debian: apt-get install openimageio-tools)")
        return 1

    lights = emitted_luminances(scene)
    threshold = args.light_threshold if args.light_threshold is not None else \
        (0.5 * min(lights) if lights else float("inf"))
    os.makedirs(out_dir, exist_ok=True)
    load_before = loadavg()
    started = time.time()
    log(f"load average before: {load_before}")

    runs = []
    summary = []
    agreement = {}
    for w, h in sizes:
        n_ref = ref_spp[f"{w}x{h}"]
        refs = {r.key: read_rgb(reference(r, w, h, n_ref, args.ref_seed, ref_dir, args.fresh_refs))
                for r in renderers}
        mask, n_bright = away_mask(list(refs.values()), threshold)
        agreement[(w, h)] = (n_ref, int(mask.sum()), n_bright,
                             reference_agreement([(r.label, refs[r.key]) for r in renderers], mask))
        per = {r.label: [] for r in renderers}
        for seed in range(1, args.seeds + 1):
            for r in renderers:  # interleaved: Cycles, stage4, stage3, Cycles, ...
                path = os.path.join(out_dir, "renders", f"{r.key}_{w}x{h}_{args.spp}spp_seed{seed}.exr")
                os.makedirs(os.path.dirname(path), exist_ok=True)
                t = r.render(w, h, args.spp, seed, path)
                img = read_rgb(path)
                ref = refs[r.key]
                row = {"size": f"{w}x{h}", "renderer": r.label, "seed": seed, "spp": args.spp,
                       "threads": args.threads, "ref_spp": n_ref,
                       "cpu_s": round(t["cpu_s"], 4), "wall_s": round(t["wall_s"], 4),
                       "process_cpu_s": round(t["process_cpu_s"], 4),
                       "rel_mse": rel_mse(img, ref), "rel_mse_away": rel_mse(img, ref, mask),
                       "loadavg": loadavg()}
                runs.append(row)
                per[r.label].append(row)
                log(f"{w}x{h} seed {seed} {r.label}: relRMSE {row['rel_mse'] ** 0.5:.4f} "
                    f"(away {row['rel_mse_away'] ** 0.5:.4f}), {row['cpu_s']:.2f} CPU s")
        base_eff = base_eff_away = None
        for r in renderers:
            rows = per[r.label]
            mse = float(np.mean([x["rel_mse"] for x in rows]))
            mse_away = float(np.mean([x["rel_mse_away"] for x in rows]))
            cpu = float(np.mean([x["cpu_s"] for x in rows]))
            eff, eff_away = 1.0 / (mse * cpu), 1.0 / (mse_away * cpu)
            if isinstance(r, Cycles):
                base_eff, base_eff_away = eff, eff_away
            per_seed = [1.0 / (x["rel_mse"] * x["cpu_s"]) for x in rows]
            summary.append({
                "size": f"{w}x{h}", "renderer": r.label, "spp": args.spp, "seeds": len(rows),
                "ref_spp": n_ref, "rel_rmse": mse ** 0.5, "cpu_s": cpu,
                "cpu_s_min": min(x["cpu_s"] for x in rows), "cpu_s_max": max(x["cpu_s"] for x in rows),
                "efficiency": eff, "efficiency_seed_min": min(per_seed), "efficiency_seed_max": max(per_seed),
                "vs_cycles": eff / base_eff if base_eff else float("nan"),
                "rel_rmse_away": mse_away ** 0.5, "efficiency_away": eff_away,
                "vs_cycles_away": eff_away / base_eff_away if base_eff_away else float("nan"),
                "cpu_per_sample_us": cpu / (args.spp * w * h) * 1e6,
                "rel_var_per_sample": mse * args.spp, "rel_var_per_sample_away": mse_away * args.spp,
            })
    load_after = loadavg()
    minutes = (time.time() - started) / 60.0
    log(f"load average after: {load_after}; {minutes:.1f} min")

    write_report(args, out_dir, runs, summary, agreement, threshold, stage_args, ref_stage_args,
                 load_before, load_after, minutes)
    return 0


if __name__ == "__main__":
    sys.exit(main())
