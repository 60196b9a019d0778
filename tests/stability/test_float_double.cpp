// Float versus double: stage3's and stage4's integrators (Eq. 4 and Eq. 5) compiled here a
// second time as C++ with every `float` of the shader source made `double` (vectors
// glm::dvec*, a few scalar built-ins given double overloads; the scene arrays stay float),
// rendered on the CPU with the same seeds as the float kernel of the backend under test.
// The same seed draws the same random numbers, so both trace the same paths until a
// rounding difference flips a decision: the difference of the images is float's error.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <vector>

#include "common/scene/analytic_scenes.h"
#include "common/render/render.h"
#include "cpu/kernel_prelude.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code

// What the shader source needs in double: vector types and the scalar built-ins that GLM
// only has as templates of one type (a float literal next to a double would not deduce).
#define PT_DOUBLE_PRELUDE                                                                      \
  using namespace pt::glsl;                                                                    \
  using vec2 = glm::dvec2;                                                                     \
  using vec3 = glm::dvec3;                                                                     \
  using vec4 = glm::dvec4;                                                                     \
  inline double max(double a, double b) { return a > b ? a : b; }                             \
  inline double min(double a, double b) { return a < b ? a : b; }                             \
  inline double clamp(double x, double a, double b) { return min(max(x, a), b); }             \
  inline double abs(double x) { return std::fabs(x); }                                         \
  inline double sqrt(double x) { return std::sqrt(x); }                                        \
  inline double inversesqrt(double x) { return 1.0 / std::sqrt(x); }                           \
  inline double cos(double x) { return std::cos(x); }                                          \
  inline double sin(double x) { return std::sin(x); }                                          \
  inline double atan(double y, double x) { return std::atan2(y, x); }                          \
  /* the offsets' "units in the last place" become double's */                                 \
  inline long long floatBitsToInt(double x) {                                                  \
    long long i;                                                                               \
    std::memcpy(&i, &x, sizeof i);                                                             \
    return i;                                                                                  \
  }                                                                                            \
  inline double intBitsToFloat(long long i) {                                                  \
    double x;                                                                                  \
    std::memcpy(&x, &i, sizeof x);                                                             \
    return x;                                                                                  \
  }

namespace d3 {
PT_DOUBLE_PRELUDE
#define float double
#include "cpu/kernel_bindings.h"
#include "stage3_importance/integrator.glsl"
#include "cpu/kernel_support.h"
#include "common/kernel/render_pixel.glsl"
#undef float
}  // namespace d3

// The shared shader files again, for the second namespace.
#undef PT_CPU_KERNEL_BINDINGS_H
#undef PT_CPU_TRIANGLE_LANES_H
#undef PT_CPU_SPHERE_LANES_H
#undef PT_KERNEL_DEFINITIONS_GLSL
#undef PT_UNIFORM_HEMISPHERE_GLSL
#undef PT_COSINE_HEMISPHERE_GLSL
#undef PT_TRIANGLE_LIGHT_GLSL
#undef PT_BOX_SLAB_GLSL
#undef PT_BOX_PAD_GLSL
#undef PT_MIS_GLSL
#undef PT_RUSSIAN_ROULETTE_GLSL
#undef PT_EMISSION_RULE_GLSL
#undef PT_BSDF_GLSL
#undef PT_GLTF_DIELECTRIC_GLSL
#undef PT_ROUGH_DIELECTRIC_GLSL
#undef PT_CAMERA_GLSL
#undef PT_FEATURES_GLSL
#undef PT_INTERSECT_GLSL
#undef PT_TEXTURE_GLSL
#undef PT_TEXTURE_LOOKUP_GLSL
#undef PT_SHADING_NORMAL_GLSL
#undef PT_BVH_GLSL
#undef PT_BVH_HIT_GLSL
#undef PT_SPHERE_POWER_GLSL
#undef PT_LIGHTS_GLSL
#undef PT_LIGHT_SAMPLE_GLSL
#undef PT_PUNCTUAL_LIGHT_GLSL
#undef PT_RENDER_PIXEL_GLSL
#undef PT_RNG_GLSL
#undef PT_ROULETTE_GLSL
#undef PT_SAMPLING_GLSL
#undef PT_SAMPLER_GLSL
#undef PT_SPAWN_GLSL
#undef PT_SPHERICAL_TRIANGLE_GLSL
#undef PT_FLOAT_MATH_GLSL
#undef PT_ENVIRONMENT_GLSL

namespace d4 {
PT_DOUBLE_PRELUDE
#define float double
#include "cpu/kernel_bindings.h"
#include "stage4_direct_indirect/integrator.glsl"
#include "cpu/kernel_support.h"
#include "common/kernel/render_pixel.glsl"
#undef float
}  // namespace d4

