#!/usr/bin/python3
"""Efficiency of the stages against smallpt's algorithm on smallpt's scene (issue #18).

The yardstick is build/bin/pt_smallpt_reference (bench/smallpt_reference.cpp): smallpt's algorithm
(cosine sampling, Russian roulette after 5 bounces with p = max albedo, glass split on the first two
hits, no per-subpixel clamp) in double precision with 2 threads. It runs twice:

  reference            smallpt's scene: its black front wall, camera rays starting 140 units ahead
  reference (open)     builtin:smallpt's geometry: no front wall, rays from the camera (--open-front --start 0)

against build/bin/stage3_importance, stage4_direct_indirect and stage5_mis on builtin:smallpt
(--backend cpu --threads 2), each with --sampler sobol (the default) and --sampler independent.
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
import fcntl
import hashlib
import os
import platform
import re
import shlex
import shutil
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "cycles"))
from compare import read_rgb, run_timed, slug  # noqa: E402  (oiiotool reader, timed subprocess)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FINDINGS_BEGIN = "<!-- FINDINGS: hand-written, kept by bench/smallpt_compare.py -->"
FINDINGS_END = "<!-- /FINDINGS -->"
GRID = (3, 4)  # regions: rows x columns


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


def repo_path(path):
    return path if os.path.isabs(path) else os.path.join(REPO, path)


def log(message):
    print(f"smallpt_compare.py: {message}", file=sys.stderr, flush=True)


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def snapshot(names, bin_dir, cache, lock):
    """Copies each program into cache/bin/<hash12>/; returns {name: (path, hash12)}."""
    fd = None
    if lock and os.path.exists(lock):
        fd = os.open(lock, os.O_RDONLY)
        log(f"locking {lock} to copy the binaries (waits for a build in progress) ...")
        fcntl.flock(fd, fcntl.LOCK_EX)
    try:
        out = {}
        for name in names:
            src = os.path.join(bin_dir, name)
            for _ in range(60):  # a binary being relinked may be missing for a moment
                if os.path.exists(src):
                    break
                time.sleep(10)
            h = sha256(src)[:12]
            dst_dir = os.path.join(cache, "bin", h)
            dst = os.path.join(dst_dir, name)
            if not os.path.exists(dst):
                os.makedirs(dst_dir, exist_ok=True)
                shutil.copy2(src, dst + ".tmp")
                os.replace(dst + ".tmp", dst)
            out[name] = (dst, h)
        return out
    finally:
        if fd is not None:
            fcntl.flock(fd, fcntl.LOCK_UN)
            os.close(fd)


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


def reference(r, a, cache):
    name = f"{r.key}_{r.digest}_{a.width}x{a.height}_{a.ref_spp}spp_seed{a.ref_seed}.exr"
    path = os.path.join(cache, "refs", name)
    meta = path[:-4] + ".txt"
    if a.fresh_refs or not (os.path.exists(path) and os.path.exists(meta)):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        log(f"reference {r.label}, {a.ref_spp} spp ...")
        t = r.render(a.width, a.height, a.ref_spp, a.ref_seed, a.threads, path)
        with open(meta, "w") as f:
            f.write(f"{t['cpu_s']:.3f} {t['wall_s']:.3f}\n{t['summary']}\n")
        log(f"  {t['cpu_s']:.1f} CPU s, {t['wall_s']:.1f} s wall")
    else:
        log(f"reference {r.label}: cached {os.path.relpath(path, REPO)}")
    with open(meta) as f:
        cpu_s = float(f.readline().split()[0])
        summary = f.readline().strip()
    return path, cpu_s, summary


def rel_mse(img, ref):
    return float(np.mean((img - ref) ** 2) / np.mean(ref) ** 2)


def regions(img):
    """Mean over R, G, B of each region of the GRID, as an array of shape GRID."""
    h, w = img.shape[:2]
    gy, gx = GRID
    out = np.zeros(GRID)
    for j in range(gy):
        for i in range(gx):
            out[j, i] = img[j * h // gy:(j + 1) * h // gy, i * w // gx:(i + 1) * w // gx].mean()
    return out


def region_rel_mse(img, ref):
    """Per region: mean of (x - ref)^2 over the region, divided by the whole reference's mean squared."""
    return regions((img - ref) ** 2) / np.mean(ref) ** 2


