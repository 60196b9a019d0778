# The valid glTF fixtures of make_fixtures.py: small files, each showing one rule of the
# loader (the contract (README.md) "Scenes"): transforms, index types, layouts, cameras,
# materials, point lights, a .glb, a Blender-like file with what is not modelled, sparse
# accessors, and texture coordinates and colours of each component type. The textures'
# own fixtures are in texture_fixtures.py.
import math
import struct

from gltf_builder import FLOAT, QUAD, TRIANGLE, U8, U16, U32, Gltf, one_triangle
from texture_fixtures import CHECKER_2X2, data_uri


# --- Valid files: one rule each --------------------------------------------------------

def transforms():
    # parent: T(1,2,3) R(90 deg about z) S(2); child: T(0,0,-1) S(1,3,1); a triangle in child
    s = math.sqrt(0.5)
    g = Gltf()
    mesh = g.mesh(TRIANGLE)
    child = g.node(root=False, translation=[0, 0, -1], scale=[1, 3, 1], mesh=mesh)
    g.node(translation=[1, 2, 3], rotation=[0, 0, s, s], scale=[2, 2, 2], children=[child])
    g.write_gltf("transform_trs.gltf")
    # the same two transforms as column-major matrices
    g = Gltf()
    mesh = g.mesh(TRIANGLE)
    child = g.node(root=False, matrix=[1, 0, 0, 0, 0, 3, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1], mesh=mesh)
    g.node(matrix=[0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1], children=[child])
    g.write_gltf("transform_matrix.gltf")


def index_types():
    # a quad drawn from vertices 256..259 (u16, u32: the high bytes count) or 0..3 (u8)
    for ctype, name, first in ((U8, "indices_u8.gltf", 0), (U16, "indices_u16.gltf", 256),
                               (U32, "indices_u32.gltf", 256)):
        g = Gltf()
        points = [(9, 9, 9)] * first + QUAD
        g.node(mesh=g.mesh(points, [first + i for i in (0, 1, 2, 0, 2, 3)], ctype=ctype))
        g.write_gltf(name)
    g = Gltf()
    g.node(mesh=g.mesh(QUAD[:3] + [QUAD[0], QUAD[2], QUAD[3]]))
    g.write_gltf("non_indexed.gltf")


def interleaved():
    # each vertex: NORMAL (12 bytes), POSITION (12 bytes), 4 bytes of padding
    g = Gltf()
    data = b"".join(struct.pack("<3f3f4x", 0, 0, 1, *p) for p in [(2, 0, 0), (3, 0, 0), (2, 1, 0)])
    view = g.view(data, stride=28)
    normal = g.add("accessors", {"bufferView": view, "componentType": FLOAT, "count": 3, "type": "VEC3"})
    pos = g.add("accessors", {"bufferView": view, "byteOffset": 12, "componentType": FLOAT,
                              "count": 3, "type": "VEC3"})
    mesh = g.add("meshes", {"primitives": [{"attributes": {"NORMAL": normal, "POSITION": pos}}]})
    g.node(mesh=mesh)
    g.write_gltf("interleaved.gltf")


def cameras():
    s = math.sqrt(0.5)
    g = one_triangle()
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1, "aspectRatio": 3.0}},
                        {"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1.5, "znear": 0.1, "zfar": 100}}]
    # parent T(0,1,5) -> [middle -> child R(90 deg about y) with the perspective camera,
    #                     sibling with the orthographic one]: depth first meets the perspective
    # camera first, breadth first or children in reverse would meet the orthographic one
    child = g.node(root=False, rotation=[0, s, 0, s], camera=0)
    middle = g.node(root=False, children=[child])
    ortho = g.node(root=False, translation=[0, 0, 10], camera=1)
    g.node(translation=[0, 1, 5], children=[middle, ortho])
    g.write_gltf("camera_perspective.gltf")
    g = one_triangle()
    g.doc["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1.5, "znear": 0.1, "zfar": 100}}]
    g.node(translation=[0, 0, 10], camera=0)
    g.write_gltf("camera_orthographic.gltf")


def materials():
    g = Gltf()
    pbr = lambda base, metallic, roughness: {"baseColorFactor": base + [1], "metallicFactor": metallic,
                                             "roughnessFactor": roughness}
    g.doc["materials"] = [
        {"name": "diffuse", "pbrMetallicRoughness": pbr([0.8, 0.2, 0.1], 0, 0.7)},
        {"name": "mirror", "pbrMetallicRoughness": pbr([0.9, 0.9, 0.9], 1, 0)},
        {"name": "ggx", "pbrMetallicRoughness": pbr([0.95, 0.64, 0.54], 1, 0.5)},
        {"name": "mixed", "pbrMetallicRoughness": pbr([0.5, 0.5, 0.5], 0.25, 0.4)},
        {"name": "glass", "pbrMetallicRoughness": pbr([1, 1, 1], 0, 0),
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}}},
        {"name": "water", "pbrMetallicRoughness": pbr([0.9, 1, 0.9], 0, 0),
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                        "KHR_materials_ior": {"ior": 1.33}}},
        {"name": "lamp", "pbrMetallicRoughness": pbr([0.5, 0.5, 0.5], 0, 1), "emissiveFactor": [1, 0.5, 0.25],
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
        {"name": "two_sided_lamp", "pbrMetallicRoughness": {"metallicFactor": 0}, "emissiveFactor": [1, 1, 1],
         "doubleSided": True},
        {"name": "unused", "pbrMetallicRoughness": pbr([0, 0, 1], 0, 1)},
    ]
    g.doc["extensionsUsed"] = ["KHR_materials_transmission", "KHR_materials_ior",
                               "KHR_materials_emissive_strength"]
    # triangle i at x = 2i uses material i; the last has none; one more reuses material 0
    for i, material in enumerate([0, 1, 2, 3, 4, 5, 6, 7, None, 0]):
        g.node(translation=[2 * i, 0, 0], mesh=g.mesh(TRIANGLE, material=material))
    g.write_gltf("materials.gltf")


