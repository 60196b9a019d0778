"""The report of bench/smallpt_compare.py (issue #18, the stages against smallpt's algorithm):
docs/results/smallpt_compare.csv (one row per renderer) and docs/results/smallpt_notes.md (the
section bench/report.py puts into docs/results.md, its FINDINGS block kept across runs): the
efficiency table, the target's verdict, the errors by region, the references' agreement, and
the machine and its load."""
import csv
import os
import platform
import re
import shlex
import sys

from smallpt_cache import repo_path
from smallpt_images import GRID, agreement

FINDINGS_BEGIN = "<!-- FINDINGS: hand-written, kept by bench/smallpt_compare.py -->"
FINDINGS_END = "<!-- /FINDINGS -->"


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


def kept_findings(path):
    if not os.path.exists(path):
        return None
    text = open(path).read()
    i, j = text.find(FINDINGS_BEGIN), text.find(FINDINGS_END)
    if i < 0 or j < i:
        return None
    return text[i:j + len(FINDINGS_END)]


def write_csv(a, renderers, summary, refs):
    """Writes --csv, one row per renderer; returns its path."""
    base = summary["smallpt"]
    rows_csv = []
    for r in renderers:
        s = summary[r.key]
        rows_csv.append(dict(renderer=r.key, label=r.label, sampler=r.sampler or "-", width=a.width, height=a.height,
                             spp=a.spp, seeds=a.seeds, rel_rmse=round(s["rmse"], 5), cpu_s=round(s["cpu"], 4),
                             efficiency=round(s["eff"], 3), vs_reference=round(s["eff"] / base["eff"], 4),
                             cpu_s_at_1spp=round(s["cpu1"], 4),
                             vs_reference_without_startup=round(s["eff_render"] / base["eff_render"], 4),
                             rel_var_per_sample=round(s["var_per_sample"], 4),
                             cpu_us_per_sample=round(s["us_per_sample"], 4), ref_spp=a.ref_spp,
                             ref_cpu_s=round(refs[r.key][1], 2), binary_sha256_12=r.digest))
    csv_path = repo_path(a.csv)
    os.makedirs(os.path.dirname(csv_path), exist_ok=True)
    with open(csv_path, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows_csv[0].keys()))
        wr.writeheader()
        wr.writerows(rows_csv)
    return csv_path


def write_notes(a, renderers, summary, refs, ref_imgs, sd, started, elapsed, load_before, load_after):
    """Writes --notes (its FINDINGS block kept) and prints it; returns its path."""
    base = summary["smallpt"]
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
          "camera rays starting 140 units ahead), as builtin:smallpt does (the camera's clip start).", "",
          "| renderer | relRMSE | CPU s | efficiency | vs reference | "
          "rel. variance per sample | CPU µs per sample | CPU s at 1 spp | without it: vs reference |",
          "|---|---|---|---|---|---|---|---|---|"]
    for r in renderers:
        s = summary[r.key]
        v1 = s["eff"] / base["eff"]
        bold = r.key.startswith("stage5") and r.sampler == "sobol"
        md.append(f"| {r.short} | {s['rmse']:.3f} | {s['cpu']:.2f} | {fmt(s['eff'])} | "
                  + (f"**{v1:.2f}**" if bold else f"{v1:.2f}") + f" | {s['var_per_sample']:.2f} | "
                  f"{s['us_per_sample']:.2f} | {s['cpu1']:.2f} | {s['eff_render'] / base['eff_render']:.2f} |")
    md += ["", "Relative variance per sample: relative MSE x spp. CPU s at 1 spp: the same process rendering 1 "
           "sample per pixel (start-up, the dynamic linking of OpenImageIO's libraries above all, scene, EXR "
           "write), measured interleaved with the others; the last column's ratios use CPU s minus it."]
    md.append("")
    s5 = summary.get("stage5_mis_sobol")
    if s5:
        v1 = s5["eff"] / base["eff"]
        verdict = "met" if v1 >= 1.5 else "missed"
        md += [f"- **Target \"stage5_mis at least 1.5x the reference's efficiency by CPU time\": {verdict}** "
               f"({v1:.2f}x the reference on the same scene; default sampler).",
               ""]
    # Where stage5's error is, region by region, against stage4 and the reference.
    if s5 and "stage4_direct_indirect_sobol" in summary:
        s4 = summary["stage4_direct_indirect_sobol"]
        md += ["Relative MSE by region (image split into 3 rows x 4 columns; each region's squared error over the "
               "whole reference's squared mean), default sampler, and stage5's efficiency ratio there "
               "(the same CPU s for every region):", "",
               "| region (row, col) | reference | stage4 | stage5 | stage5 / stage4 efficiency | "
               "stage5 / reference efficiency |", "|---|---|---|---|---|---|"]
        for j in range(GRID[0]):
            for i in range(GRID[1]):
                m_r, m4, m5 = base["region_mse"][j, i], s4["region_mse"][j, i], s5["region_mse"][j, i]
                md.append(f"| {j}, {i} | {m_r:.3g} | {m4:.3g} | {m5:.3g} | "
                          f"{(m4 * s4['cpu']) / (m5 * s5['cpu']):.2f} | {(m_r * base['cpu']) / (m5 * s5['cpu']):.2f} |")
        md.append("")

    md += ["Do the converged images agree? Each renderer's reference against another's: the image mean, the "
           "mean without the image's top row of pixels, per channel, the median and the largest difference of "
           "the 12 region means (z: that difference over a rough noise scale, from the seeds' spread scaled to "
           "the references' samples) and the largest |z|, and the RMS difference of the row means (over the "
           "image mean), upright and against the other image upside down:", "",
           "| references | mean | mean, rows 1+ | R / G / B | regions: median | regions: largest | max abs z | "
           "rows / flipped |",
           "|---|---|---|---|---|---|---|---|"]
    pairs = [("smallpt", "stage4_direct_indirect_sobol"), ("smallpt", "stage5_mis_sobol"),
             ("stage3_importance_sobol", "stage4_direct_indirect_sobol"),
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
    return notes_path
