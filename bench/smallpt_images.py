"""The image measures of bench/smallpt_compare.py (issue #18, the stages against smallpt's
algorithm): the relative MSE against a reference, the means and errors of a 3 x 4 grid of
regions, and the row of the "do the converged images agree?" table for two references."""
import numpy as np

GRID = (3, 4)  # regions: rows x columns


def rel_mse(img, ref):
    return float(np.mean((img - ref) ** 2) / np.mean(ref) ** 2)


def regions(img):
    """Mean over R, G, B of each region of the GRID, as an array of shape GRID."""
    h, w = img.shape[:2]
    gy, gx = GRID
    out = np.zeros(GRID)
    for j in range(gy):
        for i in range(gx):
            out[j, i] = img[j * h // gy:(j + 1) * h // gy, i * w // gx:(i + 1) * w // gx].mean()
    return out


def region_rel_mse(img, ref):
    """Per region: mean of (x - ref)^2 over the region, divided by the whole reference's mean squared."""
    return regions((img - ref) ** 2) / np.mean(ref) ** 2


def agreement(label_a, a, sd_a, label_b, b, sd_b):
    """One table row: image mean, channels, regions (largest |difference| and its z), flip check."""
    scale = b.mean()
    whole = (a.mean() / scale - 1.0) * 100.0
    ch = (a.mean(axis=(0, 1)) / b.mean(axis=(0, 1)) - 1.0) * 100.0
    ra, rb = regions(a), regions(b)
    diff = (ra / rb - 1.0) * 100.0
    z = (ra - rb) / np.sqrt(sd_a ** 2 + sd_b ** 2 + 1e-30)
    k = np.unravel_index(np.argmax(np.abs(diff)), diff.shape)
    below_top = (a[1:].mean() / b[1:].mean() - 1.0) * 100.0
    rows_a, rows_b = a.mean(axis=(1, 2)), b.mean(axis=(1, 2))
    row_dev = np.sqrt(np.mean((rows_a - rows_b) ** 2)) / scale * 100.0
    flip_dev = np.sqrt(np.mean((rows_a[::-1] - rows_b) ** 2)) / scale * 100.0
    return (f"| {label_a} vs {label_b} | {whole:+.2f}% | {below_top:+.2f}% | "
            f"{ch[0]:+.2f}% / {ch[1]:+.2f}% / {ch[2]:+.2f}% | "
            f"{np.median(diff):+.2f}% | {diff[k]:+.2f}% (row {k[0]}, col {k[1]}; z {z[k]:+.1f}) | "
            f"{np.max(np.abs(z)):.1f} | {row_dev:.2f}% / {flip_dev:.0f}% ({'upright' if row_dev < flip_dev else 'FLIPPED?'}) |")
