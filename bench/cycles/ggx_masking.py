#!/usr/bin/python3
"""The GGX conductor's directional albedo (F = 1) with the glTF specification's masking against
Cycles 3.4's (issue 46, the "05" residual of bench/cycles/compare_gltf.py). Not part of the
article: bench machinery; no renderer is run.

stage5 (common/kernel/bsdf.glsl ggx_g2) masks with Smith's height-correlated
G2 = 1 / (1 + L(wo) + L(wi)), the specification's V_GGX (Appendix B); Cycles before Blender 4.0
with the separable G1(wo) G1(wi) = 1 / ((1 + L(wo)) (1 + L(wi))), L the GGX Lambda. Their ratio is
1 + L(wo) L(wi) / (1 + L(wo) + L(wi)) >= 1. This integrates E(wo) = integral of D G / (4 cos_o) over
the hemisphere of wi (midpoint rule, 800 x 1600 cells) for both at alpha = roughness^2 = 1 and
view angles 0 to 80 degrees, and writes their ratio.

  /usr/bin/python3 bench/cycles/ggx_masking.py --publish docs/results/gltf_real
"""
import argparse
import csv
import os
import shutil
import sys

import numpy as np


def ggx_lambda(mu, alpha):
    tan2 = (1.0 - mu * mu) / np.maximum(mu * mu, 1e-30)
    return 0.5 * (np.sqrt(1.0 + alpha * alpha * tan2) - 1.0)


def albedos(theta_deg, alpha, n=800):
    """(height-correlated, separable) directional albedo of a GGX conductor with F = 1."""
    mu = (np.arange(n) + 0.5) / n
    phi = (np.arange(2 * n) + 0.5) / (2 * n) * 2.0 * np.pi
    m, p = np.meshgrid(mu, phi, indexing="ij")
    s = np.sqrt(1.0 - m * m)
    wi = np.stack([s * np.cos(p), s * np.sin(p), m], -1)
    t = np.radians(theta_deg)
    wo = np.array([np.sin(t), 0.0, np.cos(t)])
    h = wi + wo
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    a2 = alpha * alpha
    d = a2 / (np.pi * (a2 * h[..., 2] ** 2 + (1.0 - h[..., 2] ** 2)) ** 2)
    lo, li = ggx_lambda(wo[2], alpha), ggx_lambda(m, alpha)
    f_cos = d / (4.0 * wo[2])  # D / (4 cos_o cos_i) times cos_i
    cell = (1.0 / n) * (np.pi / n)
    return (float(np.sum(f_cos / (1.0 + lo + li)) * cell),
            float(np.sum(f_cos / ((1.0 + lo) * (1.0 + li))) * cell))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out-dir", default="out/gltf_residuals")
    p.add_argument("--publish", default=None)
    args = p.parse_args()
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    out_dir = os.path.join(repo, args.out_dir)
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, "ggx_masking.csv")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["roughness", "view_deg", "albedo_height_correlated", "albedo_separable", "ratio"])
        for theta in (0, 30, 45, 60, 70, 80):
            corr, sep = albedos(theta, 1.0)
            w.writerow([1, theta, f"{corr:.4f}", f"{sep:.4f}", f"{corr / sep:.4f}"])
            print(f"ggx_masking.py: roughness 1, view {theta} deg: {corr:.4f} / {sep:.4f} = {corr / sep:.4f}")
    if args.publish:
        shutil.copy(path, os.path.join(repo, args.publish))
    return 0


if __name__ == "__main__":
    sys.exit(main())
