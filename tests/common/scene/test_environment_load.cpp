// Tests of the environment map on the host (common/scene/environment.cpp; issue #49, beyond
// the article, whose sky is one colour): the tables make_environment builds, its checks of
// the texels, and load_environment reading .hdr and .exr files that the test writes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "common/base/error.h"
#include "common/scene/environment.h"
#include "tests/support/cli_run.h"
#include "tests/support/stderr_capture.h"

namespace fs = std::filesystem;

namespace test_environment_load {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

std::vector<float> random_rgb(uint w, uint h, std::uint32_t seed) {
  std::mt19937 g(seed);
  std::vector<float> rgb(3 * w * h);
  for (float& c : rgb) c = std::uniform_real_distribution<float>(0.0f, 3.0f)(g);
  return rgb;
}

// The table's cumulative distributions (environment.h): the rows', then each row's.
void check_cdfs(const pt::Environment& e) {
  const std::size_t w = e.width, h = e.height;
  REQUIRE(e.table.size() == w * h + (h + 1) + h * (w + 1));
  auto check = [&](std::size_t first, std::size_t n) {
    CHECK(e.table[first] == 0.0f);
    CHECK(e.table[first + n] == 1.0f);
    for (std::size_t i = 0; i < n; i++) CHECK(e.table[first + i] <= e.table[first + i + 1]);
  };
  check(w * h, h);
  for (std::size_t y = 0; y < h; y++) check(w * h + h + 1 + y * (w + 1), w);
}

// Writes a float image (channels per texel, rows from the top) with OpenImageIO.
void write_image(const fs::path& path, int w, int h, int channels, const std::vector<float>& data) {
  auto out = OIIO::ImageOutput::create(path.string());
  REQUIRE(out);
  REQUIRE(out->open(path.string(), OIIO::ImageSpec(w, h, channels, OIIO::TypeDesc::FLOAT)));
  REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, data.data()));
  out->close();
}

// An 8 x 4 RGB image whose top row differs from the rest.
std::vector<float> top_row_image() {
  std::vector<float> rgb(3 * 8 * 4);
  for (int i = 0; i < 8 * 4; i++) {
    bool top = i < 8;
    rgb[3 * i + 0] = top ? 5.3f : 0.3f + 0.01f * float(i);
    rgb[3 * i + 1] = top ? 2.7f : 0.2f;
    rgb[3 * i + 2] = top ? 1.1f : 0.7f;
  }
  return rgb;
}

// What load_environment throws: its exit code and one line.
int thrown_code(const std::string& path, std::string& message) {
  try {
    pt::load_environment(path, 1.0f, 0.0f);
  } catch (const pt::Error& e) {
    message = e.what();
    return e.code();
  }
  return 0;
}

void check_throws(const std::string& path, int code, const std::string& words) {
  std::string message;
  pt_test::StderrCapture quiet;  // warnings before the error are not the test's
  int got = thrown_code(path, message);
  INFO(path << ": " << message);
  CHECK(got == code);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message.find(words) != std::string::npos);
}

}  // namespace

TEST_CASE("environment tables: cdfs start at 0, never fall and end at exactly 1; the pdf averages 1",
          "[environment]") {
  for (auto [w, h] : {std::pair<uint, uint>{16, 8}, {12, 9}, {2, 1}, {64, 32}}) {
    std::vector<float> rgb = random_rgb(w, h, w * 31 + h);
    for (uint x = 0; x < 3 * w; x++) rgb[3 * w * (h / 2) + x] = 0.0f;  // a black row
    auto env = pt::make_environment("random", w, h, rgb, 1.0f, 0.0f);
    INFO(w << " x " << h);
    check_cdfs(*env);
    double mean = 0.0;
    for (std::size_t i = 0; i < std::size_t(w) * h; i++) mean += env->table[i];
    CHECK(mean / (double(w) * h) == Approx(1.0).epsilon(1e-5));
  }
}

