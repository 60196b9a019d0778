// Tests of the glTF loader (the contract (README.md) "Scenes"; common/scene/gltf_materials.cpp):
// metallic-roughness factors and the material extensions become the contract's materials,
// and KHR_lights_punctual point lights sit at their nodes; fixtures from tests/data/gltf.
#include <catch2/catch.hpp>

#include <cmath>

#include "tests/support/gltf_checks.h"

using namespace pt::test;

// --- Materials ------------------------------------------------------------------------

TEST_CASE("metallic-roughness factors become the contract's materials", "[loader]") {
  pt::Scene scene = load("materials.gltf");  // triangle i at x = 2i
  SECTION("metallic 0 is Lambertian with the base colour as albedo") {
    const pt::Material& m = material_at(scene, 0);
    CHECK(m.kind == pt::kMaterialDiffuse);
    check_point(m.base_color, {0.8f, 0.2f, 0.1f});
  }
  SECTION("metallic 1 with roughness 0 is a mirror") {
    CHECK(material_at(scene, 2).kind == pt::kMaterialMirror);
  }
  SECTION("metallic 1 with roughness 0.5 is GGX with alpha = roughness^2") {
    const pt::Material& m = material_at(scene, 4);
    CHECK(m.kind == pt::kMaterialConductor);
    CHECK(m.alpha == Approx(0.25f));
    check_point(m.base_color, {0.95f, 0.64f, 0.54f});
  }
  SECTION("metallic between 0 and 1 mixes conductor and diffuse") {
    const pt::Material& m = material_at(scene, 6);
    CHECK(m.kind == pt::kMaterialMixed);
    CHECK(m.metallic == Approx(0.25f));
    CHECK(m.alpha == Approx(0.16f));
  }
  SECTION("transmission is glass with ior 1.5 by default") {
    const pt::Material& m = material_at(scene, 8);
    CHECK(m.kind == pt::kMaterialGlass);
    CHECK(m.ior == Approx(1.5f));
  }
  SECTION("KHR_materials_ior sets the glass's ior; the base colour tints it") {
    const pt::Material& m = material_at(scene, 10);
    CHECK(m.kind == pt::kMaterialGlass);
    CHECK(m.ior == Approx(1.33f));
    check_point(m.base_color, {0.9f, 1.0f, 0.9f});
  }
  SECTION("emission is emissiveFactor times emissiveStrength, front face only") {
    const pt::Material& m = material_at(scene, 12);
    check_point(m.emission, {4.0f, 2.0f, 1.0f});
    CHECK(m.double_sided == 0u);
  }
  SECTION("doubleSided emits from both faces") {
    const pt::Material& m = material_at(scene, 14);
    check_point(m.emission, {1.0f, 1.0f, 1.0f});
    CHECK(m.double_sided == 1u);
    CHECK(m.kind == pt::kMaterialDiffuse);
  }
  SECTION("no material is glTF's default: base colour 1, metallic 1, roughness 1") {
    const pt::Material& m = material_at(scene, 16);
    CHECK(m.kind == pt::kMaterialConductor);
    CHECK(m.alpha == Approx(1.0f));
    check_point(m.base_color, {1, 1, 1});
  }
  SECTION("each material used is added once; unused ones are not") {
    REQUIRE(scene.triangles.size() == 10);
    CHECK(scene.triangles[9].material == scene.triangles[0].material);
    CHECK(scene.materials.size() == 9);
  }
}

// --- Lights ---------------------------------------------------------------------------

TEST_CASE("KHR_lights_punctual lights sit at their node with intensity / 683 lm/W times colour, in the order met",
          "[loader]") {
  pt::Scene scene = load("point_light.gltf");
  REQUIRE(scene.point_lights.size() == 4);
  const pt::PointLight& point = scene.point_lights[0];
  CHECK(point.kind == pt::kPunctualPoint);
  check_point(point.position, {1, 2, 0});
  check_point(point.intensity, glm::vec3(5, 10, 2.5f) / 683.0f);  // candela to W/sr
  const pt::PointLight& spot = scene.point_lights[1];  // "spot": {} takes the defaults
  CHECK(spot.kind == pt::kPunctualSpot);
  check_point(spot.direction, {0, 0, -1});
  CHECK(spot.cos_inner == Approx(1.0f));
  CHECK(spot.cos_outer == Approx(std::cos(0.7853981634)));
  check_point(spot.intensity, glm::vec3(7.0f / 683.0f));
  const pt::PointLight& sun = scene.point_lights[2];
  CHECK(sun.kind == pt::kPunctualDirectional);
  check_point(sun.direction, {0, 0, -1});
  check_point(sun.intensity, glm::vec3(2.0f / 683.0f));  // lux to W/m^2
  check_point(scene.point_lights[3].position, {0, 0, -4});
  check_point(scene.point_lights[3].intensity, glm::vec3(3.0f / 683.0f));  // colour defaults to white
}
