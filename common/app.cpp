// The pieces of a stage's main() (see app.h).
#include "common/app.h"

#include <cstdio>
#include <new>

#include "common/error.h"

namespace pt {

int guarded_main(const char* stage, const std::function<int()>& body) {
  try {
    return body();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", stage, e.what());
    return e.code();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: out of memory; render a smaller image or scene\n", stage);
    return kExitBadOption;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s; please report it with the command line\n", stage, e.what());
    return 1;
  }
}

std::unique_ptr<Backend> make_backend(const Options& options, const StageKernels& kernels,
                                      GpuBackendFactory make_gpu) {
  if (options.backend == "cpu") return make_cpu_backend(kernels, options.threads);
  if (options.backend == "gpu") return make_gpu(kernels, options.device);
  try {
    return make_gpu(kernels, options.device);
  } catch (const Error& e) {
    if (e.code() != kExitNoDevice) throw;
    std::fprintf(stderr, "%s: %s; --backend auto falls back to the CPU\n", kernels.name, e.what());
    return make_cpu_backend(kernels, options.threads);
  }
}

RenderSettings render_settings(const Options& o, const char* stage) {
  RenderSettings s;
  s.width = o.width;
  s.height = o.height;
  s.spp = o.spp;
  s.seed = o.seed;
  s.sky = o.sky;
  s.progress = true;
  s.label = stage;
  return s;
}

ImageMetadata image_metadata(const char* stage, const Options& o, const Backend& backend,
                             const RenderResult& r) {
  ImageMetadata m;
  m.stage = stage;
  m.backend = backend.kind() + " (" + backend.device_name() + ")";
  m.scene = o.scene;
  m.spp = r.film.spp();
  m.seed = o.seed;
  m.seconds = r.seconds;
  return m;
}

std::string summary_line(const char* stage, const Backend& backend, const RenderResult& r) {
  const Film& f = r.film;
  double samples = double(f.width()) * double(f.height()) * double(f.spp());
  char line[512];
  std::snprintf(line, sizeof line, "%s: backend %s (%s), %dx%d, %llu spp, %.3f s, %.3g samples/s", stage,
                backend.kind().c_str(), backend.device_name().c_str(), f.width(), f.height(),
                (unsigned long long)f.spp(), r.seconds, r.seconds > 0.0 ? samples / r.seconds : 0.0);
  return line;
}

}  // namespace pt
