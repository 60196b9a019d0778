// Test support for the tests of film parts and their merge (tests/common/app/test_film_file.cpp,
// test_film_part_refusals.cpp): their scratch folder, and one part of a render (a range of its
// samples, rendered on the CPU) written as an .exr. Not part of the article: the machinery
// of the stage programs' --samples FIRST:COUNT and pt_merge.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <catch2/catch.hpp>

#include "common/app/film_file.h"
#include "common/app/image_output.h"
#include "tests/support/test_render.h"

namespace pt::test {

inline std::filesystem::path scratch(const std::string& name) {
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("pt_film_file_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

// Renders the samples [first, first + count) of `scene` on the CPU and writes them as a part.
inline std::string render_part(const StageKernels& kernels, const Scene& scene, RenderSettings s, std::uint64_t first,
                               std::uint64_t count, const std::string& name, bool keep_halves = false) {
  s.first_sample = first, s.spp = count;
  std::unique_ptr<Backend> backend = make_backend("cpu", kernels);
  RenderResult r = render(*backend, scene, s);
  REQUIRE(r.film.spp() == count);
  ImageMetadata meta;
  meta.stage = kernels.name, meta.backend = "cpu", meta.scene = scene.name, meta.spp = count, meta.seed = s.seed;
  meta.film = &r.film;
  meta.identity = film_identity(kernels.name, scene, s);
  meta.ranges = {{first, count}};
  meta.keep_halves = keep_halves;
  const std::string path = scratch(name).string();
  OutputFile(path).write(r.film.mean_rgb(), s.width, s.height, meta);
  return path;
}

}  // namespace pt::test
