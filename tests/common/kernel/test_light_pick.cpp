// Picking one light of many (common/kernel/lights.glsl pick_light_entry, the alias table
// scene_lights.cpp builds), compiled as the CPU kernels compile it: each light is picked with
// its probability (in proportion to its power), the kernel picks what the table says, and the
// number it leaves for placing the point is uniform. The article's Eq. (5) with several lights:
// a light picked with probability P(light), its estimate divided by it (erratum 5).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/scene/scene.h"
#include "cpu/kernel_prelude.h"
#include "tests/support/test_render.h"

namespace {  // internal linkage: each test file compiles its own copy of the kernel code
namespace kernel {
#include "tests/support/light_kernel.h"
}  // namespace kernel

// Each light's chance of being picked by the alias table: 1 / n of every cell, shared between
// the cell's own light (its threshold) and its alias (the rest).
std::vector<double> alias_chances(const pt::Scene& s) {
  const std::size_t n = s.light_alias.size();
  std::vector<double> chance(n, 0.0);
  for (std::size_t k = 0; k < n; k++) {
    const double t = double(s.light_alias[k].threshold);
    chance[k] += t / double(n);
    chance[s.light_alias[k].alias] += (1.0 - t) / double(n);
  }
  return chance;
}

}  // namespace

TEST_CASE("light sampling: lights are picked in proportion to their power", "[stage4][lights]") {
  pt::Scene s;
  uint dim = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(1.0f)));
  uint bright = s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(3.0f), true));
  s.add_triangle({0, 1, 0}, {1, 1, 0}, {0, 1, 1}, dim);     // area 0.5, one side
  s.add_triangle({0, 2, 0}, {2, 2, 0}, {0, 2, 1}, bright);  // area 1, both sides, 3x brighter
  s.point_lights.push_back(pt::make_point_light({0, 3, 0}, {1, 1, 1}));
  pt::build_light_table(s);
  REQUIRE(s.lights.size() == 3);
  // Powers: pi 0.5 1, pi 1 2 3, 4 pi 1 -> 0.5 : 6 : 4.
  CHECK(s.lights[0].pick == Approx(0.5 / 10.5).epsilon(1e-5));
  CHECK(s.lights[1].pick == Approx(6.0 / 10.5).epsilon(1e-5));
  CHECK(s.lights[2].pick == Approx(4.0 / 10.5).epsilon(1e-5));
  CHECK(s.triangles[0].light == 0u);
  // The alias table (Vose): light 0's share, 3 x 0.5 / 10.5 of a cell, is the bottom of cell 0
  // and a brighter light has the rest of it; each light's parts add up to its pick.
  const std::vector<double> chance = alias_chances(s);
  for (std::size_t i = 0; i < 3; i++) CHECK(chance[i] == Approx(s.lights[i].pick).epsilon(1e-6));
  kernel::bind_scene(s);
  CHECK(kernel::pick_light_entry(0.0f).entry == 0u);  // the bottom of cell 0 is light 0's own
  CHECK(kernel::pick_light_entry(0.99f).entry == s.light_alias[2].alias);
}

TEST_CASE("light sampling: the alias table picks every light with its probability, in one read",
          "[stage4][lights]") {
  // Light tables of 1, 2, 7 and 100,000 emitters of powers spread over ten decades (cells
  // a light fills alone, cells split between two), and the u where the pick changes: every
  // cell's edges and every threshold, with their float neighbours.
  std::mt19937 rng(pt::test::test_seed(17));
  std::uniform_real_distribution<float> decade(-5.0f, 5.0f), unit(0.0f, 1.0f);
  for (int count : {1, 2, 7, 100000}) {
    pt::Scene s;
    for (int i = 0; i < count; i++) {
      const float power = std::pow(10.0f, decade(rng));
      const float x = float(i % 300), z = float(i / 300);
      s.add_triangle({x, 1.0f, z}, {x + 0.5f, 1.0f, z}, {x, 1.0f, z + 0.5f},
                     s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(power))));
    }
    pt::build_light_table(s);
    kernel::bind_scene(s);
    REQUIRE(s.light_alias.size() == s.lights.size());
    INFO(count << " lights");
    // Each light's chance, summed over the cells it has a part of, is its pick probability:
    // to float precision, the precision of the thresholds (a pick of 1e-6 of a 100,000-cell
    // table is a tenth of a cell).
    const std::vector<double> chance = alias_chances(s);
    double worst = 0.0;
    for (int i = 0; i < count; i++) {
      worst = std::max(worst, std::abs(chance[i] / double(s.lights[i].pick) - 1.0));
    }
    CHECK(worst < 1e-5);
    // The kernel picks what the table says, with the light's entry bit for bit, and leaves
    // a number in [0, 1).
    std::vector<float> us = {0.0f, 0x1.fffffep-1f};
    for (int k = 0; k < count; k++) {
      for (float edge : {float(k) / float(count), (float(k) + s.light_alias[k].threshold) / float(count)}) {
        us.push_back(edge);
        us.push_back(std::nextafter(edge, 0.0f));
        us.push_back(std::nextafter(edge, 1.0f));
      }
    }
    for (int i = 0; i < 100000; i++) us.push_back(unit(rng));
    int wrong = 0, out_of_range = 0;
    for (float u : us) {
      if (!(u >= 0.0f && u < 1.0f)) continue;  // samples are in [0, 1) (kOneMinusEpsilon)
      const float scaled = u * float(count);
      const uint cell = std::min(uint(scaled), uint(count - 1));
      const float f = std::min(scaled - float(cell), 0x1.fffffep-1f);
      const uint expected = f < s.light_alias[cell].threshold ? cell : s.light_alias[cell].alias;
      const kernel::LightPick got = kernel::pick_light_entry(u);
      const pt::Light& l = s.lights[expected];
      wrong += got.entry != expected || got.light.kind != l.kind || got.light.index != l.index ||
               got.light.pick != l.pick;
      out_of_range += !(got.u >= 0.0f && got.u < 1.0f);
    }
    CHECK(wrong == 0);
    CHECK(out_of_range == 0);
  }
}

