// Tests of the camera rules of the contract (README.md) "Camera" for real files (issue #19):
// with no camera the bounds are framed from a raised three-quarter view with every corner
// in the picture (common/scene/scene_camera.cpp frame_bounds); --camera N|NAME picks one of the
// file's cameras (select_camera); a perspective camera's aspectRatio sets the image height
// when only --width is given (common/app/app.cpp), and a scene that will render black is
// warned about.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <string>

#include "common/base/error.h"
#include "common/scene/scene_loading.h"
#include "tests/support/cli_run.h"
#include "tests/support/gltf_writer.h"

using pt::test::GltfWriter;

namespace test_gltf_cameras {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

std::string scratch() { return pt_test::scratch_dir("pt_cameras").string(); }

// Where a world point lands in the image: x, y in [-1, 1] across the image when visible.
glm::vec2 project(const pt::Camera& c, glm::vec3 p, float& depth) {
  glm::vec3 d = p - c.origin;
  depth = glm::dot(d, c.forward);
  return glm::vec2(glm::dot(d, c.right) / (depth * c.extent_x), glm::dot(d, c.up) / (depth * c.extent_y));
}

// Two cameras ("Front" on node CamFront, unnamed on node CamSide) over a unit quad.
std::string two_camera_file(double aspect_ratio = 0.0) {
  GltfWriter g;
  g.node({{"mesh", g.quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, g.diffuse(glm::vec3(0.5f)))}});
  g.node({{"camera", g.perspective(0.5, aspect_ratio, "Front")}, {"name", "CamFront"}, {"translation", {0.5, 0.5, 3}}});
  g.node({{"camera", g.perspective(0.7)}, {"name", "CamSide"}, {"translation", {4, 0.5, 0}}, {"rotation", {0, 0.7071068, 0, 0.7071068}}});
  return g.write(scratch() + "/two_cameras.gltf");
}

pt_test::Run stage(const char* program, const std::string& args) {
  return pt_test::run_program(program, "--backend cpu --spp 2 " + args, "", pt_test::scratch_dir("pt_cameras_run"));
}

}  // namespace

TEST_CASE("cameras: with no camera the framing sees every corner of the bounds from above, at three quarters",
          "[gltf][camera]") {
  struct Case {
    glm::vec3 lo, hi;
  };
  const Case cases[] = {{{-1, -1, -1}, {1, 1, 1}},           // a cube
                        {{-5, 0, -5}, {5, 0, 5}},            // a Blender floor in the XZ plane
                        {{0, 0, 0}, {10, 0.1f, 0.1f}},       // a long thin rod
                        {{1000, 2000, -3000}, {1001, 2002, -2999}},  // far from the origin
                        {{-1, -1, 0}, {1, 1, 0}}};           // a square in the XY plane
  for (float aspect : {1.0f, 16.0f / 9.0f, 0.5f}) {
    for (const Case& c : cases) {
      pt::Scene scene;
      scene.region = pt::Bounds{c.lo, c.hi};
      pt::Camera cam = pt::make_camera(scene, aspect);
      INFO("bounds (" << c.lo.x << "," << c.lo.y << "," << c.lo.z << ")-(" << c.hi.x << "," << c.hi.y << ","
                      << c.hi.z << "), aspect " << aspect);
      CHECK(cam.forward.y < -0.3f);  // looking down
      CHECK(std::abs(cam.forward.x) > 0.3f);  // and neither along x nor along z: three faces of a box show
      CHECK(std::abs(cam.forward.z) > 0.3f);
      CHECK(std::abs(cam.up.y) > 0.5f);  // image up is the world's up
      float widest = 0.0f;
      for (int k = 0; k < 8; k++) {
        glm::vec3 p((k & 1) ? c.hi.x : c.lo.x, (k & 2) ? c.hi.y : c.lo.y, (k & 4) ? c.hi.z : c.lo.z);
        float depth = 0.0f;
        glm::vec2 xy = project(cam, p, depth);
        CHECK(depth > 0.0f);
        CHECK(std::abs(xy.x) <= 1.0f);
        CHECK(std::abs(xy.y) <= 1.0f);
        widest = std::max({widest, std::abs(xy.x), std::abs(xy.y)});
      }
      CHECK(widest > 0.9f);  // as close as fits: the scene fills the picture
    }
  }
}

