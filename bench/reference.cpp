// pt_bench: the true image of a bench scene (bench.h). Analytic scenes have it in closed
// form (the furnace: Le / (1 - albedo); the floors under square lights: Lambert's polygon
// formula, tests/support/lambert.h); the others get a long stage4 render, cached on disk
// under a key that changes with the scene, the size and the kernel (its SPIR-V), so a
// changed renderer never compares against an old reference.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "bench/bench.h"
#include "common/scene/analytic_scenes.h"
#include "common/base/error.h"
#include "tests/support/lambert.h"

namespace pt::bench {

namespace {

// FNV-1a, 64 bits: enough to tell one scene, size and kernel from another.
struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, std::size_t bytes) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; i++) h = (h ^ p[i]) * 1099511628211ull;
  }
  template <class T, class A> void add_vector(const std::vector<T, A>& v) { add(v.data(), v.size() * sizeof(T)); }
};

// The floor under a square light (analytic_scenes.h), pixel by pixel: albedo / pi times
// the irradiance, averaged over the pixel by Gauss-Legendre points.
std::vector<float> floor_light_image(const analytic::FloorLightScene& a, int size) {
  std::vector<float> rgb(std::size_t(size) * size * 3);
  auto radiance = [](double sx, double sy, const void* data) {
    const analytic::FloorLightScene& a = *static_cast<const analytic::FloorLightScene*>(data);
    double l = a.light_half, h = a.light_height;
    std::vector<glm::dvec3> light = {{-l, h, -l}, {l, h, -l}, {l, h, l}, {-l, h, l}};
    glm::dvec3 p(sx * a.view_half, 0.0, -sy * a.view_half);  // what screen point (sx, sy) sees
    return a.albedo / M_PI * test::polygon_irradiance(light, p, {0.0, 1.0, 0.0}, 1.0);
  };
  for (int y = 0; y < size; y++) {
    for (int x = 0; x < size; x++) {
      double v = test::rect_average(2.0 * x / size - 1.0, 1.0 - 2.0 * (y + 1) / size, 2.0 * (x + 1) / size - 1.0,
                                    1.0 - 2.0 * y / size, radiance, &a);
      for (int c = 0; c < 3; c++) rgb[(std::size_t(y) * size + x) * 3 + c] = float(v * a.emission[c]);
    }
  }
  return rgb;
}

bool closed_form(const std::string& scene, int size, Reference& out) {
  analytic::FloorLightScene floor;
  if (scene == "furnace") {
    analytic::FurnaceScene f;
    out.rgb.assign(std::size_t(size) * size * 3, f.emission / (1.0f - f.albedo));
  } else if (scene == "floor_light" || scene == "floor_small_light" || scene == "floor_large_light") {
    float half = scene == "floor_light" ? floor.light_half
                 : scene == "floor_small_light" ? analytic::kSmallLightHalf : analytic::kLargeLightHalf;
    floor.emission *= (floor.light_half * floor.light_half) / (half * half);  // as builtin_scenes.cpp
    floor.light_half = half;
    out.rgb = floor_light_image(floor, size);
  } else {
    return false;
  }
  out.source = "closed form";
  return true;
}

std::uint64_t reference_key(const Scene& s, const Config& config, const StageKernels& kernels) {
  Hash h;
  h.add_vector(s.triangles), h.add_vector(s.spheres), h.add_vector(s.materials), h.add_vector(s.point_lights);
  h.add_vector(s.triangle_attributes), h.add_vector(s.material_textures), h.add_vector(s.textures), h.add_vector(s.texels);
  h.add_vector(s.triangle_shading);
  if (s.camera) {
    h.add(&s.camera->kind, sizeof s.camera->kind), h.add(&s.camera->to_world, sizeof s.camera->to_world);
    h.add(&s.camera->yfov, sizeof(float)), h.add(&s.camera->xmag, sizeof(float)), h.add(&s.camera->ymag, sizeof(float));
  }
  h.add(&config.size, sizeof config.size);
  h.add(&config.reference_seconds, sizeof config.reference_seconds);
  h.add(kernels.spirv.data(), kernels.spirv.size_bytes());  // the kernel itself
  return h.h;
}

