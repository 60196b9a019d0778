#!/usr/bin/python3
"""Efficiency of the stages against smallpt's algorithm on smallpt's scene (issue #18).

The yardstick is build/bin/pt_smallpt_reference (bench/smallpt_reference.cpp): smallpt's algorithm
(cosine sampling, Russian roulette after 5 bounces with p = max albedo, glass split on the first two
hits, no per-subpixel clamp) in double precision with 2 threads, on smallpt's scene (its black
front wall, camera rays starting 140 units ahead), against build/bin/stage3_importance,
stage4_direct_indirect and stage5_mis on builtin:smallpt, the same scene (the front wall and the
camera's clip start of 140), --backend cpu --threads 2, each with --sampler sobol (the default)
and --sampler independent.
At --width x --height (64x48): each renderer's own reference of --ref-spp (16384) samples, cached in
--cache-dir under the binary's hash, then --seeds (4) renders of --spp (256) samples per renderer,
interleaved (every renderer for seed 1, then for seed 2, ...) so that a change in the machine's load
falls on all of them. Each render is measured against its own renderer's reference:

  relative RMSE   sqrt(mean over pixels and R,G,B of (x - ref)^2) / mean over pixels and R,G,B of ref
                  (docs/results.md's definition); squared and averaged over the seeds, then the root
  CPU s           user + sys of the whole process (os.wait4), averaged over the seeds
  efficiency      1 / (relative MSE x CPU s)

The references' own noise adds to each measured MSE (about spp / ref_spp of it, 1.6%); not subtracted.
The converged images are compared with each other (image means, per channel, a 4 x 3 grid of regions
with a rough noise scale from the seeds' spread, and the row means of an upside-down image).

The binaries are copied (under /work/main/.build.lock's flock when that file exists, so a build in
progress is waited for) into --cache-dir/bin/<hash>/ and run from there: a rebuild during the run
cannot mix two versions.

Needs Debian 12's python3 with python3-numpy, and openimageio-tools (oiiotool reads the EXR files).
Writes docs/results/smallpt_compare.csv (one row per renderer), docs/results/smallpt_notes.md (the
section bench/report.py puts into docs/results.md; text between the FINDINGS markers is kept across
runs) and --cache-dir/runs.csv (every render).

  /usr/bin/python3 bench/smallpt_compare.py                                   # about 20 min on 2 cores
  /usr/bin/python3 bench/smallpt_compare.py --ref-spp 1024 --spp 64 --seeds 2 --notes /tmp/n.md --csv /tmp/c.csv
"""
import argparse
import csv
import datetime
import os
import shutil
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "cycles"))
from compare import read_rgb, run_timed, slug  # noqa: E402  (oiiotool reader, timed subprocess)
from smallpt_cache import REPO, log, reference, repo_path, snapshot  # noqa: E402  (bench/, beside this script)
from smallpt_images import GRID, regions, region_rel_mse, rel_mse  # noqa: E402
from smallpt_report import loadavg, write_csv, write_notes  # noqa: E402


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--width", type=int, default=64)
    p.add_argument("--height", type=int, default=48)
    p.add_argument("--spp", type=int, default=256, help="samples per pixel of the measured renders")
    p.add_argument("--ref-spp", type=int, default=16384, help="samples per pixel of each renderer's reference")
    p.add_argument("--seeds", type=int, default=4, help="measured renders per renderer (seeds 1..N)")
    p.add_argument("--ref-seed", type=int, default=1000003, help="seed of the references (not among 1..N)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--bin-dir", default="build/bin", help="where the programs are (relative to the repository)")
    p.add_argument("--stages", default="stage3_importance,stage4_direct_indirect,stage5_mis")
    p.add_argument("--samplers", default="sobol,independent")
    p.add_argument("--cache-dir", default="build/bench_cache/smallpt_compare",
                   help="binaries, references and renders (relative to the repository)")
    p.add_argument("--lock", default="/work/main/.build.lock",
                   help="flock'ed while the binaries are copied, if it exists ('' for none)")
    p.add_argument("--fresh-refs", action="store_true", help="render the references again even if cached")
    p.add_argument("--notes", default="docs/results/smallpt_notes.md")
    p.add_argument("--csv", default="docs/results/smallpt_compare.csv")
    return p.parse_args()


class Renderer:
    def __init__(self, key, label, short, binary, digest, args, is_stage, sampler):
        self.key, self.label, self.short = key, label, short
        self.binary, self.digest, self.args = binary, digest, args
        self.is_stage, self.sampler = is_stage, sampler

    def command(self, w, h, spp, seed, threads, out):
        cmd = [self.binary]
        if self.is_stage:
            cmd += ["--scene", "builtin:smallpt", "--backend", "cpu"]
        cmd += ["--width", str(w), "--height", str(h), "--spp", str(spp), "--seed", str(seed),
                "--threads", str(threads), "--out", out] + self.args
        return cmd

    def render(self, w, h, spp, seed, threads, out):
        output, cpu, wall = run_timed(self.command(w, h, spp, seed, threads, out))
        last = output.strip().splitlines()[-1] if output.strip() else ""
        return {"cpu_s": cpu, "wall_s": wall, "summary": last}


