#!/usr/bin/env python3
# Writes the glTF scenes shipped with the project, read by the loader of the contract (README.md)
# "Scenes": cornell.gltf (the Cornell box of builtin:cornell as a file) and
# glossy_glass.gltf (GGX metal, glass, an area light and a point light). Standard library only.
import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
FLOAT, U16 = 5126, 5123

# A cube [-1, 1]^3: 8 corners, 6 faces counter-clockwise seen from outside (split into
# triangles along the same diagonals as add_box of builtin_scenes.cpp).
CUBE_POINTS = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
CUBE_QUADS = [(1, 5, 7, 3), (4, 0, 2, 6),   # +z, -z
              (5, 4, 6, 7), (0, 1, 3, 2),   # +x, -x
              (3, 7, 6, 2), (0, 4, 5, 1)]   # +y, -y


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def outward(points, triangles):
    """Checks that every triangle of a closed mesh around the origin faces away from it."""
    for t in triangles:
        p0, p1, p2 = (points[i] for i in t)
        centre = tuple((a + b + c) / 3 for a, b, c in zip(p0, p1, p2))
        assert dot(cross(sub(p1, p0), sub(p2, p0)), centre) > 0, t
    return triangles


def quads_to_triangles(quads):
    return [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]


def icosphere(subdivisions):
    """A unit icosphere: the icosahedron with each triangle split in four, pushed out."""
    g = (1 + math.sqrt(5)) / 2
    points = [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g),
              (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]
    points = [tuple(x / math.sqrt(1 + g * g) for x in p) for p in points]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                m = tuple((x + y) / 2 for x, y in zip(points[a], points[b]))
                n = math.sqrt(dot(m, m))
                points.append(tuple(x / n for x in m))
                middle[key] = len(points) - 1
            return middle[key]

        faces = [t for a, b, c in faces
                 for t in ((a, mid(a, b), mid(c, a)), (b, mid(b, c), mid(a, b)),
                           (c, mid(c, a), mid(b, c)), (mid(a, b), mid(b, c), mid(c, a)))]
    return points, outward(points, faces)


class Gltf:
    """A glTF document under construction with one embedded buffer."""

    def __init__(self, generator):
        self.doc = {"asset": {"version": "2.0", "generator": generator}, "scene": 0,
                    "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                    "accessors": [], "bufferViews": [], "buffers": []}
        self.bin = bytearray()
        self.mesh_data = []  # (points, triangles, material) of each mesh, for check_coplanar

    def add(self, array, item):
        self.doc.setdefault(array, []).append(item)
        return len(self.doc[array]) - 1

    def view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data), "target": target}
        self.bin += data
        return self.add("bufferViews", view)

    def mesh(self, name, points, triangles, material):
        self.mesh_data.append((points, triangles, material))
        lo = [min(p[k] for p in points) for k in range(3)]
        hi = [max(p[k] for p in points) for k in range(3)]
        pos = self.add("accessors", {
            "bufferView": self.view(b"".join(struct.pack("<3f", *p) for p in points), 34962),
            "componentType": FLOAT, "count": len(points), "type": "VEC3", "min": lo, "max": hi})
        flat = [i for t in triangles for i in t]
        idx = self.add("accessors", {
            "bufferView": self.view(struct.pack("<%dH" % len(flat), *flat), 34963),
            "componentType": U16, "count": len(flat), "type": "SCALAR"})
        return self.add("meshes", {"name": name, "primitives": [
            {"attributes": {"POSITION": pos}, "indices": idx, "material": material}]})

    def material(self, name, base, metallic=0.0, roughness=1.0, **extra):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(base) + [1.0],
                                                    "metallicFactor": metallic,
                                                    "roughnessFactor": roughness}}
        m.update(extra)
        return self.add("materials", m)

    def node(self, **fields):
        index = self.add("nodes", fields)
        self.doc["scenes"][0]["nodes"].append(index)
        return index

    def world_triangles(self):
        """Every triangle of the scene in world space, with its node's name and material."""
        out = []
        for node in self.doc["nodes"]:
            if "mesh" not in node:
                continue
            points, triangles, material = self.mesh_data[node["mesh"]]
            world = [transform(node, p) for p in points]
            out += [(node["name"], material, tuple(world[i] for i in t)) for t in triangles]
        return out

    def check_coplanar(self):
        """Refuses two overlapping triangles in one plane where a ray can reach the tie: renderers
        resolve it differently (a glass cube whose bottom lay on the floor rendered 4.5% darker
        in Cycles than here). Faces of opaque closed solids resting on a surface are allowed:
        the only rays that could meet them would start inside the solid."""
        transmissive = {i for i, m in enumerate(self.doc["materials"])
                        if "KHR_materials_transmission" in m.get("extensions", {})}
        tris = self.world_triangles()
        for i, (name_a, mat_a, a) in enumerate(tris):
            for name_b, mat_b, b in tris[i + 1:]:
                if name_a == name_b or (mat_a not in transmissive and mat_b not in transmissive):
                    continue
                if coplanar_overlap(a, b):
                    raise SystemExit("make_scenes.py: %s and %s have overlapping faces in one plane; "
                                     "move one of them apart" % (name_a, name_b))

    def write(self, name):
        self.check_coplanar()
        self.doc["buffers"] = [{"byteLength": len(self.bin), "uri": "data:application/octet-stream;base64," +
                                base64.b64encode(bytes(self.bin)).decode()}]
        with open(os.path.join(HERE, name), "w") as f:
            f.write(json.dumps(self.doc, indent=1) + "\n")


