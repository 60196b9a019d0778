"""The report of bench/cycles/compare.py (issue 23, the Cycles comparison): the references
compared with each other (image means, row means, an upside-down image), and the tables it
writes, OUT/runs.csv (every render), OUT/summary.csv and OUT/summary.md."""
import csv
import datetime
import os
import shlex
import subprocess

import numpy as np

from compare_renderers import REPO, log


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


def write_report(args, out_dir, runs, summary, agreement, threshold, stage_args, ref_stage_args,
                 load_before, load_after, minutes):
    """Writes OUT/runs.csv, OUT/summary.csv and OUT/summary.md, and prints the table."""
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
