#!/usr/bin/env python3
# Writes the BVH's measuring scene to the path given (not shipped: 1.3 MB): the Cornell
# box of scenes/make_scenes.py with a finely tessellated sphere (icosphere, 6 subdivisions,
# 81920 triangles) in place of the boxes, for stage1's samples/s with --accel none and bvh.
# The BVH follows the article's GPU section, which ends "yet without an acceleration structure".
import base64
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes"))
import make_scenes  # noqa: E402  (the glTF writer and the icosphere)


def main(path, subdivisions=6):
    g = make_scenes.Gltf("make_sphere_mesh.py: a tessellated sphere in the Cornell box")
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    white = make_scenes.cornell_room(g)
    points, faces = make_scenes.icosphere(subdivisions)
    g.node(name="sphere", mesh=g.mesh("sphere", points, faces, white), translation=[0, -0.45, 0], scale=[0.5] * 3)
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.6911, "znear": 0.1, "zfar": 100}}]
    g.node(name="camera", camera=0, translation=[0, 0, 3.9])
    g.doc["buffers"] = [{"byteLength": len(g.bin), "uri": "data:application/octet-stream;base64," +
                         base64.b64encode(bytes(g.bin)).decode()}]
    with open(path, "w") as f:
        f.write(json.dumps(g.doc) + "\n")
    print(f"{path}: {len(faces) + 12} triangles")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "sphere_mesh.gltf")