#undef PT_DOUBLE_PRELUDE

using namespace pt;
using namespace pt::test;

// The double kernel's image (mean per pixel, luminance), all samples in one pass.
#define PT_RENDER_DOUBLE(ns)                                                                   \
  std::vector<double> render_double_##ns(const Scene& scene, const RenderSettings& s) {        \
    uint counters[kCounterCount] = {};                                                         \
    ns::triangles = scene.triangles.data();                                                    \
    ns::spheres = scene.spheres.data();                                                        \
    ns::materials = scene.materials.data();                                                    \
    ns::point_lights = scene.point_lights.data();                                              \
    ns::lights = scene.lights.data();                                                          \
    ns::light_alias = scene.light_alias.data();                                                \
    std::vector<MaterialTextures> neutral = neutral_material_textures(scene.materials.size());  \
    ns::material_textures = neutral.data(); /* the scenes have no textures (texture.glsl) */    \
    ns::counters = counters;                                                                   \
    ns::params = make_frame_params(scene, s);                                                  \
    ns::params.sample_count = uint(s.spp);                                                     \
    std::vector<double> image;                                                                 \
    for (int y = 0; y < s.height; y++)                                                         \
      for (int x = 0; x < s.width; x++) {                                                      \
        glm::dvec4 v = ns::render_pixel(uint(x), uint(y));                                     \
        image.push_back((0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z) / double(s.spp));        \
      }                                                                                        \
    return image;                                                                              \
  }
PT_RENDER_DOUBLE(d3)
PT_RENDER_DOUBLE(d4)
#undef PT_RENDER_DOUBLE

struct Difference {
  double image;  // |mean float - mean double| / mean double over the image
  double pixel;  // the largest such ratio of one pixel
  int differing; // pixels whose relative difference exceeds 1e-4
};

Difference compare(const Film& f, const std::vector<double>& d) {
  Difference r{0.0, 0.0, 0};
  double sum_f = 0.0, sum_d = 0.0;
  for (int y = 0; y < f.height(); y++)
    for (int x = 0; x < f.width(); x++) {
      glm::dvec3 c = f.mean(x, y);
      double lf = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z, ld = d[std::size_t(y) * f.width() + x];
      sum_f += lf, sum_d += ld;
      double rel = std::abs(lf - ld) / std::max(std::abs(ld), 1e-30);
      r.pixel = std::max(r.pixel, rel);
      r.differing += rel > 1e-4;
    }
  r.image = std::abs(sum_f - sum_d) / sum_d;
  return r;
}

}  // namespace

TEST_CASE("stability: float kernels and the same source built with double agree on the analytic scenes",
          "[stage3][stage4][stability]") {
  struct Case {
    const char* name;
    Scene scene;
    glm::vec3 sky;
  };
  analytic::PointInSphereScene point;
  std::vector<Case> cases;
  cases.push_back({"furnace 0.5", analytic::make_furnace({}), glm::vec3(0.0f)});
  cases.push_back({"floor light", analytic::make_floor_light({}), glm::vec3(0.0f)});
  cases.push_back({"glass slab 1.5", analytic::make_glass_slab({}), glm::vec3(0.0f)});
  cases.push_back({"mirror", analytic::make_mirror({}), glm::vec3(0.0f)});
  cases.push_back({"sphere under the sky", analytic::make_sphere({}), glm::vec3(0.5f, 1.0f, 2.0f)});
  cases.push_back({"point light in a sphere", analytic::make_point_in_sphere(point), glm::vec3(0.0f)});
  for (const Case& c : cases) {
    for (int stage : {3, 4}) {
      RenderSettings s = settings(8, 8, 16, test_seed(7900));
      s.roulette = kRouletteThroughput;
      s.sky = c.sky;
      const StageKernels& kernels = stage == 3 ? stage3::kernels() : stage4::kernels();
      if (stage == 3 && !c.scene.point_lights.empty()) continue;  // stage3 cannot see point lights
      Film f = render_on_test_backend(kernels, c.scene, s).film;
      std::vector<double> d = stage == 3 ? render_double_d3(c.scene, s) : render_double_d4(c.scene, s);
      Difference diff = compare(f, d);
      INFO(c.name << ", stage" << stage << ": image mean differs by " << diff.image << " (relative), pixels by up to "
                  << diff.pixel << ", " << diff.differing << " of 64 by more than 1e-4");
      // Paths are the same until a rounding difference flips a decision (a roulette draw,
      // glass's reflect-or-refract): then one sample of 16 differs, by up to its own size.
      // Seen: image means 0 to 3e-7 apart, pixels up to 1.5e-5 (the furnace's long paths).
      CHECK(diff.image < 1e-5);
      CHECK(diff.differing <= 2);
    }
  }
}
