// The host memory a render needs, checked before it starts (memory.h).
#include "common/render/memory.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "common/base/error.h"

namespace pt {

std::uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kb;
  std::string unit;
  while (meminfo >> key >> kb >> unit) {
    if (key == "MemAvailable:") return kb * 1024;
  }
  return std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGE_SIZE));
}

void check_image_memory(int width, int height, bool resuming) {
  // Film: 4 doubles per pixel (twice while a checkpoint's film is read in), and 2 more for
  // the halves' sums under the default sampler (film.h, track_halves); pass buffer: 4 floats
  // per pixel; output: 3 floats.
  const std::uint64_t films = resuming ? 2 : 1;
  const std::uint64_t host_per_pixel =
      films * 4 * sizeof(double) + 2 * sizeof(double) + 4 * sizeof(float) + 3 * sizeof(float);
  std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height), bytes = 0;
  if (pixels > (std::uint64_t(1) << 31)) {
    throw Error(kExitBadOption, "image " + std::to_string(width) + "x" + std::to_string(height) +
                                    " has more than 2^31 pixels; render a smaller image");
  }
  if (__builtin_mul_overflow(pixels, host_per_pixel, &bytes) || bytes > available_memory_bytes()) {
    char line[256];
    std::snprintf(line, sizeof line, "image %dx%d needs %.1f GB of memory, this machine has %.1f GB available; "
                  "render a smaller image", width, height, double(pixels) * double(host_per_pixel) / 1e9,
                  double(available_memory_bytes()) / 1e9);
    throw Error(kExitBadOption, line);
  }
}

}  // namespace pt
