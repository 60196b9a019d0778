// The rough dielectric of KHR_materials_transmission with roughness (kMaterialRoughGlass,
// common/kernel/rough_dielectric.glsl through bsdf.glsl; docs/gltf_material.md, "Rough
// transmission"), compiled here as C++ exactly as the CPU kernels compile it: chi-square of
// its sampling against its pdf from both sides of the surface, the generalised reciprocity
// of its BTDF, and a white furnace: the albedo its sampling estimates against the albedo
// integrated numerically from f, and the energy it keeps never above 1.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"

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

// Rough glass as a surface hit shows it: eta relative to the side wo is on (1.5: from the
// outside in; 1 / 1.5: from the inside out).
pt::Material rough_glass(double roughness, double eta) {
  pt::Material m = pt::make_rough_glass(glm::vec3(1.0f), 1.5f, float(roughness));
  m.ior = float(eta);
  return m;
}

struct Albedo {
  double radiance = 0.0;  // the integral of f |cos| (transmission carries 1 / eta^2)
  double energy = 0.0;    // the same with the refraction's eta^2 undone: R + T, at most 1
};

// Numerical integration over the microfacet normal h, drawn in proportion to D(h) cos(h)
// by the inverse of GGX's distribution (tan^2 = alpha^2 x / (1 - x), phi = 2 pi y), with
// x = 1 - s^2 (dx = 2 s ds) so that the integrand's 1 / cos(h) at the horizon stays finite;
// the midpoint rule on n x n cells of (s, y). Each h gives one reflected and one refracted direction, f there
// times |cos| times the Jacobian |dwi / dh| (4 wo.h; (wo.h + eta wi.h)^2 / (eta^2 |wi.h|)).
// It reads only f (eval_lobe), never the sampler or its pdf.
Albedo integrated_albedo(const pt::Material& m, glm::vec3 wo, int n) {
  const double alpha = m.alpha, eta = m.ior;
  Albedo a;
  for (int i = 0; i < n; i++) {
    double sv = (i + 0.5) / n, x = 1.0 - sv * sv;
    double tan2 = alpha * alpha * x / (1.0 - x);
    double cos_h = 1.0 / std::sqrt(1.0 + tan2), sin_h = std::sqrt(tan2) * cos_h;
    double d = alpha * alpha / (M_PI * std::pow(alpha * alpha * cos_h * cos_h + sin_h * sin_h, 2.0));
    for (int j = 0; j < n; j++) {
      double phi = 2.0 * M_PI * (j + 0.5) / n;
      glm::dvec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
      glm::dvec3 o(wo);
      double co = glm::dot(o, h);
      if (co <= 0.0) continue;
      double per_h = 2.0 * sv / (d * cos_h * double(n) * double(n));  // dh of this cell
      glm::dvec3 r = 2.0 * co * h - o;
      if (r.z > 0.0) {
        double f = kernel::eval_lobe(pt::kMaterialRoughGlass, m, wo, glm::vec3(r)).x;
        a.radiance += f * r.z * 4.0 * co * per_h;
        a.energy += f * r.z * 4.0 * co * per_h;
      }
      double cos2_t = 1.0 - (1.0 - co * co) / (eta * eta);
      if (cos2_t <= 0.0) continue;
      glm::dvec3 t = (co / eta - std::sqrt(cos2_t)) * h - o / eta;
      if (t.z >= 0.0) continue;
      double ci = glm::dot(t, h);
      double f = kernel::eval_lobe(pt::kMaterialRoughGlass, m, wo, glm::vec3(t)).x;
      double jacobian = (co + eta * ci) * (co + eta * ci) / (eta * eta * -ci);
      a.radiance += f * -t.z * jacobian * per_h;
      a.energy += eta * eta * f * -t.z * jacobian * per_h;
    }
  }
  return a;
}

struct Estimate {
  Albedo mean, stderr_;
};

