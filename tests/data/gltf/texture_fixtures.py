# The texture and vertex-colour fixtures of make_fixtures.py (issue #19;
# common/scene/gltf_textures.h): PNG images built byte by byte, as data URIs, in a .glb's
# buffer and in files beside the scene; samplers, texture transforms, images that cannot be
# decoded or are too large, the fuzzer's image-bearing seed and the image tests' sky planes.
import base64
import struct

from gltf_builder import FLOAT, QUAD, Gltf


# A Lambertian glTF material: metallic 0 and no specular layer (KHR_materials_specular's
# specularFactor 0), for the image tests whose closed forms are Lambert's.
LAMBERT = {"KHR_materials_specular": {"specularFactor": 0}}

def png(width, height, rows, color_type=6, depth=8):
    """A PNG from rows of raw samples (bytes, filter 0 prepended here): colour type 6 RGBA,
    2 RGB, 0 grey, 4 grey + alpha; depth 8 or 16 (big-endian samples), 1 for grey."""
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    header = struct.pack(">IIBBBBB", width, height, depth, color_type, 0, 0, 0)
    raw = b"".join(b"\0" + bytes(r) for r in rows)
    assert len(rows) == height
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) +
            chunk(b"IEND", b""))


def data_uri(data, mime="image/png"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())


# The texture of tex_basic.gltf: 2 x 2 RGBA texels, row 0 on top.
CHECKER_2X2 = png(2, 2, [[255, 0, 0, 255, 0, 255, 0, 255], [0, 0, 255, 255, 128, 128, 128, 128]])


def textured_quad(g, material=0, colors=None, uv=((0, 0), (1, 0), (1, 1), (0, 1)), points=QUAD):
    """A quad (two triangles) with TEXCOORD_0 (and COLOR_0 as VEC4 floats when given)."""
    attrs = {"POSITION": g.positions(points)}
    attrs["TEXCOORD_0"] = g.add("accessors", {"bufferView": g.view(b"".join(struct.pack("<2f", *t) for t in uv)),
                                              "componentType": FLOAT, "count": 4, "type": "VEC2"})
    if colors:
        data = b"".join(struct.pack("<4f", *c) for c in colors)
        attrs["COLOR_0"] = g.add("accessors", {"bufferView": g.view(data), "componentType": FLOAT,
                                               "count": 4, "type": "VEC4"})
    prim = {"attributes": attrs, "indices": g.indices([0, 1, 2, 0, 2, 3]), "material": material}
    return g.add("meshes", {"primitives": [prim]})