TEST_CASE("environment tables: a black map gets a uniform table (and no NaN)", "[environment]") {
  auto env = pt::make_environment("black", 8, 4, std::vector<float>(3 * 8 * 4, 0.0f), 1.0f, 0.0f);
  check_cdfs(*env);
  for (std::size_t i = 0; i < 32; i++) CHECK(env->table[i] == 1.0f);
  for (std::size_t y = 0; y <= 4; y++) CHECK(env->table[32 + y] == Approx(y / 4.0));
  for (std::size_t x = 0; x <= 8; x++) CHECK(env->table[32 + 5 + 2 * 9 + x] == Approx(x / 8.0));
  CHECK(env->mean_luminance == 0.0);
}

TEST_CASE("environment tables: strength scales the radiance and the mean, not the pdf; negative texels become 0",
          "[environment]") {
  std::vector<float> rgb = random_rgb(8, 4, 3);
  auto one = pt::make_environment("one", 8, 4, rgb, 1.0f, 0.0f);
  auto more = pt::make_environment("more", 8, 4, rgb, 2.5f, 0.0f);
  for (std::size_t i = 0; i < rgb.size(); i++) CHECK(more->radiance[i] == Approx(2.5f * rgb[i]));
  for (std::size_t i = 0; i < one->table.size(); i++) CHECK(more->table[i] == Approx(one->table[i]).margin(1e-6));
  CHECK(more->mean_luminance == Approx(2.5 * one->mean_luminance));

  rgb[0] = -1.0f, rgb[4] = -0.5f;
  pt_test::StderrCapture capture;
  auto clipped = pt::make_environment("negative", 8, 4, rgb, 1.0f, 0.0f);
  std::string warning = capture.text();
  CHECK(clipped->radiance[0] == 0.0f);
  CHECK(clipped->radiance[4] == 0.0f);
  CHECK(clipped->radiance[1] == rgb[1]);
  CHECK(pt_test::lines(warning) == 1);
  CHECK(warning.find("negative") != std::string::npos);
}

TEST_CASE("environment tables: a NaN or infinite texel is a bad scene that names the texel", "[environment]") {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity()}) {
    std::vector<float> rgb(3 * 8 * 4, 0.5f);
    rgb[3 * (2 * 8 + 5) + 1] = bad;  // texel (5, 2)
    try {
      pt::make_environment("bad.exr", 8, 4, rgb, 1.0f, 0.0f);
      FAIL("no error for " << bad);
    } catch (const pt::Error& e) {
      INFO(e.what());
      CHECK(e.code() == pt::kExitBadScene);
      CHECK(std::string(e.what()).find("(5, 2)") != std::string::npos);
      CHECK(std::string(e.what()).find("bad.exr") != std::string::npos);
    }
  }
}

TEST_CASE("environment tables: the mean luminance of a constant map is its luminance", "[environment]") {
  for (auto [w, h] : {std::pair<uint, uint>{16, 8}, {7, 5}, {2, 1}}) {
    std::vector<float> rgb(3 * w * h);
    for (std::size_t i = 0; i < rgb.size(); i++) rgb[i] = i % 3 == 0 ? 0.4f : i % 3 == 1 ? 1.3f : 2.0f;
    auto env = pt::make_environment("flat", w, h, rgb, 1.0f, 0.0f);
    CHECK(env->mean_luminance == Approx(0.2126 * 0.4 + 0.7152 * 1.3 + 0.0722 * 2.0).epsilon(1e-5));
  }
}