// The albedo as the path tracers sample it (stage3): sample_lobe with three numbers, the
// weight f |cos| / pdf.
Estimate sampled_albedo(const pt::Material& m, glm::vec3 wo, int n) {
  double s[2] = {0, 0}, s2[2] = {0, 0};
  for (int i = 0; i < n; i++) {
    glm::vec2 u = kernel::rng_next_vec2();
    glm::vec3 u3(u.x, u.y, kernel::rng_next_float());
    kernel::LobeSample ls = kernel::sample_lobe(pt::kMaterialRoughGlass, m, wo, u3);
    double w = 0.0;
    if (ls.pdf > 0.0f) {
      w = kernel::eval_lobe(pt::kMaterialRoughGlass, m, wo, ls.wi).x * kernel::lobe_cos(pt::kMaterialRoughGlass, ls.wi) /
          ls.pdf;
    }
    double e = w * kernel::lobe_eta2(pt::kMaterialRoughGlass, m, ls.wi);
    s[0] += w, s2[0] += w * w, s[1] += e, s2[1] += e * e;
  }
  Estimate est;
  double mean[2], se[2];
  for (int k = 0; k < 2; k++) {
    mean[k] = s[k] / n;
    se[k] = std::sqrt(std::max(s2[k] / n - mean[k] * mean[k], 0.0) / (n - 1));
  }
  est.mean.radiance = mean[0], est.mean.energy = mean[1];
  est.stderr_.radiance = se[0], est.stderr_.energy = se[1];
  return est;
}

const double kEtas[] = {1.5, 1.0 / 1.5};  // entering, leaving (total internal reflection)

}  // namespace

TEST_CASE("rough glass: sampling fits its pdf, reflection and refraction, from both sides (chi-square)",
          "[statistical][rough_glass]") {
  // (Below alpha 0.03 the two lobes' peaks, one graded, outgrow the bins' integration.)
  const double alphas[] = {0.03, 0.1, 0.5, 1.0};
  const double etas[] = {1.5, 1.0 / 1.5, 2.4};
  const double degrees[] = {0.0, 60.0, 85.0};
  const double tests = 4.0 * 3.0 * 3.0;
  std::uint32_t seed = test_seed(46500);
  kernel::rng_seed(46u, 5u, test_seed(46501));
  for (double alpha : alphas) {
    for (double eta : etas) {
      for (double deg : degrees) {
        pt::Material m = rough_glass(std::sqrt(alpha), eta);
        glm::vec3 wo = incident(deg);
        Chi2Options options;
        options.samples = 300000;
        // The sharper of the two lobes' peaks (the refracted one, or the mirror direction
        // where there is none: total internal reflection).
        double s = std::sin(deg * M_PI / 180.0) / eta;
        options.peak = s < 1.0 ? glm::dvec3(-s, 0.0, -std::sqrt(1.0 - s * s)) : glm::dvec3(-wo.x, -wo.y, wo.z);
        Chi2Result r = chi2_test(
            [&](glm::vec2 u) {
              return kernel::sample_lobe(pt::kMaterialRoughGlass, m, wo, glm::vec3(u.x, u.y, kernel::rng_next_float())).wi;
            },
            [&](glm::dvec3 w) { return double(kernel::lobe_pdf(pt::kMaterialRoughGlass, m, wo, glm::vec3(w))); },
            options, seed++);
        INFO("alpha " << alpha << ", eta " << eta << ", " << deg << " degrees\n" << r.table);
        CHECK(r.not_unit == 0);
        CHECK(r.non_finite == 0);
        CHECK(r.integral == Approx(1.0).margin(3e-3));
        CHECK(r.p_value > sidak_alpha(1e-3, tests));
      }
    }
  }
}

