// The feature set a scene uses (common/scene/scene.h: scene_features), printed by every render's
// summary line: shapes, material kinds, light kinds and the sky.
#include <catch2/catch.hpp>

#include "cpu/cpu_variants.h"
#include "common/scene/scene_loading.h"

using namespace pt;

TEST_CASE("features: built-in and shipped scenes report what they use", "[features]") {
  CHECK(scene_features(make_builtin_scene("cornell"), glm::vec3(0.0f)) == "triangles; diffuse; emissive triangles");
  CHECK(scene_features(make_builtin_scene("sphere"), glm::vec3(1.0f)) == "spheres; diffuse; sky");
  CHECK(scene_features(make_builtin_scene("mirror"), glm::vec3(0.0f)) == "triangles; diffuse, mirror; emissive triangles");
  CHECK(scene_features(make_builtin_scene("glass_slab"), glm::vec3(0.0f)) == "triangles; diffuse, glass; emissive triangles");
  CHECK(scene_features(make_builtin_scene("point_in_sphere"), glm::vec3(0.0f)) == "spheres; diffuse; punctual lights");
  CHECK(scene_features(make_builtin_scene("furnace_sphere"), glm::vec3(0.0f)) == "spheres; diffuse; emissive spheres");
  CHECK(scene_features(load_scene(PT_SOURCE_DIR "/scenes/glossy_glass.gltf"), glm::vec3(0.0f)) ==
        "triangles; diffuse, GGX conductor, glass, glTF dielectric; emissive triangles, punctual lights");
  // The benchmark's scenes (bench/runs.txt), and the one with every feature.
  CHECK(scene_features(make_builtin_scene("cornell_glossy"), glm::vec3(0.0f)) == "triangles; diffuse, GGX conductor; emissive triangles");
  CHECK(scene_features(make_builtin_scene("cornell_glass"), glm::vec3(0.0f)) == "triangles, spheres; diffuse, glass; emissive triangles");
  CHECK(scene_features(make_builtin_scene("smallpt"), glm::vec3(0.0f)) == "spheres; diffuse, mirror, glass; emissive spheres");
  CHECK(scene_features(make_builtin_scene("floor_small_light"), glm::vec3(0.0f)) == "triangles; diffuse; emissive triangles");
  CHECK(scene_features(make_builtin_scene("floor_large_light"), glm::vec3(0.0f)) == "triangles; diffuse; emissive triangles");
  CHECK(scene_feature_mask(make_builtin_scene("every_feature"), glm::vec3(0.1f)) == (kFeatureAll & ~kFeatureEnvironment));
  // An environment map (--env) is the sky too: with it, every feature.
  Scene lit = make_builtin_scene("every_feature");
  lit.environment = make_environment("grey", 4, 2, std::vector<float>(24, 0.5f), 1.0f, 0.0f);
  CHECK(scene_feature_mask(lit, glm::vec3(0.0f)) == kFeatureAll);
  CHECK(scene_features(lit, glm::vec3(0.0f)).find("sky, environment map") != std::string::npos);
  Scene empty;
  CHECK(scene_features(empty, glm::vec3(0.0f)) == "none; none; none");
}

TEST_CASE("features: the CPU runs the smallest compiled variant that covers the scene", "[features]") {
  Scene cornell = make_builtin_scene("cornell");
  uint mask = scene_feature_mask(cornell, glm::vec3(0.0f));
  CHECK(mask == (kFeatureTriangles | kFeatureDiffuse | kFeatureTriangleLights));
  CHECK(cpu_variant_index(mask, 2) == 0u);  // no sphere, delta, GGX or other-light code
  CHECK(cpu_variant_features(0, 2) == kCpuBaseFeatures);
  // A mixed material brings its two lobes; alpha 0 makes the metal lobe a mirror.
  Scene mixed;
  mixed.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, mixed.add_material(make_gltf_material({1, 1, 1}, 0.5f, 0.0f, 0.0f, 1.5f, {}, false)));
  CHECK(scene_feature_mask(mixed, glm::vec3(0.0f)) ==
        (kFeatureTriangles | kFeatureMixed | kFeatureDiffuse | kFeatureMirror));
  // A glTF file's material brings its dielectric (with the Lambert base), and the
  // conductor's lobe only where metallic is above 0.
  Scene plastic;
  GltfPbr pbr;
  pbr.metallic = 0.0f, pbr.roughness = 0.5f;
  plastic.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, plastic.add_material(make_gltf_pbr_material(pbr)));
  CHECK(scene_feature_mask(plastic, glm::vec3(0.0f)) == (kFeatureTriangles | kFeatureDielectric | kFeatureDiffuse));
  pbr.metallic = 0.5f, pbr.roughness = 0.0f;
  plastic.materials[0] = make_gltf_pbr_material(pbr);
  CHECK(scene_feature_mask(plastic, glm::vec3(0.0f)) ==
        (kFeatureTriangles | kFeatureDielectric | kFeatureDiffuse | kFeatureMirror));
  CHECK(cpu_variant_index(kFeatureDielectric, 2) == 1u);  // the general copy
  CHECK(cpu_variant_index(kFeatureRoughGlass, 2) == 1u);  // rough glass: the general copy too
  // For every feature set: the variant chosen covers it, and no smaller variant does.
  for (unsigned count : {1u, 2u}) {
    for (uint features = 0u; features <= kFeatureAll; features++) {
      if ((features & ~kFeatureAll) != 0u) continue;  // a bit no feature has (yet)
      unsigned chosen = cpu_variant_index(features, count);
      REQUIRE(chosen < count);
      REQUIRE((cpu_variant_features(chosen, count) & features) == features);
      for (unsigned other = 0; other < count; other++) {
        if ((cpu_variant_features(other, count) & features) == features) {
          REQUIRE((cpu_variant_features(chosen, count) & ~cpu_variant_features(other, count)) == 0u);
        }
      }
    }
  }
}
