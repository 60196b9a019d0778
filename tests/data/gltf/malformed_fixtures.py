# The malformed glTF fixtures of make_fixtures.py: each file broken in one way, for the
# loader's checks (common/scene/gltf_validate.h).
import json

from gltf_builder import TRIANGLE, U16, Gltf, one_triangle, write_text


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
