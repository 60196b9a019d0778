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
import csv
import datetime
import json
import os
import re
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RENDER_CYCLES = os.path.join(REPO, "bench", "cycles", "render_cycles.py")
LUMA = np.array([0.2126, 0.7152, 0.0722])


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


def slug(text):
    s = re.sub(r"[^A-Za-z0-9]+", "_", text).strip("_")
    return s or "default"


def log(message):
    print(f"compare.py: {message}", file=sys.stderr, flush=True)


# --- images -------------------------------------------------------------------------------------

def read_rgb(path):
    """R, G, B of an EXR as float64 (H, W, 3), row 0 on top, through oiiotool (openimageio-tools)."""
    with tempfile.TemporaryDirectory() as tmp:
        rgb = os.path.join(tmp, "rgb.exr")
        subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "float", "-o", rgb], check=True,
                       stdout=subprocess.DEVNULL)
        text = subprocess.run(["oiiotool", "--dumpdata", rgb], check=True, capture_output=True,
                              text=True).stdout
    header = re.search(r":\s+(\d+) x\s+(\d+), 3 channel", text)
    if not header:
        raise RuntimeError(f"{path}: unexpected oiiotool --dumpdata output")
    w, h = int(header.group(1)), int(header.group(2))
    img = np.zeros((h, w, 3))
    seen = 0
    for m in re.finditer(r"Pixel \((\d+), (\d+)\): (\S+) (\S+) (\S+)", text):
        x, y = int(m.group(1)), int(m.group(2))
        img[y, x] = (float(m.group(3)), float(m.group(4)), float(m.group(5)))
        seen += 1
    if seen != w * h:
        raise RuntimeError(f"{path}: read {seen} pixels of {w}x{h}")
    return img


def luminance(img):
    return img @ LUMA


