// The light table (scene.h): every emissive triangle and sphere and every punctual light,
// each picked in proportion to its power (emissive textures counted by their mean), and the
// sky's share of the picks. stage4's direct light, Eq. (5) (docs/stage4_direct_indirect.md);
// the kernels pick from it in common/kernel/lights.glsl.
#include "common/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "common/base/srgb.h"
#include "common/scene/environment.h"

namespace pt {

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// The mean linear RGB of a texture whose texels are sRGB: the emissive texture's share of a
// light's power (what the texture averages to where its uv cover it evenly).
glm::dvec3 srgb_texture_mean(const Scene& scene, uint index) {
  const Texture& t = scene.textures[index];
  double lut[256];
  for (int i = 0; i < 256; i++) lut[i] = srgb_to_linear(i / 255.0);
  glm::dvec3 sum(0.0);
  const std::size_t n = std::size_t(t.width) * t.height;
  for (std::size_t i = 0; i < n; i++) {
    uint v = scene.texels[t.offset + i];
    sum += glm::dvec3(lut[v & 255u], lut[v >> 8 & 255u], lut[v >> 16 & 255u]);
  }
  return n ? sum / double(n) : glm::dvec3(0.0);
}

// The emission a triangle light's power counts: the material's, times the mean of its
// emissive texture (texture.glsl multiplies the two at every point).
glm::vec3 mean_emission(const Scene& scene, uint material, std::vector<std::optional<glm::dvec3>>& means) {
  glm::vec3 e = scene.materials[material].emission;
  if (!uses_textures(scene)) return e;
  uint tex = scene.material_textures[material].emissive;
  if (tex == kNoTexture) return e;
  if (means.size() < scene.textures.size()) means.resize(scene.textures.size());
  if (!means[tex]) means[tex] = srgb_texture_mean(scene, tex);
  return glm::vec3(glm::dvec3(e) * *means[tex]);
}
// A punctual light's power, by which the light table picks it (any positive number would
// be unbiased; the closer to the light's share of the light, the less noise). A point
// light sends I into 4 pi sr; a spot light into its cone, up to halfway along the falloff
// (2 pi (1 - cos) of the angle between inner and outer; a hard edge, inner >= outer: the
// outer); a directional light the scene's cross-section, pi r^2 (r: its bounding sphere's).
double punctual_power(const Scene& scene, const PointLight& l) {
  double i = luminance(l.intensity), cos_inner = std::max(double(l.cos_inner), double(l.cos_outer));
  if (l.kind == kPunctualSpot) return 2.0 * M_PI * (1.0 - 0.5 * (cos_inner + double(l.cos_outer))) * i;
  if (l.kind == kPunctualDirectional) {
    Bounds b = scene.bounds();
    double r = b.empty() ? 1.0 : 0.5 * double(glm::length(b.hi - b.lo));
    return M_PI * r * r * i;
  }
  return 4.0 * M_PI * i;
}
}  // namespace

void build_light_table(Scene& scene) {
  scene.lights.clear();
  std::vector<double> power;
  std::vector<std::optional<glm::dvec3>> texture_means;  // of the emissive textures met
  for (std::size_t i = 0; i < scene.triangles.size(); i++) {
    Triangle& t = scene.triangles[i];
    const Material& m = scene.materials[t.material];
    if (!is_emissive(m)) continue;
    double area = 0.5 * glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
    double sides = m.double_sided != 0u ? 2.0 : 1.0;
    t.light = uint(scene.lights.size());
    scene.lights.push_back(Light{kLightTriangle, uint(i), 0.0f});
    power.push_back(M_PI * area * sides * luminance(mean_emission(scene, t.material, texture_means)));
  }
  for (std::size_t i = 0; i < scene.spheres.size(); i++) {
    Sphere& s = scene.spheres[i];
    const Material& m = scene.materials[s.material];
    if (!is_emissive(m)) continue;
    double r = s.radius;
    s.light = uint(scene.lights.size());
    scene.lights.push_back(Light{kLightSphere, uint(i), 0.0f});
    power.push_back(M_PI * 4.0 * M_PI * r * r * luminance(m.emission));
  }
  for (std::size_t i = 0; i < scene.point_lights.size(); i++) {
    scene.lights.push_back(Light{kLightPoint, uint(i), 0.0f});
    power.push_back(punctual_power(scene, scene.point_lights[i]));
  }
  double total = 0.0;
  for (double p : power) total += p;
  scene.light_power = total;
  // Lights of zero luminance (pure blue, say) still get a small share, so none is missed.
  std::vector<double> share(power.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < power.size(); i++) {
    share[i] = std::max(total > 0.0 ? power[i] / total : 1.0 / double(power.size()), 1e-6);
    sum += share[i];
  }
  for (std::size_t i = 0; i < power.size(); i++) scene.lights[i].pick = float(share[i] / sum);
  build_light_alias(scene);
  build_light_runs(scene);
}

