// Tests of the glTF loader's checks (common/scene/gltf_validate.h): each kind of malformed
// file, one fixture from tests/data/gltf each, becomes pt::Error with exit code 3 and a
// one-line message that names what is wrong.
#include <catch2/catch.hpp>

#include "tests/support/gltf_checks.h"

using namespace pt::test;

// --- Malformed files --------------------------------------------------------------------

TEST_CASE("a missing file is an error that names it", "[loader]") {
  require_bad_scene(fixture("no_such_scene.gltf"), {"no_such_scene.gltf", "no such file"});
}

TEST_CASE("a file that is neither .gltf nor .glb is an error", "[loader]") {
  require_bad_scene(fixture("scene.obj"), {"scene.obj", ".gltf or .glb"});
}

TEST_CASE("invalid JSON is an error", "[loader]") {
  require_bad_scene(fixture("bad_json.gltf"), {"bad_json.gltf:", "invalid JSON"});
}

TEST_CASE("tinygltf's own parse errors become one line", "[loader]") {
  require_bad_scene(fixture("tinygltf_error.gltf"), {"tinygltf_error.gltf:", "'type'"});
}

TEST_CASE("an accessor running past its bufferView is an error", "[loader]") {
  require_bad_scene(fixture("accessor_past_view.gltf"),
                    {"accessors[0] (POSITION of meshes[0].primitives[0])", "runs past bufferViews[0]",
                     "needs 480 bytes, has 36", "glTF 2.0 specification"});
}

TEST_CASE("a bufferView running past its buffer is an error", "[loader]") {
  require_bad_scene(fixture("view_past_buffer.gltf"),
                    {"bufferViews[0]", "runs past buffers[0]", "needs 44 bytes, has 40"});
}

TEST_CASE("an accessor byteOffset near 2^64 does not wrap around", "[loader]") {
  require_bad_scene(fixture("accessor_offset_2_64.gltf"), {"runs past bufferViews[0]", "overflow"});
}

TEST_CASE("a bufferView byteOffset near 2^64 does not wrap around", "[loader]") {
  require_bad_scene(fixture("view_offset_2_64.gltf"), {"runs past buffers[0]", "overflow"});
}

TEST_CASE("an accessor with count 0 is an error", "[loader]") {
  require_bad_scene(fixture("count_zero.gltf"), {"accessors[0]", "count 0"});
}

TEST_CASE("an index past the vertex count is an error", "[loader]") {
  require_bad_scene(fixture("index_past_vertices.gltf"),
                    {"indices of meshes[0].primitives[0]", "is 7", "vertex count (3)"});
}

TEST_CASE("a material index out of range is an error", "[loader]") {
  require_bad_scene(fixture("material_out_of_range.gltf"),
                    {"meshes[0].primitives[0].material = 5", "out of range"});
}

TEST_CASE("a mesh index out of range is an error", "[loader]") {
  require_bad_scene(fixture("mesh_out_of_range.gltf"), {"nodes[0].mesh = 3", "out of range"});
}

TEST_CASE("a node index out of range is an error", "[loader]") {
  require_bad_scene(fixture("node_out_of_range.gltf"), {"nodes[0].children[0] = 9", "out of range"});
}

TEST_CASE("an index too large for an int is an error, not truncated", "[loader]") {
  require_bad_scene(fixture("index_too_large.gltf"), {"nodes[0].mesh = 4294967296", "out of range"});
}

TEST_CASE("a node that is its own child is an error", "[loader]") {
  require_bad_scene(fixture("node_own_child.gltf"), {"nodes[0] is its own child", "cycle"});
}

TEST_CASE("a cycle through two nodes is an error", "[loader]") {
  require_bad_scene(fixture("node_cycle.gltf"), {"own ancestor", "cycle"});
}

TEST_CASE("a NaN position is an error", "[loader]") {
  require_bad_scene(fixture("nan_position.gltf"), {"vertex 1", "not finite", "nan"});
}

TEST_CASE("an infinite position is an error", "[loader]") {
  require_bad_scene(fixture("inf_position.gltf"), {"vertex 2", "not finite", "inf"});
}

TEST_CASE("a translation that is infinite as a 32-bit float is an error", "[loader]") {
  require_bad_scene(fixture("huge_translation.gltf"), {"nodes[0].translation[0]", "not a finite"});
}

TEST_CASE("a required extension that is not supported is an error naming it", "[loader]") {
  require_bad_scene(fixture("required_extension.gltf"), {"extensionsRequired", "KHR_draco_mesh_compression"});
}

TEST_CASE("positions that are not 32-bit floats are an error", "[loader]") {
  require_bad_scene(fixture("position_not_float.gltf"), {"POSITION", "VEC3 of FLOAT"});
}

TEST_CASE("buffer URIs may not leave the scene's folder", "[loader]") {
  for (const char* name : {"uri_dotdot.gltf", "uri_absolute.gltf", "uri_encoded_dotdot.gltf"}) {
    INFO(name);
    require_bad_scene(fixture(name), {"buffers[0].uri", "outside the scene's folder"});
  }
}

TEST_CASE("an image whose bufferView runs past its buffer is an error", "[loader]") {
  require_bad_scene(fixture("image_view_past_buffer.gltf"),
                    {"images[0]", "runs past buffers[0]", "needs 1036 bytes, has 44"});
}

TEST_CASE("a .glb whose BIN chunk runs past the end of the file is an error", "[loader]") {
  require_bad_scene(fixture("truncated.glb"), {"truncated.glb:", "BIN chunk"});
}
