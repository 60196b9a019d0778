// Checkpoint files (see checkpoint.h). Layout, host byte order (x86-64 and ARM64: little
// endian): 8-byte magic, the render key, the stage name (32 bytes), width, height, spp,
// passes, the counters, the seconds, then width * height * 4 doubles of film sums, and
// last an FNV-1a hash of every byte before it, which finds truncation and damage.
#include "common/app/checkpoint.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "common/app/replace_file.h"
#include "common/base/error.h"
#include "common/scene/environment.h"
#include "common/scene/scene.h"

namespace pt {
namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'P', 'T', 'C', 'K', 'P', 'T', 0, 2};  // the last byte: format version (2: passes end at 1, 2, 4, 8, 16, 32, ...)

struct Header {
  char magic[8];
  std::uint64_t key;
  char stage[32];
  std::uint32_t width, height;
  std::uint64_t spp, passes;
  std::uint64_t depth_cap, zero_pdf, non_finite;
  std::uint32_t first_non_finite_pixel, reserved;
  double seconds, kernel_seconds;
};
static_assert(sizeof(Header) == 8 + 8 + 32 + 8 + 16 + 24 + 8 + 16);

struct Fnv {
  std::uint64_t h = 14695981039346656037ull;
  void add(const void* data, std::size_t bytes) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; i++) h = (h ^ p[i]) * 1099511628211ull;
  }
  template <class T, class A>
  void add_vector(const std::vector<T, A>& v) {
    std::uint64_t n = v.size();
    add(&n, sizeof n);
    if (n) add(v.data(), n * sizeof(T));
  }
};

[[noreturn]] void refuse(const std::string& path, const std::string& why, const std::string& todo) {
  throw Error(kExitBadOption, "checkpoint '" + path + "' " + why + "; " + todo);
}

}  // namespace

std::uint64_t bytes_hash(const void* data, std::size_t bytes) {
  Fnv f;
  f.add(data, bytes);
  return f.h;
}

std::uint64_t scene_hash(const Scene& scene) {
  Fnv f;
  f.add_vector(scene.triangles);
  f.add_vector(scene.spheres);
  f.add_vector(scene.materials);
  f.add_vector(scene.point_lights);
  f.add_vector(scene.lights);
  // Textures and vertex colours (empty without them).
  f.add_vector(scene.triangle_attributes);
  f.add_vector(scene.material_textures);
  if (!scene.triangle_shading.empty()) f.add_vector(scene.triangle_shading);  // keeps older keys
  f.add_vector(scene.textures);
  f.add_vector(scene.texels);
  if (scene.environment) {  // the map as the kernel reads it (radiance x strength)
    f.add_vector(scene.environment->radiance);
    f.add(&scene.environment->width, sizeof scene.environment->width);
  }
  return f.h;
}

std::uint64_t render_key(const char* stage, const Scene& scene, const RenderSettings& s) {
  Fnv f;
  f.add(stage, std::strlen(stage) + 1);
  const std::uint64_t content = scene_hash(scene);
  f.add(&content, sizeof content);
  // The frame parameters hold the camera, size, seed, sky, roulette, depth cap and the
  // scene's scale; the per-pass fields stay zero.
  FrameParams params = make_frame_params(scene, s);
  params.accel = kAccelNone;  // the BVH gives the same image: a checkpoint resumes either way
  f.add(&params, sizeof params);
  std::uint32_t general = s.all_features ? 1u : 0u;
  f.add(&general, sizeof general);
  f.add(&s.first_sample, sizeof s.first_sample);  // --samples FIRST:COUNT: a part starts there
  return f.h;
}

void save_checkpoint(const std::string& path, std::uint64_t key, const char* stage, const RenderResult& r) {
  Header h;
  std::memset(&h, 0, sizeof h);
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.key = key;
  std::strncpy(h.stage, stage, sizeof h.stage - 1);
  h.width = std::uint32_t(r.film.width());
  h.height = std::uint32_t(r.film.height());
  h.spp = r.film.spp();
  h.passes = r.passes;
  h.depth_cap = r.counters.depth_cap;
  h.zero_pdf = r.counters.zero_pdf;
  h.non_finite = r.counters.non_finite;
  h.first_non_finite_pixel = r.counters.first_non_finite_pixel;
  h.seconds = r.seconds;
  h.kernel_seconds = r.kernel_seconds;
  const std::vector<double>& sums = r.film.sums();
  Fnv f;
  f.add(&h, sizeof h);
  f.add(sums.data(), sums.size() * sizeof(double));

  // The old checkpoint stays whole until the new one is on the disk (replace_file.h).
  replace_file(path, {{&h, sizeof h}, {sums.data(), sums.size() * sizeof(double)}, {&f.h, sizeof f.h}},
               "free some space or choose another --out folder", "checkpoint");
}

