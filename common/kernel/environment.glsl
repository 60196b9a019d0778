// Light from an environment map (issue #49; beyond the article, whose sky is one colour): an
// equirectangular HDR image at infinity. Its radiance for a direction (bilinear, as Blender's
// Environment Texture), and, for stages 4 and 5, a direction drawn from a piecewise-constant
// 2D distribution over the image, proportional to luminance x sin(theta), with its pdf in
// solid angle (pbrt's "infinite area light"; docs/stage4_direct_indirect.md).
// The host builds the tables (common/scene/environment.cpp); kernels read them by
// environment_texel and environment_table (cpu/kernel_bindings.h, gpu/kernel_bindings.glsl).
#ifndef PT_ENVIRONMENT_GLSL
#define PT_ENVIRONMENT_GLSL

#include "common/kernel/sampling.glsl"

// Orientation (Blender's for a world Environment Texture, with glTF's +Y up; docs/
// environment.md): the image's centre column looks along +X, u = 0.75 along +Z, its top
// row is +Y. The map is turned by --env-rotate about +Y, as Blender's Mapping node turns
// the vector it looks the image up with: direction d of the world reads the image at
// environment_uv(d), d first turned into the map's frame.
vec3 world_to_map(vec3 d) {
  return vec3(params.env_cos * d.x + params.env_sin * d.z, d.y, -params.env_sin * d.x + params.env_cos * d.z);
}

vec3 map_to_world(vec3 d) {
  return vec3(params.env_cos * d.x - params.env_sin * d.z, d.y, params.env_sin * d.x + params.env_cos * d.z);
}

// Whether the sky is a map: the kernel has the map's code (kFeatureEnvironment; every bit is
// set in the general kernel, --all-features and the CPU's general copy) and the render has a
// map (env_width 0 without one).
bool has_environment() {
  return has_feature(kFeatureEnvironment) && params.env_width != 0u;
}

// (u, v) in [0, 1]^2 of a unit direction in the map's frame; v = 0 is the image's top row.
vec2 environment_uv(vec3 d) {
  float u = 0.5f + atan(d.z, d.x) / (2.0f * kPi);
  float v = acos(clamp(d.y, -1.0f, 1.0f)) / kPi;
  return vec2(u, v);
}

// The direction of the map's frame at (u, v): theta = pi v from +Y, phi = 2 pi (u - 1/2).
vec3 environment_direction(vec2 uv) {
  float theta = kPi * uv.y;
  float phi = 2.0f * kPi * (uv.x - 0.5f);
  float sin_theta = sin(theta);
  return vec3(sin_theta * cos(phi), cos(theta), sin_theta * sin(phi));
}

// The radiance at (u, v): bilinear between the four nearest texel centres, wrapping around
// in u, clamped at the poles in v (Blender's "Linear" interpolation).
vec3 environment_radiance_uv(vec2 uv) {
  int w = int(params.env_width), h = int(params.env_height);
  float fx = uv.x * float(w) - 0.5f;
  float fy = uv.y * float(h) - 0.5f;
  float x0f = floor(fx), y0f = floor(fy);
  float tx = fx - x0f, ty = fy - y0f;
  int x0 = (int(x0f) + w) % w;  // fx >= -1/2: never below -w
  int x1 = x0 + 1 == w ? 0 : x0 + 1;
  int y0 = clamp(int(y0f), 0, h - 1), y1 = clamp(int(y0f) + 1, 0, h - 1);
  vec3 a = environment_texel(uint(y0 * w + x0)), b = environment_texel(uint(y0 * w + x1));
  vec3 c = environment_texel(uint(y1 * w + x0)), d = environment_texel(uint(y1 * w + x1));
  return (a * (1.0f - tx) + b * tx) * (1.0f - ty) + (c * (1.0f - tx) + d * tx) * ty;
}

// The radiance arriving along -d, from the map in direction d (world space, unit).
vec3 environment_radiance(vec3 d) {
  return environment_radiance_uv(environment_uv(world_to_map(d)));
}

// environment_table: the texels' pdf over the unit square of (u, v) (width x height values,
// rows from the top), then the cumulative distribution over the rows (height + 1 values,
// 0 ... 1), then each row's cumulative distribution over its columns (width + 1 values each).
uint environment_marginal_offset() { return params.env_width * params.env_height; }
uint environment_row_offset(uint y) {
  return environment_marginal_offset() + params.env_height + 1u + y * (params.env_width + 1u);
}

// The largest index i in [0, n - 1] with cdf[first + i] <= u (cdf[first] = 0 <= u < 1):
// an entry of zero probability (cdf[i] == cdf[i + 1]) is never the answer.
uint environment_find(uint first, uint n, float u) {
  uint lo = 0u, hi = n - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) / 2u;
    if (environment_table(first + mid) <= u) lo = mid;
    else hi = mid - 1u;
  }
  return lo;
}

// The pdf in solid angle of drawing the world direction d (unit): the texel's pdf over (u, v)
// divided by the Jacobian 2 pi^2 sin(theta) of the mapping to directions.
float environment_pdf(vec3 d) {
  vec3 m = world_to_map(d);
  float sin_theta = length(vec2(m.x, m.z));  // not sqrt(1 - y^2), which loses its digits near the poles
  if (!(sin_theta > 0.0f)) return 0.0f;
  vec2 uv = environment_uv(m);
  uint x = min(uint(uv.x * float(params.env_width)), params.env_width - 1u);
  uint y = min(uint(uv.y * float(params.env_height)), params.env_height - 1u);
  return environment_table(y * params.env_width + x) / (2.0f * kPi * kPi * sin_theta);
}

// A direction drawn from the map's distribution with the 2-D sample u: a row by the
// marginal distribution, a column by the row's, uniform within the texel.
struct EnvironmentSample {
  vec3 wi;        // world direction toward the map
  float pdf;      // solid-angle pdf (0: none drawn)
  vec3 radiance;  // the map's radiance from wi
};

EnvironmentSample sample_environment(vec2 u) {
  uint w = params.env_width, h = params.env_height;
  uint marginal = environment_marginal_offset();
  uint y = environment_find(marginal, h, u.y);
  float lo = environment_table(marginal + y), width = environment_table(marginal + y + 1u) - lo;
  float dv = min((u.y - lo) / width, kOneMinusEpsilon);
  uint row = environment_row_offset(y);
  uint x = environment_find(row, w, u.x);
  float clo = environment_table(row + x), cwidth = environment_table(row + x + 1u) - clo;
  float du = min((u.x - clo) / cwidth, kOneMinusEpsilon);
  vec2 uv = vec2((float(x) + du) / float(w), (float(y) + dv) / float(h));
  vec3 m = environment_direction(uv);
  float sin_theta = sin(kPi * uv.y);
  float pdf = environment_table(y * w + x) / (2.0f * kPi * kPi * sin_theta);
  if (!(pdf > 0.0f) || isinf(pdf)) return EnvironmentSample(vec3(0.0f, 1.0f, 0.0f), 0.0f, vec3(0.0f));
  return EnvironmentSample(map_to_world(m), pdf, environment_radiance_uv(uv));
}

// What a ray that leaves the scene in direction d sees: the map where the scene has one
// (kFeatureEnvironment), else the uniform sky (--sky; black by default).
vec3 sky_radiance(vec3 d) {
  if (has_environment()) return environment_radiance(d);
  return vec3(params.sky);
}

#endif  // PT_ENVIRONMENT_GLSL
