"""The environment-map bench's inputs (issue 49, "Measures"), written at run time, never shipped.
Not part of the article: bench machinery for bench/env/*.py and bench/cycles/compare_env.py.

  mirror_sphere(path)      a smooth unit mirror sphere (glTF metal, roughness 0) and a camera on +Z
  patch_map(path, ...)     a grey map with one red square patch centred on a given direction
  sun_map(path)            a dim sky with a 2-texel sun of radiance 1e4 (importance sampling's case)
  upsampled(src, path)     a blender-data world resized to 4096 x 2048 (the table's build time)
The map directions follow docs/environment (Blender's Environment Texture, glTF +Y up):
u = 0.5 + atan2(z, x) / 2 pi, v from the top row = acos(y) / pi.
"""
import base64
import json
import math
import os
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "scenes"))
import make_scenes  # noqa: E402  (the glTF writer and the icosphere)

WORLDS = "/usr/share/blender/datafiles/studiolights/world"


def map_uv(d):
    """(u, v) in [0, 1) of a glTF direction on an unrotated map, v from the image's top."""
    n = math.sqrt(sum(c * c for c in d))
    x, y, z = (c / n for c in d)
    return (0.5 + math.atan2(z, x) / (2 * math.pi)) % 1.0, math.acos(max(-1.0, min(1.0, y))) / math.pi


def mirror_sphere(path, camera_z=3.2, yfov=0.8, subdivisions=5):
    g = make_scenes.Gltf("bench/env/env_scenes.py: a mirror sphere for the orientation check")
    mirror = g.material("mirror", (1.0, 1.0, 1.0), metallic=1.0, roughness=0.0)
    points, faces = make_scenes.icosphere(subdivisions)
    mesh = g.mesh("sphere", points, faces, mirror)
    normals = [tuple(c / math.sqrt(sum(v * v for v in p)) for c in p) for p in points]
    acc = g.add("accessors", {
        "bufferView": g.view(b"".join(struct.pack("<3f", *n) for n in normals), 34962),
        "componentType": make_scenes.FLOAT, "count": len(normals), "type": "VEC3"})
    g.doc["meshes"][mesh]["primitives"][0]["attributes"]["NORMAL"] = acc
    g.node(name="sphere", mesh=mesh)
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": yfov, "aspectRatio": 1.0,
                                                                "znear": 0.1, "zfar": 100}}]
    g.node(name="camera", camera=0, translation=[0, 0, camera_z])
    g.doc["buffers"] = [{"byteLength": len(g.bin), "uri": "data:application/octet-stream;base64," +
                         base64.b64encode(bytes(g.bin)).decode()}]
    with open(path, "w") as f:
        f.write(json.dumps(g.doc) + "\n")
    return path


def oiiotool(*args):
    subprocess.run(["oiiotool"] + list(args), check=True, stdout=subprocess.DEVNULL)


def patch_map(path, direction, width=512, height=256, size=8, grey=0.2, red=20.0):
    """Grey map, one size x size texel red patch whose centre is the texel corner nearest `direction`."""
    u, v = map_uv(direction)
    x0, y0 = int(round(u * width)) - size // 2, int(round(v * height)) - size // 2
    oiiotool("--pattern", f"constant:color={grey},{grey},{grey}", f"{width}x{height}", "3",
             f"--fill:color={red},0,0", f"{size}x{size}+{x0}+{y0}", "-d", "float", "-o", path)
    return (x0 + size / 2) / width, (y0 + size / 2) / height


def sun_map(path, width=1024, height=512, sky=(0.03, 0.04, 0.06), sun=1.0e4, sun_dir=(0.5, 0.6, 0.62)):
    """A dim sky and a 2 x 1 texel sun of radiance `sun` (white) at sun_dir (normalised here)."""
    u, v = map_uv(sun_dir)
    x, y = int(u * width), int(v * height)
    oiiotool("--pattern", "constant:color=" + ",".join(str(c) for c in sky), f"{width}x{height}", "3",
             f"--fill:color={sun},{sun},{sun}", f"2x1+{x}+{y}", "-d", "float", "-o", path)
    return path


def upsampled(src, path, width=4096, height=2048):
    oiiotool(src, "--resize", f"{width}x{height}", "-d", "float", "-o", path)
    return path
