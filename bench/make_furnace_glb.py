#!/usr/bin/env python3
# Writes a furnace of any size as a binary glTF (.glb) to the path given, for the BVH's
# scale check (issue 17: "10 M triangles load and render on the CPU"): a latitude-longitude
# sphere of radius 1 whose triangles emit 1 on both sides and reflect with albedo 0.5, with
# a camera at its centre. Any closed surface gives Le / (1 - albedo) = 2 inside, so the
# render of the largest mesh still has a known answer. Not shipped (10 M triangles: 180 MB).
# Usage: bench/make_furnace_glb.py PATH [TRIANGLES]   (default 10,000,000)
import json
import math
import struct
import sys
from array import array


def main(path, triangles=10_000_000):
    # rows x cols quads, two triangles each; the two pole rows each lose one triangle per
    # quad to a zero-area one, which the loader skips (it says how many): at least
    # `triangles` of them have an area.
    cols = max(3, int(math.sqrt(triangles)))
    rows = max(2, -(-(triangles + 2 * cols) // (2 * cols)))
    points = array("f")
    for r in range(rows + 1):
        theta = math.pi * r / rows
        y, ring = math.cos(theta), math.sin(theta)
        for c in range(cols):
            phi = 2.0 * math.pi * c / cols
            points.extend((ring * math.cos(phi), y, ring * math.sin(phi)))
    indices = array("I")
    for r in range(rows):
        a0, b0 = r * cols, (r + 1) * cols
        for c in range(cols):
            c1 = (c + 1) % cols
            indices.extend((a0 + c, b0 + c, a0 + c1, a0 + c1, b0 + c, b0 + c1))
    lo = [min(points[i::3]) for i in range(3)]
    hi = [max(points[i::3]) for i in range(3)]
    index_bytes = indices.tobytes()
    point_bytes = points.tobytes()
    binary = index_bytes + point_bytes
    doc = {
        "asset": {"version": "2.0", "generator": "bench/make_furnace_glb.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"camera": 0}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.2, "znear": 0.01, "zfar": 10}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": 0, "material": 0, "mode": 4}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0},
                       "emissiveFactor": [1, 1, 1], "doubleSided": True}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(index_bytes), "target": 34963},
                        {"buffer": 0, "byteOffset": len(index_bytes), "byteLength": len(point_bytes),
                         "target": 34962}],
        "accessors": [{"bufferView": 0, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
                      {"bufferView": 1, "componentType": 5126, "count": len(points) // 3, "type": "VEC3",
                       "min": lo, "max": hi}],
    }
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(binary)))
        f.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
        f.write(struct.pack("<II", len(binary), 0x004E4942) + binary)
    print(f"{path}: {len(indices) // 3 - 2 * cols} triangles, and {2 * cols} of zero area at the poles")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: bench/make_furnace_glb.py PATH [TRIANGLES]")
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 10_000_000)
