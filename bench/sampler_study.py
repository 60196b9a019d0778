#!/usr/bin/python3
"""What the sampler buys (issue 23, "Samples that cover the domain"; docs/sampling.md): the
error and the cost of Owen-scrambled Sobol samples (--sampler sobol, the default) against
independent ones (--sampler independent), on the stages' own CPU backend, in one run.

For each scene and stage: a reference of --ref-spp samples (sobol, seed 999), then for each
sample count, sampler and seed a render against it, interleaved (sobol, independent, sobol,
... so that a change in the machine's load falls on both):

  relative RMSE   sqrt(mean over pixels and R,G,B of (x - ref)^2) / mean of ref; squared and
                  averaged over the seeds, then the root
  CPU s / Msample user + sys of the whole process per million samples, at the largest count
                  (start-up and the EXR write included, so small images overstate it alike)

Sample counts that are not powers of two show what they cost: the counts' RMSE against the
line through the powers of two around them. The reference's own noise is not subtracted.

Needs Debian 12's python3 with python3-numpy and openimageio-tools (oiiotool reads the EXRs).
Writes OUT/sampler_runs.csv and OUT/sampler_study.md (the tables docs/results.md quotes).

  /usr/bin/python3 bench/sampler_study.py                 # about 3 minutes on 2 cores
  /usr/bin/python3 bench/sampler_study.py --seeds 2 --ref-spp 4096   # quick
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "cycles"))
from compare import read_rgb, run_timed  # noqa: E402  (oiiotool reader, timed subprocess)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CASES = [  # (scene, size, stage): a smooth integrand with a closed form, and the Cornell box
    ("builtin:floor_light", 32, "stage4_direct_indirect"),
    ("builtin:floor_light", 32, "stage2_montecarlo"),
    ("builtin:cornell", 64, "stage4_direct_indirect"),
    ("builtin:cornell", 64, "stage3_importance"),
]
COUNTS = [16, 24, 32, 48, 64, 96, 100, 128, 256]


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bin-dir", default=os.path.join(ROOT, "build", "bin"))
    p.add_argument("--out", default=os.path.join(ROOT, "build", "sampler_study"))
    p.add_argument("--seeds", type=int, default=4)
    p.add_argument("--ref-spp", type=int, default=32768)
    p.add_argument("--threads", type=int, default=2)
    return p.parse_args()


def render(args, stage, scene, size, spp, seed, sampler, out):
    cmd = [os.path.join(args.bin_dir, stage), "--scene", scene, "--width", str(size), "--height", str(size),
           "--spp", str(spp), "--seed", str(seed), "--sampler", sampler, "--backend", "cpu",
           "--threads", str(args.threads), "--out", out]
    _, cpu, _ = run_timed(cmd)
    return read_rgb(out), cpu


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows, table = [], []
    for scene, size, stage in CASES:
        name = f"{stage} {scene} {size}x{size}"
        print(f"sampler_study: {name}: reference {args.ref_spp} spp", file=sys.stderr, flush=True)
        ref, _ = render(args, stage, scene, size, args.ref_spp, 999, "sobol", os.path.join(args.out, "ref.exr"))
        mean = ref.mean()
        err = {}
        cost = {}
        for spp in COUNTS:
            for seed in range(args.seeds):
                for sampler in ("sobol", "independent"):
                    img, cpu = render(args, stage, scene, size, spp, seed, sampler, os.path.join(args.out, "x.exr"))
                    rel_mse = float(((img - ref) ** 2).mean()) / mean ** 2
                    err.setdefault((sampler, spp), []).append(rel_mse)
                    if spp == COUNTS[-1]:
                        cost.setdefault(sampler, []).append(cpu / (size * size * spp) * 1e6)
                    rows.append({"case": name, "sampler": sampler, "spp": spp, "seed": seed,
                                 "rel_mse": rel_mse, "cpu_s": cpu})
        rmse = {k: (sum(v) / len(v)) ** 0.5 for k, v in err.items()}
        table.append((name, rmse, {k: sum(v) / len(v) for k, v in cost.items()}))
    with open(os.path.join(args.out, "sampler_runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    lines = [f"Relative RMSE against a {args.ref_spp}-spp reference, RMS over {args.seeds} seeds; "
             f"CPU s per million samples at {COUNTS[-1]} spp ({args.threads} threads).", ""]
    lines.append("| case | sampler | " + " | ".join(f"{n} spp" for n in COUNTS) + " | CPU s / Msample |")
    lines.append("|---|---|" + "---|" * (len(COUNTS) + 1))
    for name, rmse, cost in table:
        for sampler in ("sobol", "independent"):
            cells = " | ".join(f"{rmse[(sampler, n)]:.4f}" for n in COUNTS)
            lines.append(f"| {name} | {sampler} | {cells} | {cost[sampler]:.3f} |")
        ratio = " | ".join(f"{rmse[('independent', n)] / rmse[('sobol', n)]:.1f}x" for n in COUNTS)
        lines.append(f"| {name} | independent / sobol | {ratio} | "
                     f"{cost['sobol'] / cost['independent']:.2f} (sobol / independent) |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.out, "sampler_study.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
