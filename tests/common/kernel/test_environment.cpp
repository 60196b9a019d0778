// Tests of the environment map's kernel functions (common/kernel/environment.glsl; issue #49,
// beyond the article, whose sky is one colour), run on the CPU: the orientation and the turn
// of --env-rotate, the pdf's integral over the sphere, the sampler against the pdf
// (chi-square per texel), and the sky's share of stage4's light picks (lights.glsl).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/chi2.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "tests/support/light_kernel.h"
}  // namespace kernel
}  // namespace

namespace {

using Map = std::shared_ptr<const pt::Environment>;

// The scene whose map the kernel reads (bind_scene keeps pointers into it).
pt::Scene& use_map(const Map& env) {
  static pt::Scene scene;
  scene = pt::Scene();
  scene.environment = env;
  kernel::bind_scene(scene);
  return scene;
}

float uniform(std::mt19937& g) { return std::min(std::uniform_real_distribution<float>(0.0f, 1.0f)(g), 0x1.fffffep-1f); }

glm::vec3 random_direction(std::mt19937& g) {
  float z = 1.0f - 2.0f * uniform(g), phi = 2.0f * float(M_PI) * uniform(g);
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Map random_map(uint w, uint h, std::uint32_t seed, float rotate = 0.0f) {
  std::mt19937 g(seed);
  std::vector<float> rgb(3 * w * h);
  for (float& c : rgb) c = 2.0f * uniform(g);
  return pt::make_environment("random", w, h, rgb, 1.0f, rotate);
}

// Black but for texel (x, y) (rows from the top).
Map one_texel_map(uint w, uint h, uint x, uint y, float rotate = 0.0f) {
  std::vector<float> rgb(3 * w * h, 0.0f);
  for (int c = 0; c < 3; c++) rgb[3 * (y * w + x) + c] = 50.0f;
  return pt::make_environment("one texel", w, h, rgb, 1.0f, rotate);
}

bool near(glm::vec3 a, glm::vec3 b, float tol) { return glm::length(a - b) <= tol; }

// The pdf integrated over the sphere: a midpoint grid over (theta from +Y, phi = atan2(z, x)),
// weights sin(theta). Its rows meet the texels' rows; its columns the texels' in steps that
// a turn shifts all alike, so the piecewise-constant pdf is integrated to rounding.
double pdf_integral(uint w, uint h) {
  const int nt = int(48 * h), np = int(48 * w);
  double sum = 0.0;
  for (int i = 0; i < nt; i++) {
    double theta = (i + 0.5) * M_PI / nt;
    for (int j = 0; j < np; j++) {
      double phi = (j + 0.5) * 2.0 * M_PI / np - M_PI;
      glm::vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi)));
      sum += double(kernel::environment_pdf(d)) * std::sin(theta);
    }
  }
  return sum * (M_PI / nt) * (2.0 * M_PI / np);
}

// Whether the map-frame (u, v) of a direction lies within 1e-4 of a texel's edge.
bool on_texel_edge(glm::vec2 uv, uint w, uint h) {
  float fx = uv.x * float(w), fy = uv.y * float(h);
  return std::abs(fx - std::round(fx)) < 1e-4f * float(w) || std::abs(fy - std::round(fy)) < 1e-4f * float(h);
}

}  // namespace

TEST_CASE("environment: +X reads the image's centre, +Z u = 0.75, -Z u = 0.25, +Y the top row, -Y the bottom",
          "[environment]") {
  use_map(random_map(8, 4, 1));
  CHECK(near(glm::vec3(kernel::environment_uv({1, 0, 0}), 0.0f), {0.5f, 0.5f, 0.0f}, 1e-6f));
  CHECK(kernel::environment_uv({0, 0, 1}).x == Approx(0.75f).margin(1e-6));
  CHECK(kernel::environment_uv({0, 0, -1}).x == Approx(0.25f).margin(1e-6));
  CHECK(kernel::environment_uv({0, 1, 0}).y == Approx(0.0f).margin(1e-6));
  CHECK(kernel::environment_uv({0, -1, 0}).y == Approx(1.0f).margin(1e-6));
  // +Y reads the top row (v clamped), at u = 0.5: halfway between texels 3 and 4 of 8.
  glm::vec3 want = 0.5f * (kernel::environment_texel(3) + kernel::environment_texel(4));
  CHECK(near(kernel::environment_radiance({0.0f, 1.0f, 0.0f}), want, 1e-5f));
}

