// Tests of what the host derives from a scene's textures (issue #19; common/scene/gltf_textures.h
// loads them): the feature set (textures, and every material kind a metallic-roughness
// texture reaches) and the light table's powers (an emitter weighed by its emissive
// texture's mean). What the loader reads: test_gltf_textures.cpp.
#include <catch2/catch.hpp>

#include <string>

#include "common/scene/gltf_textures.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/texels.h"

using namespace pt;
using namespace pt::test;
using pt_test::rgba;

TEST_CASE("textures: the feature set has textures, and every kind a metallic-roughness texture reaches",
          "[texture][features]") {
  Scene scene = load("tex_basic.gltf");
  // metallic 0.75 x B (255): glTF's dielectric mixed with the metal; roughness 0.5 x G
  // (128): GGX. The diffuse lobe is the dielectric's base.
  uint mask = scene_feature_mask(scene, glm::vec3(0.0f));
  CHECK((mask & kFeatureTextures) != 0u);
  CHECK((mask & kFeatureDielectric) != 0u);
  CHECK((mask & kFeatureMixed) == 0u);
  CHECK((mask & kFeatureDiffuse) != 0u);
  CHECK((mask & kFeatureConductor) != 0u);
  CHECK((mask & kFeatureMirror) == 0u);
  CHECK(feature_names(mask).find("textures") != std::string::npos);
  // Texels whose blue runs from 0 to 255 and green from 0: with metallic and roughness
  // factors 1, every lobe: the dielectric's (B 0), mirror (G 0) and GGX.
  scene.textures[2].texel_min = rgba(0, 0, 0, 255);
  scene.textures[2].texel_max = rgba(0, 255, 255, 255);
  scene.material_textures[0].metallic_factor = 1.0f;
  scene.material_textures[0].roughness_factor = 1.0f;
  mask = scene_feature_mask(scene, glm::vec3(0.0f));
  const uint lobes = kFeatureDiffuse | kFeatureMirror | kFeatureConductor | kFeatureDielectric;
  CHECK((mask & lobes) == lobes);
  // A material without a specular layer keeps the built-in rule: mixed between 0 and 1.
  scene.materials[0] =
      make_gltf_material(scene.materials[0].base_color, 0.5f, 0.5f, 0.0f, 1.5f, glm::vec3(0.0f), false);
  mask = scene_feature_mask(scene, glm::vec3(0.0f));
  const uint mixed_lobes = kFeatureDiffuse | kFeatureMirror | kFeatureConductor | kFeatureMixed;
  CHECK((mask & mixed_lobes) == mixed_lobes);
  // Without textures: no texture code, and the factors' kinds alone.
  Scene plain = load("materials.gltf");
  CHECK((scene_feature_mask(plain, glm::vec3(0.0f)) & kFeatureTextures) == 0u);
  CHECK_FALSE(uses_textures(plain));
}

TEST_CASE("textures: the light table weighs a textured emitter by its emissive texture's mean", "[texture][lights]") {
  // Two equal triangles of emission 1: one plain, one whose emissive texture's texels are
  // sRGB 255 and 0 (mean 0.5): it gets a third of the picks.
  Scene s;
  uint plain = s.add_material(make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  uint textured = s.add_material(make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, plain);
  s.add_triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, textured);
  s.material_textures.assign(2, no_material_textures());
  s.triangle_attributes.assign(2, no_triangle_attributes());
  s.textures.push_back(Texture{0u, 2u, 1u, kWrapRepeat, kWrapRepeat, kFilterLinear, rgba(0, 0, 0, 255),
                               rgba(255, 255, 255, 255)});
  s.texels = {rgba(255, 255, 255, 255), rgba(0, 0, 0, 255)};
  s.material_textures[textured].emissive = 0u;
  build_light_table(s);
  REQUIRE(s.lights.size() == 2);
  CHECK(s.lights[0].pick == Approx(2.0 / 3.0).epsilon(1e-6));
  CHECK(s.lights[1].pick == Approx(1.0 / 3.0).epsilon(1e-6));
  // The pieces stay parallel as a scene grows.
  s.add_material(make_diffuse(glm::vec3(0.5f)));
  s.add_triangle({0, 0, 2}, {1, 0, 2}, {0, 1, 2}, 2u);
  CHECK(s.material_textures.size() == s.materials.size());
  CHECK(s.triangle_attributes.size() == s.triangles.size());
}
