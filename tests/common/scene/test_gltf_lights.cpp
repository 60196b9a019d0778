// Tests of the glTF loader's KHR_lights_punctual lights (issue #19, common/scene/gltf_cameras_lights.cpp
// add_light): a spot or directional light shines along its node's -Z, rotated and scaled
// as the node is; a spot light's cone angles become cosines, and angles outside the
// extension's rules are refused in one line, while inner >= outer (Blender's Spot Blend 0)
// is a hard-edged cone (issue #46); intensities in candela and lux become W/sr and W/m^2 at
// 683 lm/W, said once on stderr (issue #46); a light type the renderer does not model is
// said once; a light's range is ignored and said so. What the lights do to an image is in
// the stages' image tests (tests/support/analytic_suite.cpp check_point_floor, and
// tests/stage4_direct_indirect/test_photometric_lights.cpp for files).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <tuple>
#include <utility>

#include "common/scene/analytic_scenes.h"
#include "common/scene/scene_loading.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/gltf_writer.h"
#include "tests/support/stderr_capture.h"

using pt::test::GltfWriter;

namespace test_gltf_lights {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

std::string scratch() { return pt_test::scratch_dir("pt_lights").string(); }

// A floor quad, so that the file has something to light.
GltfWriter with_floor() {
  GltfWriter g;
  g.node({{"mesh", g.quad({-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, g.diffuse(glm::vec3(0.5f)))}});
  return g;
}

}  // namespace

TEST_CASE("lights: a spot light points along its node's -Z, its cones as cosines", "[gltf][loader][punctual]") {
  GltfWriter g = with_floor();
  // Rotated -90 degrees about x: -Z turns to -Y, straight down; the node's scale is not in
  // the direction.
  int spot = g.light("spot", {1.0f, 0.5f, 0.25f}, 8.0, 0.2, 0.5);
  g.light_node(spot, {{"translation", {0, 3, 0}}, {"rotation", {-0.7071068, 0, 0, 0.7071068}}, {"scale", {2, 2, 2}}});
  pt::Scene scene = pt::load_gltf(g.write(scratch() + "/spot.gltf"));
  REQUIRE(scene.point_lights.size() == 1);
  const pt::PointLight& l = scene.point_lights[0];
  CHECK(l.kind == pt::kPunctualSpot);
  pt::test::check_point(l.position, {0, 3, 0});
  pt::test::check_point(l.direction, {0, -1, 0});
  pt::test::check_point(l.intensity, glm::vec3(8, 4, 2) / 683.0f);
  CHECK(l.cos_inner == Approx(std::cos(0.2)));
  CHECK(l.cos_outer == Approx(std::cos(0.5)));
}

TEST_CASE("lights: a directional light shines along its node's -Z wherever the node is", "[gltf][loader][punctual]") {
  GltfWriter g = with_floor();
  int sun = g.light("directional", {1.0f, 1.0f, 1.0f}, 3.0);
  // Rotated 90 degrees about y: -Z turns to -X.
  g.light_node(sun, {{"translation", {5, 5, 5}}, {"rotation", {0, 0.7071068, 0, 0.7071068}}});
  pt::Scene scene = pt::load_gltf(g.write(scratch() + "/sun.gltf"));
  pt::build_light_table(scene);
  REQUIRE(scene.point_lights.size() == 1);
  CHECK(scene.point_lights[0].kind == pt::kPunctualDirectional);
  pt::test::check_point(scene.point_lights[0].direction, {-1, 0, 0});
  pt::test::check_point(scene.point_lights[0].intensity, glm::vec3(3.0f / 683.0f));
  // The light table picks it by the irradiance over the scene's cross-section: it is the
  // only light, so it is always picked.
  REQUIRE(scene.lights.size() == 1);
  CHECK(scene.lights[0].pick == 1.0f);
}

TEST_CASE("lights: spot cone angles outside [0, pi/2] are refused in one line", "[gltf][loader][punctual]") {
  for (auto [inner, outer, words] : {std::tuple{0.1, 1.6, "outerConeAngle"}, std::tuple{1.6, 1.7, "innerConeAngle"}}) {
    GltfWriter g = with_floor();
    g.light_node(g.light("spot", {1.0f, 1.0f, 1.0f}, 1.0, inner, outer));
    INFO("inner " << inner << ", outer " << outer);
    pt::test::require_bad_scene(g.write(scratch() + "/bad_spot.gltf"), {"spot", words});
  }
}

TEST_CASE("lights: a light type the renderer does not know is skipped and said once; a range is ignored and said",
          "[gltf][loader][punctual]") {
  GltfWriter g = with_floor();
  int area = g.light("area", {1.0f, 1.0f, 1.0f}, 1.0);
  g.light_node(area);
  g.light_node(area, {{"translation", {0, 1, 0}}});
  int point = g.light("point", {1.0f, 1.0f, 1.0f}, 1.0);
  g.light_node(point, {{"translation", {0, 2, 0}}});
  std::string file = g.write(scratch() + "/area.gltf");
  // The range goes in by hand: the writer has no field for it.
  std::string text = pt_test::read_file(file);
  std::size_t at = text.find("\"type\": \"point\"");
  REQUIRE(at != std::string::npos);
  text.insert(at, "\"range\": 5, ");
  std::ofstream(file) << text;
  pt_test::StderrCapture capture;
  pt::Scene scene = pt::load_gltf(file);
  std::string err = capture.text();
  INFO(err);
  CHECK(scene.point_lights.size() == 1);
  CHECK(pt_test::occurrences(err, "\"area\"") == 1);
  CHECK(pt_test::occurrences(err, "range") == 1);
}

TEST_CASE("lights: photometric intensities become radiometric at 683 lm/W: cd to W/sr, lux to W/m^2, said once",
          "[gltf][loader][punctual]") {
  GltfWriter g = with_floor();
  g.light_node(g.light("point", {1.0f, 0.5f, 0.25f}, 683.0), {{"translation", {0, 1, 0}}});
  g.light_node(g.light("spot", {1.0f, 1.0f, 1.0f}, 1366.0, 0.2, 0.5), {{"translation", {0, 2, 0}}});
  g.light_node(g.light("directional", {1.0f, 1.0f, 1.0f}, 6830.0));
  std::string file = g.write(scratch() + "/units.gltf");
  pt_test::StderrCapture capture;
  pt::Scene scene = pt::load_gltf(file);
  std::string err = capture.text();
  INFO(err);
  REQUIRE(scene.point_lights.size() == 3);
  pt::test::check_point(scene.point_lights[0].intensity, {1.0f, 0.5f, 0.25f});  // 683 cd: 1 W/sr, times the colour
  pt::test::check_point(scene.point_lights[1].intensity, {2, 2, 2});            // 1366 cd: 2 W/sr
  pt::test::check_point(scene.point_lights[2].intensity, {10, 10, 10});         // 6830 lux: 10 W/m^2
  CHECK(pt_test::occurrences(err, "683 lm/W") == 1);
  CHECK_THAT(err, Catch::Contains("3 KHR_lights_punctual lights"));
  CHECK(pt_test::occurrences(err, "\n") == 1);
}

TEST_CASE("lights: the built-in scenes keep their radiometric intensities", "[gltf][loader][punctual]") {
  pt::Scene scene = pt::make_builtin_scene("point_floor");
  REQUIRE(scene.point_lights.size() == 1);
  pt::test::check_point(scene.point_lights[0].intensity, pt::analytic::PointFloorScene().intensity);
}

TEST_CASE("lights: a spot with inner >= outer (Blender's Spot Blend 0) is a hard-edged cone at the outer angle",
          "[gltf][loader][punctual]") {
  for (auto [inner, outer] : {std::pair{0.5, 0.5}, std::pair{0.6, 0.3}, std::pair{0.0, 0.0}}) {
    GltfWriter g = with_floor();
    g.light_node(g.light("spot", {1.0f, 1.0f, 1.0f}, 683.0, inner, outer), {{"translation", {0, 2, 0}}});
    std::string file = g.write(scratch() + "/hard_spot.gltf");
    INFO("inner " << inner << ", outer " << outer);
    pt_test::StderrCapture capture;
    pt::Scene scene = pt::load_scene(file);
    std::string err = capture.text();
    INFO(err);
    CHECK(err.find("ConeAngle") == std::string::npos);  // accepted as it is, not warned
    REQUIRE(scene.point_lights.size() == 1);
    const pt::PointLight& l = scene.point_lights[0];
    CHECK(l.cos_outer == Approx(std::cos(outer)));
    CHECK(l.cos_inner == l.cos_outer);
    // The light table's power is the cone's exactly: 2 pi (1 - cos outer) I.
    REQUIRE(scene.lights.size() == 1);
    CHECK(scene.light_power == Approx(2.0 * M_PI * (1.0 - std::cos(outer))).margin(1e-9));
  }
}

}  // namespace test_gltf_lights