def machine():
    model = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores"


def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def fmt(x):
    return f"{x:.3g}" if abs(x) < 1000 else f"{x:.0f}"


def agreement(label_a, a, sd_a, label_b, b, sd_b):
    """One table row: image mean, channels, regions (largest |difference| and its z), flip check."""
    scale = b.mean()
    whole = (a.mean() / scale - 1.0) * 100.0
    ch = (a.mean(axis=(0, 1)) / b.mean(axis=(0, 1)) - 1.0) * 100.0
    ra, rb = regions(a), regions(b)
    diff = (ra / rb - 1.0) * 100.0
    z = (ra - rb) / np.sqrt(sd_a ** 2 + sd_b ** 2 + 1e-30)
    k = np.unravel_index(np.argmax(np.abs(diff)), diff.shape)
    below_top = (a[1:].mean() / b[1:].mean() - 1.0) * 100.0
    rows_a, rows_b = a.mean(axis=(1, 2)), b.mean(axis=(1, 2))
    row_dev = np.sqrt(np.mean((rows_a - rows_b) ** 2)) / scale * 100.0
    flip_dev = np.sqrt(np.mean((rows_a[::-1] - rows_b) ** 2)) / scale * 100.0
    return (f"| {label_a} vs {label_b} | {whole:+.2f}% | {below_top:+.2f}% | "
            f"{ch[0]:+.2f}% / {ch[1]:+.2f}% / {ch[2]:+.2f}% | "
            f"{np.median(diff):+.2f}% | {diff[k]:+.2f}% (row {k[0]}, col {k[1]}; z {z[k]:+.1f}) | "
            f"{np.max(np.abs(z)):.1f} | {row_dev:.2f}% / {flip_dev:.0f}% ({'upright' if row_dev < flip_dev else 'FLIPPED?'}) |")