TEST_CASE("cameras: the file's cameras in the order met, the first by default, --camera by index or name",
          "[gltf][camera]") {
  pt::Scene scene = pt::load_gltf(two_camera_file());
  REQUIRE(scene.cameras.size() == 2);
  CHECK(scene.cameras[0].name == "Front");
  CHECK(scene.cameras[0].node == "CamFront");
  CHECK(scene.cameras[1].name.empty());
  CHECK(scene.cameras[1].node == "CamSide");
  REQUIRE(scene.camera);
  CHECK(scene.camera->yfov == Approx(0.5f));

  pt::select_camera(scene, "1");
  CHECK(scene.camera->yfov == Approx(0.7f));
  pt::select_camera(scene, "Front");
  CHECK(scene.camera->yfov == Approx(0.5f));
  pt::select_camera(scene, "CamSide");
  CHECK(scene.camera->yfov == Approx(0.7f));
  CHECK(glm::vec3(scene.camera->to_world[3]).x == Approx(4.0f));

  for (const char* wrong : {"2", "Back", "-1", "99999999999999"}) {
    INFO("--camera " << wrong);
    try {
      pt::select_camera(scene, wrong);
      FAIL("no error");
    } catch (const pt::Error& e) {
      CHECK(e.code() == pt::kExitBadOption);
      std::string m = e.what();
      CHECK(m.find("'Front'") != std::string::npos);
      CHECK(m.find("CamSide") != std::string::npos);
    }
  }
  pt::Scene builtin = pt::load_scene("builtin:cornell");
  CHECK_THROWS_AS(pt::select_camera(builtin, "0"), pt::Error);
}

TEST_CASE("cameras: aspectRatio sets the height when only --width is given, and a conflict is said once",
          "[stage1][gltf][camera][cli]") {
  std::string file = two_camera_file(2.0);
  std::string out = scratch() + "/wide.exr";
  pt_test::Run r = stage(PT_STAGE1_BIN, "--scene " + file + " --width 64 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto in = OIIO::ImageInput::open(out);
  REQUIRE(in);
  CHECK(in->spec().width == 64);
  CHECK(in->spec().height == 32);
  CHECK(r.err.find("aspectRatio 2 sets the image to 64 x 32") != std::string::npos);

  r = stage(PT_STAGE1_BIN, "--scene " + file + " --height 10 --out " + out);
  REQUIRE(r.code == 0);
  in = OIIO::ImageInput::open(out);
  CHECK(in->spec().width == 20);

  r = stage(PT_STAGE1_BIN, "--scene " + file + " --width 16 --height 16 --out " + out);
  REQUIRE(r.code == 0);
  CHECK(pt_test::occurrences(r.err, "differs from --width/--height") == 1);  // beside the "has 2 cameras" line
  CHECK(r.err.find("sets the image to") == std::string::npos);

  r = stage(PT_STAGE1_BIN, "--scene " + file + " --camera Nope --out " + out);
  pt_test::check_error(r, "stage1_raycast", pt::kExitBadOption, "has no such camera");
}

TEST_CASE("cameras: a file with no camera is framed and said so; with no light the image is said to be black",
          "[stage1][stage2][gltf][camera][cli]") {
  GltfWriter g;
  g.node({{"mesh", g.quad({-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, g.diffuse(glm::vec3(0.5f)))}});
  std::string file = g.write(scratch() + "/floor.gltf");
  std::string out = scratch() + "/floor.exr";
  pt_test::Run r = stage(PT_STAGE1_BIN, "--scene " + file + " --width 8 --height 8 --out " + out);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("no camera: framing its bounds") != std::string::npos);
  CHECK(r.err.find("no light") == std::string::npos);  // stage1 shows the base colour

  r = stage(PT_STAGE2_BIN, "--scene " + file + " --width 8 --height 8 --out " + out);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("has no light") != std::string::npos);
  CHECK(r.err.find("--sky 1,1,1") != std::string::npos);
  r = stage(PT_STAGE2_BIN, "--scene " + file + " --width 8 --height 8 --sky 1,1,1 --out " + out);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("no light") == std::string::npos);
}

}  // namespace test_gltf_cameras
