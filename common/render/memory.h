// The memory probe: whether this machine has the host memory an image needs (memory.cpp).
#pragma once

#include <cstdint>

namespace pt {

// Bytes of host memory a render of this size needs (film + pass buffer; a resumed render
// holds a second film, the checkpoint's, while it starts: resuming = true), with overflow
// checks; throws pt::Error(2) naming the numbers if the machine does not have them. The
// GPU backend checks its own device's limits.
void check_image_memory(int width, int height, bool resuming = false);

// The host memory available now (MemAvailable of /proc/meminfo, else all of it).
std::uint64_t available_memory_bytes();

}  // namespace pt
