// Ray-scene intersection: brute force over every primitive in one function, as the
// article keeps it (section on raycasting: the one procedure an acceleration structure
// would later replace). Triangles use the watertight test of Woop, Benthin and Wald
// (JCGT 2013), so rays aimed at shared edges and vertices never slip through a mesh;
// spheres use the cancellation-free quadratic of Haines et al. (Ray Tracing Gems, ch. 7).
#ifndef PT_INTERSECT_GLSL
#define PT_INTERSECT_GLSL

#include "common/kernel/camera.glsl"
#include "common/kernel/spawn.glsl"
#include "common/kernel/texture_lookup.glsl"
#include "common/kernel/sphere_power.glsl"

const float kInfinity = 3.402823466e38f;  // the largest float: "no hit yet"

struct Hit {
  float t;    // distance along the ray (directions are unit length)
  float b1;   // barycentric weight of p1 (triangles)
  float b2;   // barycentric weight of p2 (triangles)
  uint prim;  // index into triangles[] or spheres[]
  uint kind;  // kPrimNone, kPrimTriangle or kPrimSphere
};

// The per-ray part of the watertight test: the axis the ray runs along most becomes z,
// and a shear maps the ray onto +z.
struct RayShear {
  int kx;
  int ky;
  int kz;
  vec3 s;  // x, y: shear of the kx, ky coordinates; z: 1 / dir[kz]
};

RayShear make_ray_shear(vec3 dir) {
  vec3 a = abs(dir);
  int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  if (dir[kz] < 0.0f) {  // keep the winding of the triangle
    int swap = kx;
    kx = ky;
    ky = swap;
  }
  return RayShear(kx, ky, kz, vec3(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0f / dir[kz]));
}

// n u / (1 - n u) for u = 2^-24, float's unit roundoff: the relative error bound of n
// chained roundings (Higham's gamma_n).
const float kGamma2 = 1.19209304e-07f;
const float kGamma3 = 1.78813966e-07f;
const float kGamma5 = 2.98023313e-07f;

// max() of two non-negative numbers as a select. The rounding bounds below use it: they
// take maxima of absolute values, never NaN where a hit is possible, so it gives what
// max() gives, and it is how glm's max works on the CPU. lavapipe compiles GLSL's max with
// NaN handling that the select does not need (4 to 6% faster there).
float larger(float a, float b) {
  return a < b ? b : a;
}

// Returns a hit with triangle `index` if it is nearer than `best`, else `best`.
Hit hit_triangle(Ray ray, RayShear rs, uint index, Hit best) {
  Triangle tri = triangle_at(index);
  vec3 a = vec3(tri.p0) - ray.origin;
  vec3 b = vec3(tri.p1) - ray.origin;
  vec3 c = vec3(tri.p2) - ray.origin;
  // Shear and scale the vertices into the ray's space.
  float ax = a[rs.kx] - rs.s.x * a[rs.kz];
  float ay = a[rs.ky] - rs.s.y * a[rs.kz];
  float bx = b[rs.kx] - rs.s.x * b[rs.kz];
  float by = b[rs.ky] - rs.s.y * b[rs.kz];
  float cx = c[rs.kx] - rs.s.x * c[rs.kz];
  float cy = c[rs.ky] - rs.s.y * c[rs.kz];
  // Edge functions: the ray passes inside when none has a sign opposite to the others.
  float u = cx * by - cy * bx;
  float v = ax * cy - ay * cx;
  float w = bx * ay - by * ax;
  if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return best;
  float det = u + v + w;
  if (det == 0.0f) return best;
  // The distance along the ray: t_scaled / det. A hit must lie ahead of the origin.
  float az = rs.s.z * a[rs.kz];
  float bz = rs.s.z * b[rs.kz];
  float cz = rs.s.z * c[rs.kz];
  float t_scaled = u * az + v * bz + w * cz;
  float inv_det = 1.0f / det;
  float t = t_scaled * inv_det;
  // Only a nearer hit replaces best: of two at the same distance, the lower index stays.
  // The result is the nearest hit whatever order the triangles are tested in, which lets
  // the CPU test them in parallel (cpu/triangle_lanes.h).
  if (!(t > 0.0f && t < best.t)) return best;
  // A t no larger than its own rounding error cannot be told from 0: its sign may be
  // wrong (a sliver far from the ray origin), and the ray would re-hit the surface it
  // left. The bound follows the error of each step above (floating-point error analysis
  // of the watertight test, as in pbrt's triangle test): the sheared coordinates, the
  // edge functions, then t_scaled. kGamma(n) = n u / (1 - n u), u = 2^-24.
  float max_x = larger(larger(abs(ax), abs(bx)), abs(cx));
  float max_y = larger(larger(abs(ay), abs(by)), abs(cy));
  float max_z = larger(larger(abs(az), abs(bz)), abs(cz));
  float max_e = larger(larger(abs(u), abs(v)), abs(w));
  float delta_x = kGamma5 * (max_x + max_z);
  float delta_y = kGamma5 * (max_y + max_z);
  float delta_z = kGamma3 * max_z;
  float delta_e = 2.0f * (kGamma2 * max_x * max_y + delta_y * max_x + delta_x * max_y);
  float delta_t = 3.0f * (kGamma3 * max_e * max_z + delta_e * max_z + delta_z * max_e) * abs(inv_det);
  if (t <= delta_t) return best;
  // A hit closer than the rounding of the vertices' own coordinates (relative to the ray
  // origin) cannot be told from the surface the ray left: a large triangle far from its
  // vertices has errors far above the spawn offset (pbrt-v4's deltaT plays this role).
  float extent = larger(larger(larger(abs(a.x), abs(a.y)), larger(abs(a.z), abs(b.x))),
                        larger(larger(abs(b.y), abs(b.z)), larger(larger(abs(c.x), abs(c.y)), abs(c.z))));
  if (t <= 4e-7f * extent) return best;
  return Hit(t, v * inv_det, w * inv_det, index, kPrimTriangle);
}

