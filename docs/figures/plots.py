"""The plots of the book: stage5's MIS weights (balance and power heuristic) for a light
strategy and a BSDF strategy along a line of directions, and the error of stages 2 to 5
against samples per pixel with an N^-1/2 line (docs/results/convergence.csv). Not part of
the article: its pictures; drawn by make_figures.py in the chapters' notation. Also the box
furnace, where stage4's variance is infinite and its error falls only about as N^-1/3."""
import csv

import numpy as np
import matplotlib.pyplot as plt

COLOURS = {"stage2_montecarlo": "#1f77b4", "stage3_importance": "#2ca02c",
           "stage4_direct_indirect": "#9467bd", "stage5_mis": "#d62728"}


def mis_weights():
    """Directions ω along one line (an angle t): a light seen between t = 0° and 30° (p_l
    uniform over it, by solid angle) and a glossy lobe centred at 18° (p_b)."""
    t = np.linspace(-40, 60, 1001)
    lo, hi = 0.0, 30.0
    p_l = np.where((t >= lo) & (t <= hi), 1.0 / (hi - lo), 0.0)
    p_b = np.exp(-0.5 * ((t - 18.0) / 6.0) ** 2) / (6.0 * np.sqrt(2 * np.pi))
    with np.errstate(invalid="ignore", divide="ignore"):
        balance = np.where(p_l + p_b > 0, p_l / (p_l + p_b), np.nan)
        power = np.where(p_l + p_b > 0, p_l ** 2 / (p_l ** 2 + p_b ** 2), np.nan)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.0, 4.6), sharex=True,
                                      gridspec_kw={"height_ratios": [1, 1.3]})
    top.plot(t, p_l, color="#ff7f0e", lw=1.5, label="p_l(ω): the light strategy")
    top.plot(t, p_b, color="#1f77b4", lw=1.5, label="p_b(ω): the BSDF strategy (a glossy lobe)")
    top.axvspan(lo, hi, color="#ff7f0e", alpha=0.08)
    top.set_ylabel("pdf (per degree)")
    top.legend(fontsize=7, loc="upper left")
    top.set_title("Two strategies for the same directions, and the weights that join them")
    inside = (t >= lo) & (t <= hi)
    bottom.plot(t[inside], power[inside], color="#ff7f0e", lw=1.8,
                label="w_l = p_l² / (p_l² + p_b²)  (power, stage5)")
    bottom.plot(t[inside], balance[inside], color="#ff7f0e", lw=1.2, ls="--",
                label="p_l / (p_l + p_b)  (balance)")
    bottom.plot(t, 1 - power, color="#1f77b4", lw=1.8, label="w_b = 1 − w_l  (power)")
    bottom.plot(t, 1 - balance, color="#1f77b4", lw=1.2, ls="--", label="1 − balance")
    bottom.set_ylim(-0.05, 1.12)
    bottom.set_ylabel("weight")
    bottom.set_xlabel("direction ω along a line (degrees)")
    bottom.annotate("only the BSDF can draw ω here:\nw_b = 1", xy=(45, 1.0), xytext=(35, 0.45), fontsize=7,
                    arrowprops=dict(arrowstyle="->", lw=0.6))
    bottom.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    return fig


def read_runs(path, scene, backend="cpu"):
    runs = {}
    with open(path, newline="", encoding="utf-8") as f:
        for r in csv.DictReader(f):
            if r["scene"] == scene and r["backend"] == backend:
                runs.setdefault(r["stage"], []).append((int(r["spp"]), float(r["rel_rmse"])))
    return {k: sorted(v) for k, v in sorted(runs.items())}


def convergence(path, scene, slopes=((0.5, "--", "∝ N^-1/2 (independent samples)"), (1.0, ":", "∝ N^-1")),
                anchor="stage2_montecarlo", title=None):
    """Relative RMSE against spp (each point a fresh render), CPU backend, with lines N^-s
    through ANCHOR's first point: samples, not seconds, so no fixed cost bends a curve."""
    runs = read_runs(path, scene)
    fig, ax = plt.subplots(figsize=(6.0, 4.2))
    for stage, pts in runs.items():
        n = np.array([p[0] for p in pts])
        e = np.array([p[1] for p in pts])
        ax.loglog(n, e, marker="o", ms=3, lw=1.2, color=COLOURS.get(stage), label=stage)
    first = runs.get(anchor) or next(iter(runs.values()))
    n0, e0 = first[0]
    nn = np.array([1, max(p[0] for v in runs.values() for p in v)])
    for s, style, label in slopes:
        ax.loglog(nn, e0 * (nn / n0) ** -s, color="k", lw=0.8, ls=style, label=label)
    ax.set_xlabel("samples per pixel N")
    ax.set_ylabel("relative RMSE against the reference")
    ax.set_title(title or f"builtin:{scene}, CPU backend, default (Sobol) sampler")
    ax.grid(True, which="both", alpha=0.25)
    ax.set_ylim(min(p[1] for v in runs.values() for p in v) / 2, max(p[1] for v in runs.values() for p in v) * 2)
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    return fig
