// A render's memory need, checked before it starts, and the steps that name a failed
// allocation (memory.h); the probe of what is available is memory_probe.cpp.
// Not part of the article: the machinery of the stage programs.
#include "common/render/memory.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <thread>
#include <vector>

#include "common/base/error.h"
#include "common/scene/scene.h"

namespace pt {

// ---- The need ----------------------------------------------------------------------
//
// Bytes per pixel and per triangle of what each step holds, from the code that allocates
// them; the peaks measured stay below the estimate (the numbers at memory_need()).
namespace {

constexpr std::uint64_t kFilm = 4 * 8;         // film.h: r, g, b, squared luminance sums (double)
constexpr std::uint64_t kFilmHalves = 2 * 8;   // film.h, track_halves: two luminance snapshots
constexpr std::uint64_t kPass = 4 * 4;         // render.cpp: one pass, a vec4 per pixel
constexpr std::uint64_t kGpuOutput = 4 * 4;    // gpu_backend.cpp: the output buffer, host-visible
constexpr std::uint64_t kGpuOneSample = 4 * 8;  // gpu_backend.cpp: run_one_sample_at_a_time's sums
constexpr std::uint64_t kCheckpointLoad = 4 * 8 + 4 * 8;  // checkpoint.cpp: the sums read + the film
constexpr std::uint64_t kMeanRgb = 3 * 4;      // Film::mean_rgb, what the image is made from
// The .exr (image_output.cpp, exr_file.cpp): 3 floats of RGB, 1 of variance, 8 uint32 of
// the film's sums (and 2 of the halves with --keep-halves) per pixel; then encoded in
// memory, into room reserved for them uncompressed.
constexpr std::uint64_t kExrChannels = (3 + 1 + 8) * 4;
constexpr std::uint64_t kExrHalves = 2 * 4;
// A .png: 3 bytes of sRGB, then its encoding, up to that much again in a vector that may
// hold twice its size while it grows; an .hdr: RGBE, 4 bytes, the same way.
constexpr std::uint64_t kPngBytes = 3 + 2 * 3;
constexpr std::uint64_t kHdrBytes = 4 + 2 * 4;
// Fixed costs: OpenEXR's header and the room reserved past it (1 MB); its line buffers:
// 16 rows of the channels, compressed and not, per column.
constexpr std::uint64_t kEncodingFixed = std::uint64_t(2) << 20;
constexpr std::uint64_t kEncodingRows = 2 * 16;
// The error map (error_map.cpp): a float per pixel, the halves' spread (double) while it is
// made, then an RGB image of its own.
constexpr std::uint64_t kErrorValues = 4;
constexpr std::uint64_t kErrorSpread = 8;
// The BVH (common/scene/bvh.cpp): each triangle's box, centroid and index while it is built
// (40 bytes), the nodes reserved at twice the triangles (64), a thread's subtree (32) and
// the index list (4); kept: the nodes and the index list.
constexpr std::uint64_t kBvhBuild = 40 + 64 + 32 + 4;
constexpr std::uint64_t kBvhKept = 64 + 4;
// The CPU backend's copies (cpu/): the triangles as 9 arrays (36 bytes, padded to a block),
// and with a BVH its 8-wide form: nodes of 224 bytes reserved at a sixteenth of the binary
// tree's bound (2 nodes a triangle), leaf blocks of 320 bytes at an eighth, and the counts
// (4 bytes a node) while it is built.
constexpr std::uint64_t kCpuTriangles = 36;
constexpr std::uint64_t kCpuWideBvh = 2 * 224 / 16 + 2 * 320 / 8 + 2 * 4;
// What a backend takes whatever the image: the CPU's threads, 32 MB; the Vulkan driver's
// compile of the kernel (lavapipe's LLVM: 57 MB for stage1, 177 MB for stage4, 210 MB for
// stage5 and 273 MB for its general kernel, the peak of an 8x8 render less the memory
// before the device was made).
constexpr std::uint64_t kCpuFixed = std::uint64_t(32) << 20;
constexpr std::uint64_t kGpuFixed = std::uint64_t(320) << 20;
// Address space only (RLIMIT_AS): each CPU thread's stack (8 MiB), and the malloc arena
// glibc may make for each worker besides the main thread and for the BVH builder's second
// thread (64 MiB reserved, kept after the thread ends). Measured: a 2048x2048 .exr needs
// 711 MB of RLIMIT_AS with 2 threads, 641 MB with 1; the estimate without them was 671 MB.
constexpr std::uint64_t kThreadStack = std::uint64_t(8) << 20;
constexpr std::uint64_t kThreadArena = std::uint64_t(64) << 20;
constexpr std::uint64_t kBvhParallelTriangles = 1u << 16;  // bvh.cpp's kParallelSize
// The GPU backend's buffers: every scene array once more (and the triangles as a uniform
// buffer when they fit one, 64 KB), the BVH's nodes and index list.
constexpr std::uint64_t kGpuUniformTriangles = 64 * 1024;

std::uint64_t mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  return __builtin_mul_overflow(a, b, &r) ? UINT64_MAX : r;
}

std::uint64_t add(std::uint64_t a, std::uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

std::string lower_extension(const std::string& path) {
  std::size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower((unsigned char)c));
  return ext;
}

// Per pixel: the image encoded in memory, film channels included for an .exr.
std::uint64_t encoding_per_pixel(const std::string& path, bool film, bool keep_halves) {
  const std::string ext = lower_extension(path);
  if (ext == "png") return kPngBytes;
  if (ext == "hdr") return kHdrBytes;
  const std::uint64_t channels = film ? kExrChannels + (keep_halves ? kExrHalves : 0) : 3 * 4;
  return 2 * channels;  // the channels, and their bytes
}

// The scene's arrays, as the GPU backend copies them (gpu_backend.cpp, set_scene).
std::uint64_t scene_array_bytes(const Scene& s) {
  std::uint64_t b = 0;
  b = add(b, mul(s.triangles.size(), sizeof(Triangle)));
  b = add(b, mul(s.spheres.size(), sizeof(Sphere)));
  b = add(b, mul(s.materials.size(), sizeof(Material)));
  b = add(b, mul(s.point_lights.size(), sizeof(PointLight)));
  b = add(b, mul(s.lights.size(), sizeof(Light)));
  b = add(b, mul(s.light_alias.size(), sizeof(LightAlias)));
  b = add(b, mul(s.triangle_attributes.size(), sizeof(TriangleAttributes)));
  b = add(b, mul(s.material_textures.size(), sizeof(MaterialTextures)));
  b = add(b, mul(s.triangle_shading.size(), sizeof(TriangleShading)));
  b = add(b, mul(s.textures.size(), sizeof(Texture)));
  b = add(b, mul(s.texels.size(), sizeof(uint)));
  if (s.environment) b = add(b, mul(s.environment->radiance.size() + s.environment->table.size(), sizeof(float)));
  return add(b, kGpuUniformTriangles);
}


// One step of the render: what it holds, named.
struct Step {
  const char* name;
  std::vector<std::pair<const char*, std::uint64_t>> parts;
  std::uint64_t total() const {
    std::uint64_t t = 0;
    for (const auto& p : parts) t = add(t, p.second);
    return t;
  }
};

}  // namespace