TEST_CASE("environment: environment_direction inverts environment_uv", "[environment]") {
  use_map(random_map(8, 4, 2));
  std::mt19937 g(pt::test::test_seed(11));
  int bad = 0;
  for (int i = 0; i < 10000; i++) {
    glm::vec3 d = random_direction(g);
    glm::vec3 back = kernel::environment_direction(kernel::environment_uv(d));
    if (!near(back, d, 1e-5f)) bad++;  // acos and atan2 to a few ulps
  }
  CHECK(bad == 0);
}

TEST_CASE("environment: --env-rotate turns the lookup about +Y; world_to_map and map_to_world are inverse",
          "[environment]") {
  std::mt19937 g(pt::test::test_seed(12));
  use_map(random_map(8, 4, 3, 37.0f));
  CHECK(kernel::params.env_cos == float(std::cos(37.0 * M_PI / 180.0)));  // bind_scene, as the backends
  CHECK(kernel::params.env_sin == float(std::sin(37.0 * M_PI / 180.0)));
  for (int i = 0; i < 1000; i++) {
    glm::vec3 d = random_direction(g);
    CHECK(near(kernel::map_to_world(kernel::world_to_map(d)), d, 1e-6f));
    CHECK(near(kernel::world_to_map(kernel::map_to_world(d)), d, 1e-6f));
  }
  // world_to_map(d) = (c x + s z, y, -s x + c z). At R = 90 degrees (c = 0, s = 1) it is
  // (z, y, -x): world +Z looks up the map's +X (the image's centre column), which +X saw
  // unturned, and world +X looks up the map's -Z (u = 0.25), which -Z saw unturned. Blender's
  // Mapping node turning its vector by +90 degrees about its Z (glTF's +Y) does the same.
  Map still = random_map(8, 4, 4), turned = random_map(8, 4, 4, 90.0f);
  std::vector<glm::vec3> dirs = {{1, 0, 0}, {0, 0, 1}, {0, 0, -1}, {0.6f, 0.0f, 0.8f}, {0.36f, 0.48f, -0.8f}};
  std::vector<glm::vec3> before;
  use_map(still);  // the radiance of the unturned map in each direction
  for (glm::vec3 d : dirs) before.push_back(kernel::environment_radiance(d));
  use_map(turned);
  CHECK(kernel::environment_uv(kernel::world_to_map({1, 0, 0})).x == Approx(0.25f).margin(1e-6));
  CHECK(near(kernel::environment_radiance({0, 0, 1}), before[0], 1e-5f));   // +Z now sees what +X saw
  CHECK(near(kernel::environment_radiance({1, 0, 0}), before[2], 1e-5f));   // +X now sees what -Z saw
  for (std::size_t i = 3; i < dirs.size(); i++) {  // in general the turned map at d is the still one at (z, y, -x)
    glm::vec3 d = dirs[i], m(d.z, d.y, -d.x);
    glm::vec3 at_m = kernel::environment_radiance(d);
    use_map(still);
    CHECK(near(kernel::environment_radiance(m), at_m, 1e-5f));
    use_map(turned);
  }
}

TEST_CASE("environment: the pdf integrates to 1 over the sphere (random, one bright texel, a pole row, rotated, not 2:1, black)",
          "[environment]") {
  struct Case { const char* name; Map env; };
  std::vector<Case> cases = {{"random 16x8", random_map(16, 8, 5)},
                             {"one bright texel", one_texel_map(16, 8, 5, 3)},
                             {"bright texel in the top row", one_texel_map(16, 8, 9, 0)},
                             {"bright texel in the bottom row", one_texel_map(16, 8, 2, 7)},
                             {"random, turned 37 degrees", random_map(16, 8, 6, 37.0f)},
                             {"one texel, turned -120 degrees", one_texel_map(16, 8, 5, 3, -120.0f)},
                             {"random 12x9 (not 2:1)", random_map(12, 9, 7)},
                             {"black (a uniform table)", pt::make_environment("black", 8, 4, std::vector<float>(96), 1.0f, 0.0f)}};
  for (const Case& c : cases) {
    use_map(c.env);
    double integral = pdf_integral(c.env->width, c.env->height);
    INFO(c.name << ": integral " << integral);
    CHECK(integral == Approx(1.0).margin(1e-4));
  }
}

