#!/usr/bin/python3
"""The environment map's orientation against Blender (issue 49, "Measures", item 2): a mirror sphere
under a grey map with one red patch, rendered by Blender's Cycles (bench/cycles/render_cycles_env.py:
Generated -> Mapping Z rotation -> Environment Texture) and by stage5 --env --env-rotate, same camera.
Not part of the article: bench machinery. Writes OUT/orientation.csv (the patch's centroid in pixels,
x right, y down, from the image's top-left corner; weight = max(R - G, 0)) and OUT/orientation.png.

  /usr/bin/python3 bench/env/orientation.py --bin-dir build-h3/bin --out-dir docs/results/env
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "cycles"))
import env_scenes  # noqa: E402
from compare_images import read_rgb  # noqa: E402
from compare_renderers import run_timed  # noqa: E402

PATCH_DIRECTION = (0.4, 0.5, 0.75)   # glTF, +Y up: up and to the right, on the camera's side


def centroid(img):
    w = np.maximum(img[..., 0] - img[..., 1], 0.0)
    ys, xs = np.mgrid[0:img.shape[0], 0:img.shape[1]] + 0.5
    return float((w * xs).sum() / w.sum()), float((w * ys).sum() / w.sum()), int((w > 0.5 * w.max()).sum())


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bin-dir", default="build/bin")
    p.add_argument("--out-dir", default="out/env")
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--rotations", default="0,60,-135")
    p.add_argument("--blender", default="blender")
    args = p.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    work = tempfile.mkdtemp(prefix="pt_env_orientation_")
    scene = env_scenes.mirror_sphere(os.path.join(work, "mirror_sphere.gltf"))
    env = os.path.join(work, "patch.exr")
    u, v = env_scenes.patch_map(env, PATCH_DIRECTION)
    n = args.size
    rows, strips = [], []
    for rot in [float(r) for r in args.rotations.split(",")]:
        cyc, st5 = os.path.join(work, f"cycles_{rot:g}.exr"), os.path.join(work, f"stage5_{rot:g}.exr")
        run_timed([args.blender, "--factory-startup", "-b", "--python",
                   os.path.join(os.path.dirname(HERE), "cycles", "render_cycles_env.py"), "--",
                   "--scene", scene, "--env", env, "--env-rotate", str(rot), "--width", str(n),
                   "--height", str(n), "--spp", str(args.spp), "--seed", "1", "--out", cyc])
        run_timed([os.path.join(args.bin_dir, "stage5_mis"), "--scene", scene, "--env", env,
                   "--env-rotate", str(rot), "--width", str(n), "--height", str(n), "--spp", str(args.spp),
                   "--backend", "cpu", "--out", st5])
        a, b = read_rgb(cyc), read_rgb(st5)
        (cx, cy, cn), (sx, sy, sn) = centroid(a), centroid(b)
        rows.append({"rotate": f"{rot:g}", "patch_u": f"{u:.5f}", "patch_v": f"{v:.5f}",
                     "cycles_x": f"{cx:.2f}", "cycles_y": f"{cy:.2f}", "stage5_x": f"{sx:.2f}",
                     "stage5_y": f"{sy:.2f}", "distance_px": f"{np.hypot(cx - sx, cy - sy):.2f}",
                     "cycles_patch_pixels": cn, "stage5_patch_pixels": sn,
                     "size": f"{n}x{n}", "spp": args.spp})
        print(f"orientation.py: rotate {rot:g}: Cycles ({cx:.2f}, {cy:.2f}), stage5 ({sx:.2f}, {sy:.2f}), "
              f"{rows[-1]['distance_px']} px apart", flush=True)
        strips.append(np.concatenate([a, b], axis=1))
    with open(os.path.join(args.out_dir, "orientation.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    # One picture: a row per rotation, Cycles left, stage5 right (sRGB through oiiotool).
    pic = np.concatenate(strips, axis=0).astype(np.float32)
    np.clip(pic, 0, 1, out=pic)
    srgb = np.where(pic <= 0.0031308, 12.92 * pic, 1.055 * np.power(pic, 1 / 2.4) - 0.055)
    write_ppm_png(os.path.join(args.out_dir, "orientation.png"), (srgb * 255 + 0.5).astype(np.uint8), work)
    return 0


def write_ppm_png(path, rgb8, work):
    """8-bit RGB to PNG through a binary PPM and oiiotool."""
    ppm = os.path.join(work, "picture.ppm")
    with open(ppm, "wb") as f:
        f.write(f"P6 {rgb8.shape[1]} {rgb8.shape[0]} 255\n".encode() + rgb8.tobytes())
    subprocess.run(["oiiotool", ppm, "-o", path], check=True, stdout=subprocess.DEVNULL)


if __name__ == "__main__":
    sys.exit(main())