// Measured on 2026-12-06 (2 threads; lavapipe for the GPU): the peak resident memory
// (VmHWM) less the resident memory at this check, over the pixels or triangles:
//   CPU .exr  101 B/pixel (stage1, 1 spp), 145 (stage4, 4 spp), 162 (stage4 with
//             --keep-halves and --error-map); estimate 156, 172 with --keep-halves;
//   CPU .png and .hdr  56 B/pixel; estimate 69 and 72;
//   GPU .exr  130 B/pixel (stage1 at 2048x2048, the kernel's compile included), .png 85;
//             estimate 172 and 85, with 320 MB for the compile;
//   triangles (builtin:furnace_mesh, 1.31 M)  CPU 144 B, GPU 130 B over the compile;
//             estimate 220 and 184.
// Under RLIMIT_AS the least limit that a 2048x2048 .exr renders under is 711 MB (2
// threads; 641 MB with 1), against an estimate of 898 MB with the threads' reserve.
MemoryNeed memory_need(const FramePlan& p) {
  const std::uint64_t px = mul(std::uint64_t(std::max(p.width, 0)), std::uint64_t(std::max(p.height, 0)));
  const std::uint64_t tris = p.scene ? p.scene->triangles.size() : 0;
  const bool bvh = p.bvh && tris > 0;
  // Held from the BVH's build to the end: the BVH, the backend's copies of the scene.
  const std::uint64_t bvh_kept = bvh ? mul(tris, kBvhKept) : 0;
  std::uint64_t copies = 0;
  if (p.scene && p.gpu) copies = add(scene_array_bytes(*p.scene), bvh_kept);
  if (p.scene && !p.gpu) {
    copies = add(mul(tris, kCpuTriangles + (bvh ? kCpuWideBvh : 0)), mul(p.scene->spheres.size(), 64));
  }
  const std::uint64_t film = mul(px, kFilm + kFilmHalves);
  const std::uint64_t resumed = p.resuming ? mul(px, kCheckpointLoad) : 0;
  const std::uint64_t gpu_output = p.gpu ? mul(px, kGpuOutput) : 0;
  const unsigned threads = p.threads ? p.threads : std::max(1u, std::thread::hardware_concurrency());
  const std::uint64_t backend = p.gpu ? kGpuFixed : kCpuFixed;
  std::vector<Step> steps;
  if (bvh) steps.push_back({"building the BVH", {{"checkpoint", resumed}, {"BVH", mul(tris, kBvhBuild)}}});
  steps.push_back({"rendering",
                   {{"film", film},
                    {"checkpoint", resumed},
                    {"pass buffers", mul(px, kPass + (p.gpu ? kGpuOutput + kGpuOneSample : 0))},
                    {"BVH", bvh_kept},
                    {p.gpu ? "GPU buffers of the scene" : "CPU copies of the scene", copies},
                    {p.gpu ? "the driver's compile of the kernel" : "CPU threads", backend}}});
  const std::vector<std::pair<const char*, std::uint64_t>> kept = {
      {"film", film}, {"BVH", bvh_kept}, {p.gpu ? "GPU buffers" : "CPU copies of the scene", add(copies, gpu_output)}};
  Step image{"writing the image", kept};
  const std::uint64_t rows = mul(std::uint64_t(std::max(p.width, 0)), kEncodingRows * kExrChannels);
  image.parts.push_back({"image encoding", add(add(kEncodingFixed, rows),
                                               mul(px, kMeanRgb + encoding_per_pixel(p.out, true, p.keep_halves)))});
  steps.push_back(image);
  if (!p.error_map.empty()) {
    Step map{"writing the error map", kept};
    const std::uint64_t per_pixel =
        kErrorValues + std::max(kErrorSpread, kMeanRgb + encoding_per_pixel(p.error_map, false, false));
    map.parts.push_back({"error map", add(kEncodingFixed, mul(px, per_pixel))});
    steps.push_back(map);
  }
  const Step* peak = &steps.front();
  for (const Step& s : steps) {
    if (s.total() > peak->total()) peak = &s;
  }
  MemoryNeed need{peak->total(), peak->name, "", 0, 0};
  for (const auto& [what, bytes] : peak->parts) {
    if (bytes < 1000000) continue;  // a part under 1 MB is not worth the words
    need.parts += (need.parts.empty() ? "" : ", ") + std::string(what) + " " + memory_size_words(bytes);
  }
  // The CPU's workers besides the main thread, and the BVH builder's second thread. Threads
  // beyond the cores are counted out: the CPU backend renders with the threads the system
  // starts (cpu/), so an --threads the address space cannot hold is no reason to refuse.
  const unsigned counted = std::min(threads, std::max(1u, std::thread::hardware_concurrency()));
  const std::uint64_t arenas = counted - 1u + (bvh && tris >= kBvhParallelTriangles ? 1u : 0u);
  need.reserved = p.gpu ? 0 : add(mul(counted + 1u, kThreadStack), mul(arenas, kThreadArena));
  need.address_space = add(need.bytes, need.reserved);
  return need;
}

