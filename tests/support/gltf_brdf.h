// The glTF 2.0 metallic-roughness BRDF written down a second time, in double and from the
// specification's Appendix B (with KHR_materials_specular's fresnel_mix), not from the
// kernel (common/kernel/gltf_dielectric.glsl): f for two directions, and the directional
// albedo integral of f cos (with the delta reflection of a smooth layer or metal)
// integrated numerically, which a white furnace's pixel is.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

namespace pt::test {

struct GltfBrdf {
  glm::dvec3 base{1.0};             // baseColorFactor
  double metallic = 0.0;
  double roughness = 0.5;           // alpha = roughness^2
  double ior = 1.5;
  double specular = 1.0;            // KHR_materials_specular's specularFactor
  glm::dvec3 specular_color{1.0};   // its specularColorFactor
};

inline double gltf_max3(glm::dvec3 v) { return std::max(std::max(v.x, v.y), v.z); }

// The dielectric layer's F0: ((1 - ior) / (1 + ior))^2 x specular colour, at most 1.
inline glm::dvec3 gltf_layer_f0(const GltfBrdf& b) {
  double r = (1.0 - b.ior) / (1.0 + b.ior);
  return glm::min(r * r * b.specular_color, glm::dvec3(1.0));
}

inline glm::dvec3 gltf_schlick(glm::dvec3 f0, double cos_theta) {
  return f0 + (glm::dvec3(1.0) - f0) * std::pow(1.0 - std::abs(cos_theta), 5.0);
}

// Appendix B's specular_brdf(alpha) = V D with the GGX D and the height-correlated Smith
// visibility V = G2 / (4 |n.l| |n.v|) in Heitz's closed form (the project's G2, docs/gltf_material.md).
inline double gltf_specular_brdf(double alpha, glm::dvec3 v, glm::dvec3 l) {
  glm::dvec3 h = glm::normalize(v + l);
  double a2 = alpha * alpha, nh = h.z;
  double d = nh * nh * (a2 - 1.0) + 1.0;
  double D = nh > 0.0 ? a2 / (M_PI * d * d) : 0.0;
  double gv = l.z * std::sqrt(v.z * v.z * (1.0 - a2) + a2);
  double gl = v.z * std::sqrt(l.z * l.z * (1.0 - a2) + a2);
  return D * 0.5 / (gv + gl);
}

// f(v, l) without the delta parts of roughness 0 (both directions above the surface):
// mix(dielectric_brdf, metal_brdf, metallic).
inline glm::dvec3 gltf_brdf(const GltfBrdf& b, glm::dvec3 v, glm::dvec3 l) {
  if (v.z <= 0.0 || l.z <= 0.0) return glm::dvec3(0.0);
  double alpha = b.roughness * b.roughness;
  double vh = glm::dot(v, glm::normalize(v + l));
  double layer = alpha > 0.0 ? gltf_specular_brdf(alpha, v, l) : 0.0;
  glm::dvec3 fr = gltf_schlick(gltf_layer_f0(b), vh);
  glm::dvec3 dielectric = (1.0 - b.specular * gltf_max3(fr)) * b.base / M_PI + b.specular * fr * layer;
  glm::dvec3 metal = layer * gltf_schlick(b.base, vh);
  return (1.0 - b.metallic) * dielectric + b.metallic * metal;
}

// The midpoint grid of gltf_albedo and glass_reflectance (transmission_mix.h): n angles
// theta_h in (0, pi/2), and 2n angles phi in (0, 2 pi), of which only the first n are
// visited. v lies in the xz-plane, so every integrand here depends on phi through cos(phi)
// alone (the dot products with v and the z components), and the grid is symmetric about
// phi = pi (phi_j and phi_{2n-1-j} = 2 pi - phi_j): the sum over the first half, doubled,
// is the sum over all 2n, at half the cost. Their sines and cosines are computed once here,
// not in the inner loop. `cell` is a cell's dtheta dphi, doubled for its mirror image.
struct HemisphereGrid {
  int n;
  double cell;
  std::vector<double> cos_phi, sin_phi;        // phi_j = (j + 0.5) pi / n, j < n
  std::vector<double> sin_theta, cos_theta;    // theta_i = (i + 0.5) (pi / 2) / n
  std::vector<double> sqrt_t, sqrt_one_minus_t;  // t_i = (i + 0.5) / n (the Lambert part)
  explicit HemisphereGrid(int n_) : n(n_), cell(2.0 * (0.5 * M_PI / n_) * (M_PI / n_)) {
    for (int j = 0; j < n; j++) {
      double phi = (j + 0.5) * M_PI / n;
      cos_phi.push_back(std::cos(phi)), sin_phi.push_back(std::sin(phi));
    }
    for (int i = 0; i < n; i++) {
      double theta = (i + 0.5) * 0.5 * M_PI / n, t = (i + 0.5) / n;
      sin_theta.push_back(std::sin(theta)), cos_theta.push_back(std::cos(theta));
      sqrt_t.push_back(std::sqrt(t)), sqrt_one_minus_t.push_back(std::sqrt(1.0 - t));
    }
  }
};

// The directional albedo: the integral of f cos over the hemisphere, plus the delta
// reflection of roughness 0. The base is integrated over cosine-distributed directions l,
// the GGX part over microfacet normals h in (theta_h, phi), l the reflection of v about h
// (dw_l = 4 (v.h) dw_h): a grid even in the angle resolves both the peak of a smooth
// surface and the microfacets near the horizon that a grazing v sees. Midpoint rule, an
// n x 2n grid each (HemisphereGrid: its half in phi, doubled).
inline glm::dvec3 gltf_albedo(const GltfBrdf& b, double cos_o, int n = 400) {
  const HemisphereGrid g(n);
  glm::dvec3 v(std::sqrt(std::max(0.0, 1.0 - cos_o * cos_o)), 0.0, cos_o);
  double alpha = b.roughness * b.roughness;
  const glm::dvec3 layer_f0 = gltf_layer_f0(b);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < n; i++) {
    const double st = g.sqrt_t[i], ct = g.sqrt_one_minus_t[i];
    const double sin_h = g.sin_theta[i], cos_h = g.cos_theta[i];
    for (int j = 0; j < n; j++) {
      // The Lambert base: cosine-distributed l (sin^2 theta = t), weight pi f_base.
      glm::dvec3 l(st * g.cos_phi[j], st * g.sin_phi[j], ct);
      glm::dvec3 fr = gltf_schlick(layer_f0, glm::dot(v, glm::normalize(v + l)));
      sum += (1.0 - b.metallic) * (1.0 - b.specular * gltf_max3(fr)) * b.base / (double(n) * n);  // 2 x 1 / (2 n^2)
      if (alpha <= 0.0) continue;
      // The GGX part: f cos dw_l = f l.z 4 (v.h) sin(theta_h) dtheta_h dphi.
      glm::dvec3 h(sin_h * g.cos_phi[j], sin_h * g.sin_phi[j], cos_h);
      double vh = glm::dot(v, h);
      if (vh <= 0.0) continue;
      glm::dvec3 r = 2.0 * vh * h - v;
      if (r.z <= 0.0) continue;
      double weight = gltf_specular_brdf(alpha, v, r) * r.z * 4.0 * vh * sin_h * g.cell;
      glm::dvec3 f = (1.0 - b.metallic) * b.specular * gltf_schlick(layer_f0, vh) + b.metallic * gltf_schlick(b.base, vh);
      sum += f * weight;
    }
  }
  if (alpha <= 0.0) {  // the mirror reflections of a smooth layer and a smooth metal
    sum += (1.0 - b.metallic) * b.specular * gltf_schlick(layer_f0, cos_o) + b.metallic * gltf_schlick(b.base, cos_o);
  }
  return sum;
}

// gltf_albedo at `count` cosines evenly over [0, 1] (first and last included), for tests
// that need it at many angles: linear interpolation between them.
struct AlbedoTable {
  std::vector<glm::dvec3> values;
  AlbedoTable(const GltfBrdf& b, int count, int n = 200) {
    for (int k = 0; k < count; k++) values.push_back(gltf_albedo(b, std::max(double(k) / (count - 1), 1e-4), n));
  }
  glm::dvec3 at(double cos_o) const {
    double x = std::clamp(cos_o, 0.0, 1.0) * double(values.size() - 1);
    std::size_t k = std::min(std::size_t(x), values.size() - 2);
    double t = x - double(k);
    return values[k] * (1.0 - t) + values[k + 1] * t;
  }
};

}  // namespace pt::test