def gltf_json(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":  # .glb: 12-byte header, then the JSON chunk
        length, kind = struct.unpack_from("<II", data, 12)
        if kind != 0x4E4F534A:
            raise RuntimeError(f"{path}: first .glb chunk is not JSON")
        return json.loads(data[20:20 + length])
    return json.loads(data)


def emitted_luminances(scene):
    out = []
    for m in gltf_json(scene).get("materials", []):
        e = m.get("emissiveFactor", [0.0, 0.0, 0.0])
        s = m.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        y = float(np.dot(LUMA, np.array(e, dtype=float) * s))
        if y > 0.0:
            out.append(y)
    return out


def away_mask(refs, threshold):
    """True where a pixel is away from the light: no reference at or above threshold there or next to it."""
    bright = np.zeros(refs[0].shape[:2], dtype=bool)
    for ref in refs:
        bright |= luminance(ref) >= threshold
    near = bright.copy()
    h, w = bright.shape
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            shifted = np.zeros_like(bright)
            shifted[max(dy, 0):h + min(dy, 0), max(dx, 0):w + min(dx, 0)] = \
                bright[max(-dy, 0):h + min(-dy, 0), max(-dx, 0):w + min(-dx, 0)]
            near |= shifted
    return ~near, int(bright.sum())


def rel_mse(img, ref, mask=None):
    if mask is not None:
        img, ref = img[mask], ref[mask]
    return float(np.mean((img - ref) ** 2) / np.mean(ref) ** 2)


# --- renderers ----------------------------------------------------------------------------------

def run_timed(cmd):
    """Runs cmd; returns (output, user + sys CPU s of the process and its children, wall s)."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    output = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"{shlex.join(cmd)} failed ({proc.returncode}):\n{output[-3000:]}")
    return output, usage.ru_utime + usage.ru_stime, wall


class Cycles:
    name = "cycles"

    def __init__(self, blender, scene, threads):
        self.blender, self.scene, self.threads = blender, scene, threads
        self.label = "Cycles"
        self.key = "cycles"

    def render(self, w, h, spp, seed, out, reference=False):
        cmd = [self.blender, "--factory-startup", "-b", "--python", RENDER_CYCLES, "--",
               "--scene", self.scene, "--width", str(w), "--height", str(h), "--spp", str(spp),
               "--seed", str(seed), "--threads", str(self.threads), "--out", out]
        output, process_cpu, wall = run_timed(cmd)
        m = re.search(r"CYCLES_RENDER cpu_s=(\S+) wall_s=(\S+)", output)
        if not m:
            raise RuntimeError(f"no CYCLES_RENDER line from blender:\n{output[-3000:]}")
        return {"cpu_s": float(m.group(1)), "wall_s": float(m.group(2)),
                "process_cpu_s": process_cpu, "process_wall_s": wall}


class Stage:
    def __init__(self, binary, scene, threads, args, ref_args):
        self.binary, self.scene, self.threads = binary, scene, threads
        self.args, self.ref_args = args, ref_args
        self.name = os.path.basename(binary)
        self.label = self.name + (" " + shlex.join(args) if args else "")
        self.key = self.name + ("_" + slug(" ".join(ref_args)) if ref_args else "")

    def render(self, w, h, spp, seed, out, reference=False):
        cmd = [self.binary, "--scene", self.scene, "--width", str(w), "--height", str(h),
               "--spp", str(spp), "--seed", str(seed), "--backend", "cpu", "--threads", str(self.threads),
               "--out", out] + (self.ref_args if reference else self.args)
        output, cpu, wall = run_timed(cmd)
        return {"cpu_s": cpu, "wall_s": wall, "process_cpu_s": cpu, "process_wall_s": wall,
                "summary": output.strip().splitlines()[-1] if output.strip() else ""}


def reference(renderer, w, h, spp, seed, ref_dir, fresh):
    path = os.path.join(ref_dir, f"{renderer.key}_{w}x{h}_{spp}spp.exr")
    meta = path[:-4] + ".json"
    if fresh or not (os.path.exists(path) and os.path.exists(meta)):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        log(f"reference {renderer.label} {w}x{h} {spp} spp ...")
        t = renderer.render(w, h, spp, seed, path, reference=True)
        with open(meta, "w") as f:
            json.dump(dict(t, spp=spp, seed=seed, width=w, height=h, label=renderer.label,
                           date=datetime.datetime.now(datetime.timezone.utc).isoformat()), f, indent=1)
        log(f"  {t['cpu_s']:.1f} CPU s, {t['process_wall_s']:.1f} s wall")
    else:
        log(f"reference {renderer.label} {w}x{h} {spp} spp: cached {os.path.relpath(path, REPO)}")
    return path


# --- main ---------------------------------------------------------------------------------------

def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def git_commit():
    try:
        return subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], check=True,
                              capture_output=True, text=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def reference_agreement(refs, mask):
    """Lines comparing every reference with the first (image means, row means, flipped rows)."""
    lines = []
    (base_label, base), others = refs[0], refs[1:]
    base_rows = base.mean(axis=(1, 2))
    scale = base.mean()
    for label, ref in others:
        channel = (ref.mean(axis=(0, 1)) / base.mean(axis=(0, 1)) - 1.0) * 100.0
        whole = (ref.mean() / scale - 1.0) * 100.0
        away = (ref[mask].mean() / base[mask].mean() - 1.0) * 100.0
        rows = ref.mean(axis=(1, 2))
        row_dev = np.max(np.abs(rows - base_rows)) / scale * 100.0
        flip_dev = np.max(np.abs(rows[::-1] - base_rows)) / scale * 100.0
        verdict = "upright" if row_dev < flip_dev else "FLIPPED?"
        lines.append(f"| {label} vs {base_label} | {whole:+.3f}% | {away:+.3f}% | "
                     f"{channel[0]:+.3f}% / {channel[1]:+.3f}% / {channel[2]:+.3f}% | "
                     f"{row_dev:.3f}% | {flip_dev:.1f}% ({verdict}) |")
    return lines


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

    with open(os.path.join(out_dir, "runs.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(runs[0].keys()))
        writer.writeheader()
        writer.writerows(runs)
    with open(os.path.join(out_dir, "summary.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(summary[0].keys()))
        writer.writeheader()
        writer.writerows(summary)

    md = [f"Scene `{args.scene}`, {args.spp} spp, {args.seeds} seeds (1..{args.seeds}) interleaved, "
          f"{args.threads} threads, each renderer against its own reference (seed {args.ref_seed}); "
          f"commit {git_commit()}; {datetime.date.today().isoformat()}; load average "
          f"{load_before} before, {load_after} after; {minutes:.1f} min.",
          f"Stage arguments: `{shlex.join(stage_args) or '(none)'}`"
          f"{'' if ref_stage_args == stage_args else f', references `{shlex.join(ref_stage_args)}`'}.",
          "",
          "| size | renderer | relRMSE | CPU s (min-max) | efficiency (per-seed range) | vs Cycles "
          "| relRMSE away | efficiency away | vs Cycles away | CPU us/sample | rel. var/sample (away) |",
          "|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in summary:
        md.append(f"| {s['size']} | {s['renderer']} | {s['rel_rmse']:.4f} | {s['cpu_s']:.2f} "
                  f"({s['cpu_s_min']:.2f}-{s['cpu_s_max']:.2f}) | {s['efficiency']:.3g} "
                  f"({s['efficiency_seed_min']:.3g}-{s['efficiency_seed_max']:.3g}) | {s['vs_cycles']:.3f} "
                  f"| {s['rel_rmse_away']:.4f} | {s['efficiency_away']:.3g} | {s['vs_cycles_away']:.3f} "
                  f"| {s['cpu_per_sample_us']:.3f} | {s['rel_var_per_sample']:.3g} "
                  f"({s['rel_var_per_sample_away']:.3g}) |")
    md += ["", "References against the first one (image mean over all pixels; over the pixels away from "
           "the light; per channel; the largest per-row mean difference, upright and upside down, "
           "relative to the image mean):", ""]
    for (w, h), (n_ref, n_away, n_bright, lines) in agreement.items():
        md += [f"{w}x{h}, {n_ref} spp: {n_bright} pixels at or above luminance {threshold:.3g} "
               f"(the light), {n_away} of {w * h} pixels away from the light.", "",
               "| references | mean | mean away | R / G / B | max row diff | upside down |",
               "|---|---|---|---|---|---|"] + lines + [""]
    with open(os.path.join(out_dir, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))
    log(f"wrote {os.path.relpath(out_dir, REPO)}/runs.csv, summary.csv, summary.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