// The nearest hit of `best` and every triangle, tested in index order: the article's
// brute-force search.
Hit nearest_triangle_in_order(Ray ray, RayShear rs, Hit best) {
  for (uint i = 0u; i < params.triangle_count; i++) best = hit_triangle(ray, rs, i, best);
  return best;
}

// The nearest hit of `best` and every triangle, as the backend searches them: the loop
// above on the GPU (gpu/triangle_search.glsl), SIMD lanes on the CPU (cpu/triangle_lanes.h),
// with the same hits bit for bit. Defined by the backend after this file.
Hit nearest_triangle(Ray ray, RayShear rs, Hit best);

// Rounding error of a sphere root, in units of the numbers it was computed from: a few
// float epsilons for the rounding of f = origin - centre, of the origin itself (the last
// hit's rounding) and of the products below.
const float kSphereRootError = 1e-6f;

// Returns a hit with sphere `index` if it is nearer than `best`, else `best`.
// Both differences of squares are taken as (x - r)(x + r) of lengths, not x^2 - r^2: with
// smallpt's walls (radius 1e5) x^2 and r^2 are 1e10, where a float's step is 1024, while
// x - r keeps the step of x (1/128). The power c (the product of the roots) is taken in
// whichever of two forms rounds less (sphere_power_from_world_origin). A root is taken only
// beyond its own error bound (as pbrt does with interval arithmetic): a ray leaving a wall
// of radius 1e5 would otherwise find that wall again next to where it left it.
Hit hit_sphere(Ray ray, uint index, Hit best) {
  vec3 center = spheres[index].center;
  float radius = spheres[index].radius;
  vec3 f = ray.origin - center;
  float b = -dot(f, ray.dir);
  float l = length(f + b * ray.dir);  // from the centre to the ray's closest point
  float disc = (radius - l) * (radius + l);
  if (disc < 0.0f) return best;
  float fl = length(f);
  float c = (fl - radius) * (fl + radius);
  float c_scale = fl * fl + radius * radius;
  vec2 from_world = sphere_power_from_world_origin(ray.origin, center, radius);
  if (from_world.y < c_scale) {
    c = from_world.x;
    c_scale = from_world.y;
  }
  float q = b + (b >= 0.0f ? sqrt(disc) : -sqrt(disc));  // the root of larger magnitude
  if (q == 0.0f) return best;  // the origin at the centre of a sphere of radius 0
  float t_small = c / q;       // the other root, by Vieta's formula
  float t = kInfinity;
  if (q > kSphereRootError * (fl + radius)) t = q;
  if (t_small > kSphereRootError * c_scale / abs(q)) t = min(t, t_small);
  if (t >= best.t) return best;
  return Hit(t, 0.0f, 0.0f, index, kPrimSphere);
}

// The nearest hit of `best` and every sphere, tested in index order.
Hit nearest_sphere_in_order(Ray ray, Hit best) {
  for (uint i = 0u; i < params.sphere_count; i++) best = hit_sphere(ray, i, best);
  return best;
}

// The nearest hit of `best` and every sphere, as the backend searches them: the loop above
// on the GPU (gpu/triangle_search.glsl), SIMD lanes on the CPU (cpu/sphere_lanes.h), with
// the same hits bit for bit. Defined by the backend after this file.
Hit nearest_sphere(Ray ray, Hit best);

// The nearest hit closer than t_max, or a hit of kind kPrimNone, every surface opaque.
Hit intersect_opaque(Ray ray, float t_max) {
  Hit best = Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone);
  // The shear is the triangle test's: a scene of spheres alone does without it (the CPU's
  // kernels always have the triangles' code, hence the count).
  if (has_feature(kFeatureTriangles) && params.triangle_count > 0u) {
    best = nearest_triangle(ray, make_ray_shear(ray.dir), best);
  }
  if (has_feature(kFeatureSpheres)) best = nearest_sphere(ray, best);
  return best;
}

// Surface.triangle of a point on a sphere.
const uint kNoTriangle = 0xffffffffu;

