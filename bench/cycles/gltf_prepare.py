"""The files of the Blender comparison (issue 46, bench/cycles/compare_gltf.py), made ready to
render: a .blend exported by Blender's own glTF exporter (bench/gltf_real/export_blend.py), a
scripted scene built and exported by Blender (bench/gltf_real/make_spheres.py), or a
shipped .gltf copied with its buffers and images and, where it has no camera, one camera node
added (the same camera for both renderers). Not part of the article: bench machinery."""
import json
import math
import os
import shutil
import subprocess

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def node_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], dtype=float).reshape(4, 4).T  # column-major
    t = np.eye(4)
    t[:3, 3] = node.get("translation", [0, 0, 0])
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    r = np.eye(4)
    r[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    s = np.diag(list(node.get("scale", [1, 1, 1])) + [1])
    return t @ r @ s


def world_bounds(doc):
    """Bounds of every triangle primitive's POSITION min/max corners, in world space."""
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    scene = doc["scenes"][doc.get("scene", 0)]
    stack = [(n, np.eye(4)) for n in scene.get("nodes", [])]
    while stack:
        index, parent = stack.pop()
        node = doc["nodes"][index]
        m = parent @ node_matrix(node)
        if "mesh" in node:
            for prim in doc["meshes"][node["mesh"]]["primitives"]:
                if prim.get("mode", 4) not in (4, 5, 6):
                    continue
                acc = doc["accessors"][prim["attributes"]["POSITION"]]
                a, b = acc["min"], acc["max"]
                for corner in [(x, y, z) for x in (a[0], b[0]) for y in (a[1], b[1]) for z in (a[2], b[2])]:
                    p = m @ np.array(list(corner) + [1.0])
                    lo, hi = np.minimum(lo, p[:3]), np.maximum(hi, p[:3])
        stack += [(c, m) for c in node.get("children", [])]
    return lo, hi


def quaternion_of(r):
    """Unit quaternion (x, y, z, w) of a rotation matrix (Shepperd's method)."""
    tr = np.trace(r)
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [(r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s, 0.25 * s]
    i = int(np.argmax(np.diag(r)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k]) * 2
    q = [0.0, 0.0, 0.0, (r[k, j] - r[j, k]) / s]
    q[i] = 0.25 * s
    q[j] = (r[j, i] + r[i, j]) / s
    q[k] = (r[k, i] + r[i, k]) / s
    return q


def add_camera(doc, direction, aspect, yfov=0.6):
    """A perspective camera looking at the bounds' centre from `direction` (world, y up), far
    enough that the bounding sphere fills the vertical field of view."""
    lo, hi = world_bounds(doc)
    centre, radius = (lo + hi) / 2, float(np.linalg.norm(hi - lo)) / 2
    d = np.array(direction, dtype=float)
    d /= np.linalg.norm(d)
    eye = centre + d * radius / math.sin(yfov / 2)
    back = d                                   # the camera looks down its -Z
    right = np.cross([0.0, 1.0, 0.0], back)
    right /= np.linalg.norm(right)
    up = np.cross(back, right)
    rot = np.column_stack([right, up, back])
    doc.setdefault("cameras", []).append({"type": "perspective", "name": "bench_camera", "perspective": {
        "yfov": yfov, "aspectRatio": aspect, "znear": radius * 0.01, "zfar": radius * 100}})
    doc["nodes"].append({"name": "bench_camera", "camera": len(doc["cameras"]) - 1,
                         "translation": [float(v) for v in eye],
                         "rotation": [float(v) for v in quaternion_of(rot)]})
    doc["scenes"][doc.get("scene", 0)].setdefault("nodes", []).append(len(doc["nodes"]) - 1)


def prepare(entry, work, blender, log):
    """The glTF file to render for one manifest entry, written under `work`."""
    src = os.path.join(REPO, entry["source"])
    dest_dir = os.path.join(work, entry["id"])
    os.makedirs(dest_dir, exist_ok=True)
    out = os.path.join(dest_dir, entry["id"] + ".gltf")
    if entry["source"].endswith(".py"):     # a scripted scene, built and exported by Blender
        r = subprocess.run([blender, "-b", "--factory-startup", "--python", src, "--", "--out", out],
                           capture_output=True, text=True)
        if r.returncode != 0 or not os.path.exists(out):
            raise RuntimeError(f"{src} failed: {r.stderr.strip()[-400:]}")
        log(f"{entry['id']}: built and exported by Blender {r.stdout.split('Blender ')[-1].split()[0]}")
    elif entry["source"].endswith((".blend", ".blend.gz")):
        # Blender reads a gzip-compressed .blend itself; the name must end in .blend.
        blend = os.path.join(dest_dir, entry["id"] + ".blend")
        shutil.copyfile(src, blend)
        for extra in entry.get("with", []):   # images the .blend names relative to itself
            shutil.copy(os.path.join(REPO, extra), dest_dir)
        cmd = [blender, "-b", "--factory-startup", blend, "--python",
               os.path.join(REPO, "bench", "gltf_real", "export_blend.py"), "--", "--out", out]
        cmd += ["--tangents"] if entry.get("export_tangents") else []
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0 or not os.path.exists(out):
            raise RuntimeError(f"export of {src} failed: {r.stderr.strip()[-400:]}")
        log(f"{entry['id']}: exported by Blender {r.stdout.split('Blender ')[-1].split()[0]}")
    else:
        for name in os.listdir(os.path.dirname(src)):
            path = os.path.join(os.path.dirname(src), name)
            if os.path.isfile(path) and not name.endswith(".gltf"):
                shutil.copy(path, dest_dir)
        with open(src) as f:
            doc = json.load(f)
        if not doc.get("cameras") and "camera" in entry:
            add_camera(doc, entry["camera"]["direction"], entry["width"] / entry["height"],
                       entry["camera"].get("yfov", 0.6))
        with open(out, "w") as f:
            json.dump(doc, f)
    return out


def lambert_copy(path):
    """The control file for stage5: every material Lambert (metallic 0, KHR_materials_specular's
    specularFactor 0, no transmission, clearcoat, sheen or volume), textures and emission kept."""
    with open(path) as f:
        doc = json.load(f)
    for m in doc.get("materials", []):
        m.setdefault("pbrMetallicRoughness", {})["metallicFactor"] = 0.0
        ext = m.setdefault("extensions", {})
        for name in ("KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_clearcoat",
                     "KHR_materials_sheen", "KHR_materials_ior"):
            ext.pop(name, None)
        ext["KHR_materials_specular"] = {"specularFactor": 0.0}
    # A primitive without a material has the default one (metallic 1): give it a white Lambert.
    bare = [prim for mesh in doc.get("meshes", []) for prim in mesh["primitives"] if "material" not in prim]
    if bare:
        doc.setdefault("materials", []).append({"name": "bench_lambert_default", "pbrMetallicRoughness": {
            "metallicFactor": 0.0}, "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}})
        for prim in bare:
            prim["material"] = len(doc["materials"]) - 1
    used = doc.setdefault("extensionsUsed", [])
    if "KHR_materials_specular" not in used:
        used.append("KHR_materials_specular")
    out = path[:-len(".gltf")] + "_lambert.gltf"
    with open(out, "w") as f:
        json.dump(doc, f)
    return out
