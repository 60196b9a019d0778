// The closed forms of the transmission mixture's tests (issue #46, KHR_materials_transmission
// between 0 and 1; docs/gltf_material.md, "Partial transmission"), in double and written from
// the specification, not from the kernel: the glass part's reflectance seen from above (exact
// dielectric Fresnel; for a rough part GGX microfacets integrated numerically).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "tests/support/gltf_brdf.h"

namespace pt::test {

// Unpolarised Fresnel reflectance of a smooth dielectric, light arriving at cosine c from
// the side of index 1 (eta = the other side's index); 1 under total internal reflection.
inline double exact_fresnel(double c, double eta) {
  c = std::clamp(c, 0.0, 1.0);
  double s2 = (1.0 - c * c) / (eta * eta);
  if (s2 >= 1.0) return 1.0;
  double t = std::sqrt(1.0 - s2);
  double parl = (eta * c - t) / (eta * c + t), perp = (c - eta * t) / (c + eta * t);
  return 0.5 * (parl * parl + perp * perp);
}

// What the glass part reflects back to the side it is seen from (the upper hemisphere),
// for a unit radiance there: Fresnel at cos_o when smooth (alpha 0), else the integral of
// F(v.h) D G2 / (4 |n.v| |n.l|) cos over l above the surface, on microfacet normals h as
// gltf_albedo integrates its layer (midpoint rule, n x 2n).
inline double glass_reflectance(double alpha, double eta, double cos_o, int n = 400) {
  if (alpha <= 0.0) return exact_fresnel(cos_o, eta);
  const HemisphereGrid g(n);  // its half in phi, doubled (gltf_brdf.h)
  glm::dvec3 v(std::sqrt(std::max(0.0, 1.0 - cos_o * cos_o)), 0.0, cos_o);
  double sum = 0.0;
  for (int i = 0; i < n; i++) {
    const double sin_h = g.sin_theta[i], cos_h = g.cos_theta[i];
    for (int j = 0; j < n; j++) {
      glm::dvec3 h(sin_h * g.cos_phi[j], sin_h * g.sin_phi[j], cos_h);
      double vh = glm::dot(v, h);
      if (vh <= 0.0) continue;
      glm::dvec3 l = 2.0 * vh * h - v;
      if (l.z <= 0.0) continue;
      sum += exact_fresnel(vh, eta) * gltf_specular_brdf(alpha, v, l) * l.z * 4.0 * vh * sin_h * g.cell;
    }
  }
  return sum;
}

// The mixture's directional reflectance (to the upper hemisphere) for a glTF material with
// transmission t: metallic x the conductor + (1 - metallic) x ((1 - t) x the dielectric +
// t x the glass's reflection); the dielectric and conductor from gltf_albedo.
inline glm::dvec3 mixture_reflectance(const GltfBrdf& b, double t, double cos_o, int n = 400) {
  GltfBrdf dielectric = b, metal = b;
  dielectric.metallic = 0.0, metal.metallic = 1.0;
  glm::dvec3 glass(t > 0.0 ? glass_reflectance(b.roughness * b.roughness, b.ior, cos_o, n) : 0.0);  // no glass part
  return b.metallic * gltf_albedo(metal, cos_o, n) +
         (1.0 - b.metallic) * ((1.0 - t) * gltf_albedo(dielectric, cos_o, n) + t * glass);
}

// mixture_reflectance at `count` cosines evenly over [0, 1], linearly interpolated.
struct MixtureTable {
  std::vector<glm::dvec3> values;
  MixtureTable(const GltfBrdf& b, double t, int count, int n = 200) {
    for (int k = 0; k < count; k++)
      values.push_back(mixture_reflectance(b, t, std::max(double(k) / (count - 1), 1e-4), n));
  }
  glm::dvec3 at(double cos_o) const {
    double x = std::clamp(cos_o, 0.0, 1.0) * double(values.size() - 1);
    std::size_t k = std::min(std::size_t(x), values.size() - 2);
    double f = x - double(k);
    return values[k] * (1.0 - f) + values[k + 1] * f;
  }
};

}  // namespace pt::test