void build_light_alias(Scene& scene) {
  // Vose's algorithm: each light's probability times n is its share of n cells of size 1.
  // A light with less than a whole cell takes one and is topped up from a light with more,
  // which becomes its alias and keeps what is left; so every cell holds at most two lights,
  // and each light's parts add up to its share. Sums in double, over the float picks the
  // kernel divides by, so that the chance of each light is its pick to float precision.
  const std::size_t n = scene.lights.size();
  double sum = 0.0;
  for (const Light& l : scene.lights) sum += double(l.pick);
  std::vector<double> share(n);
  std::vector<std::size_t> small, large;
  for (std::size_t i = 0; i < n; i++) {
    share[i] = double(scene.lights[i].pick) / sum * double(n);
    (share[i] < 1.0 ? small : large).push_back(i);
  }
  scene.light_alias.clear();
  scene.light_alias.reserve(n);
  for (std::size_t i = 0; i < n; i++) {
    scene.light_alias.push_back(LightAlias{1.0f, uint(i), scene.lights[i], scene.lights[i]});
  }
  while (!small.empty() && !large.empty()) {
    const std::size_t s = small.back(), l = large.back();
    small.pop_back();
    LightAlias& cell = scene.light_alias[s];
    cell.threshold = float(share[s]);
    cell.alias = uint(l);
    cell.other = scene.lights[l];
    share[l] -= 1.0 - share[s];
    if (share[l] < 1.0) large.pop_back(), small.push_back(l);
  }
  // What is left holds a whole cell up to rounding: threshold 1, as made above.
}

void build_light_runs(Scene& scene) {
  // build_light_table lists the triangle lights first, in the triangles' order.
  const std::size_t n = scene.lights.size();
  scene.light_runs.clear();
  scene.triangle_light_count = 0;
  for (std::size_t i = 0; i < n && scene.lights[i].kind == kLightTriangle; i++) {
    if (i == 0 || scene.lights[i].index != scene.lights[i - 1].index + 1) {
      scene.light_runs.push_back(LightRun{uint(i), scene.lights[i].index});
    }
    scene.triangle_light_count = uint(i + 1);
  }
  if (scene.light_runs.size() > kMaxLightRuns) scene.light_runs.clear(), scene.triangle_light_count = 0;
}

float sky_pick_probability(const Scene& scene, glm::vec3 sky) {
  // An environment map stands for a uniform sky of its mean luminance (the same power).
  float sky_lum = scene.environment ? float(scene.environment->mean_luminance) : luminance(sky);
  if (!(sky_lum > 0.0f)) return 0.0f;
  if (scene.lights.empty()) return 1.0f;
  double lights = scene.light_power;
  // The sky's power into the scene: radiance times pi times the bounding sphere's disk.
  Bounds b = scene.bounds();
  double r = b.empty() ? 1.0 : 0.5 * glm::length(b.hi - b.lo);
  double sky_power = M_PI * sky_lum * M_PI * r * r;
  return float(std::clamp(sky_power / (sky_power + lights), 0.05, 0.95));
}

}  // namespace pt