def main():
    a = parse_args()
    if shutil.which("oiiotool") is None:
        log("oiiotool not found (Debian: apt-get install openimageio-tools)")
        return 2
    cache = repo_path(a.cache_dir)
    os.makedirs(cache, exist_ok=True)
    stages = [s for s in a.stages.split(",") if s]
    samplers = [s for s in a.samplers.split(",") if s]
    bins = snapshot(["pt_smallpt_reference"] + stages, repo_path(a.bin_dir), cache, a.lock)

    ref_bin, ref_hash = bins["pt_smallpt_reference"]
    renderers = [
        Renderer("smallpt", "reference (smallpt's scene: front wall, rays start 140 ahead)", "reference",
                 ref_bin, ref_hash, [], False, ""),
    ]
    for st in stages:
        path, h = bins[st]
        for sm in samplers:
            short = st.split("_")[0]
            renderers.append(Renderer(f"{st}_{slug(sm)}", f"{st} --sampler {sm}", f"{short} ({sm})",
                                      path, h, ["--sampler", sm], True, sm))

    load_before = loadavg()
    start = time.time()
    started = datetime.datetime.now(datetime.timezone.utc)
    refs = {}
    for r in renderers:
        refs[r.key] = reference(r, a, cache)
    ref_imgs = {k: read_rgb(v[0]) for k, v in refs.items()}

    runs_dir = os.path.join(cache, "runs")
    os.makedirs(runs_dir, exist_ok=True)
    runs = []
    imgs = {r.key: [] for r in renderers}
    startup = {r.key: [] for r in renderers}
    for seed in range(1, a.seeds + 1):
        for r in renderers:
            out = os.path.join(runs_dir, f"{r.key}_{a.width}x{a.height}_{a.spp}spp_seed{seed}.exr")
            t = r.render(a.width, a.height, a.spp, seed, a.threads, out)
            img = read_rgb(out)
            imgs[r.key].append(img)
            e = rel_mse(img, ref_imgs[r.key])
            runs.append(dict(renderer=r.key, label=r.label, seed=seed, spp=a.spp, width=a.width, height=a.height,
                             cpu_s=round(t["cpu_s"], 4), wall_s=round(t["wall_s"], 4), rel_mse=e,
                             rel_rmse=e ** 0.5, binary_sha256_12=r.digest, summary=t["summary"]))
            log(f"seed {seed} {r.label}: rel RMSE {e ** 0.5:.4f}, {t['cpu_s']:.2f} CPU s, {t['wall_s']:.2f} s wall")
        for r in renderers:  # the fixed cost: the same process at 1 spp
            out = os.path.join(runs_dir, f"{r.key}_{a.width}x{a.height}_1spp_seed{seed}.exr")
            t = r.render(a.width, a.height, 1, seed, a.threads, out)
            startup[r.key].append(t["cpu_s"])
            runs.append(dict(renderer=r.key, label=r.label, seed=seed, spp=1, width=a.width, height=a.height,
                             cpu_s=round(t["cpu_s"], 4), wall_s=round(t["wall_s"], 4), rel_mse="", rel_rmse="",
                             binary_sha256_12=r.digest, summary=t["summary"]))
    load_after = loadavg()
    elapsed = time.time() - start

    with open(os.path.join(cache, "runs.csv"), "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(runs[0].keys()))
        wr.writeheader()
        wr.writerows(runs)

    pixels = a.width * a.height
    summary = {}
    for r in renderers:
        rr = [x for x in runs if x["renderer"] == r.key and x["spp"] == a.spp]
        mse = float(np.mean([x["rel_mse"] for x in rr]))
        cpu = float(np.mean([x["cpu_s"] for x in rr]))
        cpu1 = float(np.mean(startup[r.key]))
        summary[r.key] = dict(mse=mse, rmse=mse ** 0.5, cpu=cpu, eff=1.0 / (mse * cpu), cpu1=cpu1,
                              eff_render=1.0 / (mse * max(cpu - cpu1, 1e-3)),
                              var_per_sample=mse * a.spp, us_per_sample=cpu / (pixels * a.spp) * 1e6,
                              region_mse=np.mean([region_rel_mse(i, ref_imgs[r.key]) for i in imgs[r.key]], axis=0))

    csv_path = write_csv(a, renderers, summary, refs)

    # Noise scale of each reference's region means: the seeds' spread at spp, scaled to ref_spp
    # (as for independent samples; it overstates a Sobol reference's).
    sd = {k: np.std([regions(i) for i in v], axis=0, ddof=1) * (a.spp / a.ref_spp) ** 0.5
          if len(v) > 1 else np.zeros(GRID) for k, v in imgs.items()}

    notes_path = write_notes(a, renderers, summary, refs, ref_imgs, sd, started, elapsed, load_before, load_after)
    log(f"wrote {os.path.relpath(csv_path, REPO)}, {os.path.relpath(notes_path, REPO)} and "
        f"{os.path.relpath(os.path.join(cache, 'runs.csv'), REPO)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
