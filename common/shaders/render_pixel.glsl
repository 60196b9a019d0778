// One pass over one pixel: params.image.w samples, from sample index params.image.z on,
// each through a point jittered uniformly inside the pixel (box filter, the contract (README.md)).
// Every stage defines `vec3 Li(Ray ray)`, its estimate of the radiance along a camera ray
// (Eq. 2, 3, 4 or 5); this file is included after it and is the same for all stages.
#ifndef PT_RENDER_PIXEL_GLSL
#define PT_RENDER_PIXEL_GLSL

float luminance(vec3 c) {
  return dot(c, vec3(0.2126f, 0.7152f, 0.0722f));
}

// Returns (sum of the samples' radiance, sum of their squared luminance); the host adds
// these up in double precision (film.cpp) and derives the mean and its variance.
vec4 render_pixel(uint x, uint y) {
  vec3 sum = vec3(0.0f);
  float sum_sq = 0.0f;
  uint pixel_index = y * params.image.x + x;
  for (uint s = 0u; s < params.image.w; s++) {
    rng_seed(pixel_index, params.image.z + s, params.options.x);
    float fx = (float(x) + rng_next_float()) / float(params.image.x);
    float fy = (float(y) + rng_next_float()) / float(params.image.y);
    vec3 L = Li(camera_ray(params.camera, vec2(fx, fy)));
    // A NaN or infinite sample would poison the pixel for ever: drop it and count it.
    if (any(isnan(L)) || any(isinf(L))) {
      atomicAdd(counters[kCounterNonFinite], 1u);
      atomicMin(counters[kCounterNonFinitePixel], pixel_index);
      continue;
    }
    float lum = luminance(L);
    sum += L;
    sum_sq += lum * lum;
  }
  return vec4(sum, sum_sq);
}

#endif  // PT_RENDER_PIXEL_GLSL
