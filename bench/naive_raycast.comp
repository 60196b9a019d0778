// The speed section's GPU reference (issue 6): the naive GLSL loop a first GPU ray caster
// would be, to measure the device itself. One camera ray per invocation, a plain loop over
// every triangle with the Möller-Trumbore test, the nearest t written out. Article: the
// raycasting step (Eq. 2), its brute-force closest-hit search, without the renderer's
// watertight test and rounding bound. Run by bench/speed_gpu.cpp on the bindings of
// gpu/compute_pipeline.h: 0 the scene's triangles, 3 the rays, 4 the counts, 5 the output.
#version 460

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct Triangle {  // common/kernel/scene_types.h's layout
  vec3 p0;
  uint material;
  vec3 p1;
  uint light;
  vec3 p2;
  uint pad;
};

layout(std430, set = 0, binding = 0) readonly buffer TriangleBuffer { Triangle triangles[]; };
layout(std430, set = 0, binding = 3) readonly buffer RayBuffer { vec4 rays[]; };  // origin, dir, unused, origin, ...
layout(std140, set = 0, binding = 4) uniform CountBuffer { uvec4 counts; };         // x: triangles, y: rays
layout(std430, set = 0, binding = 5) writeonly buffer OutputBuffer { float t_out[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= counts.y) return;
  vec3 o = rays[3u * i].xyz;
  vec3 d = rays[3u * i + 1u].xyz;
  float best = 3.402823466e38;
  for (uint k = 0u; k < counts.x; k++) {
    vec3 p0 = triangles[k].p0;
    vec3 e1 = triangles[k].p1 - p0;
    vec3 e2 = triangles[k].p2 - p0;
    vec3 p = cross(d, e2);
    float det = dot(e1, p);
    if (abs(det) < 1e-12) continue;
    float inv_det = 1.0 / det;
    vec3 s = o - p0;
    float u = dot(s, p) * inv_det;
    if (u < 0.0 || u > 1.0) continue;
    vec3 q = cross(s, e1);
    float v = dot(d, q) * inv_det;
    if (v < 0.0 || u + v > 1.0) continue;
    float t = dot(e2, q) * inv_det;
    if (t > 1e-6 && t < best) best = t;
  }
  t_out[i] = best;
}
