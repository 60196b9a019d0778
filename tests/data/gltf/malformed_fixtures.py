# The malformed glTF fixtures of make_fixtures.py: each file broken in one way, for the
# loader's checks (common/scene/gltf_validate.h); also files that need an extension the
# renderer does not read, and Git LFS pointers in place of a scene or its buffer.
import json
import struct

from gltf_builder import TRIANGLE, U16, Gltf, one_triangle, write_text
from valid_fixtures import sparse_no_view_triangle


# --- Malformed files: one fault each -----------------------------------------------------

def broken():
    write_text("bad_json.gltf", '{"asset": {"version": "2.0"}, "nodes": [ }\n')
    g = one_triangle()
    del g.doc["accessors"][0]["type"]  # tinygltf's own check
    g.write_gltf("tinygltf_error.gltf")
    g = one_triangle()
    g.doc["accessors"][0]["count"] = 40  # 480 bytes from a 36-byte bufferView
    g.write_gltf("accessor_past_view.gltf")
    g = one_triangle()
    g.doc["bufferViews"][0]["byteLength"] = 36
    g.doc["bufferViews"][0]["byteOffset"] = 8
    g.bin += b"\0" * 4  # buffer 40 bytes, view needs 44
    g.write_gltf("view_past_buffer.gltf")
    g = one_triangle()
    g.doc["accessors"][0]["byteOffset"] = 2**64 - 16
    g.write_gltf("accessor_offset_2_64.gltf")
    g = one_triangle()
    g.doc["bufferViews"][0]["byteOffset"] = 2**64 - 8
    g.write_gltf("view_offset_2_64.gltf")
    g = one_triangle()
    g.doc["accessors"][0]["count"] = 0
    g.write_gltf("count_zero.gltf")
    g = Gltf()
    g.node(mesh=g.mesh(TRIANGLE, [0, 1, 7]))
    g.write_gltf("index_past_vertices.gltf")
    g = one_triangle()
    g.doc["materials"] = [{"name": "only"}]
    g.doc["meshes"][0]["primitives"][0]["material"] = 5
    g.write_gltf("material_out_of_range.gltf")
    g = one_triangle()
    g.doc["nodes"][0]["mesh"] = 3
    g.write_gltf("mesh_out_of_range.gltf")
    g = one_triangle()
    g.doc["nodes"][0]["children"] = [9]
    g.write_gltf("node_out_of_range.gltf")
    g = one_triangle()
    g.doc["nodes"][0]["mesh"] = 2**32  # tinygltf would truncate it to 0
    g.write_gltf("index_too_large.gltf")
    g = one_triangle()
    g.doc["nodes"][0]["children"] = [0]
    g.write_gltf("node_own_child.gltf")
    g = one_triangle()
    g.node(root=False, children=[0])
    g.doc["nodes"][0]["children"] = [1]
    g.doc["scenes"][0]["nodes"] = []
    g.write_gltf("node_cycle.gltf")
    one_triangle([(0, 0, 0), (float("nan"), 0, 0), (0, 1, 0)]).write_gltf("nan_position.gltf")
    one_triangle([(0, 0, 0), (1, 0, 0), (0, float("inf"), 0)]).write_gltf("inf_position.gltf")
    g = one_triangle()
    g.doc["nodes"][0]["translation"] = [1e39, 0, 0]  # finite in JSON, infinite as a float
    g.write_gltf("huge_translation.gltf")
    g = one_triangle()
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    g.write_gltf("required_extension.gltf")
    g = one_triangle()
    g.doc["accessors"][0]["componentType"] = U16
    g.write_gltf("position_not_float.gltf")
    for name, uri in (("uri_dotdot.gltf", "../outside.bin"), ("uri_absolute.gltf", "/etc/hostname"),
                      ("uri_encoded_dotdot.gltf", "sub/%2e%2e/%2E%2E/outside.bin")):
        g = one_triangle()
        g.write_gltf(name)
        g.doc["buffers"][0]["uri"] = uri
        write_text(name, json.dumps(g.doc, indent=1) + "\n")
    g = one_triangle()
    g.doc["images"] = [{"bufferView": g.view(b"\x89PNG\r\n\x1a\n"), "mimeType": "image/png"}]
    g.doc["bufferViews"][-1]["byteLength"] = 1000
    g.write_gltf("image_view_past_buffer.gltf")
    g = one_triangle()
    g.write_glb("truncated.glb", bin_chunk_extra=64)


