// The tests of the hemisphere samplers (labs 2 and 3, the article's Eqs. 3 and 4) tested
// by mutation: each known-wrong answer a student might write (a direction that forgets
// sin theta's radius, theta drawn uniformly, a pdf off by a constant, the cosine sampler's
// radius without its square root, ...) fails the checks that test_sampling.cpp applies to
// the real samplers, and every right answer passes them whatever its convention (which
// number sets theta, u or 1 - u). The checks: the chi-square fit of the directions to the
// pdf, directions of unit length, and the pdf equal to the mapping's own density.
// Held back from the labs' handouts ([held_back], docs/labs/teachers.md): its right answers
// are labs 2 and 3's.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "tests/support/chi2.h"
#include "tests/support/test_render.h"

using namespace pt::test;

namespace {

using Sampler = std::function<glm::vec3(glm::vec2)>;
using Pdf = std::function<double(glm::dvec3)>;

constexpr float kPi = 3.14159265358979f;

struct Answer {
  const char* name;
  Sampler sample;
  Pdf pdf;
};

// A direction from cos(theta) and phi.
glm::vec3 direction(float z, float phi) {
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

double uniform_pdf(glm::dvec3 w) { return w.z > 0.0 ? 1.0 / (2.0 * M_PI) : 0.0; }
double cosine_pdf(glm::dvec3 w) { return w.z > 0.0 ? w.z / M_PI : 0.0; }

// What the checks say of one answer: "" when it passes all of them.
std::string verdict(const Answer& a, std::uint32_t seed) {
  Chi2Options o;
  o.samples = 200'000;
  const Chi2Result r = chi2_test(a.sample, a.pdf, o, seed);
  std::string first;
  const int mismatches = mapping_density_mismatches(a.sample, a.pdf, &first);
  std::string why;
  if (r.not_unit > 0) why += std::to_string(r.not_unit) + " directions not of unit length; ";
  if (r.non_finite > 0) why += std::to_string(r.non_finite) + " not finite; ";
  // Significance 1e-3 for each of the answers below (one false alarm in a thousand runs).
  if (r.p_value < 1e-3) why += "chi-square p " + std::to_string(r.p_value) + "; ";
  if (mismatches > 0) why += std::to_string(mismatches) + " of 100 points: " + first;
  return why;
}

}  // namespace

TEST_CASE("sampler checks: right answers pass whatever their convention", "[sampling][mutants][held_back]") {
  const std::vector<Answer> right = {
      {"uniform, cos theta = u.x", [](glm::vec2 u) { return direction(u.x, 2.0f * kPi * u.y); }, uniform_pdf},
      {"uniform, cos theta = 1 - u.x", [](glm::vec2 u) { return direction(1.0f - u.x, 2.0f * kPi * u.y); }, uniform_pdf},
      {"uniform, u.y sets theta", [](glm::vec2 u) { return direction(u.y, 2.0f * kPi * u.x); }, uniform_pdf},
      {"cosine, sin theta = sqrt(u.x)", [](glm::vec2 u) { return direction(std::sqrt(1.0f - u.x), 2.0f * kPi * u.y); },
       cosine_pdf},
      {"cosine, cos theta = sqrt(u.x)", [](glm::vec2 u) { return direction(std::sqrt(u.x), 2.0f * kPi * u.y); },
       cosine_pdf},
  };
  std::uint32_t seed = test_seed(100);
  for (const Answer& a : right) {
    INFO(a.name);
    CHECK(verdict(a, seed++) == "");
  }
}

TEST_CASE("sampler checks: every known-wrong answer fails them", "[sampling][mutants][held_back]") {
  const std::vector<Answer> wrong = {
      {"uniform, the radius forgotten: (cos phi, sin phi, z)",
       [](glm::vec2 u) { return glm::vec3(std::cos(2.0f * kPi * u.y), std::sin(2.0f * kPi * u.y), u.x); }, uniform_pdf},
      {"uniform, theta uniform in [0, pi/2]",
       [](glm::vec2 u) { return direction(std::cos(0.5f * kPi * u.x), 2.0f * kPi * u.y); }, uniform_pdf},
      {"uniform, pdf 1 / pi", [](glm::vec2 u) { return direction(u.x, 2.0f * kPi * u.y); },
       [](glm::dvec3 w) { return w.z > 0.0 ? 1.0 / M_PI : 0.0; }},
      {"uniform, pdf 1 / (4 pi) (the sphere's)", [](glm::vec2 u) { return direction(u.x, 2.0f * kPi * u.y); },
       [](glm::dvec3 w) { return w.z > 0.0 ? 1.0 / (4.0 * M_PI) : 0.0; }},
      {"uniform, phi = pi u.y (half the circle)", [](glm::vec2 u) { return direction(u.x, kPi * u.y); }, uniform_pdf},
      {"cosine, sin theta = u.x (no square root)", [](glm::vec2 u) { return direction(std::sqrt(1.0f - u.x * u.x), 2.0f * kPi * u.y); },
       cosine_pdf},
      {"cosine, the uniform sampler's directions", [](glm::vec2 u) { return direction(u.x, 2.0f * kPi * u.y); },
       cosine_pdf},
      {"cosine, pdf cos theta (no 1 / pi)", [](glm::vec2 u) { return direction(std::sqrt(1.0f - u.x), 2.0f * kPi * u.y); },
       [](glm::dvec3 w) { return w.z > 0.0 ? w.z : 0.0; }},
      {"cosine, pdf 1 / (2 pi)", [](glm::vec2 u) { return direction(std::sqrt(1.0f - u.x), 2.0f * kPi * u.y); },
       uniform_pdf},
      {"cosine, below the surface: z = -sqrt(1 - u.x)",
       [](glm::vec2 u) { return direction(-std::sqrt(1.0f - u.x), 2.0f * kPi * u.y); }, cosine_pdf},
  };
  std::uint32_t seed = test_seed(200);
  for (const Answer& a : wrong) {
    INFO(a.name);
    CHECK(verdict(a, seed++) != "");
  }
}
