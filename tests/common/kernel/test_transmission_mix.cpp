// KHR_materials_transmission between 0 and 1 (issue #46; docs/gltf_material.md, "Partial
// transmission"): the glTF material as metallic x conductor + (1 - metallic) x ((1 - T) x
// dielectric + T x glass), one part chosen per hit (choose_lobe, gltf_dielectric.glsl),
// compiled here as C++ exactly as the CPU kernels compile it: the choice's frequencies, the
// reflectance each part's sampling estimates against the closed form, and the loader's kinds.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/gltf_brdf.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"
#include "tests/support/transmission_mix.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "cpu/kernel_begin.h"
#include "common/kernel/rng.glsl"
#include "common/kernel/sampling.glsl"
#include "common/kernel/bsdf.glsl"
#include "cpu/kernel_support.h"
}  // namespace kernel
}  // namespace

using namespace pt::test;

namespace {

glm::vec3 incident(double degrees) {
  double t = degrees * M_PI / 180.0;
  return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

pt::Material material_of(const GltfBrdf& b, double transmission) {
  pt::GltfPbr p;
  p.base = glm::vec3(b.base), p.metallic = float(b.metallic), p.roughness = float(b.roughness);
  p.ior = float(b.ior), p.transmission = float(transmission);
  return pt::make_gltf_pbr_material(p);
}

enum Part { kConductor, kGlass, kDielectric };

Part part_of(uint lobe) {
  if (lobe == pt::kMaterialConductor || lobe == pt::kMaterialMirror) return kConductor;
  if (lobe == pt::kMaterialGlass || lobe == pt::kMaterialRoughGlass) return kGlass;
  return kDielectric;
}

// One sample of what the material sends back above the surface (wo seen from the front,
// light from above only): the part (choose_lobe), then its delta bounce or its sampled
// direction, f |cos| / pdf where the direction leaves upwards, else 0.
glm::dvec3 reflect_sample(const pt::Material& m, glm::vec3 wo) {
  uint lobe = kernel::choose_lobe(m, wo, kernel::rng_next_float());
  if (kernel::is_delta_lobe(lobe)) {
    kernel::DeltaBounce b = kernel::sample_delta_lobe(lobe, m, wo, true, kernel::rng_next_float());
    return b.wi.z > 0.0f ? glm::dvec3(b.weight) : glm::dvec3(0.0);
  }
  glm::vec2 u = kernel::rng_next_vec2();
  kernel::LobeSample s = kernel::sample_lobe(lobe, m, wo, glm::vec3(u.x, u.y, kernel::rng_next_float()));
  if (!(s.pdf > 0.0f) || s.wi.z <= 0.0f) return glm::dvec3(0.0);
  return glm::dvec3(kernel::eval_lobe(lobe, m, wo, s.wi) * kernel::lobe_cos(lobe, s.wi) / s.pdf);
}

}  // namespace

TEST_CASE("transmission: a material with 0 < T < 1 picks the conductor, the glass and the dielectric with "
          "probabilities metallic, (1 - metallic) T and (1 - metallic) (1 - T) (chi-square)",
          "[transmission][statistical]") {
  const int n = 200000;
  const double tests = 2.0 * 3.0 * 2.0;
  kernel::rng_seed(46u, 7u, test_seed(47000));
  for (double roughness : {0.0, 0.5}) {
    for (double metallic : {0.0, 0.3, 0.7}) {
      for (double degrees : {0.0, 70.0}) {  // the choice must not depend on wo
        GltfBrdf b;
        b.base = {0.8, 0.6, 0.4}, b.metallic = metallic, b.roughness = roughness;
        const double t = 0.4;
        pt::Material m = material_of(b, t);
        REQUIRE(m.kind == pt::kMaterialDielectric);
        glm::vec3 wo = incident(degrees);
        double count[3] = {0.0, 0.0, 0.0};
        for (int i = 0; i < n; i++) count[part_of(kernel::choose_lobe(m, wo, kernel::rng_next_float()))] += 1.0;
        const double p[3] = {metallic, (1.0 - metallic) * t, (1.0 - metallic) * (1.0 - t)};
        double chi2 = 0.0;
        int dof = -1;
        for (int k = 0; k < 3; k++) {
          if (p[k] == 0.0) {
            CHECK(count[k] == 0.0);
            continue;
          }
          chi2 += (count[k] - n * p[k]) * (count[k] - n * p[k]) / (n * p[k]);
          dof++;
        }
        // p-value of chi-square with 1 or 2 degrees of freedom.
        double p_value = dof == 2 ? std::exp(-0.5 * chi2) : std::erfc(std::sqrt(0.5 * chi2));
        INFO("roughness " << roughness << ", metallic " << metallic << ", " << degrees << " degrees: " << count[0]
                          << " " << count[1] << " " << count[2] << ", chi2 " << chi2);
        CHECK(p_value > sidak_alpha(1e-3, tests));
      }
    }
  }
}

TEST_CASE("transmission: what each part's sampling reflects back is the mixture's closed form, smooth and rough",
          "[transmission][statistical]") {
  const int n = 100000;
  const double tests = 2.0 * 2.0 * 3.0 * 3.0;
  const double z = normal_two_sided_quantile(sidak_alpha(1e-3, tests));
  kernel::rng_seed(46u, 8u, test_seed(47100));
  for (double roughness : {0.0, 0.5}) {
    for (double metallic : {0.0, 0.3}) {
      GltfBrdf b;
      b.base = {0.9, 0.6, 0.3}, b.metallic = metallic, b.roughness = roughness;
      const double t = 0.6;
      pt::Material m = material_of(b, t);
      for (double degrees : {0.0, 45.0, 75.0}) {
        glm::vec3 wo = incident(degrees);
        glm::dvec3 want = mixture_reflectance(b, t, double(wo.z), 800);
        glm::dvec3 sum(0.0), sum2(0.0);
        for (int i = 0; i < n; i++) {
          glm::dvec3 x = reflect_sample(m, wo);
          sum += x, sum2 += x * x;
        }
        glm::dvec3 mean = sum / double(n);
        glm::dvec3 se = glm::sqrt(glm::max(sum2 / double(n) - mean * mean, glm::dvec3(0.0)) / double(n - 1));
        INFO("roughness " << roughness << ", metallic " << metallic << ", " << degrees << " degrees: sampled "
                          << mean.x << " +- " << se.x << ", closed form " << want.x);
        for (int c = 0; c < 3; c++) CHECK(std::abs(mean[c] - want[c]) <= z * se[c] + 2e-4 * want[c] + 1e-6);
      }
    }
  }
}

TEST_CASE("transmission: the loader keeps T = 0 and T = 1 as before, makes 0 < T < 1 a glTF dielectric that "
          "needs the glass features, and metallic 1 a metal",
          "[transmission]") {
  GltfBrdf b;
  b.base = {0.8, 0.8, 0.8}, b.roughness = 0.0;
  CHECK(material_of(b, 0.0).kind == pt::kMaterialDielectric);
  CHECK(material_of(b, 0.0).transmission == 0.0f);
  CHECK(material_of(b, 1.0).kind == pt::kMaterialGlass);
  b.roughness = 0.4;
  CHECK(material_of(b, 1.0).kind == pt::kMaterialRoughGlass);
  auto mask_of = [](const pt::Material& m) {
    pt::Scene s;
    s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, s.add_material(m));
    return pt::scene_feature_mask(s, glm::vec3(0.0f));
  };
  for (double roughness : {0.0, 0.4}) {
    b.roughness = roughness;
    pt::Material m = material_of(b, 0.2);
    INFO("roughness " << roughness);
    CHECK(m.kind == pt::kMaterialDielectric);
    CHECK(m.transmission == 0.2f);
    uint glass = roughness > 0.0 ? pt::kFeatureRoughGlass : pt::kFeatureGlass;
    uint other = roughness > 0.0 ? pt::kFeatureGlass : pt::kFeatureRoughGlass;
    CHECK((mask_of(m) & (pt::kFeatureDielectric | glass)) == (pt::kFeatureDielectric | glass));
    CHECK((mask_of(m) & other) == 0u);
    CHECK((mask_of(material_of(b, 0.0)) & (pt::kFeatureGlass | pt::kFeatureRoughGlass)) == 0u);
  }
  b.metallic = 1.0;  // metallic x conductor + 0 x the rest: a metal
  CHECK(material_of(b, 0.5).kind == pt::kMaterialConductor);
}