# --- Sparse accessors: one fault each ------------------------------------------------------

def broken_sparse():
    g = sparse_no_view_triangle()
    g.bin[0:8] = struct.pack("<2I", 1, 5)  # count is 3
    g.write_gltf("sparse_index_past_count.gltf")
    g = sparse_no_view_triangle()
    g.bin[0:8] = struct.pack("<2I", 2, 1)
    g.write_gltf("sparse_not_increasing.gltf")
    g = sparse_no_view_triangle()
    g.doc["accessors"][0]["sparse"]["indices"]["byteOffset"] = 4  # 2 u32 from 4: 12 bytes of 8
    g.write_gltf("sparse_indices_past_view.gltf")
    g = sparse_no_view_triangle()
    g.doc["accessors"][0]["sparse"]["count"] = 2**32 + 2  # tinygltf would read 2
    g.write_gltf("sparse_count_too_large.gltf")
    g = sparse_no_view_triangle()
    # 384 MiB of zeros from a few bytes of JSON (11 million triangles: fewer than the BVH's
    # 2^28, which the triangle count refuses before any accessor is read)
    g.doc["accessors"][0]["count"] = 2**25
    g.write_gltf("sparse_zeros_too_large.gltf")


# --- Required extensions the renderer does not read ------------------------------------------

def required_extensions():
    # Draco as exporters write it: the accessors have no data, the primitive's extension
    # points at the compressed bytes (tinygltf alone would call the file malformed)
    g = Gltf()
    view = g.view(b"DRACO" + b"\0" * 11)
    pos = g.add("accessors", {"componentType": 5126, "count": 3, "type": "VEC3"})
    idx = g.add("accessors", {"componentType": U16, "count": 3, "type": "SCALAR"})
    g.add("meshes", {"primitives": [{"attributes": {"POSITION": pos}, "indices": idx, "extensions": {
        "KHR_draco_mesh_compression": {"bufferView": view, "attributes": {"POSITION": 0}}}}]})
    g.node(mesh=0)
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    g.write_gltf("required_draco.gltf")
    g = one_triangle()
    g.doc["bufferViews"][0]["extensions"] = {"EXT_meshopt_compression": {
        "buffer": 0, "byteLength": 36, "byteStride": 12, "count": 3, "mode": "ATTRIBUTES"}}
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["EXT_meshopt_compression", "KHR_mesh_quantization"]
    g.write_gltf("required_meshopt.gltf")
    g = Gltf()
    data = struct.pack("<9H", 0, 0, 0, 65535, 0, 0, 0, 65535, 0)
    pos = g.add("accessors", {"bufferView": g.view(data), "componentType": U16, "count": 3, "type": "VEC3"})
    g.node(mesh=g.add("meshes", {"primitives": [{"attributes": {"POSITION": pos}}]}))
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    g.write_gltf("required_quantization.gltf")
    for name, extension, mime in (("required_basisu.gltf", "KHR_texture_basisu", "image/ktx2"),
                                  ("required_webp.gltf", "EXT_texture_webp", "image/webp")):
        g = one_triangle()
        g.doc["images"] = [{"uri": "texture." + mime[6:], "mimeType": mime}]
        g.doc["textures"] = [{"extensions": {extension: {"source": 0}}}]
        g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = [extension]
        g.write_gltf(name)
    g = one_triangle()
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["EXT_made_up_extension"]
    g.write_gltf("required_unknown.gltf")


# --- Git LFS pointers: a clone without `git lfs pull` ----------------------------------------

LFS_POINTER = ("version https://git-lfs.github.com/spec/v1\n"
               "oid sha256:4d7a214614ab2935c943f9e0ff69d22eadbb8f32b1258daaa5e2ca24d17e2393\n"
               "size 12345\n")


def lfs_pointers():
    write_text("lfs_pointer.gltf", LFS_POINTER)
    write_text("lfs_pointer.glb", LFS_POINTER)
    one_triangle().write_gltf("lfs_buffer.gltf", bin_name="lfs_buffer.bin")
    write_text("lfs_buffer.bin", LFS_POINTER)
