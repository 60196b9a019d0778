// PT_FAULT, parsed (see fault.h).
#include "gpu/fault.h"

#include <cstdlib>
#include <string>

#include "common/base/error.h"

namespace pt::gpu {

namespace {

Fault parse(const char* env) {
  Fault f;
  if (!env || !*env) return f;
  std::string v = env;
  const std::string lost = "device_lost:pass=";
  if (v == "no_loader") {
    f.no_loader = true;
  } else if (v == "no_device") {
    f.no_device = true;
  } else if (v == "small_limits") {
    f.small_limits = true;
  } else if (v == "small_texel_limit") {
    f.small_texel_limit = true;
  } else if (v.rfind(lost, 0) == 0 && v.size() > lost.size() &&
             v.find_first_not_of("0123456789", lost.size()) == std::string::npos && v.size() - lost.size() < 12) {
    f.device_lost_pass = std::strtoull(v.c_str() + lost.size(), nullptr, 10);
  }
  if (!f.no_loader && !f.no_device && !f.small_limits && !f.small_texel_limit && f.device_lost_pass == 0) {
    throw Error(kExitBadOption, "PT_FAULT='" + v +
                                    "' is not a fault; use no_loader, no_device, small_limits, small_texel_limit "
                                    "or device_lost:pass=N (N >= 1), or unset it");
  }
  return f;
}

}  // namespace

const Fault& fault() {
  static const Fault f = parse(std::getenv("PT_FAULT"));
  return f;
}

}  // namespace pt::gpu