TEST_CASE("environment: sample_environment's directions follow environment_pdf (chi-square per texel)",
          "[environment][statistical]") {
  struct Case { const char* name; Map env; };
  std::vector<Case> cases = {{"random 16x8", random_map(16, 8, 8)},
                             {"one bright texel", one_texel_map(16, 8, 5, 3)},
                             {"bright texel in the top row", one_texel_map(16, 8, 9, 0)},
                             {"random, turned 37 degrees", random_map(16, 8, 9, 37.0f)},
                             {"random 12x9 (not 2:1)", random_map(12, 9, 10)}};
  // Šidák: 1% for the whole test, over its maps.
  const double alpha = 1.0 - std::pow(0.99, 1.0 / double(cases.size()));
  std::uint32_t seed = pt::test::test_seed(20);
  for (const Case& c : cases) {
    use_map(c.env);
    const uint w = c.env->width, h = c.env->height;
    // Each texel's probability: environment_pdf integrated over it (4 x 4 midpoints of
    // (u, v) in the map's frame, Jacobian 2 pi^2 sin(theta)).
    std::vector<double> expected(w * h, 0.0);
    const int n = 100000, k = 4;
    for (uint y = 0; y < h; y++)
      for (uint x = 0; x < w; x++)
        for (int i = 0; i < k; i++)
          for (int j = 0; j < k; j++) {
            glm::vec2 uv((float(x) + (j + 0.5f) / k) / float(w), (float(y) + (i + 0.5f) / k) / float(h));
            glm::vec3 d = kernel::map_to_world(kernel::environment_direction(uv));
            double jac = 2.0 * M_PI * M_PI * std::sin(M_PI * double(uv.y));
            expected[y * w + x] += double(kernel::environment_pdf(d)) * jac / (double(k * k) * w * h) * n;
          }
    std::vector<double> observed(w * h, 0.0);
    int strays = 0, edge = 0;
    std::mt19937 g(seed++);
    for (int s = 0; s < n; s++) {
      kernel::EnvironmentSample e = kernel::sample_environment({uniform(g), uniform(g)});
      glm::vec2 uv = kernel::environment_uv(kernel::world_to_map(e.wi));
      uint x = std::min(uint(uv.x * float(w)), w - 1), y = std::min(uint(uv.y * float(h)), h - 1);
      if (expected[y * w + x] == 0.0) (on_texel_edge(uv, w, h) ? edge : strays)++;
      else observed[y * w + x] += 1.0;
    }
    // Pool the texels expecting fewer than 5 samples.
    double chi2 = 0.0, pool_o = 0.0, pool_e = 0.0;
    int bins = 0;
    for (std::size_t i = 0; i < expected.size(); i++) {
      if (expected[i] == 0.0) continue;
      if (expected[i] < 5.0) { pool_o += observed[i], pool_e += expected[i]; continue; }
      chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i], bins++;
    }
    if (pool_e > 0.0) chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e, bins++;
    const double p = pt::test::chi2_upper_tail(chi2, bins - 1);
    INFO(c.name << ": chi2 " << chi2 << " over " << bins << " bins, p-value " << p << " (alpha " << alpha
                << "), samples in texels of pdf 0: " << strays << " (+" << edge << " on an edge)");
    CHECK((strays == 0 && edge <= n / 10000));
    CHECK(p > alpha);
  }
}

TEST_CASE("environment: a sample's pdf and radiance are environment_pdf's and environment_radiance's for its direction",
          "[environment]") {
  std::mt19937 g(pt::test::test_seed(30));
  for (Map env : {random_map(16, 8, 11), one_texel_map(16, 8, 9, 0), random_map(12, 9, 12, 200.0f)}) {
    use_map(env);
    int compared = 20000, pdf_bad = 0, radiance_bad = 0, edge = 0;
    double worst = 0.0, worst_y = 0.0;
    for (int s = 0; s < compared; s++) {
      kernel::EnvironmentSample e = kernel::sample_environment({uniform(g), uniform(g)});
      REQUIRE(e.pdf > 0.0f);
      double rel = std::abs(double(kernel::environment_pdf(e.wi)) / double(e.pdf) - 1.0);
      if (rel > 1e-3 && on_texel_edge(kernel::environment_uv(kernel::world_to_map(e.wi)), env->width, env->height)) edge++;
      else if (rel > 1e-3) pdf_bad++, worst_y = rel > worst ? e.wi.y : worst_y, worst = std::max(worst, rel);
      glm::vec3 want = kernel::environment_radiance(e.wi);
      if (!near(e.radiance, want, 1e-4f * (1.0f + glm::length(want)))) radiance_bad++;
    }
    INFO(env->path << " " << env->width << "x" << env->height << ": " << pdf_bad << " of " << compared
                   << " pdfs off by more than 1e-3 (worst " << worst << " at y = " << worst_y << "), " << edge
                   << " on a texel's edge");
    CHECK(pdf_bad == 0);
    CHECK(edge <= compared / 1000);
    CHECK(radiance_bad == 0);
  }
}

