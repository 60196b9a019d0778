// Test support for the reliability tests of stage1_raycast as users run it
// (tests/stages/test_cli_reliability.cpp, test_cli_devices.cpp, test_cli_memory.cpp): running
// it in their scratch folder, reading back the image it wrote, and whether a Vulkan device is
// here. Not part of the article: the machinery of the stage programs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "tests/support/cli_run.h"

namespace pt_test::stage1_cli {

inline std::string slurp(const std::filesystem::path& p) { return pt_test::read_file(p); }

inline std::filesystem::path scratch() { return pt_test::scratch_dir("pt_rel_cli"); }

inline std::string path(const std::string& name) { return (scratch() / name).string(); }

inline Run run(const std::string& args, const std::string& env = "") {
  return pt_test::run_program(PT_STAGE1_BIN, args, env, scratch());
}

inline void check_error(const Run& r, int code, const std::string& words) {
  pt_test::check_error(r, "stage1_raycast", code, words);
}

struct Image {
  std::vector<float> pixels;
  std::uint64_t spp = 0;
};

inline Image read_image(const std::string& file) {
  Image image;
  auto in = OIIO::ImageInput::open(file);
  if (!in) return image;
  const OIIO::ImageSpec& spec = in->spec();
  image.pixels.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data());
  image.spp = std::stoull(std::string(spec.get_string_attribute("pt:spp", "0")));
  return image;
}

// Whether this machine has a Vulkan device (lavapipe counts); the device tests need one.
inline bool have_vulkan_device() {
  static int have = -1;
  if (have < 0) have = run("--backend gpu --width 8 --height 8 --out " + path("probe.exr")).code == 0;
  return have == 1;
}

}  // namespace pt_test::stage1_cli
