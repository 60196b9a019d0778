// Rough glass (KHR_materials_transmission with roughness, issue #46; docs/gltf_material.md,
// "Rough transmission") in rendered images, on the backend under test (pt_tests: the CPU,
// pt_gpu_tests: Vulkan): each stage samples it as it samples (stage2 the uniform sphere,
// stage3 the BSDF, stage4 light samples through the glass, stage5 both weighed), and all
// agree in expectation on a rough slab in front of an area light; as the roughness goes
// to 0 the image goes to the smooth slab's closed form; a white rough sphere under a
// uniform sky never shows more than the sky. Tolerances come from the batches' variance.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/support/image_checks.h"
#include "tests/support/rough_glass_scenes.h"
#include "tests/support/statistics.h"
#include "tests/support/test_render.h"
#include "tests/support/texture_scenes.h"

using namespace pt;
using namespace pt::test;

namespace {

// The image mean (channel 0; the scenes are grey) of independent batches: its mean and
// standard error.
struct Mean {
  double mean = 0.0, stderr_ = 0.0;
};

Mean image_mean(const StageKernels& kernels, const Scene& scene, RenderSettings s, int batches) {
  std::vector<Film> films = render_batches(kernels, scene, s, batches);
  double sum = 0.0, sum2 = 0.0;
  for (const Film& f : films) {
    double m = 0.0;
    for (int y = 0; y < f.height(); y++) {
      for (int x = 0; x < f.width(); x++) m += f.mean(x, y).x;
    }
    m /= double(f.width()) * f.height();
    sum += m, sum2 += m * m;
  }
  Mean r;
  r.mean = sum / batches;
  r.stderr_ = std::sqrt(std::max(sum2 / batches - r.mean * r.mean, 0.0) / (batches - 1));
  return r;
}

// Whether two estimates differ by no more than z standard errors of their difference.
bool agree(const Mean& a, const Mean& b, double z) {
  return std::abs(a.mean - b.mean) <= z * std::sqrt(a.stderr_ * a.stderr_ + b.stderr_ * b.stderr_);
}

// The smooth slab's closed form (builtin:glass_slab): (1 - R) / (1 + R), R at normal incidence.
double smooth_slab_transmittance(double ior) {
  double r = (ior - 1.0) / (ior + 1.0);
  return (1.0 - r * r) / (1.0 + r * r);
}

}  // namespace

TEST_CASE("rough glass: stages 2 to 5 agree in expectation on a rough slab in front of an area light",
          "[stage2][stage3][stage4][stage5][rough_glass][statistical]") {
  // The emitter is seen only through the slab: stage4 finds it by light samples taken at
  // the glass (refraction), stage3 only by BSDF samples, stage5 by both.
  Scene scene = rough_glass_slab(0.8f);  // stage2's uniform sphere: heavy-tailed at low roughness
  REQUIRE(scene.materials.at(0).kind == kMaterialRoughGlass);
  REQUIRE((scene_feature_mask(scene, glm::vec3(0.0f)) & (kFeatureRoughGlass | kFeatureGlass)) == kFeatureRoughGlass);
  const int batches = 16;
  std::uint32_t seed = test_seed(46700);
  std::vector<Mean> means;
  std::vector<StageKernels> stages = path_tracing_stages();
  for (const StageKernels& kernels : stages) {
    RenderSettings s = settings(12, 12, std::string(kernels.name) == "stage2_montecarlo" ? 256 : 64, seed += 100);
    s.roulette = kRouletteThroughput;
    means.push_back(image_mean(kernels, scene, s, batches));
  }
  const double z = student_two_sided_quantile(sidak_alpha(1e-3, 6.0), batches - 1);
  for (std::size_t i = 0; i < means.size(); i++) {
    for (std::size_t j = i + 1; j < means.size(); j++) {
      INFO(stages[i].name << " " << means[i].mean << " +- " << means[i].stderr_ << ", " << stages[j].name << " "
                          << means[j].mean << " +- " << means[j].stderr_);
      CHECK(agree(means[i], means[j], z));
    }
  }
  // Light reaches the camera through the slab: far from nothing, below the smooth slab.
  CHECK(means[3].mean > 0.3);
  CHECK(means[3].mean < smooth_slab_transmittance(1.5));
}

TEST_CASE("rough glass: as the roughness goes to 0 the slab's image goes to the smooth slab's closed form",
          "[stage3][stage5][rough_glass][statistical]") {
  const double want = smooth_slab_transmittance(1.5);  // 0.9231
  const int batches = 12;
  std::uint32_t seed = test_seed(46800);
  double last_gap = 1.0;
  for (float roughness : {0.3f, 0.1f, 0.01f}) {
    Scene scene = rough_glass_slab(roughness);
    for (const StageKernels& kernels : {stage3::kernels(), stage5::kernels()}) {
      RenderSettings s = settings(8, 8, 32, seed += 100);
      s.roulette = kRouletteThroughput;
      Mean got = image_mean(kernels, scene, s, batches);
      double gap = want - got.mean;
      INFO(kernels.name << ", roughness " << roughness << ": " << got.mean << " +- " << got.stderr_ << ", smooth "
                        << want);
      const double z = student_two_sided_quantile(sidak_alpha(1e-3, 6.0), batches - 1);
      // Rough glass loses what single scattering drops, never gains.
      CHECK(gap > -z * got.stderr_);
      if (roughness == 0.01f) CHECK(std::abs(gap) <= z * got.stderr_ + 2e-3);  // the smooth slab within noise
      if (std::string(kernels.name) == "stage5_mis") {
        CHECK(gap < last_gap + z * got.stderr_);
        last_gap = gap;
      }
    }
  }
}

TEST_CASE("rough glass: a white rough sphere under a uniform sky never shows more than the sky (furnace)",
          "[stage3][stage5][rough_glass][statistical]") {
  const int batches = 8;
  std::uint32_t seed = test_seed(46900);
  for (float roughness : {0.1f, 0.5f, 1.0f}) {
    Scene scene = rough_glass_sphere(roughness);
    for (const StageKernels& kernels : {stage3::kernels(), stage5::kernels()}) {
      RenderSettings s = settings(12, 12, 32, seed += 100);
      s.sky = glm::vec3(1.0f);
      s.roulette = kRouletteThroughput;
      std::vector<Film> films = render_batches(kernels, scene, s, batches);
      // Per pixel over the batches: mean and standard error; none above the sky.
      const double z = student_two_sided_quantile(sidak_alpha(1e-3, 144.0 * 6.0), batches - 1);
      int above = 0;
      double lowest = 1.0;
      for (int y = 0; y < 12; y++) {
        for (int x = 0; x < 12; x++) {
          double sum = 0.0, sum2 = 0.0;
          for (const Film& f : films) sum += f.mean(x, y).x, sum2 += f.mean(x, y).x * f.mean(x, y).x;
          double m = sum / batches;
          double se = std::sqrt(std::max(sum2 / batches - m * m, 0.0) / (batches - 1));
          above += m > 1.0 + z * se + 1e-5;
          lowest = std::min(lowest, m);
        }
      }
      INFO(kernels.name << ", roughness " << roughness << ": darkest pixel " << lowest);
      CHECK(above == 0);
      std::printf("rough glass furnace: %s roughness %.1f darkest pixel %.4f\n", kernels.name, roughness,
                  lowest);
    }
  }
}
