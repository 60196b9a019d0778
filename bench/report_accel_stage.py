"""pt_bench's report, the stage section (issue 50), for bench/report_accel.py: from accel_stage.csv,
accel_stage_run.txt and, when kept beside them, accel_stage_before.csv (and _round1, _before_round10), the tables of a stage's render
on the 1.3 M-triangle mesh against Embree on the same rays and of a sample's cost.
Not part of the article: machinery for measuring the step after it (the BVH)."""
import csv
import os

STAGE_TARGETS = {"stage1": 0.5, "stage4": 0.4}  # the render's rays against Embree's, by CPU time


def read_rows(path):
    if not os.path.exists(path):
        return {}
    return {(r["stage"], r["view"], r["quantity"]): r for r in csv.DictReader(open(path))}


def stage_section(out_dir, read_keys):
    rows = read_rows(os.path.join(out_dir, "accel_stage.csv"))
    if not rows:
        return []
    before = read_rows(os.path.join(out_dir, "accel_stage_before.csv"))
    round1 = read_rows(os.path.join(out_dir, "accel_stage_round1.csv"))
    before_r10 = read_rows(os.path.join(out_dir, "accel_stage_before_round10.csv"))
    run = read_keys(os.path.join(out_dir, "accel_stage_run.txt"))
    keys = sorted({(s, v) for (s, v, _) in rows}, key=lambda k: (k[0], ["inside", "outside", "grazing"].index(k[1])))

    def f(table, s, v, q, field, fmt="%.3g"):
        r = table.get((s, v, q))
        ok = r and r[field] not in ("", None) and not (q == "cost_camera" and float(r[field]) == 0.0)
        return fmt % float(r[field]) if ok else "-"  # stage4's camera rays are not timed alone

    md = ["## Stage programs on the 1.3 M-triangle mesh against Embree on their own rays (issue 50)", "",
          "Made by `%s` on %s; load average before: %s, after: %s; %s, %s CPU threads; %s; %s alternating rounds "
          "(medians). Every rate is by CPU time (getrusage: all threads, times the cores), the measure on a "
          "loaded machine. builtin:furnace_mesh (1,310,720 triangles) seen from inside (its own camera at the "
          "centre), outside (3 radii away) and grazing (inside, 0.1 from the wall, looking along it); stage1 "
          "at %s, stage4 at half that side, 16 spp. The rays are the stage's own: its camera rays as "
          "render_pixel() makes them (sampler, jitter, camera_ray, in the render's order), and for stage4 "
          "every ray a recording copy of its kernel traced (camera, bounce, shadow: the nearest hit closer "
          "than the light point, as occluded() asks). *render*: render() handed the BVH in both its forms, the "
          "binary tree and the CPU's 8-wide one (counted as part of the build: the backend's set_scene, the "
          "passes, the film), *collapsing*: render() handed the binary tree only, its set_scene collapsing it "
          "(what *render* was before issue 50's second round), *+ build*: render() building the BVH too; *walk*: the CPU's wide BVH alone on the same rays; Embree: rtcIntersect1 on them; *round "
          "one*: accel_stage_round1.csv, the section by the build after issue 50's first round (its *render* "
          "collapsed in set_scene), run side by side with an earlier run of this section (accel_stage_before_guide.csv, before the light pick's guide table); *before issue 50*: accel_stage_before.csv, "
          "the section by the build before either round, run beside round one's; *before round ten*: "
          "accel_stage_before_round10.csv, the section by the build before issue 50's tenth round (the light "
          "table's alias table), run just before this one (the pairs before: accel_stage_round10_pair*_before.csv "
          "and _after.csv; the run after round nine: accel_stage_round9.csv)." % (
              run.get("command", "pt_bench --section stage"), run.get("date", "?"), run.get("load_before", "?"),
              run.get("load_after", "?"), run.get("machine", "machine not recorded"), run.get("threads", "?"), run.get("embree", "Embree"),
              run.get("rounds", "?"), "%sx%s" % (rows[keys[0] + ("render_no_build",)]["width"],
                                                   rows[keys[0] + ("render_no_build",)]["height"])), ""]
    md += ["| stage | view | rays | render M rays/s | render / Embree | before round ten | collapsing / Embree | round one "
           "| before issue 50 | + build / Embree | walk / Embree | walk before round ten | round one's walk "
           "| Embree M rays/s | target |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s, v in keys:
        walk = [q for (s2, v2, q) in rows if (s2, v2) == (s, v) and q.startswith("walk_")]
        ratios = ", ".join("%s %s" % (q[5:], f(rows, s, v, q, "ratio_to_embree", "%.2f")) for q in walk)
        emb = ", ".join("%s %s" % (q[5:], f(rows, s, v, "embree_" + q[5:], "mrays_per_cpu_s", "%.2f")) for q in walk)
        ratio = rows[(s, v, "render_no_build")]["ratio_to_embree"]
        met = "met" if ratio and float(ratio) >= STAGE_TARGETS[s] else "missed"
        ratios1 = ", ".join("%s %s" % (q[5:], f(round1, s, v, q, "ratio_to_embree", "%.2f")) for q in walk)
        ratios10 = ", ".join("%s %s" % (q[5:], f(before_r10, s, v, q, "ratio_to_embree", "%.2f")) for q in walk)
        md.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s %.1f: **%s** |" % (
            s, v, rows[(s, v, "render_no_build")]["rays"], f(rows, s, v, "render_no_build", "mrays_per_cpu_s"),
            f(rows, s, v, "render_no_build", "ratio_to_embree", "%.2f"),
            f(before_r10, s, v, "render_no_build", "ratio_to_embree", "%.2f"),
            f(rows, s, v, "render_collapsing", "ratio_to_embree", "%.2f"),
            f(round1, s, v, "render_no_build", "ratio_to_embree", "%.2f"),
            f(before, s, v, "render_no_build", "ratio_to_embree", "%.2f"),
            f(rows, s, v, "render_with_build", "ratio_to_embree", "%.2f"), ratios, ratios10, ratios1, emb, s, STAGE_TARGETS[s], met))
    md += ["", "A sample's cost, ns of CPU time per sample (the render's CPU time over its samples; *rest*: the "
           "render's passes less the camera rays and the walk alone on the same rays, i.e. shading, the sampler's "
           "other numbers, the pixel loop, and the walk's cost beyond its own timing):", "",
           "| stage | view | render | set_scene | camera ray | traversal | rest | film | build_bvh | collapse to 8 wide | "
           "Embree's rays |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for s, v in keys:
        emb = sum(float(r["cpu_ns_per_sample"]) for (s2, v2, q), r in rows.items()
                  if (s2, v2) == (s, v) and q.startswith("embree_") and q != "embree_build")
        md.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.0f |" % (
            s, v, *(f(rows, s, v, q, "cpu_ns_per_sample", "%.0f") for q in
                    ("render_no_build", "cost_set_scene", "cost_camera", "cost_traversal", "cost_rest", "cost_film",
                     "build_bvh", "collapse_wide")), emb))
    md += ["", "What changed and where the time goes: [acceleration](acceleration.md), \"A stage program against "
           "Embree on its own rays (issue 50)\". The section runs alone (`pt_bench --section stage`, a few minutes); "
           "bench/report_accel.py adds this table under the accel section when docs/results/accel_stage.csv is there.",
           ""]
    return md
