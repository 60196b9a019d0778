// Tests of the glTF loader's KHR_lights_punctual lights (issue #19, common/scene/gltf_cameras_lights.cpp
// add_light): a spot or directional light shines along its node's -Z, rotated and scaled
// as the node is; a spot light's cone angles become cosines, and angles outside the
// extension's rules are refused in one line; a light type the renderer does not model is
// said once; a light's range is ignored and said so. What the lights do to an image is in
// the stages' image tests (tests/support/analytic_suite.cpp check_point_floor).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <tuple>

#include "common/scene/scene_loading.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_checks.h"
#include "tests/support/gltf_writer.h"
#include "tests/support/stderr_capture.h"

using pt::test::GltfWriter;

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
  pt::test::check_point(l.intensity, {8, 4, 2});
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
  pt::test::check_point(scene.point_lights[0].intensity, {3, 3, 3});
  // The light table picks it by the irradiance over the scene's cross-section: it is the
  // only light, so it is always picked.
  REQUIRE(scene.lights.size() == 1);
  CHECK(scene.lights[0].pick == 1.0f);
}

TEST_CASE("lights: spot cone angles outside 0 <= inner < outer <= pi/2 are refused in one line",
          "[gltf][loader][punctual]") {
  for (auto [inner, outer, words] : {std::tuple{0.5, 0.5, "must be less than its outerConeAngle"},
                                     std::tuple{0.6, 0.3, "must be less than its outerConeAngle"},
                                     std::tuple{0.1, 1.6, "outerConeAngle"},
                                     std::tuple{1.6, 1.7, "innerConeAngle"}}) {
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
