// Loads OpenImageIO's module on first use (see openimageio.h): pt_openimageio.so from the
// folder of the running program (build/bin), once per process.
#include "common/base/openimageio.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <mutex>

namespace pt {
namespace {

// The folder of the running program, with a trailing '/'; "" if it cannot be found.
std::string program_folder() {
  char path[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) return "";
  std::string p(path, std::size_t(n));
  return p.substr(0, p.rfind('/') + 1);
}

}  // namespace

const ImageCodec* openimageio(std::string& why) {
  static std::once_flag once;
  static const ImageCodec* codec = nullptr;
  static std::string failure;
  std::call_once(once, [] {
    const std::string module = program_folder() + "pt_openimageio.so";
    void* handle = ::dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = ::dlerror();
      failure = "cannot load " + module + " (" + (e ? e : "no reason given") +
                "): it is built into build/bin beside the programs; keep it beside this one (or write an .exr, "
                "which does not need it)";
      return;
    }
    auto entry = reinterpret_cast<ImageCodecEntry>(::dlsym(handle, PT_IMAGE_CODEC_ENTRY));
    codec = entry ? entry() : nullptr;
    if (!codec) failure = module + " has no " PT_IMAGE_CODEC_ENTRY ": rebuild the project (cmake --build build)";
  });
  why = failure;
  return codec;
}

}  // namespace pt
