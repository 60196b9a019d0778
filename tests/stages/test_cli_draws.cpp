// What a glTF file draws, as a user runs a stage on it (the contract (README.md) "Scenes", Geometry and
// Camera): a file of only lines exits 3 with the counts, --gltf-scene picks one of the file's scenes
// (exit 2 naming those there are when it has no such one), --frame frames the scene where the file
// has a camera. Not part of the article: the machinery of the stage programs.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "tests/common/scene/gltf_draw_files.h"
#include "tests/support/cli_run.h"

namespace fs = std::filesystem;

namespace test_cli_draws {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

using pt_test::Run;

fs::path scratch() { return pt_test::scratch_dir("pt_draws_cli"); }

Run run(const std::string& args) {
  return pt_test::run_program(PT_STAGE1_BIN, "--backend cpu --width 32 --height 24 --spp 1 " + args, "", scratch());
}

double image_mean(const std::string& file) {
  auto in = OIIO::ImageInput::open(file);
  REQUIRE(in);
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  double sum = 0.0;
  for (float v : pixels) sum += v;
  return sum / double(pixels.size());
}

// A square at z = 0 facing +z; scene 0 'Main' holds it and a camera at z = -5 that looks away
// from it (down -z); scene 1 'Empty' holds a line only.
std::string two_scene_file() {
  pt::test::DrawFile f;
  int square = f.mesh({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, 4);
  f.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}}}}};
  int camera = f.node({{"camera", 0}, {"translation", {0, 0, -5}}});
  f.scene({f.node({{"mesh", square}}), camera}, "Main");
  f.scene({f.node({{"mesh", f.mesh({{0, 0, 0}, {1, 0, 0}}, 1)}})}, "Empty");
  return f.write(scratch(), "two_scenes");
}

}  // namespace

TEST_CASE("stage1 on a file of only lines exits 3 with the counts", "[cli][draws]") {
  const std::string file = two_scene_file();
  Run r = run("--scene " + file + " --gltf-scene Empty --out " + (scratch() / "lines.png").string());
  pt_test::check_error(r, "stage1_raycast", 3, "no triangles to draw: 1 primitive of mode LINES skipped");
  CHECK(!fs::exists(scratch() / "lines.png"));
}

TEST_CASE("--gltf-scene picks a scene by index or name and names the scenes there are", "[cli][draws]") {
  const std::string file = two_scene_file();
  Run bad = run("--scene " + file + " --gltf-scene 7 --out " + (scratch() / "bad.png").string());
  pt_test::check_error(bad, "stage1_raycast", 2, "--gltf-scene 7: ");
  CHECK(bad.err.find("its scenes: 0 'Main', 1 'Empty'") != std::string::npos);

  Run by_name = run("--scene " + file + " --gltf-scene Main --out " + (scratch() / "main.png").string());
  CHECK(by_name.code == 0);
  Run plain = run("--scene " + file + " --out " + (scratch() / "plain.png").string());
  INFO(plain.err);
  CHECK(plain.code == 0);
  CHECK(plain.err.find("the file has 2 scenes; drawing scene 0 'Main' (--gltf-scene N|NAME picks another)") !=
        std::string::npos);

  Run builtin = run("--scene builtin:cornell --gltf-scene 1 --out " + (scratch() / "builtin.png").string());
  pt_test::check_error(builtin, "stage1_raycast", 2, "--gltf-scene 1 picks one of a glTF file's scenes");
}

TEST_CASE("--frame replaces the file's camera by one that frames the scene", "[cli][draws]") {
  const std::string file = two_scene_file();
  const std::string own = (scratch() / "own.exr").string(), framed = (scratch() / "framed.exr").string();
  Run a = run("--scene " + file + " --out " + own);
  Run b = run("--scene " + file + " --frame --out " + framed);
  INFO(a.err << b.err);
  REQUIRE(a.code == 0);
  REQUIRE(b.code == 0);
  CHECK(image_mean(own) == 0.0);  // the file's camera looks away from the square
  CHECK(image_mean(framed) > 0.0);
  CHECK(b.err.find("--frame: framing the bounds of") != std::string::npos);

  Run both = run("--scene " + file + " --frame --camera 0 --out " + framed);
  pt_test::check_error(both, "stage1_raycast", 2, "--frame and --camera both choose the view");
}

}  // namespace test_cli_draws
