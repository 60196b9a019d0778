// Regression fixtures of the glTF fuzzer (tests/fuzz/fuzz_gltf.cpp): every input that ever
// crashed the loader or gave anything but a clean pt::Error(3) is kept in
// tests/fuzz/crashes/ (named .glb when it starts with the GLB magic, else .gltf, as the
// fuzzer loads it) and loaded here on every run, and under the sanitizers in build-asan:
// it must load or be refused with exit 3, never crash.
// Not part of the article: the loader's robustness (the contract (README.md) "Scenes").
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "common/base/error.h"
#include "common/scene/scene_loading.h"

namespace fs = std::filesystem;

TEST_CASE("fuzz: every input that ever crashed the glTF loader now loads or exits 3", "[fuzz][reliability]") {
  const fs::path crashes = fs::path(PT_SOURCE_DIR) / "tests" / "fuzz" / "crashes";
  REQUIRE(fs::is_directory(crashes));
  for (const auto& entry : fs::directory_iterator(crashes)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    INFO(entry.path().filename().string());
    try {
      pt::Scene scene = pt::load_gltf(entry.path().string());
      CHECK(scene.triangles.size() + scene.spheres.size() < (std::size_t(1) << 32));
    } catch (const pt::Error& e) {
      CHECK(e.code() == pt::kExitBadScene);
    }
  }
}
