// Sampling routines shared by the stages, each as the triple sample_X / X_pdf / invert_X
// (pbrt-v4's convention): directions in a local frame whose +z is the surface normal.
// stage2 (Eq. 3) draws uniformly over the hemisphere; stage3 (Eq. 4) adds more.
#ifndef PT_SAMPLING_GLSL
#define PT_SAMPLING_GLSL

#include "common/kernel/sampler.glsl"

const float kPi = 3.14159265358979f;

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

// The two hemisphere samplers and their pdfs, declared here and defined in
// uniform_hemisphere.glsl and cosine_hemisphere.glsl, or by a lab's file in that lab's
// build (labs/, cmake/Labs.cmake): the build picks the definitions.
// Uniform over the hemisphere z > 0: density 1 / (2 pi) (stage2, Eq. 3).
vec3 sample_uniform_hemisphere(vec2 u);
float uniform_hemisphere_pdf();
// What a uniformly sampled bounce multiplies the path by: (2 pi / N) f cos theta, N = 1.
vec3 uniform_bounce_weight(vec3 f, vec3 wi);
// Cosine-weighted over the hemisphere z > 0: density cos(theta) / pi (stage3, Eq. 4).
vec3 sample_cosine_hemisphere(vec2 u);
float cosine_hemisphere_pdf(float cos_theta);

#endif  // PT_SAMPLING_GLSL
