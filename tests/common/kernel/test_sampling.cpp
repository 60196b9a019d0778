// The sampling routines of common/shaders (sampling.glsl, bsdf.glsl), compiled here as C++
// exactly as the CPU kernels compile them (the GPU compiles the same source):
// chi-square goodness-of-fit of every sampler against its pdf, Šidák-corrected over the
// whole suite; each hemisphere pdf against its mapping's density; the GGX inverse's round trip;
// the pdfs' integrals; energy of every lobe.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/chi2.h"
#include "tests/support/histogram_picture.h"
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

const double kAlphas[] = {1e-4, 0.01, 0.1, 0.5, 1.0};
const double kAnglesDeg[] = {0.0, 30.0, 60.0, 80.0, 89.0, 89.9};
// Every chi-square test of this file shares one significance level (Šidák): 2 hemisphere
// samplers + alphas x angles GGX configurations.
const double kChi2Tests = 2.0 + 5.0 * 6.0;
const double kAlphaPerTest = sidak_alpha(1e-3, kChi2Tests);

glm::vec3 incident(double degrees) {
  double t = degrees * M_PI / 180.0;
  return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

// The histogram against the pdf, written for the student to look at whether the test
// passes or not (docs/labs/lab2.md): its place is in the failure message.
void require_fit(const Chi2Result& r, const std::string& picture = "") {
  INFO(r.table);
  std::string why = "no picture asked for";
  const std::string path = picture.empty() ? "" : test_picture_path(picture);
  const bool written = !path.empty() && write_histogram_picture(path, r, why);
  INFO((written ? "the histogram against the pdf: " + path : "no histogram picture: " + why));
  CHECK(r.not_unit == 0);  // a direction is a unit vector: the bins alone would not see its length
  CHECK(r.non_finite == 0);
  CHECK(r.p_value > kAlphaPerTest);
}


}  // namespace

