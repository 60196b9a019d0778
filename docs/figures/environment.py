"""The environment map's figures (docs/environment.md, stage4's chapter): the lat-long orientation,
and a map beside the density its light sampling draws from (luminance x sin θ over each texel's
3 x 3 neighbourhood, as common/scene/environment.cpp). Not part of the article: issue #49's pictures.
Reads env_sunrise_64x32.csv (a CC0 Blender world, downsampled), so it needs no EXR reader."""
import csv
import os

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.colors import LogNorm

HERE = os.path.dirname(os.path.abspath(__file__))
MAP = os.path.join(HERE, "env_sunrise_64x32.csv")


def read_map(path=MAP):
    """The CSV's texels as an array [height, width, 3] of linear RGB, row 0 the image's top."""
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    w = 1 + max(int(r["x"]) for r in rows)
    h = 1 + max(int(r["y"]) for r in rows)
    rgb = np.zeros((h, w, 3))
    for r in rows:
        rgb[int(r["y"]), int(r["x"])] = (float(r["r"]), float(r["g"]), float(r["b"]))
    return rgb


def srgb(linear):
    """Linear radiance to displayable sRGB in [0, 1] (clamped, as the renderer's .png)."""
    x = np.clip(linear, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def sampling_density(rgb):
    """The pdf over (u, v) in [0, 1]^2 that the renderer samples (mean 1): each texel's
    luminance averaged over its neighbours with weights 1/8, 6/8, 1/8 along each axis (u
    wraps, v is clamped), times the mean of sin θ over its row."""
    h, w, _ = rgb.shape
    lum = rgb @ np.array([0.2126, 0.7152, 0.0722])
    tap = (0.125, 0.75, 0.125)
    across = sum(t * np.roll(lum, -d, axis=1) for t, d in zip(tap, (-1, 0, 1)))
    up = np.vstack([across[:1], across[:-1]])     # the row above, clamped at the top
    down = np.vstack([across[1:], across[-1:]])   # the row below, clamped at the bottom
    smooth = tap[0] * up + tap[1] * across + tap[2] * down
    theta0 = np.pi * np.arange(h) / h
    theta1 = np.pi * np.arange(1, h + 1) / h
    mean_sin = (np.cos(theta0) - np.cos(theta1)) / (theta1 - theta0)
    f = smooth * mean_sin[:, None]
    return f * (w * h) / f.sum()


def draw_samples(pdf, n, seed=1):
    """n points (u, v) drawn as stage4 draws them: a row by the marginal cdf, a column by
    that row's conditional cdf, uniform inside the texel."""
    h, w = pdf.shape
    rng = np.random.default_rng(seed)
    rows = pdf.sum(axis=1)
    marginal = np.concatenate([[0.0], np.cumsum(rows)]) / rows.sum()
    u1, u2, j1, j2 = rng.random((4, n))
    y = np.clip(np.searchsorted(marginal, u1, side="right") - 1, 0, h - 1)
    x = np.empty(n, dtype=int)
    for k in range(n):
        cond = np.concatenate([[0.0], np.cumsum(pdf[y[k]])]) / pdf[y[k]].sum()
        x[k] = np.clip(np.searchsorted(cond, u2[k], side="right") - 1, 0, w - 1)
    return (x + j1) / w, (y + j2) / h


def orientation():
    """The lat-long image over (u, v) with the directions its columns and rows look along:
    glTF axes, +Y up (Blender's world Environment Texture)."""
    rgb = read_map()
    fig, ax = plt.subplots(figsize=(7.0, 3.9))
    ax.imshow(srgb(rgb) * 0.55 + 0.45, extent=(0, 1, 1, 0), interpolation="bilinear", aspect="auto")
    for u in np.arange(0, 1.001, 0.125):
        ax.axvline(u, color="k", lw=0.5 if u % 0.25 else 1.0, alpha=0.6)
    for v in np.arange(0, 1.001, 0.125):
        ax.axhline(v, color="k", lw=0.5 if v % 0.5 else 1.0, alpha=0.6)
    box = dict(boxstyle="round,pad=0.25", fc="white", ec="k", lw=0.6)
    for u, name in ((0.0, "−X"), (0.25, "−Z"), (0.5, "+X"), (0.75, "+Z"), (1.0, "−X")):
        ax.text(u, 0.5, name, ha="center", va="center", fontsize=11, weight="bold", bbox=box)
    ax.text(0.5, 0.035, "+Y (up): the whole top row", ha="center", va="top", fontsize=9, bbox=box)
    ax.text(0.5, 0.965, "−Y (down): the whole bottom row", ha="center", va="bottom", fontsize=9, bbox=box)
    ax.set_xlim(0, 1)
    ax.set_ylim(1, 0)
    ax.set_xticks(np.arange(0, 1.001, 0.25))
    ax.set_yticks([0, 0.25, 0.5, 0.75, 1])
    ax.set_xlabel("u (column / width): φ = 2π (u − ½), the angle from +X toward +Z")
    ax.set_ylabel("v (row / height, from the top)\nθ = π v from +Y")
    ax.set_title("A direction (x, y, z), glTF axes: u = ½ + atan2(z, x) / 2π, v = acos(y) / π\n"
                 "(faded beneath: env_sunrise_64x32; --env-rotate 90 turns the centre's view to +Z)",
                 fontsize=9)
    fig.tight_layout()
    return fig


def density():
    """The map, the density p(u, v) its light sampling draws from (log scale), directions
    drawn from it, and the marginal density of the rows."""
    rgb = read_map()
    pdf = sampling_density(rgb)
    su, sv = draw_samples(pdf, 300)
    fig = plt.figure(figsize=(9.0, 3.3), layout="constrained")
    grid = fig.add_gridspec(1, 3, width_ratios=[2, 2.25, 0.5])
    left = fig.add_subplot(grid[0])
    left.imshow(srgb(rgb), extent=(0, 1, 1, 0), interpolation="nearest", aspect="auto")
    left.set_title("the map: 64 × 32 texels\n(linear RGB shown as sRGB)", fontsize=8)
    left.set_xlabel("u")
    left.set_ylabel("v (θ = π v from +Y)")
    mid = fig.add_subplot(grid[1], sharey=left)
    im = mid.imshow(pdf, extent=(0, 1, 1, 0), interpolation="nearest", aspect="auto", cmap="magma",
                    norm=LogNorm(vmin=max(pdf.max() * 1e-4, pdf[pdf > 0].min()), vmax=pdf.max()))
    mid.plot(su, sv, ".", ms=2.2, color="#4fc3f7", alpha=0.8)
    mid.set_title("its density p(u, v) ∝ luminance × sin θ\n(log scale), and 300 directions drawn",
                  fontsize=8)
    mid.set_xlabel("u")
    mid.tick_params(labelleft=False)
    fig.colorbar(im, ax=mid, fraction=0.05, pad=0.02).set_label("p(u, v), mean 1", fontsize=7)
    right = fig.add_subplot(grid[2], sharey=left)
    h = pdf.shape[0]
    rows = pdf.mean(axis=1)
    v = (np.arange(h) + 0.5) / h
    right.barh(v, rows, height=1.0 / h, color="#888888")
    right.set_xscale("log")
    right.set_title("rows:\nmarginal", fontsize=8)
    right.set_xlabel("p(v)")
    right.tick_params(labelleft=False)
    return fig
