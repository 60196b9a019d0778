"""pt_bench's report, the acceleration section (issue 17), for bench/report.py: from
accel.csv, accel_build.csv and accel_run.txt (pt_bench --section accel), the log-log plot
of rays per second against the triangle count for camera, bounce and shadow rays (accel_rays.png), the table of every method
and count, the build table, issue 17's targets with the measured ratios and whether each
is met, and the check that the methods find the same hits. Hand-written findings come from
accel_notes.md in the same folder."""
import os
from collections import OrderedDict

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_accel_stage import stage_section  # noqa: E402  (bench/, beside this script)


ACCEL_METHODS = OrderedDict([("brute_cpu", "brute force (CPU, --accel none)"), ("bvh_cpu", "BVH (CPU)"),
                             ("bvh_gpu", "BVH (GPU backend)"), ("embree", "Embree 3 (rtcIntersect1; any hit: rtcOccluded1)")])
RAY_SETS = ("camera", "bounce", "shadow", "shadow_any")
RAY_SET_TITLES = {"camera": "camera rays", "bounce": "bounce rays", "shadow": "shadow rays (nearest hit)",
                  "shadow_any": "shadow rays (any hit)"}
TARGET_SETS = ("camera", "bounce")  # the ray sets of issue 17's targets
ACCEL_TARGET_EMBREE = 0.5   # CPU BVH >= 0.5x Embree on the ~1M-triangle mesh
ACCEL_TARGET_GPU = 0.5      # GPU (lavapipe) BVH >= 0.5x CPU BVH
ACCEL_TARGET_BUILD = 2.0    # our load + build <= 2x Embree's high-quality build


def read_keys(path):
    """Lines 'key: value' (accel_run.txt)."""
    if not os.path.exists(path):
        return {}
    out = {}
    for line in open(path):
        if ":" in line:
            k, v = line.split(":", 1)
            out[k.strip()] = v.strip()
    return out


def num(v):
    return float(v) if v not in (None, "") else None


def plot_accel(rows, out_dir):
    fig, axes = plt.subplots(1, 4, figsize=(18, 4.2), sharey=True)
    for ax, rays in zip(axes, RAY_SETS):
        for method, label in ACCEL_METHODS.items():
            pts = [(int(r["triangles"]), num(r["mrays_per_s"])) for r in rows
                   if r["rays"] == rays and r["method"] == method and num(r["mrays_per_s"])]
            if pts:
                ax.loglog([p[0] for p in pts], [p[1] * 1e6 for p in pts], marker="o", markersize=3, label=label)
        ax.set_xlabel("triangles")
        ax.set_title(RAY_SET_TITLES[rays])
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("rays per second (wall clock)")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "accel_rays.png"), dpi=90)
    plt.close(fig)
    return "accel_rays.png"