def lights():
    g = one_triangle()
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "spot": {}, "intensity": 7},
        {"type": "point", "color": [0.5, 1, 0.25], "intensity": 10},
        {"type": "directional", "intensity": 2},
        {"type": "point", "intensity": 3}]}}
    light = lambda i: {"KHR_lights_punctual": {"light": i}}
    child = g.node(root=False, translation=[0, 2, 0], extensions=light(1))
    g.node(translation=[1, 0, 0], children=[child])
    g.node(extensions=light(0))
    g.node(extensions=light(2))
    g.node(translation=[0, 0, -4], extensions=light(3))
    g.write_gltf("point_light.gltf")


def glb():
    g = one_triangle([(0, 0, 1), (1, 0, 1), (0, 1, 1)])
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]
    g.node(translation=[0, 0, 5], camera=0)
    g.doc["images"] = [{"bufferView": g.view(CHECKER_2X2), "mimeType": "image/png"}]  # decoded by OpenImageIO
    g.doc["textures"] = [{"source": 0}]
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}]
    g.doc["meshes"][0]["primitives"][0]["material"] = 0
    g.write_glb("textured.glb")


def blender_like():
    g = Gltf()
    g.doc["asset"]["generator"] = "Khronos glTF Blender I/O (imitated)"
    g.doc["extensionsUsed"] = ["KHR_texture_transform", "EXT_made_up_extension"]
    tri = g.positions([(0, 0, 0), (2, 0, 0), (0, 2, 0)])
    line = g.positions([(0, 0, 0), (0, 0, 5)])
    morph = g.positions([(0, 0, 1)] * 3)
    g.doc["meshes"].append({"primitives": [
        {"attributes": {"POSITION": tri}, "mode": 4, "material": 0, "targets": [{"POSITION": morph}]},
        {"attributes": {"POSITION": line}, "mode": 1}], "weights": [0.0]})
    g.doc["materials"] = [{"name": "Material", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": 1, "extensions": {"KHR_texture_transform": {"scale": [2, 2]}}},
        "metallicFactor": 0, "roughnessFactor": 0.5}, "normalTexture": {"index": 0}}]
    # the normal texture's image is missing: normal textures are not modelled, so never read
    g.doc["images"] = [{"uri": "textures/not_there.png"}, {"uri": data_uri(CHECKER_2X2)}]
    g.doc["textures"] = [{"source": 0}, {"source": 1}]
    joint = g.node(root=False, translation=[0, 1, 0])
    g.node(name="Armature", children=[joint])
    g.node(name="Cube", mesh=0, skin=0, translation=[10, 0, 0])
    g.doc["skins"] = [{"joints": [joint]}]
    times = g.add("accessors", {"bufferView": g.view(struct.pack("<2f", 0, 1)), "componentType": FLOAT,
                                "count": 2, "type": "SCALAR", "min": [0], "max": [1]})
    moves = g.positions([(0, 1, 0), (0, 2, 0)])
    g.doc["animations"] = [{"channels": [{"sampler": 0, "target": {"node": joint, "path": "translation"}}],
                            "samplers": [{"input": times, "output": moves}]}]
    g.write_gltf("blender_like.gltf")


def layouts():
    g = one_triangle([(0, 0, 2), (1, 0, 2), (0, 1, 2)])
    g.write_gltf("separate_bin.gltf", bin_name="separate_bin.bin")
    # no scenes: every root node is drawn, children included
    g = Gltf()
    mesh = g.mesh(TRIANGLE)
    child = g.node(root=False, translation=[0, 0, 1], mesh=mesh)
    g.node(mesh=mesh, children=[child])
    g.node(translation=[5, 0, 0], mesh=mesh)
    del g.doc["scene"], g.doc["scenes"]
    g.write_gltf("no_scenes.gltf")
    # two scenes, the second is the default
    g = one_triangle()
    g.node(root=False, translation=[0, 7, 0], mesh=0)
    g.doc["scenes"].append({"nodes": [1]})
    g.doc["scene"] = 1
    g.write_gltf("default_scene.gltf")
    # one good triangle, two without area in the file, one flattened by its node
    g = Gltf()
    g.node(mesh=g.mesh(TRIANGLE + [(0, 0, 0), (1, 1, 1), (2, 2, 2)] + [(1, 0, 0), (1, 0, 0), (0, 1, 0)]))
    g.node(scale=[0, 1, 1], mesh=g.mesh(TRIANGLE))
    g.write_gltf("degenerate.gltf")