def kept_findings(path):
    if not os.path.exists(path):
        return None
    text = open(path).read()
    i, j = text.find(FINDINGS_BEGIN), text.find(FINDINGS_END)
    if i < 0 or j < i:
        return None
    return text[i:j + len(FINDINGS_END)]


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
        Renderer("smallpt_open", "reference (builtin:smallpt's geometry: --open-front --start 0)",
                 "reference, open", ref_bin, ref_hash, ["--open-front", "--start", "0"], False, ""),
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
    base, base_open = summary["smallpt"], summary["smallpt_open"]

    rows_csv = []
    for r in renderers:
        s = summary[r.key]
        rows_csv.append(dict(renderer=r.key, label=r.label, sampler=r.sampler or "-", width=a.width, height=a.height,
                             spp=a.spp, seeds=a.seeds, rel_rmse=round(s["rmse"], 5), cpu_s=round(s["cpu"], 4),
                             efficiency=round(s["eff"], 3), vs_reference=round(s["eff"] / base["eff"], 4),
                             vs_reference_open=round(s["eff"] / base_open["eff"], 4),
                             cpu_s_at_1spp=round(s["cpu1"], 4),
                             vs_reference_without_startup=round(s["eff_render"] / base["eff_render"], 4),
                             vs_reference_open_without_startup=round(s["eff_render"] / base_open["eff_render"], 4),
                             rel_var_per_sample=round(s["var_per_sample"], 4),
                             cpu_us_per_sample=round(s["us_per_sample"], 4), ref_spp=a.ref_spp,
                             ref_cpu_s=round(refs[r.key][1], 2), binary_sha256_12=r.digest))
    csv_path = repo_path(a.csv)
    os.makedirs(os.path.dirname(csv_path), exist_ok=True)
    with open(csv_path, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows_csv[0].keys()))
        wr.writeheader()
        wr.writerows(rows_csv)

    # Noise scale of each reference's region means: the seeds' spread at spp, scaled to ref_spp
    # (as for independent samples; it overstates a Sobol reference's).
    sd = {k: np.std([regions(i) for i in v], axis=0, ddof=1) * (a.spp / a.ref_spp) ** 0.5
          if len(v) > 1 else np.zeros(GRID) for k, v in imgs.items()}

    nice = os.nice(0)
    command = ("nice -n %d " % nice if nice else "") + "/usr/bin/python3 bench/smallpt_compare.py" + \
        (" " + shlex.join(sys.argv[1:]) if sys.argv[1:] else "")
    md = ["## smallpt: the stages against smallpt's algorithm (issue #18)", "",
          "<!-- Made by bench/smallpt_compare.py; bench/report.py puts this file into docs/results.md. "
          "Everything but the FINDINGS block is rewritten by each run. -->", "",
          f"Measured {started.strftime('%Y-%m-%d %H:%M')} UTC on {machine()}, `{command}` "
          f"({elapsed / 60:.0f} min; load average {load_before} before, {load_after} after"
          + (f"; the script and its renders ran at niceness {nice}" if nice else "") + "). "
          f"builtin:smallpt at {a.width}x{a.height}, {a.spp} spp, {a.seeds} seeds interleaved across the renderers, "
          f"{a.threads} threads, the stages on `--backend cpu`; each renderer against its own "
          f"{a.ref_spp}-spp reference; relative RMSE as above (RMSE over pixels and R, G, B / the reference's mean, "
          "its square averaged over the seeds); CPU s: user + sys of the whole process (start-up, scene, render, "
          "EXR write), mean of the seeds; efficiency = 1 / (relative MSE x CPU s).", "",
          "The yardstick, `pt_smallpt_reference` (bench/smallpt_reference.cpp), is smallpt's algorithm written "
          "afresh: cosine sampling, Russian roulette from the 6th hit with p = the largest albedo, glass split into "
          "reflection and refraction on the first two hits (then one of them, reflection with probability "
          "0.25 + 0.5 F), a box pixel filter instead of smallpt's 2x2 tent subpixels and their clamp, "
          "double precision, our materials' radiometry. \"reference\" renders smallpt's scene (its black front wall, "
          "camera rays starting 140 units ahead); \"reference, open\" builtin:smallpt's geometry (no front wall, "
          "rays from the camera).", "",
          "| renderer | relRMSE | CPU s | efficiency | vs reference | vs reference, open | "
          "rel. variance per sample | CPU µs per sample | CPU s at 1 spp | without it: vs reference, vs open |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in renderers:
        s = summary[r.key]
        v1, v2 = s["eff"] / base["eff"], s["eff"] / base_open["eff"]
        bold = r.key.startswith("stage5") and r.sampler == "sobol"
        md.append(f"| {r.short} | {s['rmse']:.3f} | {s['cpu']:.2f} | {fmt(s['eff'])} | "
                  + (f"**{v1:.2f}**" if bold else f"{v1:.2f}") + " | "
                  + (f"**{v2:.2f}**" if bold else f"{v2:.2f}") + f" | {s['var_per_sample']:.2f} | "
                  f"{s['us_per_sample']:.2f} | {s['cpu1']:.2f} | {s['eff_render'] / base['eff_render']:.2f}, "
                  f"{s['eff_render'] / base_open['eff_render']:.2f} |")
    md += ["", "Relative variance per sample: relative MSE x spp. CPU s at 1 spp: the same process rendering 1 "
           "sample per pixel (start-up, the dynamic linking of OpenImageIO's libraries above all, scene, EXR "
           "write), measured interleaved with the others; the last column's ratios use CPU s minus it."]
    md.append("")
    s5 = summary.get("stage5_mis_sobol")
    if s5:
        v1, v2 = s5["eff"] / base["eff"], s5["eff"] / base_open["eff"]
        verdict = "met" if min(v1, v2) >= 1.5 else ("met against one reference only" if max(v1, v2) >= 1.5
                                                    else "missed")
        md += [f"- **Target \"stage5_mis at least 1.5x the reference's efficiency by CPU time\": {verdict}** "
               f"({v1:.2f}x the reference, {v2:.2f}x the reference on builtin:smallpt's geometry; default sampler).",
               ""]
    # Where stage5's error is, region by region, against stage4 and the open reference.
    if s5 and "stage4_direct_indirect_sobol" in summary:
        s4 = summary["stage4_direct_indirect_sobol"]
        md += ["Relative MSE by region (image split into 3 rows x 4 columns; each region's squared error over the "
               "whole reference's squared mean), default sampler, and stage5's efficiency ratio there "
               "(the same CPU s for every region):", "",
               "| region (row, col) | reference, open | stage4 | stage5 | stage5 / stage4 efficiency | "
               "stage5 / reference-open efficiency |", "|---|---|---|---|---|---|"]
        for j in range(GRID[0]):
            for i in range(GRID[1]):
                m_o, m4, m5 = base_open["region_mse"][j, i], s4["region_mse"][j, i], s5["region_mse"][j, i]
                md.append(f"| {j}, {i} | {m_o:.3g} | {m4:.3g} | {m5:.3g} | "
                          f"{(m4 * s4['cpu']) / (m5 * s5['cpu']):.2f} | {(m_o * base_open['cpu']) / (m5 * s5['cpu']):.2f} |")
        md.append("")

    md += ["Do the converged images agree? Each renderer's reference against another's: the image mean, the "
           "mean without the image's top row of pixels, per channel, the median and the largest difference of "
           "the 12 region means (z: that difference over a rough noise scale, from the seeds' spread scaled to "
           "the references' samples) and the largest |z|, and the RMS difference of the row means (over the "
           "image mean), upright and against the other image upside down:", "",
           "| references | mean | mean, rows 1+ | R / G / B | regions: median | regions: largest | max abs z | "
           "rows / flipped |",
           "|---|---|---|---|---|---|---|---|"]
    pairs = [("smallpt_open", "stage4_direct_indirect_sobol"), ("smallpt", "stage4_direct_indirect_sobol"),
             ("smallpt", "smallpt_open"), ("stage3_importance_sobol", "stage4_direct_indirect_sobol"),
             ("stage5_mis_sobol", "stage4_direct_indirect_sobol"),
             ("stage4_direct_indirect_independent", "stage4_direct_indirect_sobol")]
    short = {r.key: r.short for r in renderers}
    for x, y in pairs:
        if x in ref_imgs and y in ref_imgs:
            md.append(agreement(short[x], ref_imgs[x], sd[x], short[y], ref_imgs[y], sd[y]))
    md.append("")
    capped = {k: re.search(r"(\d+) paths? stopped at the depth cap", v[2]) for k, v in refs.items()}
    md.append("References' CPU s: " + "; ".join(
        f"{short[k]} {v[1]:.0f}" + (f" ({capped[k].group(1)} paths stopped at the depth cap)" if capped[k] else "")
        for k, v in refs.items()) + ". Binaries (sha256, 12 digits): " + ", ".join(
        sorted({f"{os.path.basename(r.binary)} {r.digest}" for r in renderers})) + ".")
    md.append("")
    notes_path = repo_path(a.notes)
    kept = kept_findings(notes_path)
    md += [kept if kept else FINDINGS_BEGIN + "\n" + FINDINGS_END, ""]
    os.makedirs(os.path.dirname(notes_path), exist_ok=True)
    with open(notes_path + ".tmp", "w") as f:
        f.write("\n".join(md).rstrip() + "\n")
    os.replace(notes_path + ".tmp", notes_path)
    print("\n".join(md))
    log(f"wrote {os.path.relpath(csv_path, REPO)}, {os.path.relpath(notes_path, REPO)} and "
        f"{os.path.relpath(os.path.join(cache, 'runs.csv'), REPO)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
