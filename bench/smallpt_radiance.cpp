// The renderer of pt_smallpt_reference (bench/smallpt_reference.cpp, issue #18's
// yardstick): smallpt's algorithm in double precision over the spheres of smallpt_scene.h,
// the nearest hit by the plain quadratic, cosine sampling, Russian roulette from the 6th hit,
// the mirror's Schlick Fresnel and the glass's exact Fresnel, both branches on the first two
// hits. The hot loop: everything it calls is in this file, so the compiler may inline it.
#include <algorithm>
#include <cmath>

#include "bench/smallpt_scene.h"

namespace pt::bench::smallpt {

namespace {

// The nearest root t > kMinT of |o + t d - c| = r, or 0: the plain quadratic, as smallpt has
// it. In double, |o - c|^2 - r^2 beside the walls of radius 1e5 (1e10 - 1e10) keeps about
// 1e-6 absolute, far inside kMinT.
constexpr double kMinT = 1e-4;
double hit_sphere(const Sphere& s, const Ray& r) {
  const V3 oc = r.o - s.centre;
  const double b = dot(oc, r.d);
  const double c0 = dot(oc, oc) - s.radius * s.radius;
  const double disc = b * b - c0;
  if (disc < 0) return 0;
  const double root = std::sqrt(disc);
  const double near = -b - root, far = -b + root;
  if (near > kMinT) return near;
  if (far > kMinT) return far;
  return 0;
}

bool intersect(const Scene& scene, const Ray& r, double& t, int& id) {
  t = 1e30;
  id = -1;
  for (int i = 0; i < static_cast<int>(scene.spheres.size()); ++i) {
    const double ti = hit_sphere(scene.spheres[i], r);
    if (ti > 0 && ti < t) {
      t = ti;
      id = i;
    }
  }
  return id >= 0;
}

// A cosine-distributed direction about the unit normal n (Duff et al.'s orthonormal basis).
V3 cosine_direction(V3 n, double u1, double u2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const V3 t1{1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
  const V3 t2{b, sign + n.y * n.y * a, -n.y};
  const double r = std::sqrt(u2), phi = 2.0 * M_PI * u1;
  return unit(t1 * (r * std::cos(phi)) + t2 * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1.0 - u2)));
}

V3 schlick(V3 f0, double cos_theta) {
  const double m = std::clamp(1.0 - cos_theta, 0.0, 1.0);
  const double m5 = m * m * m * m * m;
  return f0 + (V3{1, 1, 1} - f0) * m5;
}

}  // namespace

// The radiance arriving along ray r; depth: the hits before this ray's origin.
V3 radiance(const Scene& scene, Ray r, int depth, Rng& rng) {
  V3 sum{}, weight{1, 1, 1};
  for (;;) {
    double t;
    int id;
    if (!intersect(scene, r, t, id)) return sum;  // black beyond the scene
    const Sphere& s = scene.spheres[id];
    const V3 x = r.o + r.d * t;
    const V3 n = unit(x - s.centre);
    const bool entering = dot(n, r.d) < 0;
    const V3 nl = entering ? n : n * -1.0;  // the normal on the side the ray came from
    sum = sum + weight * s.emission;
    const double p = max3(s.albedo);
    if (p <= 0) return sum;  // nothing more can be added through this surface
    if (++depth > 5) {       // Russian roulette from the 6th hit on
      if (rng.uniform() >= p) return sum;
      weight = weight * (1.0 / p);
    }
    if (s.kind == Kind::Diffuse) {
      weight = weight * s.albedo;
      const double u1 = rng.uniform(), u2 = rng.uniform();
      r = {x, cosine_direction(nl, u1, u2)};
      continue;
    }
    const double cos_i = -dot(r.d, nl);
    const Ray reflected{x, unit(r.d + nl * (2.0 * cos_i))};
    if (s.kind == Kind::Mirror) {
      weight = weight * schlick(s.albedo, cos_i);
      r = reflected;
      continue;
    }
    // Glass of index 1.5: eta = n_transmitted / n_incident; exact unpolarised Fresnel.
    const double eta = entering ? 1.5 : 1.0 / 1.5;
    const double cos2_t = (eta * eta - 1.0 + cos_i * cos_i) / (eta * eta);
    if (cos2_t <= 0) {  // total internal reflection
      r = reflected;
      continue;
    }
    const double cos_t = std::sqrt(cos2_t);
    const double r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double F = 0.5 * (r_parl * r_parl + r_perp * r_perp);
    const Ray refracted{x, unit(r.d * (1.0 / eta) + nl * (cos_i / eta - cos_t))};
    if (depth <= 2) {  // the first two hits: both branches
      const V3 lr = radiance(scene, reflected, depth, rng);
      const V3 lt = radiance(scene, refracted, depth, rng);
      return sum + weight * (lr * F + s.albedo * lt * (1.0 - F));
    }
    const double P = 0.25 + 0.5 * F;  // deeper: one branch
    if (rng.uniform() < P) {
      weight = weight * (F / P);
      r = reflected;
    } else {
      weight = weight * s.albedo * ((1.0 - F) / (1.0 - P));
      r = refracted;
    }
  }
}

}  // namespace pt::bench::smallpt