TEST_CASE("sampling: uniform and cosine hemisphere samples fit their pdfs (chi-square)", "[sampling][statistical]") {
  Chi2Options o;
  Chi2Result uniform = chi2_test(kernel::sample_uniform_hemisphere,
                                 [](glm::dvec3 w) { return w.z > 0.0 ? double(kernel::uniform_hemisphere_pdf()) : 0.0; },
                                 o, test_seed(1));
  require_fit(uniform, "uniform_hemisphere.png");
  CHECK(uniform.integral == Approx(1.0).epsilon(1e-6));
  Chi2Result cosine = chi2_test(kernel::sample_cosine_hemisphere,
                                [](glm::dvec3 w) { return double(kernel::cosine_hemisphere_pdf(float(w.z))); }, o,
                                test_seed(2));
  require_fit(cosine, "cosine_hemisphere.png");
  CHECK(cosine.integral == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("sampling: GGX visible normals fit their pdf for every roughness and incidence (chi-square)",
          "[sampling][statistical][ggx]") {
  std::uint32_t seed = test_seed(10);
  for (double alpha : kAlphas) {
    for (double degrees : kAnglesDeg) {
      glm::vec3 wo = incident(degrees);
      float a = float(alpha);
      auto sample = [&](glm::vec2 u) {
        glm::vec3 h = kernel::sample_ggx_vndf(wo, a, u);
        return 2.0f * glm::dot(wo, h) * h - wo;
      };
      auto pdf = [&](glm::dvec3 wi) { return double(kernel::ggx_vndf_pdf(wo, glm::vec3(wi), a)); };
      Chi2Options o;
      o.peak = glm::dvec3(-wo.x, -wo.y, wo.z);
      o.z_edge = -double(wo.z);  // where the half vector meets the horizon, the pdf jumps to 0
      Chi2Result r = chi2_test(sample, pdf, o, seed++);
      INFO("alpha " << alpha << ", incidence " << degrees << " degrees");
      require_fit(r);
      // The reflected directions' pdf covers the sphere once (some fall below the horizon).
      CHECK(r.integral == Approx(1.0).epsilon(2e-3));
    }
  }
}

TEST_CASE("sampling: each hemisphere sampler's pdf is the density of its mapping, whatever its convention",
          "[sampling]") {
  std::string uniform_first, cosine_first;
  const int uniform = mapping_density_mismatches(
      kernel::sample_uniform_hemisphere, [](glm::dvec3) { return double(kernel::uniform_hemisphere_pdf()); },
      &uniform_first);
  const int cosine = mapping_density_mismatches(
      kernel::sample_cosine_hemisphere, [](glm::dvec3 w) { return double(kernel::cosine_hemisphere_pdf(float(w.z))); },
      &cosine_first);
  INFO("uniform: " << uniform_first << "; cosine: " << cosine_first);
  CHECK(uniform == 0);
  CHECK(cosine == 0);
}

TEST_CASE("sampling: invert_ggx_vndf undoes sample_ggx_vndf", "[sampling][ggx]") {
  for (double alpha : {0.01, 0.1, 0.5, 1.0}) {
    for (double degrees : {0.0, 30.0, 60.0, 85.0}) {
      glm::vec3 wo = incident(degrees);
      for (float x : {0.05f, 0.37f, 0.5f, 0.93f}) {
        for (float y : {0.1f, 0.3f, 0.61f, 0.9f}) {
          glm::vec3 h = kernel::sample_ggx_vndf(wo, float(alpha), glm::vec2(x, y));
          glm::vec2 u = kernel::invert_ggx_vndf(wo, float(alpha), h);
          INFO("alpha " << alpha << ", " << degrees << " degrees, u = " << x << ", " << y);
          CHECK(u.x == Approx(x).margin(2e-4));
          CHECK(u.y == Approx(y).margin(2e-4));
        }
      }
    }
  }
}

TEST_CASE("sampling: a mixed material picks the conductor with probability metallic; glass reflects with "
          "probability Fresnel", "[sampling][statistical]") {
  const int n = 200000;
  pt::Material mixed = pt::make_gltf_material(glm::vec3(0.8f), 0.3f, 0.5f, 0.0f, 1.5f, glm::vec3(0.0f), false);
  kernel::rng_seed(1u, 2u, test_seed(3));
  int conductor = 0;
  const glm::vec3 wo(0.0f, 0.0f, 1.0f);  // a mixed material's choice does not depend on it
  for (int i = 0; i < n; i++) conductor += kernel::choose_lobe(mixed, wo, kernel::rng_next_float()) == pt::kMaterialConductor;
  CHECK(binomial_two_sided_p(std::uint64_t(conductor), n, 0.3) > 1e-4);

  pt::Material glass = pt::make_glass(glm::vec3(1.0f), 1.5f);
  for (double degrees : {0.0, 45.0, 80.0}) {
    for (bool entering : {true, false}) {
      glm::vec3 wo = incident(degrees);
      double f = kernel::fresnel_dielectric(wo.z, entering ? 1.5f : 1.0f / 1.5f);
      int reflected = 0;
      for (int i = 0; i < n; i++) reflected += kernel::sample_glass(glass, wo, entering, kernel::rng_next_float()).wi.z > 0.0f;
      INFO(degrees << " degrees, entering " << entering << ", Fresnel " << f);
      if (f >= 1.0) CHECK(reflected == n);  // total internal reflection
      else CHECK(binomial_two_sided_p(std::uint64_t(reflected), n, f) > 1e-4);
    }
  }
  // Normal incidence: R = ((n - 1) / (n + 1))^2 exactly.
  CHECK(kernel::fresnel_dielectric(1.0f, 1.5f) == Approx(0.04).epsilon(1e-5));
}

namespace {
// The mean of f cos / pdf over n importance samples of a lobe (its directional albedo).
double lobe_albedo(pt::Material m, uint lobe, glm::vec3 wo, int n) {
  double sum = 0.0;
  for (int i = 0; i < n; i++) {
    kernel::LobeSample s = kernel::sample_lobe(lobe, m, wo, kernel::rng_next_vec2());
    if (s.pdf > 0.0f) sum += double(kernel::eval_lobe(lobe, m, wo, s.wi).x * std::max(s.wi.z, 0.0f) / s.pdf);
  }
  return sum / n;
}
}  // namespace

TEST_CASE("sampling: no lobe creates energy; a white GGX conductor loses energy as alpha grows, never gains",
          "[sampling][energy]") {
  kernel::rng_seed(5u, 6u, 7u);
  pt::Material white_diffuse = pt::make_diffuse(glm::vec3(1.0f));
  for (double degrees : kAnglesDeg) {
    glm::vec3 wo = incident(degrees);
    // Cosine sampling of a white Lambertian: every sample weighs exactly 1.
    CHECK(lobe_albedo(white_diffuse, pt::kMaterialDiffuse, wo, 1000) == Approx(1.0).epsilon(1e-5));
    double previous = 1.0 + 1e-9;
    for (double alpha : kAlphas) {
      pt::Material metal = pt::make_metal(glm::vec3(1.0f), float(std::sqrt(alpha)));
      double albedo = lobe_albedo(metal, pt::kMaterialConductor, wo, 200000);
      UNSCOPED_INFO("white GGX albedo, alpha " << alpha << ", " << degrees << " degrees: " << albedo);
      INFO("alpha " << alpha << ", incidence " << degrees << ": albedo " << albedo);
      CHECK(albedo <= 1.0 + 1e-3);
      // Single scattering loses the energy of paths that hit the surface twice: nothing at
      // alpha -> 0, more as alpha grows. Beyond 80 degrees masking, not roughness, rules:
      // there the albedo is not monotone in alpha (docs/results/stage3_notes.md lists the
      // measured values).
      if (degrees <= 80.0) CHECK(albedo <= previous + 5e-3);  // F G2 / G1 spreads < 0.01 here
      if (degrees <= 80.0 && alpha <= 1e-4) CHECK(albedo >= 0.999);
      previous = albedo;
    }
  }
}
