"""pt_bench's report, issue 22's sections, for bench/report.py: the time each stage and
backend needs to reach a per-pixel relative RMSE of 10%, 3% and 1%, read off the measured
curve of convergence.csv by log-log interpolation between the two checkpoints around each
level; and the split's cost (4 parts plus pt_merge against one run), whose numbers are
hand-written in split_notes.md (bench/split_cost.sh measures them) in the same folder."""
import math
import os

LEVELS = (0.10, 0.03, 0.01)
REFERENCE_MARGIN = 2.0   # a level below 2x the reference's own error is flagged


def time_to_level(points, level):
    """points: (wall_s, rel_rmse) in the order measured. The first checkpoint at or below
    `level`, and the one before it, give the line log(error) = a + b log(time); its time at
    `level` is returned as (seconds, None). Never reached: (None, (last time, last error)).
    Reached at the first checkpoint already: (-seconds, None), an upper bound."""
    for i, (t, e) in enumerate(points):
        if e <= level:
            if i == 0:
                return -t, None
            t0, e0 = points[i - 1]
            if e0 <= 0 or e <= 0 or e0 == e or t0 <= 0:
                return t, None
            slope = (math.log(t) - math.log(t0)) / (math.log(e) - math.log(e0))
            return math.exp(math.log(t0) + slope * (math.log(level) - math.log(e0))), None
    t, e = points[-1]
    return None, (t, e)


def cell(points, level, ref_err):
    t, last = time_to_level(points, level)
    flag = " \u2021" if level < REFERENCE_MARGIN * ref_err else ""
    if last:
        return "> %.3g s (at %.3g%%)%s" % (last[0], 100 * last[1], flag)
    if t < 0:
        return "\u2264 %.3g s%s" % (-t, flag)
    return "%.3g s%s" % (t, flag)


def error_targets_section(runs, date):
    """runs: {(scene, stage, backend): [convergence.csv rows in spp order]}."""
    md = ["## Time to reach 10%, 3% and 1% per-pixel error (issue 22)", "",
          "The trade as a user asks it: how long each stage needs, on each bench scene and backend, until "
          "its image is within 10%%, 3%% or 1%% of the reference per pixel (relative RMSE: the RMSE over pixels "
          "and channels divided by the reference's mean, as above). Read off the curve of the error study of "
          "%s (docs/results/convergence.csv: each checkpoint a fresh render of 1, 2, 4, ... spp, its wall "
          "time including the per-render fixed costs): the first checkpoint at or below the level and the one "
          "before it are joined by a straight line in log(error) against log(time), as error ~ C t^-1/2 is "
          "between any two checkpoints, and the table gives that line's time at the level. \"> T s (at E)\": "
          "the run stopped at T seconds with the error E, short of the level; at -1/2 reaching it would take "
          "T (E / level)^2. \u2021: the level is below twice the reference's own per-pixel error (given per "
          "scene above), so the measured error is dominated by the reference's and the time overstates the "
          "true one, or the level cannot be measured at all." % date, "",
          "| scene | stage | backend | 10% | 3% | 1% |", "|---|---|---|---|---|---|"]
    for (scene, stage, backend), rows in runs.items():
        points = [(float(r["wall_s"]), float(r["rel_rmse"])) for r in rows]
        ref_err = float(rows[0]["reference_rel_error"] or 0.0)
        md.append("| %s | %s | %s | %s |" % (scene, stage, backend,
                                            " | ".join(cell(points, lv, ref_err) for lv in LEVELS)))
    md.append("")
    return md


def split_section(results_dir):
    """The hand-written split-cost notes, if any (split_notes.md)."""
    notes = os.path.join(results_dir, "split_notes.md")
    if not os.path.exists(notes):
        return []
    return [open(notes).read().rstrip(), ""]