def textures():
    import os

    from gltf_builder import HERE
    # tex_basic: base colour (clamp / mirrored, nearest), emissive (defaults, transformed),
    # metallic-roughness (a 16-bit RGB image), normal and occlusion textures (warned about),
    # COLOR_0; material 1 and images 2 and 3 are never used, so never read or decoded
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_texture_transform"]
    mr16 = png(1, 1, [struct.pack(">3H", 0, 32896, 65535)], color_type=2, depth=16)
    g.doc["images"] = [{"uri": data_uri(CHECKER_2X2)}, {"bufferView": g.view(mr16), "mimeType": "image/png"},
                       {"uri": data_uri(b"\x89PNG\r\n\x1a\n broken")}, {"uri": "not_there.png"}]
    g.doc["samplers"] = [{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728, "minFilter": 9728}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 0}, {"source": 1}, {"source": 2}, {"source": 3}]
    transform = {"offset": [0.25, 0.5], "rotation": 0.3, "scale": [2, 3]}
    g.doc["materials"] = [
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1], "baseColorTexture": {"index": 0},
                                  "metallicFactor": 0.75, "roughnessFactor": 0.5,
                                  "metallicRoughnessTexture": {"index": 2}},
         "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 1, "extensions": {"KHR_texture_transform": transform}},
         "normalTexture": {"index": 1}, "occlusionTexture": {"index": 1}},
        {"pbrMetallicRoughness": {"baseColorTexture": {"index": 3}, "metallicRoughnessTexture": {"index": 4}}}]
    colors = [(1, 0, 0, 1), (0, 1, 0, 1), (0, 0, 1, 0.5), (1, 1, 1, 1)]
    g.node(mesh=textured_quad(g, colors=colors))
    g.write_gltf("tex_basic.gltf")
    # tex_channels: grey, grey + alpha and palette-free RGB images give RGBA texels
    g = Gltf()
    grey = png(2, 1, [[0, 200]], color_type=0)
    grey_alpha = png(1, 1, [[77, 99]], color_type=4)
    rgb = png(1, 1, [[10, 20, 30]], color_type=2)
    g.doc["images"] = [{"uri": data_uri(grey)}, {"uri": data_uri(grey_alpha)}, {"uri": data_uri(rgb)}]
    g.doc["textures"] = [{"source": 0}, {"source": 1}, {"source": 2}]
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                    "metallicRoughnessTexture": {"index": 2}},
                           "emissiveTexture": {"index": 1}, "emissiveFactor": [1, 1, 1]}]
    g.node(mesh=textured_quad(g))
    g.write_gltf("tex_channels.gltf")
    # an image in a file next to the scene; TEXCOORD_1 asked for (the quad has none: warned, read at (0, 0))
    with open(os.path.join(HERE, "tex_external.png"), "wb") as f:
        f.write(png(1, 1, [[10, 20, 30, 40]]))
    # a Git LFS pointer in place of the image file (a clone without `git lfs pull`)
    with open(os.path.join(HERE, "tex_lfs.png"), "w") as f:
        f.write("version https://git-lfs.github.com/spec/v1\n"
                "oid sha256:4d7a214614ab2935c943f9e0ff69d22eadbb8f32b1258daaa5e2ca24d17e2393\nsize 12345\n")
    for name, uri in (("tex_external.gltf", "tex_external.png"), ("tex_missing.gltf", "tex_missing.png"),
                      ("tex_lfs.gltf", "tex_lfs.png"),
                      # files outside the scene's folder (tests/CMakeLists.txt); "../gltf/x.png"
                      # would resolve back inside it, and is read
                      ("tex_outside.gltf", "../../CMakeLists.txt"),
                      ("tex_outside_encoded.gltf", "%2E%2E/%2E%2E/CMakeLists.txt")):
        g = Gltf()
        g.doc["images"] = [{"uri": uri}]
        g.doc["textures"] = [{"source": 0}]
        g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}}]
        g.node(mesh=textured_quad(g))
        g.write_gltf(name)
    # images that cannot be decoded, or are too large: each used by the quad's material
    truncated = CHECKER_2X2[:len(CHECKER_2X2) - 20]  # the IDAT chunk cut short
    import zlib
    garbage = b"not deflate data"
    bad_deflate = (CHECKER_2X2[:33] + struct.pack(">I", len(garbage)) + b"IDAT" + garbage +
                   struct.pack(">I", zlib.crc32(b"IDAT" + garbage)) + CHECKER_2X2[-12:])  # chunks intact
    wide = png(16385, 1, [[0] * 16385], color_type=0)
    huge = png(16384, 16384, [b"\0" * 2048] * 16384, color_type=0, depth=1)  # 1 GiB of texels
    cases = [("tex_malformed.gltf", [data_uri(b"\x89PNG\r\n\x1a\n" + b"\0\0\0\x0dIHDR broken")]),
             ("tex_not_png.gltf", [data_uri(b"GIF89a\1\0\1\0\0\0\0;", "image/gif")]),
             ("tex_truncated.glb", [truncated]), ("tex_bad_deflate.glb", [bad_deflate]),
             ("tex_oversized.gltf", [data_uri(wide)]),
             ("tex_total.glb", [huge, huge])]
    for name, images in cases:
        g = Gltf()
        views = {}  # the same bytes in one bufferView (tex_total's two images)
        g.doc["images"] = [{"uri": i} if isinstance(i, str) else
                           {"bufferView": views.setdefault(i, g.view(i)) if i not in views else views[i],
                            "mimeType": "image/png"} for i in images]
        g.doc["textures"] = [{"source": k} for k in range(len(images))]
        g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        if len(images) > 1:
            g.doc["materials"][0]["emissiveTexture"] = {"index": 1}
        g.node(mesh=textured_quad(g))
        if name.endswith(".glb"):
            g.write_glb(name)
        else:
            g.write_gltf(name)
    # KHR_texture_transform's own example: offset (0, 1), a quarter turn, scale 0.5 read
    # the image's lower-left quadrant, turned
    g = Gltf()
    g.doc["images"] = [{"uri": data_uri(CHECKER_2X2)}]
    g.doc["textures"] = [{"source": 0}]
    example = {"offset": [0, 1], "rotation": 1.57079632679, "scale": [0.5, 0.5]}
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {
        "index": 0, "extensions": {"KHR_texture_transform": example}}}}]
    g.node(mesh=textured_quad(g))
    g.write_gltf("tex_transform.gltf")
    # a sampler with a wrap mode glTF does not have; a texture index out of range
    g = Gltf()
    g.doc["images"] = [{"uri": data_uri(CHECKER_2X2)}]
    g.doc["samplers"] = [{"wrapS": 1234}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}]
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    g.node(mesh=textured_quad(g))
    g.write_gltf("tex_bad_sampler.gltf")
    g.doc["samplers"] = [{}]
    g.doc["materials"][0]["emissiveTexture"] = {"index": 3}
    g.write_gltf("tex_bad_index.gltf")
    # the image-bearing seed of the fuzzer's corpus (tests/fuzz): a .glb whose quad reads
    # three textures and COLOR_0, under a camera
    g = Gltf()
    g.doc["images"] = [{"bufferView": g.view(CHECKER_2X2), "mimeType": "image/png"},
                       {"bufferView": g.view(mr16), "mimeType": "image/png"}]
    g.doc["samplers"] = [{"wrapS": 33648, "wrapT": 33071, "magFilter": 9729}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 1}]
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                    "metallicRoughnessTexture": {"index": 1}},
                           "emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform": transform}},
                           "emissiveFactor": [0.5, 0.5, 0.5]}]
    g.doc["extensionsUsed"] = ["KHR_texture_transform"]
    g.doc["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}]
    g.node(translation=[0.5, 0.5, 2], camera=0)
    g.node(mesh=textured_quad(g, colors=colors))
    g.write_glb("tex_seed.glb")
    # the sky plane of the image tests (tests/stages/test_texture_images.cpp): a 2 x 2 quad
    # at z = 0 filling an orthographic camera's view, a 4 x 4 texture repeated twice over it
    g = Gltf()
    rows = [sum(([(37 * i + 11) % 256, (91 * i + 200) % 256, (53 * i + 7) % 256, 255]
                 for i in range(4 * y, 4 * y + 4)), []) for y in range(4)]
    g.doc["images"] = [{"uri": data_uri(png(4, 4, rows))}]
    g.doc["samplers"] = [{"magFilter": 9728}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}]
    # Lambertian: no specular layer (KHR_materials_specular's factor 0), the glTF material's base alone
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 1, 1], "baseColorTexture": {"index": 0},
                                                    "metallicFactor": 0}, "extensions": LAMBERT}]
    g.doc["extensionsUsed"] = ["KHR_materials_specular"]
    g.doc["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}]
    g.node(translation=[0, 0, 1], camera=0)
    plane = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    g.node(mesh=textured_quad(g, uv=((0, 2), (2, 2), (2, 0), (0, 0)), points=plane))
    g.write_gltf("tex_sky_plane.gltf")
    # the sky plane with holes (alphaMode MASK, cutoff 0.5): its texels' alpha a checkerboard
    # of 0 and 255; before it at z = 0.5 a 6 x 6 quad whose MASK material has alpha 0.2 and no
    # texture (a hole everywhere); a BLEND quad out of the view (drawn opaque, warned about)
    g = Gltf()
    rows = [sum(([(37 * i + 11) % 256, (91 * i + 200) % 256, (53 * i + 7) % 256, 255 * ((i + y) % 2)]
                 for i in range(4 * y, 4 * y + 4)), []) for y in range(4)]
    g.doc["images"] = [{"uri": data_uri(png(4, 4, rows))}]
    g.doc["samplers"] = [{"magFilter": 9728}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}]
    g.doc["materials"] = [
        {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 1, 1], "baseColorTexture": {"index": 0},
                                  "metallicFactor": 0}, "alphaMode": "MASK", "extensions": LAMBERT},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 0.2], "metallicFactor": 0},
         "alphaMode": "MASK", "alphaCutoff": 0.25, "extensions": LAMBERT},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 0.2], "metallicFactor": 0}, "alphaMode": "BLEND",
         "extensions": LAMBERT}]
    g.doc["extensionsUsed"] = ["KHR_materials_specular"]
    g.doc["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}]
    g.node(translation=[0, 0, 1], camera=0)
    g.node(mesh=textured_quad(g, uv=((0, 2), (2, 2), (2, 0), (0, 0)), points=plane))
    g.node(mesh=textured_quad(g, material=1, points=[(-3, -3, 0.5), (3, -3, 0.5), (3, 3, 0.5), (-3, 3, 0.5)]))
    g.node(mesh=textured_quad(g, material=2, points=[(10, 0, 0), (11, 0, 0), (11, 1, 0), (10, 1, 0)]))
    g.write_gltf("tex_mask.gltf")
