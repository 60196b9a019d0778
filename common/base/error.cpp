// Warnings printed once each (the contract (README.md): unsupported features are named once).
#include "common/base/error.h"

#include <cstdio>
#include <mutex>
#include <set>

namespace pt {

void warn_once(const std::string& message) {
  static std::mutex mutex;
  static std::set<std::string> seen;
  std::lock_guard<std::mutex> lock(mutex);
  if (seen.insert(message).second) std::fprintf(stderr, "warning: %s\n", message.c_str());
}

}  // namespace pt
