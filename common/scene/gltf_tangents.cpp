// Per-vertex tangents for a normal-mapped glTF primitive that has NORMAL but no TANGENT, made as
// MikkTSpace makes them in essence (the specification says clients SHOULD; Blender does), issue #46.
// Beyond the article, whose surfaces are flat: what a normal map's tangent frame is where the file
// leaves it out (docs/shading_normals.md, "What is read").
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

#include "common/scene/gltf_scene_builder.h"

namespace pt::gltf {

namespace {

// A vertex's weld key: the bits of its position, normal and uv (MikkTSpace welds vertices that
// agree in all three, so a file that splits a vertex for another attribute gets one tangent).
using WeldKey = std::array<std::uint32_t, 8>;

WeldKey weld_key(glm::vec3 p, glm::vec3 n, glm::vec2 uv) {
  const float f[8] = {p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y};
  WeldKey k;
  std::memcpy(k.data(), f, sizeof f);
  return k;
}

glm::dvec3 unit_or_zero(glm::dvec3 v) {
  const double len = glm::length(v);
  return len > 0.0 && std::isfinite(len) ? v / len : glm::dvec3(0.0);
}

// v without its component along the unit n, made unit (zero if nothing is left).
glm::dvec3 in_plane(glm::dvec3 v, glm::dvec3 n) { return unit_or_zero(v - glm::dot(v, n) * n); }

// What the corners of one welded vertex on faces of one UV orientation add up.
struct Sum {
  glm::dvec3 tangent{0.0};  // sum of angle * (dP/du in the vertex's tangent plane, unit)
  double handedness = 0.0;  // sum of angle * the face's handedness
  double weight = 0.0;      // sum of the corner angles
};

}  // namespace

std::vector<glm::vec4> vertex_tangents(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                                       const std::vector<glm::vec2>& uv, const std::vector<std::uint32_t>& indices) {
  const std::size_t count = positions.size();
  std::vector<glm::vec4> out(count, glm::vec4(0.0f));
  if (normals.size() != count || uv.size() != count) return out;
  // Weld: each vertex's representative.
  std::map<WeldKey, std::uint32_t> first;
  std::vector<std::uint32_t> rep(count);
  for (std::uint32_t i = 0; i < count; ++i) rep[i] = first.emplace(weld_key(positions[i], normals[i], uv[i]), i).first->second;
  // Two sums per representative: faces whose UVs run one way round and the other (MikkTSpace
  // keeps mirrored UV islands apart even where they share a vertex).
  std::vector<Sum> sums(2 * count);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t v[3] = {indices[t], indices[t + 1], indices[t + 2]};
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::dvec3(positions[v[k]]);
    const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const double du1 = double(uv[v[1]].x) - uv[v[0]].x, dv1 = double(uv[v[1]].y) - uv[v[0]].y;
    const double du2 = double(uv[v[2]].x) - uv[v[0]].x, dv2 = double(uv[v[2]].y) - uv[v[0]].y;
    const double r = du1 * dv2 - du2 * dv1;
    if (!(std::abs(r) > 0.0) || !std::isfinite(r)) continue;  // no UV area: adds nothing
    const glm::dvec3 dpdu = (e1 * dv2 - e2 * dv1) / r, dpdv = (e2 * du1 - e1 * du2) / r;
    const glm::dvec3 face = unit_or_zero(glm::cross(e1, e2));
    if (face == glm::dvec3(0.0)) continue;  // no area: skipped by the loader too
    const int side = r > 0.0 ? 0 : 1;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 n = unit_or_zero(glm::dvec3(normals[v[k]]));
      if (n == glm::dvec3(0.0)) continue;
      const glm::dvec3 t = in_plane(dpdu, n);
      if (t == glm::dvec3(0.0)) continue;
      // The corner's angle, its two edges seen in the vertex's tangent plane.
      const glm::dvec3 a = in_plane(p[(k + 1) % 3] - p[k], n), b = in_plane(p[(k + 2) % 3] - p[k], n);
      const double angle = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
      // glTF's v runs down the image, a normal map's green up it: the bitangent
      // handedness * cross(n, t) runs along -dP/dv (as tangents_from_uvs).
      const double hand = glm::dot(glm::cross(n, t), -dpdv) < 0.0 ? -1.0 : 1.0;
      Sum& s = sums[2 * std::size_t(rep[v[k]]) + std::size_t(side)];
      s.tangent += angle * t;
      s.handedness += angle * hand;
      s.weight += angle;
    }
  }
  // Each vertex takes the sum of the orientation its faces weigh most, made orthogonal to its
  // normal (Gram-Schmidt) and unit; a vertex that got nothing keeps a zero tangent, which
  // shade_triangle replaces by the one its triangle makes from the UVs.
  for (std::uint32_t i = 0; i < count; ++i) {
    const Sum& a = sums[2 * std::size_t(rep[i])];
    const Sum& b = sums[2 * std::size_t(rep[i]) + 1];
    const Sum& s = a.weight >= b.weight ? a : b;
    const glm::dvec3 t = in_plane(s.tangent, unit_or_zero(glm::dvec3(normals[i])));
    if (s.weight > 0.0 && t != glm::dvec3(0.0)) out[i] = glm::vec4(glm::vec3(t), s.handedness < 0.0 ? -1.0f : 1.0f);
  }
  return out;
}

}  // namespace pt::gltf