def rotate(q, v):
    """v rotated by the unit quaternion q = (x, y, z, w)."""
    u, w = q[:3], q[3]
    t = tuple(2 * c for c in cross(u, v))
    return tuple(v[k] + w * t[k] + cross(u, t)[k] for k in range(3))


def transform(node, p):
    """A point of a node's mesh in world space (translation, rotation, scale; no parents)."""
    s = node.get("scale", [1, 1, 1])
    p = tuple(p[k] * s[k] for k in range(3))
    p = rotate(node.get("rotation", [0, 0, 0, 1]), p)
    return tuple(p[k] + node.get("translation", [0, 0, 0])[k] for k in range(3))


def coplanar_overlap(a, b, eps=1e-6):
    """Whether triangles a and b lie in one plane and share an area (not only an edge)."""
    n = cross(sub(a[1], a[0]), sub(a[2], a[0]))
    size = math.sqrt(dot(n, n))
    if size == 0:
        return False
    n = tuple(c / size for c in n)
    scale = max(abs(c) for p in a + b for c in p) or 1.0
    if any(abs(dot(n, sub(p, a[0]))) > eps * scale for p in b):
        return False
    # Project on the plane's two other axes; the triangles overlap unless an edge separates them.
    drop = max(range(3), key=lambda k: abs(n[k]))
    a2 = [tuple(p[k] for k in range(3) if k != drop) for p in a]
    b2 = [tuple(p[k] for k in range(3) if k != drop) for p in b]
    for tri in (a2, b2):
        for k in range(3):
            p, q = tri[k], tri[(k + 1) % 3]
            axis = (q[1] - p[1], p[0] - q[0])
            pa = [axis[0] * x + axis[1] * y for x, y in a2]
            pb = [axis[0] * x + axis[1] * y for x, y in b2]
            if max(pa) <= min(pb) + eps * scale * scale or max(pb) <= min(pa) + eps * scale * scale:
                return False
    return True


def about_y(angle):
    return [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)]


def about_x(angle):
    return [math.sin(angle / 2), 0.0, 0.0, math.cos(angle / 2)]


def emissive(strength, color):
    # glTF keeps emissiveFactor in [0, 1]; KHR_materials_emissive_strength scales it
    peak = max(color)
    return {"emissiveFactor": [c / peak for c in color],
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength * peak}}}


# Lambertian: metallic 0 and no specular layer (KHR_materials_specular's specularFactor 0),
# the built-in scenes' diffuse material as a glTF material
LAMBERT = {"KHR_materials_specular": {"specularFactor": 0.0}}


