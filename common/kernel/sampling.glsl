// Sampling routines shared by the stages, each as the triple sample_X / X_pdf / invert_X
// (pbrt-v4's convention): directions in a local frame whose +z is the surface normal.
// stage2 (Eq. 3) draws uniformly over the hemisphere; stage3 (Eq. 4) adds more.
#ifndef PT_SAMPLING_GLSL
#define PT_SAMPLING_GLSL

const float kPi = 3.14159265358979f;

#include "labs/lab_hooks.glsl"
#include "labs/lab2.glsl"
#include "labs/lab3.glsl"

// An orthonormal basis around a unit normal, without branches on the normal's direction
// except its sign (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
struct Frame {
  vec3 t;  // tangent
  vec3 b;  // bitangent
  vec3 n;  // normal: local +z
};

Frame make_frame(vec3 n) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float b = n.x * n.y * a;
  return Frame(vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x), vec3(b, s + n.y * n.y * a, -n.y), n);
}

vec3 frame_to_world(Frame f, vec3 v) {
  return v.x * f.t + v.y * f.b + v.z * f.n;
}

vec3 frame_to_local(Frame f, vec3 v) {
  return vec3(dot(v, f.t), dot(v, f.b), dot(v, f.n));
}

// Uniform over the hemisphere z > 0: cos(theta) = u.x, phi = 2 pi u.y; pdf 1 / (2 pi).
vec3 sample_uniform_hemisphere(vec2 u) {
  PT_LAB_HOOK(2, lab2_sample_uniform_hemisphere(u));  // lab 2 (docs/labs/lab2.md)
  float z = u.x;
  float r = sqrt(max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

float uniform_hemisphere_pdf() {
  PT_LAB_HOOK(2, lab2_uniform_hemisphere_pdf());
  return 1.0f / (2.0f * kPi);
}

vec2 invert_uniform_hemisphere(vec3 w) {
  float phi = atan(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return vec2(w.z, phi / (2.0f * kPi));
}

// Cosine-weighted over the hemisphere z > 0 (Malley's method: uniform on the disk, lifted
// up): pdf cos(theta) / pi, the diffuse lobe's own shape (stage3, Eq. 4).
vec3 sample_cosine_hemisphere(vec2 u) {
  PT_LAB_HOOK(3, lab3_sample_cosine_hemisphere(u));  // lab 3 (docs/labs/lab3.md)
  float r = sqrt(u.x);
  float phi = 2.0f * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - u.x)));
}

float cosine_hemisphere_pdf(float cos_theta) {
  PT_LAB_HOOK(3, lab3_cosine_hemisphere_pdf(cos_theta));
  return max(cos_theta, 0.0f) * (1.0f / kPi);
}

vec2 invert_cosine_hemisphere(vec3 w) {
  float phi = atan(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return vec2(w.x * w.x + w.y * w.y, phi / (2.0f * kPi));
}

vec2 rng_next_vec2() {
  float a = rng_next_float();
  return vec2(a, rng_next_float());
}

#endif  // PT_SAMPLING_GLSL
