// Tests of the glTF loader (the contract (README.md) "Scenes"; common/scene/gltf_materials.cpp):
// metallic-roughness factors and the material extensions become the contract's materials,
// and KHR_lights_punctual point lights sit at their nodes; fixtures from tests/data/gltf.
#include <catch2/catch.hpp>

#include <cmath>

#include "tests/support/cli_run.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/gltf_writer.h"
#include "tests/support/stderr_capture.h"

using namespace pt::test;
using pt::test::GltfWriter;

// --- Materials ------------------------------------------------------------------------

TEST_CASE("metallic-roughness factors become the contract's materials", "[loader]") {
  pt::Scene scene = load("materials.gltf");  // triangle i at x = 2i
  SECTION("metallic 0 is a dielectric: a GGX layer of F0 0.04 (ior 1.5) over a Lambert base of the base colour") {
    const pt::Material& m = material_at(scene, 0);
    CHECK(m.kind == pt::kMaterialDielectric);
    CHECK(m.metallic == 0.0f);
    check_point(m.base_color, {0.8f, 0.2f, 0.1f});
    check_point(m.specular_f0, {0.04f, 0.04f, 0.04f});
    CHECK(m.specular == 1.0f);
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
  SECTION("metallic between 0 and 1 mixes the conductor and the dielectric") {
    const pt::Material& m = material_at(scene, 6);
    CHECK(m.kind == pt::kMaterialDielectric);
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
    CHECK(m.kind == pt::kMaterialDielectric);
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

TEST_CASE("KHR_materials_specular weighs and tints the dielectric's layer; specularFactor 0 is Lambert; "
          "unmodelled extensions are named once per file",
          "[loader][gltf_material]") {
  GltfWriter g;
  auto plain = [](glm::vec3 base, double metallic) {
    return GltfWriter::Json{{"pbrMetallicRoughness",
                             {{"baseColorFactor", {base.x, base.y, base.z, 1.0}}, {"metallicFactor", metallic},
                              {"roughnessFactor", 0.5}}}};
  };
  GltfWriter::Json tinted = plain({0.5f, 0.5f, 0.5f}, 0.0);
  tinted["extensions"] = {{"KHR_materials_ior", {{"ior", 2.0}}},
                          {"KHR_materials_specular",
                           {{"specularFactor", 0.5}, {"specularColorFactor", {1.0, 2.0, 40.0}}}},
                          {"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}};
  GltfWriter::Json lambert = plain({0.3f, 0.6f, 0.9f}, 0.0);
  lambert["extensions"] = {{"KHR_materials_specular", {{"specularFactor", 0.0}}}};
  GltfWriter::Json mixed = plain({0.9f, 0.8f, 0.7f}, 0.4);
  mixed["extensions"] = {{"KHR_materials_specular", {{"specularFactor", 0.0}}}};
  int materials[3] = {g.material(tinted), g.material(lambert), g.material(mixed)};
  for (int i = 0; i < 3; i++) {
    float x = 2.0f * float(i);
    g.node({{"mesh", g.mesh({{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}}, materials[i])}});
  }
  for (const char* ext : {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_clearcoat",
                          "KHR_materials_sheen"}) {
    g.uses(ext);
  }
  std::string path = g.write(pt_test::scratch_dir("pt_gltf_materials").string() + "/specular.gltf");
  pt_test::StderrCapture capture;
  pt::Scene scene = pt::load_gltf(path);
  pt::load_gltf(path);  // a second read of the same file says nothing new
  std::string err = capture.text();
  // F0 = ((2 - 1) / (2 + 1))^2 x colour, each channel at most 1; the weight is the factor.
  const pt::Material& t = material_at(scene, 0);
  CHECK(t.kind == pt::kMaterialDielectric);
  check_point(t.specular_f0, {1.0f / 9.0f, 2.0f / 9.0f, 1.0f});
  CHECK(t.specular == 0.5f);
  CHECK(t.alpha == Approx(0.25f));
  // No layer: the built-in scenes' kinds, exactly (Appendix B with weight 0).
  CHECK(material_at(scene, 2).kind == pt::kMaterialDiffuse);
  CHECK(material_at(scene, 4).kind == pt::kMaterialMixed);
  CHECK(material_at(scene, 4).metallic == Approx(0.4f));
  INFO(err);
  CHECK(pt_test::occurrences(err, "KHR_materials_clearcoat, KHR_materials_sheen; they are not modelled") == 1);
  CHECK(pt_test::occurrences(err, "KHR_materials_specular;") == 0);  // modelled: not in that list
}

TEST_CASE("KHR_materials_transmission with roughness is rough glass (alpha = roughness^2); roughness 0 or ior 1 "
          "is smooth glass",
          "[loader][rough_glass]") {
  GltfWriter g;
  auto glass = [](double roughness, double ior) {
    return GltfWriter::Json{
        {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 1.0, 0.8, 1.0}}, {"roughnessFactor", roughness}}},
        {"extensions",
         {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}, {"KHR_materials_ior", {{"ior", ior}}}}}};
  };
  int materials[3] = {g.material(glass(0.5, 1.33)), g.material(glass(0.0, 1.5)), g.material(glass(0.5, 1.0))};
  for (int i = 0; i < 3; i++) {
    float x = 2.0f * float(i);
    g.node({{"mesh", g.mesh({{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}}, materials[i])}});
  }
  g.uses("KHR_materials_transmission");
  g.uses("KHR_materials_ior");
  pt::Scene scene = pt::load_gltf(g.write(pt_test::scratch_dir("pt_gltf_materials").string() + "/rough_glass.gltf"));
  const pt::Material& rough = material_at(scene, 0);
  CHECK(rough.kind == pt::kMaterialRoughGlass);
  CHECK(rough.alpha == Approx(0.25f));
  CHECK(rough.ior == Approx(1.33f));
  check_point(rough.base_color, {0.9f, 1.0f, 0.8f});
  CHECK(material_at(scene, 2).kind == pt::kMaterialGlass);
  CHECK(material_at(scene, 4).kind == pt::kMaterialGlass);  // index-matched: nothing bends
  CHECK((pt::scene_feature_mask(scene, glm::vec3(0.0f)) & (pt::kFeatureRoughGlass | pt::kFeatureGlass)) ==
        (pt::kFeatureRoughGlass | pt::kFeatureGlass));
  CHECK(pt::feature_names(pt::kFeatureRoughGlass).find("rough glass") != std::string::npos);
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
