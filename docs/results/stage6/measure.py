#!/usr/bin/env python3
"""Measures stage5_mis against stage6_variance_aware (and hand-made variants of stage6) for
docs/reference/stage6.md: not part of the article, machinery of the stage6 chapter's numbers.
Relative RMSE against a long reference render, CPU seconds, efficiency 1 / (relMSE x CPU s).

  docs/results/stage6/measure.py --bin build/bin --work out/s6m --csv docs/results/stage6/efficiency.csv \
      --scene cornell:256:4 --program stage5=stage5_mis --program stage6=stage6_variance_aware \
      [--reference stage5_mis:16384] [--rr throughput] [--seeds 4] [--mode spp|time]

--scene NAME:SPP:SECONDS renders builtin:NAME at 64 x 64, SPP samples per pixel (--mode spp)
or for SECONDS (--mode time, --time-budget); --program LABEL=PATH (relative to --bin, or a path)
is one row per scene; builtin:furnace is compared with its closed form, 2 in every pixel.
Every run has one thread (--threads 1) and the default sampler; seeds 1 ... --seeds; the
reference seed 1000 (another seed: independent of every run), rendered once into --work as
ref_NAME.exr (with its summary line in ref_NAME.exr.txt): put another render there to use it
instead. Needs oiiotool.
"""
import argparse
import csv
import os
import re
import resource
import subprocess
import sys

SIZE = 64
CLOSED_FORM = {"furnace": 2.0, "furnace_sphere": 2.0}


def run(exe, args):
    """Runs one render; returns (CPU seconds of the child: user + system, its stdout+stderr)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(["nice", "-n", "10", exe] + args, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"measure: {exe} {' '.join(args)} failed ({p.returncode}): {p.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, p.stdout + p.stderr


def stats_avg(path, channels):
    out = subprocess.run(["oiiotool", path, "--ch", channels, "--printstats"], capture_output=True,
                         text=True, check=True).stdout
    return [float(x) for x in re.search(r"Stats Avg:\s*([^\(]*)\(", out).group(1).split()]


def rms_error(test, ref):
    out = subprocess.run(["oiiotool", test, "--ch", "R,G,B", ref, "--ch", "R,G,B", "--diff"],
                         capture_output=True, text=True).stdout
    return float(re.search(r"RMS error = ([0-9.eE+-]+)", out).group(1))


def reference(args, scene):
    """The reference image of a scene and its own estimated per-pixel relative error."""
    path = os.path.join(args.work, f"ref_{scene}.exr")
    if scene in CLOSED_FORM:
        v = CLOSED_FORM[scene]
        if not os.path.isfile(path):
            subprocess.run(["oiiotool", "--pattern", f"constant:color={v},{v},{v}", f"{SIZE}x{SIZE}", "3",
                            "-d", "float", "-o", path], check=True)
        return path, "closed form", 0.0
    exe, spp = args.reference.split(":")
    if not os.path.isfile(path):
        _, log = run(exe_path(args, exe), ["--backend", "cpu", "--scene", f"builtin:{scene}", "--width", str(SIZE),
                                            "--height", str(SIZE), "--spp", spp, "--seed", "1000",
                                            "--out", path])
        with open(path + ".txt", "w") as f:
            f.write(log)
    with open(path + ".txt") as f:
        log = f.read()
    err = float(re.search(r"per-pixel relative error ([0-9.eE+-]+)", log).group(1))
    made = re.match(r"(\S+): .*?, (\d+) spp", log)  # the program and spp that made it
    return path, f"{made.group(1)} {made.group(2)} spp", err


def exe_path(args, name):
    return name if os.sep in name else os.path.join(args.bin, name)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("--bin", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--csv", required=True)
    p.add_argument("--scene", action="append", required=True)
    p.add_argument("--program", action="append", required=True)
    p.add_argument("--reference", default="stage5_mis:16384")
    p.add_argument("--rr", default="throughput")
    p.add_argument("--seeds", type=int, default=4)
    p.add_argument("--mode", choices=("spp", "time"), default="spp")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    programs = [tuple(x.split("=", 1)) for x in args.program]
    fields = ["scene", "program", "rr", "mode", "seeds", "spp", "cpu_s", "rel_rmse", "efficiency",
              "reference", "reference_rel_error"]
    new = not os.path.isfile(args.csv)
    with open(args.csv, "a", newline="") as f:
        w = csv.writer(f)
        if new:
            w.writerow(fields)
        for item in args.scene:
            scene, spp, seconds = item.split(":")
            ref, ref_name, ref_err = reference(args, scene)
            mean = sum(stats_avg(ref, "R,G,B")) / 3.0
            # Interleaved: seed by seed, every program, so that the load moves all alike.
            acc = {label: [0.0, 0.0, 0.0] for label, _ in programs}  # cpu, squared rel error, spp
            for seed in range(1, args.seeds + 1):
                for label, exe in programs:
                    out = os.path.join(args.work, f"{scene}_{label}_{args.rr}_{args.mode}_{seed}.exr")
                    budget = ["--spp", spp] if args.mode == "spp" else ["--time-budget", seconds]
                    cpu, log = run(exe_path(args, exe), ["--backend", "cpu", "--threads", "1", "--scene",
                                                         f"builtin:{scene}", "--width", str(SIZE), "--height",
                                                         str(SIZE), "--seed", str(seed), "--rr", args.rr,
                                                         "--out", out] + budget)
                    reached = int(re.search(r"(\d+) spp", log).group(1))
                    rel = rms_error(out, ref) / mean
                    a = acc[label]
                    a[0] += cpu
                    a[1] += rel * rel
                    a[2] += reached
            for label, _ in programs:
                cpu, mse, n = (x / args.seeds for x in acc[label])
                row = [scene, label, args.rr, args.mode, args.seeds, f"{n:.0f}", f"{cpu:.3f}", f"{mse ** 0.5:.4g}",
                       f"{1.0 / (mse * cpu):.4g}", ref_name, f"{ref_err:.3g}"]
                w.writerow(row)
                f.flush()
                print(",".join(str(x) for x in row), flush=True)


if __name__ == "__main__":
    main()