void check_memory(const FramePlan& p) {
  const std::uint64_t pixels = std::uint64_t(std::max(p.width, 0)) * std::uint64_t(std::max(p.height, 0));
  const std::string size = std::to_string(p.width) + "x" + std::to_string(p.height);
  if (pixels > (std::uint64_t(1) << 31)) {
    throw Error(kExitBadOption, "image " + size + " has more than 2^31 pixels; render a smaller image");
  }
  const MemoryNeed need = memory_need(p);
  const AvailableMemory available = available_memory();
  std::string what = "a " + size + " render";
  if (p.scene) what += " of " + std::to_string(p.scene->triangles.size()) + " triangles";
  if (p.gpu) what += " on the GPU";
  const std::string todo = "; render a smaller image or scene, or give the job more memory";
  if (need.bytes > available.bytes) {
    throw Error(kExitBadOption, what + " needs " + memory_size_words(need.bytes) + " of memory while " + need.step + " (" +
                                    need.parts + ") but " + memory_size_words(available.bytes) + " is available, bound by " +
                                    available.bound + todo);
  }
  if (need.address_space > available.address_space) {
    throw Error(kExitBadOption, what + " needs " + memory_size_words(need.address_space) + " of address space while " +
                                    need.step + " (" + need.parts + ", stacks and malloc arenas of its threads " +
                                    memory_size_words(need.reserved) + ") but " + memory_size_words(available.address_space) +
                                    " is available, bound by " + available.address_space_bound + todo);
  }
}

// ---- Steps, for the message of a failed allocation ---------------------------------

namespace {
thread_local const MemoryStep* innermost_step = nullptr;
// The innermost step that an exception left while it unwound: run_guarded's handler runs
// after the steps are gone. A fixed buffer: no allocation while memory runs out.
thread_local char unwound_step[256] = "";
}  // namespace

MemoryStep::MemoryStep(std::string what)
    : what_(std::move(what)), outer_(innermost_step), exceptions_(std::uncaught_exceptions()) {
  innermost_step = this;
  unwound_step[0] = 0;
}

MemoryStep::~MemoryStep() {
  innermost_step = outer_;
  if (std::uncaught_exceptions() > exceptions_ && !unwound_step[0]) {
    std::snprintf(unwound_step, sizeof unwound_step, "%s", what_.c_str());
  }
}

std::string MemoryStep::current() { return innermost_step ? innermost_step->what_ : std::string(unwound_step); }

}  // namespace pt
