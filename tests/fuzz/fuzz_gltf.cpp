// libFuzzer target for the glTF loader (the contract (README.md) "Scenes"; the article's
// scenes come from glTF files): every input is written to a file and loaded as a .glb
// (when it starts with the GLB magic) or a .gltf. A malformed file must end in pt::Error
// (exit 3 with one line in the programs); a crash, a sanitizer report, a hang or any
// other exception is a finding, and its input is kept in tests/fuzz/crashes/ as a
// regression fixture that the test suite loads every run (tests/fuzz/CMakeLists.txt).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "common/base/error.h"
#include "common/scene/scene_loading.h"
#include "common/scene/scene_sanity.h"

namespace {

std::string scratch_path(const char* ext) {
  static const std::string base = [] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/pt_fuzz_" + std::to_string(::getpid());
  }();
  return base + ext;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = scratch_path(glb ? ".glb" : ".gltf");
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  if (size) std::fwrite(data, 1, size, f);
  std::fclose(f);
  // The budget the programs take from the machine (scene_sanity.h), here well inside
  // -rss_limit_mb: instancing a mesh on many nodes is refused, not a finding.
  pt::set_scene_memory_budget(std::uint64_t(512) << 20);
  try {
    pt::Scene scene = pt::load_gltf(path);
    (void)scene;
  } catch (const pt::Error& e) {
    if (e.code() != pt::kExitBadScene) {
      std::fprintf(stderr, "a malformed scene gave exit %d, not 3: %s\n", e.code(), e.what());
      std::abort();
    }
  }
  std::remove(path.c_str());
  return 0;
}