RenderResult load_checkpoint(const std::string& path, std::uint64_t key, const char* stage, int width, int height,
                             std::uint64_t first_sample) {
  const std::string redo = "delete it and render again without --resume";
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) refuse(path, "is a folder", "give --resume the checkpoint file's path");
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    refuse(path, "is not a regular file", "give --resume the checkpoint file's path");
  }
  if (!fs::is_regular_file(status)) {
    refuse(path, "does not exist", "render with --checkpoint SECONDS first, or give --resume the checkpoint's path");
  }
  std::uintmax_t size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) refuse(path, "cannot be read", "check its permissions");
  Header h;
  if (size < sizeof h + sizeof(std::uint64_t) || !in.read(reinterpret_cast<char*>(&h), sizeof h)) {
    refuse(path, "is truncated (" + std::to_string(size) + " bytes)", redo);
  }
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0) refuse(path, "is not a checkpoint of this program's version", redo);
  // Memory for the sums only for the size the options ask for (already checked against
  // the machine's memory).
  if (int(h.width) != width || int(h.height) != height) {
    refuse(path, "is of a " + std::to_string(h.width) + "x" + std::to_string(h.height) + " image, not " +
                     std::to_string(width) + "x" + std::to_string(height),
           "resume with the same --width and --height");
  }
  // The size the header promises, computed with overflow checks before anything is allocated.
  std::uint64_t values = 0, bytes = 0;
  if (__builtin_mul_overflow(std::uint64_t(h.width) * std::uint64_t(h.height), std::uint64_t(4), &values) ||
      __builtin_mul_overflow(values, std::uint64_t(sizeof(double)), &bytes) ||
      bytes + sizeof h + sizeof(std::uint64_t) != size) {
    refuse(path, "is truncated or damaged (" + std::to_string(size) + " bytes, not what its header says)", redo);
  }
  std::vector<double> sums(values);
  std::uint64_t stored = 0;
  if (!in.read(reinterpret_cast<char*>(sums.data()), std::streamsize(bytes)) ||
      !in.read(reinterpret_cast<char*>(&stored), sizeof stored)) {
    refuse(path, "is truncated", redo);
  }
  Fnv f;
  f.add(&h, sizeof h);
  f.add(sums.data(), bytes);
  if (f.h != stored) refuse(path, "is damaged (its checksum does not match)", redo);
  // A checkpoint is saved after whole passes: its samples end where a pass ends.
  if (h.passes > h.spp || h.spp >= kSampleIndexLimit || !is_pass_end(first_sample + h.spp)) {
    refuse(path, "is damaged (" + std::to_string(h.spp) + " spp in " + std::to_string(h.passes) + " passes)", redo);
  }
  h.stage[sizeof h.stage - 1] = 0;
  if (std::strcmp(h.stage, stage) != 0) {
    refuse(path, std::string("is of ") + h.stage + ", not " + stage, std::string("resume it with ") + h.stage + ", or render without --resume");
  }
  if (h.key != key) {
    refuse(path, "is of a different render (scene, seed, sky or --all-features, --rr, --depth-cap differ)",
           "resume with the options it was made with, or render without --resume");
  }
  RenderResult r{Film(width, height), h.seconds, h.kernel_seconds, {}, 0, {}, {}, {}};
  r.film.restore(h.spp, std::move(sums));
  r.passes = h.passes;
  r.counters.depth_cap = h.depth_cap;
  r.counters.zero_pdf = h.zero_pdf;
  r.counters.non_finite = h.non_finite;
  r.counters.first_non_finite_pixel = h.first_non_finite_pixel;
  return r;
}

}  // namespace pt
