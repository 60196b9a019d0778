// A glTF primitive's shading frame per triangle (issue #46; beyond the article, whose surfaces
// are flat): NORMAL and TANGENT read and placed in world space, tangents made from the UVs
// where the file has none, and whether a triangle needs any of it (kTriangleShadingNormals).
// The kernel side is common/kernel/shading_normal.glsl; the rule is docs/shading_normals.md.
#include <cmath>
#include <string>
#include <vector>

#include "common/scene/gltf_scene_builder.h"
#include "common/scene/gltf_validate.h"

namespace pt::gltf {

namespace {

// A vertex normal further than this from its face normal (cosine below 1 - kFlatTolerance,
// about 0.8 degrees) makes the triangle smooth-shaded; closer ones are rounding of a flat face.
constexpr double kFlatTolerance = 1e-4;

glm::dvec3 unit_or_zero(glm::dvec3 v) {
  const double len = glm::length(v);
  return len > 0.0 && std::isfinite(len) ? v / len : glm::dvec3(0.0);
}

}  // namespace

PrimitiveShading read_shading(const tinygltf::Model& model, const tinygltf::Primitive& prim, std::size_t vertex_count,
                              const std::string& file, const std::string& where) {
  PrimitiveShading s;
  auto normal = prim.attributes.find("NORMAL"), tangent = prim.attributes.find("TANGENT");
  if (normal != prim.attributes.end()) {
    std::string what = "accessors[" + std::to_string(normal->second) + "] (NORMAL of " + where + ")";
    s.normals = read_positions(model, normal->second, file, what);  // VEC3 of FLOAT, finite
    if (s.normals.size() != vertex_count) {
      fail(file, what + " has " + std::to_string(s.normals.size()) + " entries, POSITION has " +
                     std::to_string(vertex_count) + "; an attribute has one per vertex: " + kReexport);
    }
  }
  if (tangent != prim.attributes.end()) {
    std::string what = "accessors[" + std::to_string(tangent->second) + "] (TANGENT of " + where + ")";
    const tinygltf::Accessor& a = model.accessors[std::size_t(tangent->second)];
    if (a.type != TINYGLTF_TYPE_VEC4 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
      fail(file, what + " must be VEC4 of FLOAT (type " + std::to_string(a.type) + ", componentType " +
                     std::to_string(a.componentType) + "): re-export without mesh quantization");
    }
    s.tangents = read_colors(model, tangent->second, vertex_count, file, what);  // VEC4 of FLOAT, finite
  }
  return s;
}

TriangleShading tangents_from_uvs(const glm::vec3 p[3], const glm::vec2 uv[3], glm::vec3 face_normal) {
  Triangle flat{p[0], 0u, p[1], 0u, p[2], 0u};
  TriangleShading s = flat_shading(flat);
  // dP/du and dP/dv of the triangle's plane: e1 = dP/du du1 + dP/dv dv1, e2 likewise.
  const glm::dvec3 e1 = glm::dvec3(p[1]) - glm::dvec3(p[0]), e2 = glm::dvec3(p[2]) - glm::dvec3(p[0]);
  const double du1 = double(uv[1].x) - uv[0].x, dv1 = double(uv[1].y) - uv[0].y;
  const double du2 = double(uv[2].x) - uv[0].x, dv2 = double(uv[2].y) - uv[0].y;
  const double r = du1 * dv2 - du2 * dv1;
  const glm::dvec3 n(face_normal);
  const glm::dvec3 dpdu = (e1 * dv2 - e2 * dv1) / r, dpdv = (e2 * du1 - e1 * du2) / r;
  glm::dvec3 t = unit_or_zero(dpdu - glm::dot(dpdu, n) * n);
  if (!(std::abs(r) > 0.0) || t == glm::dvec3(0.0)) return s;  // no UV area: any tangent (flat_shading's)
  // glTF's uv has v down the image, and a normal map's green points up it: the bitangent
  // handedness * cross(n, t) runs along -dP/dv (as glTF's TANGENT.w, MikkTSpace from Blender).
  const float handedness = glm::dot(glm::cross(n, t), -dpdv) < 0.0 ? -1.0f : 1.0f;
  s.tangent0 = s.tangent1 = s.tangent2 = glm::vec3(t);
  s.handedness0 = s.handedness1 = s.handedness2 = handedness;
  return s;
}

bool shade_triangle(const PrimitiveShading& prim, const std::uint32_t corner[3], const glm::vec3 p[3],
                    const glm::vec2 uv[3], const glm::dmat4& world, bool normal_mapped, TriangleShading& out) {
  const glm::vec3 face = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
  out = normal_mapped ? tangents_from_uvs(p, uv, face) : flat_shading(Triangle{p[0], 0u, p[1], 0u, p[2], 0u});
  bool smooth = false;
  if (!prim.normals.empty()) {
    // Normals by the inverse transpose of the node's transform, then made unit.
    const glm::dmat3 m(world), normal_matrix = glm::transpose(glm::inverse(m));
    glm::dvec3 n[3], sum(0.0);
    for (int k = 0; k < 3; ++k) {
      n[k] = unit_or_zero(normal_matrix * glm::dvec3(prim.normals[corner[k]]));
      if (n[k] == glm::dvec3(0.0)) n[k] = glm::dvec3(face);  // a zero normal in the file: the face's
      sum += n[k];
    }
    // Normals that point against the winding (a file whose faces are wound backwards, or a
    // mirroring transform) are turned to the front face, which decides emission and sides.
    const double flip = glm::dot(sum, glm::dvec3(face)) < 0.0 ? -1.0 : 1.0;
    glm::vec3* normals[3] = {&out.normal0, &out.normal1, &out.normal2};
    for (int k = 0; k < 3; ++k) {
      *normals[k] = glm::vec3(flip * n[k]);
      smooth = smooth || glm::dot(flip * n[k], glm::dvec3(face)) < 1.0 - kFlatTolerance;
    }
    if (!prim.tangents.empty()) {
      // The file's tangents, placed by the node's transform; a mirroring transform (or the
      // flip above) turns the bitangent, which the handedness makes up for.
      const double mirror = glm::determinant(m) < 0.0 ? -1.0 : 1.0;
      glm::vec3* tangents[3] = {&out.tangent0, &out.tangent1, &out.tangent2};
      float* hands[3] = {&out.handedness0, &out.handedness1, &out.handedness2};
      for (int k = 0; k < 3; ++k) {
        const glm::vec4 t = prim.tangents[corner[k]];
        glm::dvec3 tw = unit_or_zero(m * glm::dvec3(t.x, t.y, t.z));
        if (tw == glm::dvec3(0.0)) continue;  // a zero tangent: the one made from the UVs
        *tangents[k] = glm::vec3(tw);
        *hands[k] = float((t.w < 0.0f ? -1.0 : 1.0) * mirror * flip);
      }
    }
  }
  return smooth || normal_mapped;
}

}  // namespace pt::gltf
