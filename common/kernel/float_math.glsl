// sin, cos and atan to within a few units in the last place of a float, for kernel code
// whose result depends on their relative precision (the spherical triangles of stage5_mis,
// spherical_triangle.glsl). The built-ins are not enough there: Vulkan lets a GPU's sin
// and cos be off by 2^-11 in absolute terms and its atan by 4096 units in the last place,
// and lavapipe's were off enough to bias stage5's image under a small light by 2e-5
// (tests/stage5_mis). These are the classical single-precision minimax polynomials (the
// coefficients of Moshier's Cephes library) after a range reduction that loses no digits.
#ifndef PT_FLOAT_MATH_GLSL
#define PT_FLOAT_MATH_GLSL

// sin and cos of r in [-pi/4, pi/4].
float sin_reduced(float r) {
  float r2 = r * r;
  return r + r * r2 * (-1.6666654611e-1f + r2 * (8.3321608736e-3f + r2 * -1.9515295891e-4f));
}

float cos_reduced(float r) {
  float r2 = r * r;
  return 1.0f - 0.5f * r2 + r2 * r2 * (4.166664568298827e-2f + r2 * (-1.388731625493765e-3f + r2 * 2.443315711809948e-5f));
}

// vec2(sin h, cos h) for h in [0, 5 pi / 4]. h - pi/2 and h - pi are formed as the exact
// difference from the float nearest the constant (exact by Sterbenz's lemma in the ranges
// where they are used), plus the constant's rounding error.
vec2 sin_cos(float h) {
  if (h <= 0.785398163f) return vec2(sin_reduced(h), cos_reduced(h));
  if (h <= 2.35619449f) {
    float r = (h - 1.57079637f) + 4.37113883e-8f;  // h - pi/2
    return vec2(cos_reduced(r), -sin_reduced(r));
  }
  float r = (h - 3.14159274f) + 8.74227766e-8f;  // h - pi
  return vec2(-sin_reduced(r), -cos_reduced(r));
}

// atan(t) for t >= 0: reduced to |t| <= tan(pi/8) by atan(t) = pi/4 + atan((t - 1) / (t + 1))
// or pi/2 + atan(-1 / t).
float atan_nonnegative(float t) {
  float base = 0.0f;
  if (t > 2.41421356f) {
    base = 1.57079633f;
    t = -1.0f / t;
  } else if (t > 0.414213562f) {
    base = 0.785398163f;
    t = (t - 1.0f) / (t + 1.0f);
  }
  float z = t * t;
  return base + ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z * t + t);
}

// atan2(y, x) for y >= 0: the angle in [0, pi] of the point (x, y).
float atan2_upper(float y, float x) {
  if (x > 0.0f) return atan_nonnegative(y / x);
  if (!(y > 0.0f)) return x < 0.0f ? 3.14159265f : 0.0f;
  return 1.57079633f + atan_nonnegative(-x / y);
}

#endif  // PT_FLOAT_MATH_GLSL
