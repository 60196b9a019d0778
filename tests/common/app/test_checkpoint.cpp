// Checkpoint and resume (common/app/checkpoint.h), below the command line: a render resumed
// from any pass's checkpoint equals the uninterrupted render bit for bit on the CPU (the
// article's estimator is a sum of independent samples, each with its own random numbers);
// the render key tells renders apart; damaged and truncated files are refused, never read.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "common/app/checkpoint.h"
#include "common/base/error.h"
#include "common/render/render.h"
#include "common/scene/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "common/render/memory.h"
#include "cpu/cpu_backend.h"
#include "tests/support/test_render.h"

namespace fs = std::filesystem;
using namespace pt;

namespace {

fs::path scratch_file(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("pt_reliability_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::vector<char> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// The error code load_checkpoint throws (0: it loaded).
int load_code(const fs::path& p, std::uint64_t key, const char* stage, int w, int h, std::string* message = nullptr) {
  try {
    load_checkpoint(p.string(), key, stage, w, h);
    return 0;
  } catch (const Error& e) {
    if (message) *message = e.what();
    return e.code();
  }
}

}  // namespace

TEST_CASE("checkpoint: a render resumed from any pass equals the uninterrupted one bit for bit (CPU)",
          "[stage4][reliability][checkpoint]") {
  Scene scene = make_builtin_scene("cornell");
  RenderSettings s = test::settings(20, 20, 40, test::test_seed(11));
  s.sky = glm::vec3(0.1f);
  RenderResult whole = test::render_on("cpu", stage4::kernels(), scene, s);

  // The same render, saving its state after every pass.
  std::vector<RenderResult> states;
  RenderHooks saving;
  saving.save_seconds = 0.0;
  saving.save = [&](const RenderResult& r) { states.push_back(r); };
  RenderResult again = test::render_on("cpu", stage4::kernels(), scene, s, saving);
  CHECK(again.film.sums() == whole.film.sums());
  REQUIRE(states.size() == 6);  // after 1, 2, 4, 8, 16, 32 spp; never after the last (cut) pass

  const std::uint64_t key = render_key("stage4_direct_indirect", scene, s);
  for (const RenderResult& state : states) {
    INFO("resumed from " << state.film.spp() << " spp");
    fs::path file = scratch_file("resume.ckpt");
    save_checkpoint(file.string(), key, "stage4_direct_indirect", state);
    RenderResult loaded = load_checkpoint(file.string(), key, "stage4_direct_indirect", 20, 20);
    CHECK(loaded.film.spp() == state.film.spp());
    CHECK(loaded.passes == state.passes);
    RenderHooks resuming;
    resuming.resume = &loaded;
    RenderResult resumed = test::render_on("cpu", stage4::kernels(), scene, s, resuming);
    CHECK(resumed.film.spp() == 40);
    CHECK(resumed.film.sums() == whole.film.sums());  // exact equality of every double
    CHECK(resumed.counters.zero_pdf == whole.counters.zero_pdf);
    CHECK(resumed.counters.depth_cap == whole.counters.depth_cap);
  }
}

TEST_CASE("checkpoint: the render key changes with everything that determines the image",
          "[stage3][stage4][reliability][checkpoint]") {
  Scene scene = make_builtin_scene("cornell");
  RenderSettings s = test::settings(16, 12, 8, 3);
  const std::uint64_t key = render_key("stage4_direct_indirect", scene, s);
  CHECK(render_key("stage4_direct_indirect", scene, s) == key);
  RenderSettings more = s;
  more.spp = 1000;  // the sample count is what a resume changes
  CHECK(render_key("stage4_direct_indirect", scene, more) == key);
  more.accel = s.accel == kAccelBvh ? kAccelNone : kAccelBvh;  // the same image either way
  CHECK(render_key("stage4_direct_indirect", scene, more) == key);

  CHECK(render_key("stage3_importance", scene, s) != key);
  std::vector<RenderSettings> changed(7, s);
  changed[0].seed = 4;
  changed[1].width = 17;
  changed[2].height = 13;
  changed[3].sky = glm::vec3(0.0f, 0.0f, 1e-3f);
  changed[4].roulette = s.roulette == kRouletteFixed ? kRouletteThroughput : kRouletteFixed;
  changed[5].depth_cap = s.depth_cap - 1;
  changed[6].all_features = true;
  for (std::size_t i = 0; i < changed.size(); i++) {
    INFO("change " << i);
    CHECK(render_key("stage4_direct_indirect", scene, changed[i]) != key);
  }
  Scene moved = scene;
  moved.triangles[0].p0.x += 1e-4f;
  CHECK(render_key("stage4_direct_indirect", moved, s) != key);
  Scene recoloured = scene;
  recoloured.materials[0].base_color.y *= 0.5f;
  CHECK(render_key("stage4_direct_indirect", recoloured, s) != key);
  // A texel of a textured scene: the textures are part of the content too.
  Scene textured = make_builtin_scene("every_feature");
  REQUIRE(!textured.texels.empty());
  const std::uint64_t textured_key = render_key("stage4_direct_indirect", textured, s);
  textured.texels[0] ^= 1u;
  CHECK(render_key("stage4_direct_indirect", textured, s) != textured_key);
  Scene relit = make_builtin_scene("every_feature");
  relit.point_lights.back().cos_outer *= 0.99f;  // a spot light's cone
  CHECK(render_key("stage4_direct_indirect", relit, s) != textured_key);
}

TEST_CASE("checkpoint: one of another render, a damaged or a truncated file is refused with exit 2",
          "[stage1][stage2][reliability][checkpoint]") {
  Scene scene = make_builtin_scene("cornell");
  RenderSettings s = test::settings(8, 6, 7, 5);
  std::vector<RenderResult> states;
  RenderHooks saving;
  saving.save = [&](const RenderResult& r) { states.push_back(r); };
  test::render_on("cpu", stage1::kernels(), scene, s, saving);
  REQUIRE(!states.empty());
  const std::uint64_t key = render_key("stage1_raycast", scene, s);
  fs::path good = scratch_file("good.ckpt"), bad = scratch_file("bad.ckpt");
  save_checkpoint(good.string(), key, "stage1_raycast", states.back());
  REQUIRE(load_code(good, key, "stage1_raycast", 8, 6) == 0);

  std::string message;
  CHECK(load_code(good, key + 1, "stage1_raycast", 8, 6, &message) == kExitBadOption);
  CHECK(message.find("different render") != std::string::npos);
  CHECK(load_code(good, key, "stage2_montecarlo", 8, 6, &message) == kExitBadOption);
  CHECK(message.find("is of stage1_raycast") != std::string::npos);
  CHECK(load_code(good, key, "stage1_raycast", 8, 7, &message) == kExitBadOption);
  CHECK(message.find("8x6") != std::string::npos);
  CHECK(load_code(scratch_file("none.ckpt"), key, "stage1_raycast", 8, 6, &message) == kExitBadOption);
  CHECK(message.find("does not exist") != std::string::npos);

  const std::vector<char> bytes = read_bytes(good);
  // Truncations: at every length through the header (120 bytes) and a little past it, then every 13th.
  for (std::size_t n = 0; n < bytes.size(); n += n < 200 ? 1 : 13) {
    write_bytes(bad, std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(n)));
    INFO("truncated to " << n << " bytes");
    REQUIRE(load_code(bad, key, "stage1_raycast", 8, 6) == kExitBadOption);
  }
  // A changed byte: every one of the header and the checksum, every 11th of the sums; and
  // bytes appended.
  std::mt19937 rng(1);
  for (std::size_t i = 0; i < bytes.size(); i += i < 200 || i + 16 > bytes.size() ? 1 : 11) {
    std::vector<char> damaged = bytes;
    damaged[i] = char(damaged[i] ^ (1 + rng() % 255));
    write_bytes(bad, damaged);
    INFO("byte " << i << " changed");
    REQUIRE(load_code(bad, key, "stage1_raycast", 8, 6, &message) == kExitBadOption);
  }
  std::vector<char> longer = bytes;
  longer.push_back(0);
  write_bytes(bad, longer);
  CHECK(load_code(bad, key, "stage1_raycast", 8, 6) == kExitBadOption);
  // Something else altogether.
  write_bytes(bad, std::vector<char>(4096, 'x'));
  CHECK(load_code(bad, key, "stage1_raycast", 8, 6, &message) == kExitBadOption);
  CHECK(message.find("not a checkpoint") != std::string::npos);
  fs::remove_all(good.parent_path());
}

TEST_CASE("checkpoint: a resumed render counts the checkpoint's film too when it checks the memory",
          "[reliability][bounds]") {
  // The need per pixel of a render (common/render/memory.h) without and with the
  // checkpoint's film; an image of available / (their mean) pixels fits the first and not
  // the second.
  pt::FramePlan plan;
  plan.width = plan.height = 10000, plan.out = "a.png";
  const double one = double(pt::memory_need(plan).bytes) / 1e8;
  plan.resuming = true;
  const double resuming = double(pt::memory_need(plan).bytes) / 1e8;
  REQUIRE(resuming > one * 1.2);
  const std::uint64_t pixels = std::uint64_t(double(pt::available_memory_bytes()) / (0.5 * (one + resuming)));
  if (pixels > (std::uint64_t(1) << 31)) {
    WARN("more memory than one image may use: nothing to check here");
    return;
  }
  plan.width = plan.height = int(std::sqrt(double(pixels)));
  plan.resuming = false;
  CHECK_NOTHROW(pt::check_memory(plan));
  plan.resuming = true;
  CHECK_THROWS_AS(pt::check_memory(plan), pt::Error);
}