def sparse_object(g, indices, ctype, values):
    """An accessor's "sparse": `indices` of type ctype, then `values` (packed bytes)."""
    fmt = {U8: "B", U16: "H", U32: "I"}[ctype]
    return {"count": len(indices),
            "indices": {"bufferView": g.view(struct.pack("<%d%s" % (len(indices), fmt), *indices)),
                        "componentType": ctype},
            "values": {"bufferView": g.view(values)}}


def sparse_no_view_triangle():
    # POSITION without a bufferView: zeros, then elements 1 and 2 set (u32 sparse indices)
    g = Gltf()
    values = struct.pack("<6f", 1, 0, 0, 0, 1, 0)
    pos = g.add("accessors", {"componentType": FLOAT, "count": 3, "type": "VEC3",
                              "sparse": sparse_object(g, [1, 2], U32, values)})
    g.node(mesh=g.add("meshes", {"primitives": [{"attributes": {"POSITION": pos}}]}))
    return g


def sparse():
    # a quad and a second quad beside it, dense; then the same mesh with POSITION and the
    # indices both sparse over a damaged bufferView (u8 and u16 sparse indices)
    points = QUAD + [(2, 0, 0), (2, 1, 0)]
    indices = [0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2]
    g = Gltf()
    g.node(mesh=g.mesh(points, indices))
    g.write_gltf("sparse_dense.gltf")
    g = Gltf()
    damaged = [p if i not in (2, 5) else (9, 9, 9) for i, p in enumerate(points)]
    g.mesh(damaged, [0, 1, 2, 0, 0, 0] + indices[6:])
    values = struct.pack("<6f", *points[2], *points[5])
    g.doc["accessors"][0]["sparse"] = sparse_object(g, [2, 5], U8, values)
    g.doc["accessors"][1]["sparse"] = sparse_object(g, [4, 5], U16, struct.pack("<2H", 2, 3))
    g.node(mesh=0)
    g.write_gltf("sparse.gltf")
    sparse_no_view_triangle().write_gltf("sparse_no_view.gltf")


def attributes():
    # one triangle with TEXCOORD_0..3 and COLOR_0..2 of each component type the glTF spec
    # allows; 8-bit elements of 2 or 3 bytes are padded to 4 (vertex attribute alignment)
    g = Gltf()
    pos = g.positions(TRIANGLE)

    def attribute(data, ctype, kind, stride=None, normalized=True):
        accessor = {"bufferView": g.view(data, stride), "componentType": ctype, "count": 3, "type": kind}
        if ctype != FLOAT and normalized:
            accessor["normalized"] = True
        return g.add("accessors", accessor)

    uv_float = attribute(struct.pack("<6f", 0.5, 1.5, -1, 2, 0.25, 0), FLOAT, "VEC2")
    uv_u8 = attribute(struct.pack("<2B2x2B2x2B2x", 0, 255, 51, 102, 255, 0), U8, "VEC2", stride=4)
    uv_u16 = attribute(struct.pack("<6H", 0, 65535, 13107, 32768, 65535, 0), U16, "VEC2")
    uv_sparse = g.add("accessors", dict(g.doc["accessors"][uv_float],
                                        sparse=sparse_object(g, [1], U8, struct.pack("<2f", 7, 8))))
    rgb_float = attribute(struct.pack("<9f", 1, 0, 0, 0, 1, 0, 0, 0, 0.5), FLOAT, "VEC3")
    rgba_u8 = attribute(struct.pack("<12B", 255, 0, 0, 255, 0, 51, 0, 102, 0, 0, 255, 0), U8, "VEC4")
    rgba_u16 = attribute(struct.pack("<12H", 65535, 0, 0, 65535, 0, 13107, 0, 0, 0, 0, 65535, 32768),
                         U16, "VEC4")
    rgb_u8 = attribute(struct.pack("<3Bx3Bx3Bx", 255, 0, 51, 0, 255, 0, 0, 0, 255), U8, "VEC3", stride=4)
    g.doc["meshes"].append({"primitives": [{"attributes": {
        "POSITION": pos, "TEXCOORD_0": uv_float, "TEXCOORD_1": uv_u8, "TEXCOORD_2": uv_u16,
        "TEXCOORD_3": uv_sparse, "COLOR_0": rgb_float}},
        {"attributes": {"POSITION": pos, "COLOR_0": rgba_u8, "COLOR_1": rgba_u16, "COLOR_2": rgb_u8}}]})
    g.node(mesh=0)
    g.write_gltf("attributes.gltf")
    # KHR_texture_transform may be required: texture coordinates are read
    g = one_triangle()
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_texture_transform"]
    g.write_gltf("required_texture_transform.gltf")