TEST_CASE("light sampling: the number left after the pick is uniform", "[stage4][lights][statistical]") {
  // One light of a 7-light table that owns one cell and parts of others: the fractions left
  // to it by uniform u must be uniform too, or the point sampled on it would not be. Counts
  // in 10 bins against a chi-square bound (9 degrees of freedom: 27.9 at p = 0.001).
  std::mt19937 rng(pt::test::test_seed(23));
  pt::Scene s;
  const float powers[] = {1.0f, 9.0f, 0.5f, 2.0f, 0.25f, 3.0f, 0.1f};
  for (int i = 0; i < 7; i++) {
    s.add_triangle({float(i), 1.0f, 0.0f}, {float(i) + 0.5f, 1.0f, 0.0f}, {float(i), 1.0f, 0.5f},
                   s.add_material(pt::make_diffuse(glm::vec3(0.0f), glm::vec3(powers[i]))));
  }
  pt::build_light_table(s);
  kernel::bind_scene(s);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (uint light = 0; light < 7; light++) {
    std::vector<double> bins(10, 0.0);
    double picked = 0.0;
    for (int i = 0; i < 400000; i++) {
      const kernel::LightPick got = kernel::pick_light_entry(unit(rng));
      if (got.entry != light) continue;
      bins[std::min(int(got.u * 10.0f), 9)] += 1.0, picked += 1.0;
    }
    double chi2 = 0.0;
    for (double b : bins) chi2 += (b - picked / 10.0) * (b - picked / 10.0) / (picked / 10.0);
    INFO("light " << light << ": picked " << picked << " times, chi-square " << chi2);
    CHECK(chi2 < 27.9);
  }
}

TEST_CASE("light sampling: the runs of emitting triangles name each triangle light's triangle",
          "[stage4][lights]") {
  // The CPU's hint (cpu/kernel_bindings.h prefetch_light_triangle) finds a light's triangle
  // through the runs instead of the light table: they must agree for every triangle light.
  // Triangles that emit in runs of 1 to 5 with dark ones between, then a sphere light and a
  // point light after them in the table; and a scene with more runs than kMaxLightRuns.
  for (int runs : {1, 7, int(pt::kMaxLightRuns) + 1}) {
    pt::Scene s;
    const uint lit = s.add_material(pt::make_diffuse(glm::vec3(0.5f), glm::vec3(1.0f)));
    const uint dark = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
    for (int r = 0; r < runs; r++) {
      for (int i = 0; i < 1 + r % 5; i++) s.add_triangle({float(i), 1, float(r)}, {float(i) + 0.5f, 1, float(r)}, {float(i), 1, float(r) + 0.5f}, lit);
      s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, dark);
    }
    s.add_sphere({0, 5, 0}, 0.5f, lit);
    s.point_lights.push_back(pt::make_point_light({0, 3, 0}, {1, 1, 1}));
    pt::build_light_table(s);
    INFO(runs << " runs");
    if (std::size_t(runs) > pt::kMaxLightRuns) {
      CHECK(s.light_runs.empty());
      CHECK(s.triangle_light_count == 0u);
      continue;
    }
    REQUIRE(s.light_runs.size() == std::size_t(runs));
    REQUIRE(s.lights[s.triangle_light_count].kind != pt::kLightTriangle);
    int wrong = 0;
    for (uint k = 0; k < s.triangle_light_count; k++) {
      std::size_t r = 0;
      while (r + 1 < s.light_runs.size() && s.light_runs[r + 1].first_light <= k) r++;
      wrong += s.light_runs[r].first_triangle + (k - s.light_runs[r].first_light) != s.lights[k].index;
    }
    CHECK(wrong == 0);
  }
}
