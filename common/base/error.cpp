// Warnings printed once each (the contract (README.md): unsupported features are named once).
#include "common/base/error.h"

#include <cstdio>
#include <mutex>
#include <set>

namespace pt {

namespace {
std::mutex warnings_mutex;
std::set<std::string> warnings_given;
}  // namespace

void warn_once(const std::string& message) {
  std::lock_guard<std::mutex> lock(warnings_mutex);
  if (warnings_given.insert(message).second) std::fprintf(stderr, "warning: %s\n", message.c_str());
}

void forget_warnings_given() {
  std::lock_guard<std::mutex> lock(warnings_mutex);
  warnings_given.clear();
}

}  // namespace pt