TEST_CASE("rough glass: f is reciprocal in reflection and obeys f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2 "
          "in refraction",
          "[rough_glass]") {
  kernel::rng_seed(46u, 6u, 7u);
  int checked = 0;
  for (double alpha : {0.05, 0.3, 0.8}) {
    for (double eta : {1.5, 1.0 / 1.5, 1.33}) {
      pt::Material m = rough_glass(std::sqrt(alpha), eta);
      pt::Material back = rough_glass(std::sqrt(alpha), 1.0 / eta);  // seen from wi's side
      for (int i = 0; i < 300; i++) {
        glm::vec3 wo = kernel::sample_uniform_hemisphere(kernel::rng_next_vec2());
        glm::vec3 wi = kernel::sample_uniform_hemisphere(kernel::rng_next_vec2());
        if (wo.z < 0.02f || wi.z < 0.02f) continue;
        float f = kernel::eval_lobe(pt::kMaterialRoughGlass, m, wo, wi).x;
        float g = kernel::eval_lobe(pt::kMaterialRoughGlass, m, wi, wo).x;
        CHECK(f == Approx(g).epsilon(1e-4).margin(1e-6));
        // Refraction: wi below the surface; the reverse path starts on wi's side, whose
        // frame has z flipped, with the inverse relative index.
        glm::vec3 below(wi.x, wi.y, -wi.z);
        float t = kernel::eval_lobe(pt::kMaterialRoughGlass, m, wo, below).x;
        float u = kernel::eval_lobe(pt::kMaterialRoughGlass, back, wi, glm::vec3(wo.x, wo.y, -wo.z)).x;
        INFO("alpha " << alpha << ", eta " << eta << ", wo " << wo.x << " " << wo.y << " " << wo.z << ", wi " << below.x
                      << " " << below.y << " " << below.z);
        // To float rounding, which the tails (a microfacet seen nearly edge-on) raise to 1e-3.
        CHECK(double(u) == Approx(eta * eta * double(t)).epsilon(5e-3).margin(1e-6));
        checked += t > 0.0f;
      }
    }
  }
  CHECK(checked > 400);  // pairs where refraction reaches wi (about half)
}

TEST_CASE("rough glass: white furnace: the sampled albedo is the integrated one, the energy kept never above 1",
          "[statistical][rough_glass]") {
  const int n = 200000;
  const double degrees[] = {0.0, 45.0, 75.0, 87.0};
  const double tests = 3.0 * 2.0 * 4.0 * 2.0;  // roughness x side x angles x (albedo, energy)
  const double z = normal_two_sided_quantile(sidak_alpha(1e-3, tests));
  kernel::rng_seed(46u, 7u, test_seed(46600));
  for (double roughness : {0.1, 0.5, 1.0}) {
    for (double eta : kEtas) {
      pt::Material m = rough_glass(roughness, eta);
      for (double deg : degrees) {
        glm::vec3 wo = incident(deg);
        Albedo want = integrated_albedo(m, wo, 400);
        Estimate got = sampled_albedo(m, wo, n);
        INFO("roughness " << roughness << ", eta " << eta << ", " << deg << " degrees: sampled albedo "
                          << got.mean.radiance << " +- " << got.stderr_.radiance << ", integrated " << want.radiance
                          << "; energy " << got.mean.energy << " / " << want.energy);
        CHECK(std::abs(got.mean.radiance - want.radiance) <= z * got.stderr_.radiance + 1e-3 * want.radiance);
        CHECK(std::abs(got.mean.energy - want.energy) <= z * got.stderr_.energy + 1e-3 * want.energy);
        CHECK(want.energy <= 1.0 + 1e-3);
        CHECK(got.mean.energy <= 1.0 + z * got.stderr_.energy);
      }
    }
  }
}

TEST_CASE("rough glass: the table of energies kept for the docs", "[.][rough_glass_table]") {
  // Run by hand (pt_tests "[rough_glass_table]"): docs/gltf_material.md's table of the
  // single-scattering loss, 1 - (R + T), integrated from f.
  for (double eta : kEtas) {
    std::printf("eta %.4f: energy kept R + T (integrated)\n", eta);
    for (double roughness : {0.1, 0.5, 1.0}) {
      pt::Material m = rough_glass(roughness, eta);
      std::printf("roughness %.1f:", roughness);
      for (double deg : {0.0, 45.0, 75.0, 87.0}) {
        std::printf("  %2.0f deg %.4f", deg, integrated_albedo(m, incident(deg), 800).energy);
      }
      std::printf("\n");
    }
  }
}