def cornell_room(g):
    """The room of builtin:cornell, [-1, 1]^3 open at +z, with its ceiling light; returns the white material."""
    white = g.material("white", (0.73, 0.73, 0.73), extensions=LAMBERT)
    red = g.material("red", (0.65, 0.05, 0.05), extensions=LAMBERT)
    green = g.material("green", (0.12, 0.45, 0.15), extensions=LAMBERT)
    light_fields = emissive(1.0, (17.0, 12.0, 4.0))
    light_fields["extensions"].update(LAMBERT)
    light = g.material("light", (0.78, 0.78, 0.78), **light_fields)
    # Each wall faces into the room (counter-clockwise seen from inside)
    walls = [("floor", white, [(-1, -1, 1), (1, -1, 1), (1, -1, -1), (-1, -1, -1)]),
             ("ceiling", white, [(-1, 1, -1), (1, 1, -1), (1, 1, 1), (-1, 1, 1)]),
             ("back", white, [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1)]),
             ("left", red, [(-1, -1, 1), (-1, -1, -1), (-1, 1, -1), (-1, 1, 1)]),
             ("right", green, [(1, -1, -1), (1, -1, 1), (1, 1, 1), (1, 1, -1)])]
    for name, material, quad in walls:
        g.node(name=name, mesh=g.mesh(name, quad, [(0, 1, 2), (0, 2, 3)], material))
    lamp = [(-0.25, 0.998, -0.25), (0.25, 0.998, -0.25), (0.25, 0.998, 0.25), (-0.25, 0.998, 0.25)]
    g.node(name="light", mesh=g.mesh("light", lamp, [(0, 1, 2), (0, 2, 3)], light))  # faces down
    return white


def cornell():
    # The same box as builtin:cornell, seen from z = 3.9
    g = Gltf("make_scenes.py: Cornell box")
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength", "KHR_materials_specular"]
    white = cornell_room(g)
    cube = g.mesh("cube", CUBE_POINTS, outward(CUBE_POINTS, quads_to_triangles(CUBE_QUADS)), white)
    g.node(name="short_box", mesh=cube, translation=[0.33, -0.7, 0.3], rotation=about_y(-0.31), scale=[0.3] * 3)
    g.node(name="tall_box", mesh=cube, translation=[-0.35, -0.4, -0.3], rotation=about_y(0.29),
           scale=[0.3, 0.6, 0.3])
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.6911, "znear": 0.1, "zfar": 100}}]
    g.node(name="camera", camera=0, translation=[0, 0, 3.9])
    g.write("cornell.gltf")


def glossy_glass():
    g = Gltf("make_scenes.py: glossy metal and glass")
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength", "KHR_materials_transmission",
                               "KHR_materials_ior", "KHR_lights_punctual"]
    floor = g.material("floor", (0.8, 0.8, 0.8))
    copper = g.material("copper", (0.95, 0.64, 0.54), metallic=1.0, roughness=0.3)
    glass = g.material("glass", (1.0, 1.0, 1.0), roughness=0.0, extensions={
        "KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.5}})
    lamp = g.material("lamp", (0.8, 0.8, 0.8), **emissive(10.0, (1.0, 1.0, 1.0)))
    quad = [(-1, 0, 1), (1, 0, 1), (1, 0, -1), (-1, 0, -1)]  # faces +y
    g.node(name="floor", mesh=g.mesh("floor", quad, [(0, 1, 2), (0, 2, 3)], floor), scale=[5, 1, 5])
    points, faces = icosphere(2)
    g.node(name="metal_sphere", mesh=g.mesh("icosphere", points, faces, copper), translation=[-1.2, 1, 0])
    cube = g.mesh("cube", CUBE_POINTS, outward(CUBE_POINTS, quads_to_triangles(CUBE_QUADS)), glass)
    # Lifted 0.01 off the floor: resting on it, its bottom face would share the floor's plane
    # (check_coplanar refuses that).
    g.node(name="glass_cube", mesh=cube, translation=[1.2, 0.76, 0.3], rotation=about_y(0.52), scale=[0.75] * 3)
    down = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)]  # faces -y
    g.node(name="area_light", mesh=g.mesh("area_light", down, [(0, 1, 2), (0, 2, 3)], lamp), translation=[0, 4, 0],
           scale=[1.5, 1, 1.5])
    # KHR_lights_punctual's intensity is in candela: 20 W/sr at 683 lm/W.
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "warm_point", "type": "point", "color": [1.0, 0.9, 0.8], "intensity": 20.0 * 683}]}}
    g.node(name="point_light", translation=[2, 3, 3], extensions={"KHR_lights_punctual": {"light": 0}})
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1, "zfar": 100}}]
    g.node(name="camera", camera=0, translation=[0, 2.2, 7], rotation=about_x(-math.atan2(1.4, 7)))
    g.write("glossy_glass.gltf")


if __name__ == "__main__":
    cornell()
    glossy_glass()