// What the integrator needs to know about the point a ray hit.
struct Surface {
  vec3 p;         // position
  vec3 n;         // unit geometric normal on the front side (CCW winding, sphere outside)
  bool front;     // the ray arrived from the front side
  uint material;  // index into materials[]
  uint triangle;  // index into triangles[] (and triangle_attributes[]), or kNoTriangle
  float b1;       // barycentric weights of p1 and p2 at p (triangles): where its
  float b2;       // textures are read (texture.glsl: surface_material)
  bool shaded;    // a triangle flagged kTriangleShadingNormals (shading_normal.glsl)
};

Surface surface_at(Ray ray, Hit hit) {
  if (!has_feature(kFeatureSpheres) || hit.kind == kPrimTriangle) {
    Triangle tri = triangle_at(hit.prim);
    vec3 p0 = tri.p0;
    vec3 p1 = tri.p1;
    vec3 p2 = tri.p2;
    // The barycentric point is more accurate than origin + t * dir far from the origin.
    vec3 p = (1.0f - hit.b1 - hit.b2) * p0 + hit.b1 * p1 + hit.b2 * p2;
    vec3 n = normalize(cross(p1 - p0, p2 - p0));
    bool shaded = has_feature(kFeatureShadingNormals) && (tri.flags & kTriangleShadingNormals) != 0u;
    return Surface(p, n, dot(ray.dir, n) < 0.0f, tri.material, hit.prim, hit.b1, hit.b2, shaded);
  }
  Sphere sph = spheres[hit.prim];
  vec3 center = sph.center;
  vec3 p = ray.origin + hit.t * ray.dir;
  vec3 n = normalize(p - center);
  return Surface(p, n, dot(ray.dir, n) < 0.0f, sph.material, kNoTriangle, 0.0f, 0.0f, false);
}

// glTF's alphaMode MASK (beyond the article; issue #19): where a masked material's alpha
// (baseColorFactor's alpha x its base colour texture's alpha x COLOR_0's alpha) is below its
// alphaCutoff the surface is not there, for every ray. Whether the hit point (b1, b2) of
// triangle `tri` is such a hole.
bool cut_out(uint tri, float b1, float b2) {
  Triangle t = triangle_at(tri);
  if ((t.flags & kTriangleMasked) == 0u) return false;  // flagged: its material has a mask
  MaterialTextures mt = material_textures[t.material];
  TriangleAttributes a = triangle_attributes[tri];
  float alpha = mt.base_alpha * triangle_color(a, b1, b2).w;
  if (mt.base_color != kNoTexture) {
    vec2 uv = slot_uv(mt.tex_coord_sets, kSlotBaseColor, vec3(mt.base_color_s), vec3(mt.base_color_t), a, b1, b2);
    alpha *= texture_lookup(mt.base_color, uv, true).w;
  }
  return alpha < mt.alpha_cutoff;
}

// At most this many holes are passed along one ray (leaves of a tree seen edge on): beyond
// them the surface counts as there.
const uint kMaxCutOuts = 64u;

// The nearest hit closer than t_max that is not in a hole of an alpha mask, or a hit of
// kind kPrimNone. A hit in a hole is passed by tracing on from just beyond it (spawn_ray:
// the same line, cleared of the surface), its distance added; scenes without alpha masks
// have one search only, the masks' code not compiled in (has_feature).
Hit intersect_scene(Ray ray, float t_max) {
  Hit best = intersect_opaque(ray, t_max);
  if (!has_feature(kFeatureAlphaMask)) return best;
  for (uint i = 0u; i < kMaxCutOuts && best.kind == kPrimTriangle && cut_out(best.prim, best.b1, best.b2); i++) {
    Surface hole = surface_at(ray, best);
    Ray beyond = spawn_ray(hole.p, hole.n, ray.dir);
    float skipped = dot(beyond.origin - ray.origin, ray.dir);
    if (!(skipped < t_max)) return Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone);
    best = intersect_opaque(beyond, t_max - skipped);
    if (best.kind == kPrimNone) return Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone);
    best.t += skipped;
  }
  return best;
}

// Whether any triangle is hit closer than t_max: the answer nearest_triangle() gives, as the
// backend finds it fastest (the BVH's any-hit walk, common/kernel/bvh.glsl, or the nearest
// hit). Defined by the backend after this file, as nearest_triangle() is.
bool occluded_triangles(Ray ray, RayShear rs, float t_max);

// Whether anything is hit closer than t_max (shadow rays): intersect_scene(ray, t_max)
// finds a hit exactly when this is true.
bool occluded_scene(Ray ray, float t_max) {
  if (has_feature(kFeatureAlphaMask)) return intersect_scene(ray, t_max).kind != kPrimNone;  // through holes
  if (has_feature(kFeatureTriangles) && params.triangle_count > 0u &&
      occluded_triangles(ray, make_ray_shear(ray.dir), t_max)) {
    return true;
  }
  return has_feature(kFeatureSpheres) && nearest_sphere(ray, Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone)).kind != kPrimNone;
}

#endif  // PT_INTERSECT_GLSL