bool read_cached(const std::string& path, int size, Reference& out) {
  OIIO::ImageBuf buf(path);
  std::ifstream info(path + ".txt");
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT) || !info) return false;
  const OIIO::ImageSpec& spec = buf.spec();
  if (spec.width != size || spec.height != size || spec.nchannels != 3) return false;
  out.rgb.resize(std::size_t(size) * size * 3);
  buf.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, out.rgb.data());
  std::getline(info, out.source);
  info >> out.relative_error;
  return bool(info);
}

void write_cached(const std::string& path, int size, const Reference& ref) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  OIIO::ImageBuf buf(OIIO::ImageSpec(size, size, 3, OIIO::TypeDesc::FLOAT), const_cast<float*>(ref.rgb.data()));
  std::string tmp = path + ".tmp.exr";
  if (!buf.write(tmp)) throw Error(kExitOutput, "cannot write the reference cache " + tmp + "; check --cache");
  std::ofstream(path + ".txt") << ref.source << "\n" << ref.relative_error << "\n";
  std::filesystem::rename(tmp, path);
}

}  // namespace

Reference reference_image(const std::string& scene_name, const Config& config) {
  Reference ref;
  if (closed_form(scene_name, config.size, ref)) return ref;
  Scene scene = load_bench_scene(scene_name);
  StageKernels kernels = stage_kernels("4");
  char key[32];
  std::snprintf(key, sizeof key, "%016llx", (unsigned long long)reference_key(scene, config, kernels));
  std::string safe = std::filesystem::path(scene_name).filename().string();
  std::string path = config.cache_dir + "/" + safe + "_" + std::to_string(config.size) + "_" + key + ".exr";
  if (read_cached(path, config.size, ref)) return ref;

  std::fprintf(stderr, "pt_bench: rendering the reference of %s (%.0f s, stage4 on the CPU) into %s\n",
               scene_name.c_str(), config.reference_seconds, path.c_str());
  RenderSettings s;
  s.width = s.height = config.size;
  s.spp = std::uint64_t(1) << 40;
  s.seed = 0x5eed0000u;  // not a seed the study uses
  s.time_budget = config.reference_seconds;
  s.roulette = kRouletteThroughput;
  RenderResult r = render(backend_for("4", "cpu"), scene, s);
  ref.rgb = r.film.mean_rgb();
  ref.source = "stage4 cpu, " + std::to_string(r.film.spp()) + " spp";
  double var = 0.0;  // per-pixel estimated relative RMSE of the reference
  for (int y = 0; y < config.size; y++)
    for (int x = 0; x < config.size; x++) var += r.film.sample_variance(x, y) / double(r.film.spp());
  const double mean = r.film.mean_luminance(), pixels = double(config.size) * config.size;
  ref.relative_error = mean > 0.0 ? std::sqrt(var / pixels) / mean : 0.0;
  write_cached(path, config.size, ref);
  return ref;
}

ErrorMetrics compare_images(const std::vector<float>& image, const Reference& reference, int size) {
  OIIO::ImageSpec spec(size, size, 3, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf a(spec, const_cast<float*>(image.data()));
  OIIO::ImageBuf b(spec, const_cast<float*>(reference.rgb.data()));
  OIIO::ImageBufAlgo::CompareResults c = OIIO::ImageBufAlgo::compare(a, b, 1e30f, 1e30f);
  OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(b);
  double mean = (stats.avg[0] + stats.avg[1] + stats.avg[2]) / 3.0;
  ErrorMetrics m;
  m.rmse = c.rms_error;
  m.relative = mean > 0.0 ? c.rms_error / mean : 0.0;
  return m;
}

}  // namespace pt::bench
