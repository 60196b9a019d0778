#!/usr/bin/python3
"""pt_bench's report (issue 6): from the CSV files of pt_bench (docs/results/*.csv), the
log-log plots of relative RMSE against time (one line per stage and backend, a PNG per
scene) and docs/results.md: the machine, the command, the time each stage and backend
needs to reach 10%, 3% and 1% relative RMSE, the efficiency ratios stage3/stage2 and
stage4/stage3, CPU against GPU samples per second, the fitted slope of log error against
log time (-1/2 for an unbiased estimator), rays per second, specialised kernels, and
rays per second against the triangle count with the BVH and Embree (issue 17), and
issue 22's times to 10%, 3% and 1% read off the curves and the split's cost (report_error_targets.py).
Hand-written findings come from docs/results/notes.md, accel_notes.md, split_notes.md,
sampler_notes.md (bench/sampler_study.py), cycles_notes.md (bench/cycles/compare.py),
smallpt_notes.md (bench/smallpt_compare.py) and stage_chapters_notes.md (the index of the
stage chapters' measurements, docs/results/stageN_notes.md), kept
between runs. Every table comes from the CSV files in the folder, so a run of one section
(pt_bench --section accel) keeps the others' tables as their last full run left them. When
the error section was re-run alone, docs/results/error_run.txt says so in one line that starts
with its date (the command, its load and time after it): the header quotes it and the error
tables carry that date. The machine is the run's (docs/results/machine.txt from bench/run.sh,
the accel section's own in accel_run.txt), not the one the report is made on."""
import argparse
import csv
import datetime
import math
import os
import subprocess
import sys
from collections import OrderedDict

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_accel import accel_section, read_keys  # noqa: E402  (bench/, beside this script)
from report_error_targets import error_targets_section, split_section  # noqa: E402

LEVELS = (0.10, 0.03, 0.01)
MIN_FIT_SPP = 16        # below this, fixed costs per render bend the curve
SLOPE_TOLERANCE = 0.1   # a fitted slope further than this from -1/2 is flagged