TEST_CASE("environment turn: whole turns drop out exactly, so a huge --env-rotate is still a turn", "[environment]") {
  auto turn = [](float degrees) {
    return pt::environment_turn(*pt::make_environment("flat", 2, 1, std::vector<float>(6, 1.0f), 1.0f, degrees));
  };
  CHECK(turn(450.0f) == turn(90.0f));
  CHECK(turn(-270.0f) == turn(90.0f));
  CHECK(turn(360.0f * 1024.0f + 30.0f) == turn(30.0f));
  // 1e30 degrees is a whole number of degrees whose remainder mod 360 is exact in double.
  const double rest = std::fmod(double(1e30f), 360.0);
  const glm::vec2 huge = turn(1e30f);
  CHECK(huge.x == Approx(std::cos(rest * M_PI / 180.0)).margin(1e-6));
  CHECK(huge.y == Approx(std::sin(rest * M_PI / 180.0)).margin(1e-6));
  CHECK(glm::length(huge) == Approx(1.0f).epsilon(1e-6));
}

TEST_CASE("environment loading: .hdr and .exr read top row first, values kept (.hdr to RGBE precision)",
          "[environment]") {
  fs::path dir = pt_test::scratch_dir("pt_env_load");
  std::vector<float> rgb = top_row_image();
  for (const char* ext : {".hdr", ".exr"}) {
    fs::path path = dir / (std::string("map") + ext);
    write_image(path, 8, 4, 3, rgb);
    auto env = pt::load_environment(path.string(), 2.0f, 15.0f);
    INFO(path);
    REQUIRE(env->width == 8);
    REQUIRE(env->height == 4);
    CHECK(env->rotate_degrees == 15.0f);
    // RGBE: 8-bit mantissas under the texel's largest channel's exponent, a step of at most
    // 1/128 of that channel (.exr: float, exact).
    const bool hdr = std::string(ext) == ".hdr";
    for (std::size_t i = 0; i < rgb.size(); i++) {
      float largest = std::max({rgb[i - i % 3], rgb[i - i % 3 + 1], rgb[i - i % 3 + 2]});
      CHECK(std::abs(env->radiance[i] - 2.0f * rgb[i]) <= (hdr ? 2.0f * largest / 128.0f : 0.0f));
    }
    CHECK(env->radiance[0] == Approx(2.0 * 5.3).epsilon(hdr ? 1.0 / 128.0 : 1e-7));  // the top row comes first
    check_cdfs(*env);
  }
  // One channel is grey.
  std::vector<float> grey(8 * 4);
  for (std::size_t i = 0; i < grey.size(); i++) grey[i] = 0.1f * float(i + 1);
  write_image(dir / "grey.exr", 8, 4, 1, grey);
  auto env = pt::load_environment((dir / "grey.exr").string(), 1.0f, 0.0f);
  for (std::size_t i = 0; i < grey.size(); i++)
    for (int c = 0; c < 3; c++) CHECK(env->radiance[3 * i + c] == Approx(grey[i]));
  fs::remove_all(dir);
}

TEST_CASE("environment loading: another extension is a bad option; a missing, broken or 1x1 file a bad scene",
          "[environment]") {
  fs::path dir = pt_test::scratch_dir("pt_env_bad");
  check_throws((dir / "sky.png").string(), pt::kExitBadOption, ".png");
  check_throws((dir / "missing.hdr").string(), pt::kExitBadScene, "missing.hdr");
  std::ofstream(dir / "garbage.hdr") << "this is not a Radiance picture\n\n-Y 4 +X 8\nxx";
  check_throws((dir / "garbage.hdr").string(), pt::kExitBadScene, "garbage.hdr");
  // A good .hdr cut in half.
  write_image(dir / "whole.hdr", 8, 4, 3, top_row_image());
  std::string bytes = pt_test::read_file(dir / "whole.hdr");
  std::ofstream(dir / "cut.hdr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  check_throws((dir / "cut.hdr").string(), pt::kExitBadScene, "cut.hdr");
  write_image(dir / "dot.exr", 1, 1, 3, {1.0f, 1.0f, 1.0f});
  check_throws((dir / "dot.exr").string(), pt::kExitBadScene, "dot.exr");
  std::ofstream(dir / "empty.exr");
  check_throws((dir / "empty.exr").string(), pt::kExitBadScene, "empty.exr");
  fs::remove_all(dir);
}

}  // namespace test_environment_load
