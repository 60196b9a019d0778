// The feature set a scene uses (common/scene.h: scene_features), printed by every render's
// summary line: shapes, material kinds, light kinds and the sky.
#include <catch2/catch.hpp>

#include "common/scene_loading.h"

using namespace pt;

TEST_CASE("features: built-in and shipped scenes report what they use", "[features]") {
  CHECK(scene_features(make_builtin_scene("cornell"), glm::vec3(0.0f)) == "triangles; diffuse; emissive triangles");
  CHECK(scene_features(make_builtin_scene("sphere"), glm::vec3(1.0f)) == "spheres; diffuse; sky");
  CHECK(scene_features(make_builtin_scene("mirror"), glm::vec3(0.0f)) == "triangles; diffuse, mirror; emissive triangles");
  CHECK(scene_features(make_builtin_scene("glass_slab"), glm::vec3(0.0f)) == "triangles; diffuse, glass; emissive triangles");
  CHECK(scene_features(make_builtin_scene("point_in_sphere"), glm::vec3(0.0f)) == "spheres; diffuse; point lights");
  CHECK(scene_features(make_builtin_scene("furnace_sphere"), glm::vec3(0.0f)) == "spheres; diffuse; emissive spheres");
  CHECK(scene_features(load_scene(PT_SOURCE_DIR "/scenes/glossy_glass.gltf"), glm::vec3(0.0f)) ==
        "triangles; diffuse, GGX conductor, glass; emissive triangles, point lights");
  Scene empty;
  CHECK(scene_features(empty, glm::vec3(0.0f)) == "none; none; none");
}
