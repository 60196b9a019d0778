// The memory probe and the memory a render needs (memory.cpp): what this process may still
// take, the peak a render will reach, figured before anything large is allocated, and the
// step the program is in when an allocation fails. Not part of the article: the machinery
// of the stage programs.
#pragma once

#include <cstdint>
#include <string>

namespace pt {

struct Scene;
struct Bvh;

// The host memory this process may still take, and the limit that bounds it: the smallest of
//   MemAvailable of /proc/meminfo (the machine),
//   the cgroup's limit less its usage (a Slurm job, a container): cgroup v2 memory.max less
//     memory.current, v1 memory.limit_in_bytes less memory.usage_in_bytes, of the process's
//     own cgroup (/proc/self/cgroup) and each one above it; page cache the cgroup can drop
//     (inactive_file of memory.stat) is not counted as used,
//   RLIMIT_AS (ulimit -v, prlimit --as) less the address space the process has
//     (/proc/self/statm).
// A source that is absent or cannot be parsed is left out; with none, the physical memory.
struct AvailableMemory {
  std::uint64_t bytes = 0;
  std::string bound;  // which one, in words: "MemAvailable of /proc/meminfo", ...
  // RLIMIT_AS's own figure (UINT64_MAX: no limit), and its words: address space that is
  // reserved but never used (thread stacks, malloc's arenas) counts against it alone.
  std::uint64_t address_space = UINT64_MAX;
  std::string address_space_bound;
};
// PT_MEMORY_ROOT=DIR (tests only) reads /proc and /sys under DIR instead: a fake machine.
AvailableMemory available_memory();
// The same from the files under `root` ("" for /), with this RLIMIT_AS (0: none).
AvailableMemory available_memory(const std::string& root, std::uint64_t address_space_limit);
std::uint64_t available_memory_bytes();  // available_memory().bytes
// A size as the messages give it: "420 MB", "20.4 GB".
std::string memory_size_words(std::uint64_t bytes);

// A render as its memory sees it. Before the scene is loaded (scene == nullptr) only the
// image's part is known.
struct FramePlan {
  int width = 0, height = 0;
  bool resuming = false;         // --resume: the checkpoint's film is held while it renders
  bool gpu = false;              // the GPU backend: its buffers are host-visible memory too
  std::string out = "out.exr";   // --out: its type says how the image is encoded in memory
  std::string error_map;         // --error-map, or none
  const Scene* scene = nullptr;  // the loaded scene: its BVH, the backend's copies of it
  bool bvh = true;               // --accel bvh
  bool keep_halves = false;      // --keep-halves: two more .exr channels
  unsigned threads = 0;          // --threads of the CPU backend (0: one per core)
};

// The peak of a render: the largest of its steps (building the BVH, rendering, writing the
// image, writing the error map), each the sum of what is held during it.
struct MemoryNeed {
  std::uint64_t bytes = 0;  // saturates at UINT64_MAX
  std::string step;         // the step of the peak, e.g. "writing the image"
  std::string parts;        // what it holds then, e.g. "film 201 MB, image encoding 470 MB"
  // The address space the peak takes (RLIMIT_AS): bytes and the CPU threads' stacks and
  // malloc arenas, reserved but mostly never touched.
  std::uint64_t address_space = 0;
  std::uint64_t reserved = 0;  // that reserve alone
};
MemoryNeed memory_need(const FramePlan& plan);

// Throws pt::Error(kExitBadOption) when the render's need is more than the memory
// available: one line with both numbers, the limit that binds, and what to do. More than
// 2^31 pixels is refused outright.
void check_memory(const FramePlan& plan);

// While one lives, a std::bad_alloc is said to happen while `what` (run_guarded): "building
// the BVH", "writing the image 'a.exr'". They nest; the innermost names the step, also
// after an exception has unwound it (a handler runs once the steps are gone).
class MemoryStep {
 public:
  explicit MemoryStep(std::string what);
  ~MemoryStep();
  MemoryStep(const MemoryStep&) = delete;
  MemoryStep& operator=(const MemoryStep&) = delete;
  // The innermost step's words; outside any, those of the innermost one the last exception
  // left, "" if none did since the last step began.
  static std::string current();

 private:
  std::string what_;
  const MemoryStep* outer_;
  int exceptions_;  // std::uncaught_exceptions() when it began
};

// A backend whose device has limits of its own besides the host's memory (the GPU backend,
// gpu/gpu_backend.cpp) also implements this; the render asks it before anything is built.
class DeviceMemoryLimits {
 public:
  virtual ~DeviceMemoryLimits() = default;
  // Throws pt::Error(kExitNoDevice) naming the buffer, its size and the device's limit when
  // the device cannot hold a render of `pixels` pixels of `scene` with the kernel of the
  // kFeature* bits `features`; `bvh`: its hierarchy once built (nullptr: checked later).
  virtual void check_device_memory(const Scene& scene, std::uint32_t features, std::uint64_t pixels,
                                   const Bvh* bvh) const = 0;
};

}  // namespace pt