def read(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def machine():
    model, cores = "unknown", os.cpu_count()
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        for line in out.splitlines():
            if line.startswith("Model name:"):
                model = line.split(":", 1)[1].strip()
    except OSError:
        pass
    return model, cores


def small_file(folder, name):
    path = os.path.join(folder, name)
    return open(path).read().strip() if os.path.exists(path) else "unknown"


def fit_slope(points):
    """Least-squares slope of log(error) against log(time)."""
    if len(points) < 3:
        return None
    xs = [math.log(t) for t, _ in points]
    ys = [math.log(e) for _, e in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else None


def group_runs(rows):
    runs = OrderedDict()
    for r in rows:
        key = (r["scene"], r["stage"], r["backend"])
        runs.setdefault(key, []).append(r)
    return runs


def time_to(rows, level):
    for r in rows:
        if float(r["rel_rmse"]) <= level:
            return "%.3g s" % float(r["wall_s"])
    return "not reached in %.3g s" % float(rows[-1]["wall_s"])


def fit_points(rows, x="wall_s"):
    """Checkpoints for the slope: enough samples, and error well above the reference's own."""
    ref_err = float(rows[0]["reference_rel_error"] or 0.0)
    return [(float(r[x]), float(r["rel_rmse"])) for r in rows
            if int(r["spp"]) >= MIN_FIT_SPP and float(r["rel_rmse"]) > 3.0 * ref_err and float(r["rel_rmse"]) > 0]


def plot_scene(scene, runs, out_dir):
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for (sc, stage, backend), rows in runs.items():
        if sc != scene:
            continue
        ax.loglog([float(r["wall_s"]) for r in rows], [float(r["rel_rmse"]) for r in rows],
                  marker="o", markersize=3, linestyle="-" if backend == "cpu" else "--",
                  label="%s %s" % (stage.split("_")[0], backend))
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("relative RMSE")
    ax.set_title(scene)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    name = "error_%s.png" % os.path.basename(scene).replace(".", "_")
    fig.savefig(os.path.join(out_dir, name), dpi=90)
    plt.close(fig)
    return name


def samples_per_s(rows):
    return float(rows[-1]["samples_per_s"])  # the longest render: fixed costs matter least


def efficiency(rows):
    return float(rows[-1]["efficiency"])



def roulette_sentence(conv):
    """How the error study's renders end their paths (convergence.csv's roulette column,
    absent before 2026-12-04, when every run used the article's p = 1/2)."""
    kinds = sorted({r.get("roulette") or "fixed" for r in conv})
    if kinds == ["throughput"]:
        return ("Every stage runs with the throughput Russian roulette (`--rr throughput`: p = the path "
                "weight's largest component; stage5 its square root, glass's 1 / eta^2 taken out), the default "
                "of stages 3 to 5 (stage2's is the article's p = 1/2), so stages 2 to 4 differ only in how they "
                "sample and stage5 has its own; before 2026-12-04 the study gave every stage the article's "
                "p = 1/2 (`pt_bench --rr fixed`)")
    if kinds == ["fixed"]:
        return ("Every stage runs with the article's Russian roulette (p = 1/2, `--rr fixed`), so the stages "
                "differ only in how they sample")
    return "The runs mix Russian roulettes (%s: convergence.csv's roulette column)" % ", ".join(kinds)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--results", default="docs/results")
    ap.add_argument("--command", default="./tutorial bench")
    ap.add_argument("--markdown", default="docs/results.md")
    a = ap.parse_args()

    conv = read(os.path.join(a.results, "convergence.csv"))
    speed = read(os.path.join(a.results, "speed.csv"))
    special = read(os.path.join(a.results, "specialisation.csv"))
    accel = read(os.path.join(a.results, "accel.csv"))
    accel_builds = read(os.path.join(a.results, "accel_build.csv"))
    if not (conv or speed or special or accel):
        sys.exit("report.py: no CSV files in %s; run build/bin/pt_bench first (bench/run.sh)" % a.results)
    runs = group_runs(conv)
    scenes = list(OrderedDict.fromkeys(k[0] for k in runs))
    # The machine of the run (machine.txt, written by bench/run.sh), not the one making this
    # report: a report made again elsewhere must not move the numbers to another machine.
    if os.path.exists(os.path.join(a.results, "machine.txt")):
        run_machine = small_file(a.results, "machine.txt")
    else:
        run_machine = "not recorded with the run (this report was made on %s, %s cores)" % machine()
    gpu_devices = sorted({r["device"] for r in conv + speed if r.get("backend") == "gpu"})

    error_run = small_file(a.results, "error_run.txt") if os.path.exists(os.path.join(a.results, "error_run.txt")) else ""
    bench_date = small_file(a.results, "bench_date.txt") if os.path.exists(
        os.path.join(a.results, "bench_date.txt")) else datetime.date.today().isoformat()
    md = ["# Results: speed against accuracy", "",
          "Made by `%s` (bench/run.sh: `build/bin/pt_bench`, then `bench/report.py`) on %s." %
          (a.command, bench_date), "",
          "- Machine: %s; GPU backend: %s." % (run_machine, ", ".join(gpu_devices) or "none"),
          "- Load average (1, 5, 15 min) before the run: %s, after: %s; the run took %s s. A load above "
          "the core count means other jobs shared the cores: wall times are then longer than the "
          "machine's own (the speed section also gives rates by CPU time)." %
          (small_file(a.results, "load_before.txt"), small_file(a.results, "load_after.txt"),
           small_file(a.results, "bench_seconds.txt")),
          "- Relative RMSE: OpenImageIO's `ImageBufAlgo::compare` RMSE over pixels and RGB channels, "
          "divided by the reference image's mean. Each checkpoint is a fresh render of 1, 2, 4, ... "
          "samples per pixel (the time a user waits for that image); efficiency is 1 / (MSE x time). "
          "%s; images are %s pixels." %
          (roulette_sentence(conv), ", ".join(sorted({"%sx%s" % (r["width"], r["height"]) for r in conv})) or "-"),
          "- References: the closed form for the analytic scenes (furnace, floors under square lights: "
          "Lambert's polygon formula), else a stage4 CPU render cached under a key of scene, size and "
          "kernel; its own estimated relative error is listed and bounds what can be measured.", ""]
    if error_run:
        md[-1:-1] = ["- The error study (convergence.csv, and every table and plot made from it) is of a later "
                     "run than the rest: %s." % error_run]

    notes = os.path.join(a.results, "notes.md")
    if os.path.exists(notes):
        md += [open(notes).read().rstrip(), ""]

    if runs:
        md += ["## Time to reach a relative RMSE", ""]
        for scene in scenes:
            png = plot_scene(scene, runs, a.results)
            keyed = [(k, v) for k, v in runs.items() if k[0] == scene]
            ref = keyed[0][1][0]
            md += ["### %s" % scene, "",
                   "Reference: %s (its relative error %.2g). ![error against time](results/%s)" %
                   (ref["reference"], float(ref["reference_rel_error"] or 0), png), "",
                   "| stage | backend | 10% | 3% | 1% | last: spp, rel. RMSE | samples/s | slope (time) | slope (spp) |",
                   "|---|---|---|---|---|---|---|---|---|"]
            for (sc, stage, backend), rows in keyed:
                slopes = [fit_slope(fit_points(rows, x)) for x in ("wall_s", "spp")]
                s = ["n/a" if v is None else "%.2f%s" % (v, "" if abs(v + 0.5) <= SLOPE_TOLERANCE else " **(!)**")
                     for v in slopes]
                md.append("| %s | %s | %s | %s | %s | %s, %.3g | %.3g | %s | %s |" % (
                    stage, backend, time_to(rows, 0.10), time_to(rows, 0.03), time_to(rows, 0.01),
                    rows[-1]["spp"], float(rows[-1]["rel_rmse"]), samples_per_s(rows), s[0], s[1]))
            md.append("")

        md += error_targets_section(runs, error_run.split()[0].rstrip(":,") if error_run else bench_date)

        md += ["## Efficiency ratios and CPU against GPU", "",
               "Efficiency 1/(MSE x time) at each run's last checkpoint; a ratio above 1 means the later "
               "stage reaches the same error sooner. GPU/CPU is the ratio of samples per second.", "",
               "stage5 (beyond the article, issue #18) is set against the better of stage3 and stage4 "
               "(target: at least 1 on every scene) and against stage3 (target: at least 20 under the small "
               "light); **bold** marks a target met.", "",
               "| scene | backend | stage3/stage2 | stage4/stage3 | stage5/max(stage3, stage4) | stage5/stage3 |",
               "|---|---|---|---|---|---|"]
        for scene in scenes:
            for backend in ("cpu", "gpu"):
                eff = {k[1].split("_")[0]: efficiency(v) for k, v in runs.items() if k[0] == scene and k[2] == backend}
                if not eff:
                    continue
                r32 = "%.3g" % (eff["stage3"] / eff["stage2"]) if "stage3" in eff and eff.get("stage2") else "-"
                r43 = "%.3g" % (eff["stage4"] / eff["stage3"]) if "stage4" in eff and eff.get("stage3") else "-"
                r5b, r53 = "-", "-"
                if "stage5" in eff and eff.get("stage3") and eff.get("stage4"):
                    best = eff["stage5"] / max(eff["stage3"], eff["stage4"])
                    r5b = ("**%.3g**" if best >= 1.0 else "%.3g") % best
                if "stage5" in eff and eff.get("stage3"):
                    ratio = eff["stage5"] / eff["stage3"]
                    met = scene == "floor_small_light" and ratio >= 20.0
                    r53 = ("**%.3g**" if met else "%.3g") % ratio
                md.append("| %s | %s | %s | %s | %s | %s |" % (scene, backend, r32, r43, r5b, r53))
        md += ["", "| scene | stage | CPU samples/s | GPU samples/s | GPU/CPU |", "|---|---|---|---|---|"]
        for scene in scenes:
            for stage in OrderedDict.fromkeys(k[1] for k in runs if k[0] == scene):
                c, g = runs.get((scene, stage, "cpu")), runs.get((scene, stage, "gpu"))
                if c and g:
                    md.append("| %s | %s | %.3g | %.3g | %.2f |" % (scene, stage, samples_per_s(c), samples_per_s(g),
                                                                   samples_per_s(g) / samples_per_s(c)))
        md += ["", "Slopes are least-squares fits of log(relative RMSE) against log(time), and against "
               "log(spp) (free of timing noise), over the checkpoints "
               "with at least %d spp and an error above 3x the reference's own; **(!)** marks a slope further "
               "than %.1f from -1/2 (see the notes above for why)." % (MIN_FIT_SPP, SLOPE_TOLERANCE), ""]

    if speed:
        md += ["## Speed: brute-force closest hit on the Cornell box", "",
               "Million rays per second by the wall clock, and by the CPU time the work got times the "
               "core count (what the cores would do without other jobs).", "",
               "| method | backend | device | M rays/s (wall) | M rays/s (CPU time) | target |",
               "|---|---|---|---|---|---|"]
        for r in speed:
            t = float(r["target_mrays_per_s"])
            md.append("| %s | %s | %s | %.2f | %.2f | %s |" % (r["method"], r["backend"], r["device"],
                                                             float(r["mrays_per_s"]), float(r["mrays_per_cpu_s"]),
                                                             "%g" % t if t > 0 else "-"))
        md.append("")

    if accel:
        md += accel_section(accel, accel_builds, read_keys(os.path.join(a.results, "accel_run.txt")), a.results)

    if special:
        md += ["## Specialised against general kernels (issue 8)", "",
               "Samples per second with the kernel specialised to the scene's features (the default) and "
               "with `--all-features` (the general kernel), best of three alternating runs each, by the "
               "wall clock and by CPU time. On builtin:every_feature (under a sky) the scene has every "
               "feature, so both kernels are the same: its ratios show the measurement's own noise.", "",
               "| scene | stage | backend | specialised | general | ratio | ratio by CPU time |",
               "|---|---|---|---|---|---|---|"]
        for r in special:
            md.append("| %s | %s | %s | %.3g | %.3g | %.2f | %.2f |" % (
                r["scene"], r["stage"], r["backend"], float(r["specialised_samples_per_s"]),
                float(r["general_samples_per_s"]), float(r["ratio"]), float(r["cpu_ratio"])))
        md.append("")

    md += split_section(a.results)
    # Hand-written sections of later issues, each measured by its own script (named inside).
    for name in ("sampler_notes.md", "cycles_notes.md", "smallpt_notes.md", "stage_chapters_notes.md"):
        path = os.path.join(a.results, name)
        if os.path.exists(path):
            md += [open(path).read().rstrip(), ""]

    with open(a.markdown + ".tmp", "w") as f:
        f.write("\n".join(md) + "\n")
    os.replace(a.markdown + ".tmp", a.markdown)


if __name__ == "__main__":
    main()
