// One pass over one pixel: params.sample_count samples, from sample index params.first_sample on,
// each through a point jittered uniformly inside the pixel (box filter, the contract (README.md));
// the sampler (sampler.glsl) chooses which uniform point.
// Every stage defines `vec3 Li(Ray ray)`, its estimate of the radiance along a camera ray
// (Eq. 2, 3, 4 or 5); this file is included after it and is the same for all stages.
#ifndef PT_RENDER_PIXEL_GLSL
#define PT_RENDER_PIXEL_GLSL

#include "common/kernel/sampler.glsl"
#include "common/kernel/camera.glsl"
#include "common/kernel/color.glsl"

// Returns the sum of the samples' radiance and, in its slot kPassRootSumSquares
// (scene_types.h), the root of the sum of their squared luminance; the host squares the
// latter and adds both up in double precision (film.cpp) for the mean and its variance. The root of the sum of squares is kept as scale x sqrt(ssq) (LAPACK's
// nrm2): a square is never formed in float, where radiance 1e20 would overflow (1e40) and
// 1e-20 flush to zero (1e-40 is below the smallest normal float; GPUs flush denormals).
vec4 render_pixel(uint x, uint y) {
  vec3 sum = vec3(0.0f);
  float scale = 0.0f;  // the largest |luminance| so far
  float ssq = 1.0f;    // sum of (luminance / scale)^2
  uint pixel_index = y * params.width + x;
  for (uint s = 0u; s < params.sample_count; s++) {
    start_sample(pixel_index, params.first_sample + s, params.seed, params.sampler_kind);
    vec2 jitter = sample_2d();  // the sampler's 2-D slot 0: a (0,2)-sequence in the pixel
    float fx = (float(x) + jitter.x) / float(params.width);
    float fy = (float(y) + jitter.y) / float(params.height);
    vec3 L = Li(camera_ray(params.camera, vec2(fx, fy)));
    // A NaN or infinite sample would poison the pixel for ever: drop it and count it.
    if (any(isnan(L)) || any(isinf(L))) {
      atomicAdd(counters[kCounterNonFinite], 1u);
      atomicMin(counters[kCounterNonFinitePixel], pixel_index);
      continue;
    }
    float a = abs(luminance(L));
    sum += L;
    if (a > scale) {
      float r = scale / a;
      ssq = 1.0f + ssq * r * r;
      scale = a;
    } else if (a > 0.0f) {
      float r = a / scale;
      ssq += r * r;
    }
  }
  vec4 result = vec4(sum, 0.0f);
  result[kPassRootSumSquares] = scale * sqrt(ssq);
  return result;
}

#endif  // PT_RENDER_PIXEL_GLSL