TEST_CASE("environment: wherever the map gives light the pdf is positive (a bright texel's bilinear footprint)",
          "[environment]") {
  for (Map env : {one_texel_map(16, 8, 5, 3), one_texel_map(16, 8, 0, 0), one_texel_map(16, 8, 15, 7, 45.0f)}) {
    use_map(env);
    int lit = 0, unsampled = 0, nt = 400, np = 800;  // finer than the texels: the footprint's edges in between
    for (int i = 0; i < nt; i++)
      for (int j = 0; j < np; j++) {
        double theta = (i + 0.37) * M_PI / nt, phi = (j + 0.61) * 2.0 * M_PI / np;
        glm::vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi)));
        if (!(glm::length(kernel::environment_radiance(d)) > 0.0f)) continue;
        lit++;
        unsampled += !(kernel::environment_pdf(d) > 0.0f);
      }
    INFO(env->path << ": " << unsampled << " of " << lit << " lit directions have pdf 0");
    CHECK((lit > 0 && unsampled == 0));
  }
}

TEST_CASE("environment: the sky's pick probability is the mean luminance's share of the power, and sample_light keeps it",
          "[environment][statistical]") {
  // A 1 x 1 emissive quad (power pi x area x luminance = pi) and a grey map of luminance 0.2:
  // the map counts as a uniform sky, P_sky = pi L pi r^2 with r the bounds' half diagonal.
  pt::Scene s;
  uint lamp = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  pt::add_quad(s, {-0.5f, 1.0f, -0.5f}, {0.5f, 1.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, {-0.5f, 1.0f, 0.5f}, lamp);
  pt::build_light_table(s);
  s.environment = pt::make_environment("grey", 16, 8, std::vector<float>(3 * 16 * 8, 0.2f), 1.0f, 0.0f);
  kernel::bind_scene(s);
  const double r = 0.5 * std::sqrt(2.0), sky_power = M_PI * 0.2 * M_PI * r * r;
  const double want = std::clamp(sky_power / (sky_power + s.light_power), 0.05, 0.95);
  CHECK(s.light_power == Approx(M_PI).epsilon(1e-5));
  CHECK(kernel::sky_pick_probability() == Approx(want).epsilon(1e-5));
  CHECK(pt::sky_pick_probability(s, glm::vec3(0.0f)) == Approx(want).epsilon(1e-5));

  kernel::rng_seed(1u, 2u, pt::test::test_seed(40));
  const int n = 200000;
  int sky = 0, pdf_bad = 0;
  for (int i = 0; i < n; i++) {
    glm::vec3 normal = i % 2 ? glm::vec3(0, 1, 0) : glm::vec3(0, -1, 0);  // the map is drawn whatever the normal
    kernel::LightSample ls = kernel::sample_light(glm::vec3(0.2f, 0.0f, 0.1f), normal);
    if (!(ls.pdf > 0.0f) || ls.dist != kernel::kInfinity) continue;
    sky++;
    double other = double(kernel::sky_light_pdf(normal, ls.wi));
    double env_pdf = double(kernel::sky_pick_probability()) * double(kernel::environment_pdf(ls.wi));
    pdf_bad += std::abs(env_pdf / other - 1.0) > 1e-6;  // and the sample's own, away from the poles (tested above)
    pdf_bad += std::abs(ls.wi.y) < 0.999f && std::abs(other / double(ls.pdf) - 1.0) > 1e-3;
  }
  const double sigma = std::sqrt(want * (1.0 - want) / n);
  INFO("sky picked " << sky << " of " << n << ", want " << want * n << " +- " << sigma * n);
  CHECK(std::abs(double(sky) / n - want) < 4.0 * sigma);
  CHECK(pdf_bad == 0);

  // The clamps: a map alone is always picked; a map far brighter than the lights at most 95%.
  pt::Scene alone;
  alone.environment = s.environment;
  CHECK(pt::sky_pick_probability(alone, glm::vec3(0.0f)) == 1.0f);
  pt::Scene bright = s;
  bright.environment = pt::make_environment("bright", 16, 8, std::vector<float>(3 * 16 * 8, 1e4f), 1.0f, 0.0f);
  CHECK(pt::sky_pick_probability(bright, glm::vec3(0.0f)) == Approx(0.95f));
}