def accel_section(rows, builds, run, out_dir):
    by = {(r["rays"], int(r["triangles"]), r["method"]): r for r in rows}
    counts = sorted({int(r["triangles"]) for r in rows})
    top = counts[-1]
    gpu = next((r["device"] for r in rows if r["method"] == "bvh_gpu" and r["device"]), "none")
    threads = next((r["threads"] for r in rows if r["method"] == "bvh_cpu"), "?")

    def rate(rays, n, method, field="mrays_per_s"):
        r = by.get((rays, n, method))
        return num(r[field]) if r else None

    def cell(rays, n, method):
        r = by.get((rays, n, method))
        if not r:
            return "-"
        v = num(r["mrays_per_s"])
        if v is None:
            return "skipped" if r["note"].startswith("skipped") else "-"
        mark = " \u2020" if method == "brute_cpu" and r["rays_checked"] and int(r["rays_checked"]) < int(
            by[(rays, n, "bvh_cpu")]["rays_checked"]) else ""
        return "%.3g%s" % (v, mark)

    def ratio(a, b):
        return "%.2f" % (a / b) if a and b else "-"

    md = ["## Acceleration structure (issue 17): rays per second against the triangle count", "",
          "Made by `%s` on %s; load average (1, 5, 15 min) before: %s, after: %s; the section took %s s. "
          "Machine: %s; %s CPU threads; GPU backend: %s; %s." % (
              run.get("command", "?"), run.get("date", "?"), run.get("load_before", "?"),
              run.get("load_after", "?"), run.get("seconds", "?"), run.get("machine", "not recorded"), threads, gpu,
              run.get("embree", "no Embree")), "",
          "The scenes: builtin:cornell (36 triangles), then the Cornell room (its walls and light, 12 triangles) "
          "with an icosphere in place of the two boxes (bench/accel_scene.cpp, placed as bench/make_sphere_mesh.py "
          "places it). Camera rays: %s, from a pinhole camera that frames the sphere (it fills 90%% of the image "
          "height, the room around it). Bounce rays: one from each camera ray's hit, cosine-distributed about the "
          "normal and spawned as the renderer spawns them (common/kernel/spawn.glsl). Shadow rays: from each camera "
          "ray's hit to a uniform point of the ceiling light (none where the light point lies behind the surface), "
          "spawned as stages 4 and 5 spawn them (common/kernel/lights.glsl, occluded()) and searched as they search: "
          "the nearest hit closer than a bound, here where occluded()'s last stretch before the light point begins "
          "(so that no method counts the light's own surface); shadow_any: the same shadow rays through the any-hit "
          "search (`occluded_scene`, the first hit found ends it; Embree's `rtcOccluded1`), as rays towards the sky "
          "and the sun are traced. Every method traces the same "
          "rays: the brute force is the renderer's `--accel none` search (cpu/triangle_lanes.h), the BVH is "
          "the one tree of common/scene/bvh.h: on the CPU as the CPU backend walks it, collapsed to 8 children and "
          "leaf blocks of up to 8 triangles on SIMD lanes (cpu/wide_bvh.h), on the GPU backend common/kernel/bvh.glsl's "
          "binary walk run by intersect_raycast.comp; Embree is `rtcIntersect1` one ray at a time on a high-quality build (tfar the shadow rays' bound). The CPU methods "
          "run on all cores, and the methods take turns (at least %s s and 3 passes each) so that they share the same load. "
          "\u2020: the brute force timed on an even sample of the rays (accel.csv says how many); skipped: even "
          "2048 rays would have taken longer than the limit." % (
              run.get("camera_rays", "?"), run.get("seconds_per_method", "?")), "",
          "![rays per second against triangles](results/%s)" % plot_accel(rows, out_dir), "",
          "Million rays per second by the wall clock:", "",
          "| rays | triangles | brute force | BVH, CPU | BVH, GPU | Embree 3 | BVH CPU / Embree | BVH GPU / BVH CPU |",
          "|---|---|---|---|---|---|---|---|"]
    for rays in RAY_SETS:
        for n in counts:
            md.append("| %s | %d | %s | %s | %s | %s | %s | %s |" % (
                rays, n, cell(rays, n, "brute_cpu"), cell(rays, n, "bvh_cpu"), cell(rays, n, "bvh_gpu"),
                cell(rays, n, "embree"), ratio(rate(rays, n, "bvh_cpu"), rate(rays, n, "embree")),
                ratio(rate(rays, n, "bvh_gpu"), rate(rays, n, "bvh_cpu"))))
    md.append("")

    b = {r["method"]: r for r in builds}
    if builds:
        md += ["Build of the %s-triangle scene, best of three:" % builds[0]["triangles"], "",
               "| build | threads | best | all runs (s) | bytes per triangle | note |", "|---|---|---|---|---|---|"]
        for r in builds:
            md.append("| %s | %s | %s | %s | %s | %s |" % (
                r["method"], r["threads"], "%.3f s" % num(r["best_s"]) if num(r["best_s"]) else "-", r["runs_s"],
                "%.1f" % num(r["bytes_per_triangle"]) if num(r["bytes_per_triangle"]) else "-", r["note"]))
        md.append("")

    def met(value, target, above, by_cpu=None):
        """The verdict by the wall clock, and by CPU time where given: on a shared machine
        the two can fall on either side of the target, and then the page says so."""
        if value is None:
            return "not measured"
        ok = value >= target if above else value <= target
        if by_cpu is None or (by_cpu >= target if above else by_cpu <= target) == ok:
            return "**met**" if ok else "**missed**"
        return "**%s** by the wall clock, **%s** by CPU time" % (("met", "missed") if ok else ("missed", "met"))

    md += ["Targets of issue 17 against this run (ratios by the wall clock; by CPU time in parentheses):", "",
           "| target | measured | |", "|---|---|---|"]
    for rays in TARGET_SETS:
        e, c = rate(rays, top, "embree"), rate(rays, top, "bvh_cpu")
        ec, cc = rate(rays, top, "embree", "mrays_per_cpu_s"), rate(rays, top, "bvh_cpu", "mrays_per_cpu_s")
        v = c / e if c and e else None
        md.append("| CPU BVH \u2265 %.1f\u00d7 Embree, %s rays, %d triangles | %s (%s) | %s |" % (
            ACCEL_TARGET_EMBREE, rays, top, ratio(c, e), ratio(cc, ec),
            met(v, ACCEL_TARGET_EMBREE, True, cc / ec if cc and ec else None)))
    for rays in TARGET_SETS:
        g, c = rate(rays, top, "bvh_gpu"), rate(rays, top, "bvh_cpu")
        gc, cc = rate(rays, top, "bvh_gpu", "mrays_per_cpu_s"), rate(rays, top, "bvh_cpu", "mrays_per_cpu_s")
        all_ratios = [rate(rays, n, "bvh_gpu") / rate(rays, n, "bvh_cpu") for n in counts
                      if rate(rays, n, "bvh_gpu") and rate(rays, n, "bvh_cpu")]
        v = g / c if g and c else None
        md.append("| GPU backend (%s) BVH \u2265 %.1f\u00d7 CPU BVH, %s rays, %d triangles | %s (%s); %s over all counts | %s |" % (
            gpu, ACCEL_TARGET_GPU, rays, top, ratio(g, c), ratio(gc, cc),
            "%.2f to %.2f" % (min(all_ratios), max(all_ratios)) if all_ratios else "-",
            met(v, ACCEL_TARGET_GPU, True, gc / cc if gc and cc else None)))
    # Against the faster of Embree's builds (all cores or one): the stricter comparison.
    ours = b.get("bvh_build")
    o = num(ours["best_s"]) if ours else None
    embree_builds = [(num(r["best_s"]), r["threads"]) for r in builds if r["method"].startswith("embree") and num(r["best_s"])]
    e, e_threads = min(embree_builds) if embree_builds else (None, "")
    md.append("| our load + build \u2264 %.0f\u00d7 Embree's high-quality build (%s triangles; Embree's faster "
              "build, on %s thread(s)) | %s s / %s s = %s | %s |" % (
                  ACCEL_TARGET_BUILD, ours["triangles"] if ours else "?", e_threads or "-", "%.3f" % o if o else "-",
                  "%.3f" % e if e else "-", ratio(o, e), met(o / e if o and e else None, ACCEL_TARGET_BUILD, False)))
    md.append("")

    # The shadow rays, which stages 4 and 5 trace as many as their bounce rays: the same ratios,
    # not among the targets.
    for rays, what in (("shadow", "nearest hit"), ("shadow_any", "any hit")):
        g, c, e = rate(rays, top, "bvh_gpu"), rate(rays, top, "bvh_cpu"), rate(rays, top, "embree")
        if c:
            md += ["Shadow rays, %s (not among the issue's targets), %d triangles: CPU BVH %s of Embree, GPU backend "
                   "%s of the CPU BVH." % (what, top, ratio(c, e), ratio(g, c)), ""]

    # Sanity: the same hits. Each method against the CPU BVH on the same rays.
    sanity = []
    for rays in RAY_SETS:
        ref = by.get((rays, top, "bvh_cpu"))
        if not ref or not ref["hits"]:
            continue
        parts = ["BVH (CPU) %s hits of %s, mean t %s" % (ref["hits"], ref["rays_checked"], ref["mean_t"])]
        for method in ("embree", "bvh_gpu", "brute_cpu"):
            r = by.get((rays, top, method))
            if r and r["hits"]:
                parts.append("%s %s hits, mean t %s, differing rays: %s" % (
                    ACCEL_METHODS[method], r["hits"], r["mean_t"], r["rays_differing_from_bvh_cpu"]))
        sanity.append("%s rays: %s" % (rays, "; ".join(parts)))
    # The verdict: Embree's hit count within 1e-4 of the rays, its mean t within 1e-5 relative.
    agree = []
    for rays in RAY_SETS:
        ref, emb = by.get((rays, top, "bvh_cpu")), by.get((rays, top, "embree"))
        if ref and emb and ref["hits"] and emb["hits"]:
            ok = (abs(int(ref["hits"]) - int(emb["hits"])) <= 1e-4 * int(ref["rays_checked"]) and
                  abs(float(ref["mean_t"]) - float(emb["mean_t"])) <= 1e-5 * float(ref["mean_t"]))
            agree.append("%s rays %s" % (rays, "agree" if ok else "**disagree**"))
    worst = {}
    for r in rows:
        if r["method"] != "bvh_cpu" and r["rays_differing_from_bvh_cpu"]:
            d = int(r["rays_differing_from_bvh_cpu"]) / max(1, int(r["rays_checked"]))
            worst[r["method"]] = max(worst.get(r["method"], 0.0), d)
    md += ["Sanity, the same hits (a ray differs when one method hits and the other misses, or the distances "
           "differ by more than 1e-5 relative), on the %d-triangle scene: %s Our BVH against Embree (hit counts "
           "within 1e-4 of the rays, mean t within 1e-5): %s. Over every scene and ray set the "
           "largest share of differing rays is %s." % (
               top, " ".join(s + "." for s in sanity) or "-", ", ".join(agree) or "not measured",
               ", ".join("%s %.2g%%" % (ACCEL_METHODS[m], 100 * v) for m, v in worst.items()) or "-"), ""]
    notes = os.path.join(out_dir, "accel_notes.md")
    if os.path.exists(notes):
        md += [open(notes).read().rstrip(), ""]
    md += stage_section(out_dir, read_keys)  # issue 50: the stages against Embree on their own rays
    return md
