#!/usr/bin/python3
"""Draws the book's figures (docs/monte_carlo.md and the stage chapters): solid angle, the
change from area to solid angle, Malley's cosine sampling, the MIS weights, the environment
map's orientation and sampling density (environment.py), and the error
against samples per pixel from docs/results/convergence.csv (the Cornell box, the box
furnace). Not part of the article: the pictures beside it. Run by `./tutorial docs` (needs Debian's python3-matplotlib).
usage: docs/figures/make_figures.py [--out docs/images/figures] [--results docs/results]"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("make_figures.py: matplotlib is missing: install python3-matplotlib "
             "(apt-get install python3-matplotlib) and run it with /usr/bin/python3")

import environment  # noqa: E402
import geometry  # noqa: E402
import plots  # noqa: E402

STYLE = {"font.size": 9, "axes.titlesize": 10, "savefig.dpi": 100, "font.family": "DejaVu Sans",
         "svg.hashsalt": "pt", "path.simplify": True}
# No date or version in the files: the same script and data give the same bytes.
METADATA = {"Software": None}


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.savefig(path, metadata=METADATA)
    plt.close(fig)
    size = os.path.getsize(path)
    print(f"{path}: {size // 1024} KB")
    if size > 150 * 1024:
        sys.exit(f"make_figures.py: {path} is {size // 1024} KB, over the 150 KB a figure may take")


def main():
    root = os.path.dirname(os.path.dirname(HERE))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join(root, "docs", "images", "figures"))
    ap.add_argument("--results", default=os.path.join(root, "docs", "results"))
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    plt.rcParams.update(STYLE)
    save(geometry.solid_angle(), a.out, "solid_angle.png")
    save(geometry.area_to_solid_angle(), a.out, "area_to_solid_angle.png")
    save(geometry.malley(), a.out, "malley_cosine_sampling.png")
    save(plots.mis_weights(), a.out, "mis_weights.png")
    save(environment.orientation(), a.out, "env_orientation.png")  # docs/environment.md
    save(environment.density(), a.out, "env_density.png")
    conv = os.path.join(a.results, "convergence.csv")
    if not os.path.isfile(conv):
        sys.exit(f"make_figures.py: {conv} is missing: run ./tutorial bench first, or give --results")
    save(plots.convergence(conv, "cornell"), a.out, "convergence_cornell.png")
    save(plots.convergence(conv, "furnace", anchor="stage4_direct_indirect",
                           slopes=((0.5, "--", "∝ N^-1/2 (finite variance)"), (1 / 3, ":", "∝ N^-1/3")),
                           title="builtin:furnace (the box furnace), CPU backend, Sobol sampler"),
         a.out, "convergence_furnace.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
