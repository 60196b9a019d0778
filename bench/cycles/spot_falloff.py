#!/usr/bin/python3
"""A spot light's falloff as Blender 3.4's Cycles renders an imported glTF spot, against the
KHR_lights_punctual cone that stage4 and stage5 render (issue 46, the "05" residual of
bench/cycles/compare_gltf.py). Not part of the article: bench machinery; no renderer is run.

Blender's glTF importer (io_scene_gltf2 3.4, blender/imp/gltf2_blender_light.py) makes a spot of
spot_size = 2 x outerConeAngle and spot_blend = 1 - innerConeAngle / outerConeAngle. Cycles 3.4
(scene/light.cpp, kernel/light/spot.h) then scales the intensity at angle theta from the axis by

  cos(theta) x smoothstep((cos(theta) - cos(outer)) / ((1 - cos(outer)) x blend))   inside the cone
                                                                                   (0 outside)

with smoothstep(x) = x^2 (3 - 2x) for x in [0, 1] (1 above): a ramp in the cosine that reaches 1 at
cos(outer) + (1 - cos(outer)) blend, and a cos(theta) factor on top. The glTF cone that the stages
render (common/kernel/punctual_light.glsl spot_falloff) is the square of the linear ramp from
cos(outer) (0) to cos(inner) (1), and 1 inside the inner cone. For each spot of the bench's files
this writes the angle where each is fully lit, the ratio glTF / Blender at angles across the cone,
and the ratio of the power each sends into its cone (the integral of the falloff over solid angle).

  /usr/bin/python3 bench/cycles/spot_falloff.py --publish docs/results/gltf_real
"""
import argparse
import csv
import math
import os
import sys

# The spots of bench/gltf_real's files as Blender 3.4's exporter writes them (radians).
SPOTS = [
    ("05_metallic_sphere_light", "Spot", 0.10471975623447705, 0.3490658402442932),
    ("04_lights", "Spot_Quadratic", 0.0, 0.2617993950843811),
    ("04_lights", "Spot_Linear", 0.0872664600610733, 0.1745329201221466),
    ("04_lights", "Spot_Constant", 0.0872664600610733, 0.0872664600610733),
]


def smoothstep(x):
    x = min(max(x, 0.0), 1.0)
    return x * x * (3.0 - 2.0 * x)


def blender_falloff(theta, inner, outer):
    """Cycles 3.4's spot attenuation for the importer's spot_size and spot_blend."""
    cos_outer, c = math.cos(outer), math.cos(theta)
    if c <= cos_outer:
        return 0.0
    blend = 1.0 - inner / outer if outer > 0 else 0.0
    smooth = (1.0 - cos_outer) * blend
    t = c - cos_outer
    return c * (smoothstep(t / smooth) if smooth > 0 and t < smooth else 1.0)


def gltf_falloff(theta, inner, outer):
    """KHR_lights_punctual's recommended falloff (the square of the ramp in the cosine)."""
    c, cos_inner, cos_outer = math.cos(theta), math.cos(inner), math.cos(outer)
    if c <= cos_outer:
        return 0.0
    if c >= cos_inner or cos_inner <= cos_outer:
        return 1.0
    ramp = (c - cos_outer) / (cos_inner - cos_outer)
    return ramp * ramp


def cone_power(falloff, inner, outer, n=20000):
    """The integral of falloff over the solid angle of the cone (midpoint rule in theta)."""
    d = outer / n
    return sum(falloff((k + 0.5) * d, inner, outer) * math.sin((k + 0.5) * d) * 2 * math.pi * d for k in range(n))


def full_angle(falloff, inner, outer, n=20000):
    """The angle out to which the spot is fully lit: the glTF falloff 1, Blender's its cos(theta)
    factor alone (the smoothstep 1); within 1e-6, on a grid of n steps over the outer angle."""
    theta = 0.0
    for k in range(n + 1):
        t = outer * k / n
        value = falloff(t, inner, outer)
        if value >= (math.cos(t) if falloff is blender_falloff else 1.0) - 1e-6:
            theta = t
        else:
            break
    return theta


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out-dir", default="out/gltf_residuals")
    p.add_argument("--publish", default=None)
    args = p.parse_args()
    fractions = (0.25, 0.5, 0.75, 0.9)
    rows = []
    for file_id, light, inner, outer in SPOTS:
        row = {"id": file_id, "light": light, "inner": f"{inner:.4f}", "outer": f"{outer:.4f}",
               "blend": f"{1.0 - inner / outer:.4f}",
               "full_angle_gltf": f"{full_angle(gltf_falloff, inner, outer):.4f}",
               "full_angle_blender": f"{full_angle(blender_falloff, inner, outer):.4f}",
               "power_ratio": f"{cone_power(gltf_falloff, inner, outer) / cone_power(blender_falloff, inner, outer):.4f}"}
        for f in fractions:
            b = blender_falloff(f * outer, inner, outer)
            row[f"ratio_at_{int(f * 100)}"] = f"{gltf_falloff(f * outer, inner, outer) / b:.4f}" if b > 0 else "nan"
        rows.append(row)
        print(" ".join(f"{k}={v}" for k, v in row.items()))
    os.makedirs(args.out_dir, exist_ok=True)
    path = os.path.join(args.out_dir, "spot_falloff.csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    if args.publish:
        os.makedirs(args.publish, exist_ok=True)
        with open(path) as src, open(os.path.join(args.publish, "spot_falloff.csv"), "w") as dst:
            dst.write(src.read())
    return 0


if __name__ == "__main__":
    sys.exit(main())
