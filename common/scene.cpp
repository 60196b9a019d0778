// Scene helpers: material rules of CONTRACT.md, bounds, and the kernel camera.
#include "common/scene.h"

#include <cmath>

namespace pt {

Bounds Scene::bounds() const {
  Bounds b;
  for (const Triangle& t : triangles) {
    b.extend(glm::vec3(t.p0)), b.extend(glm::vec3(t.p1)), b.extend(glm::vec3(t.p2));
  }
  for (const Sphere& s : spheres) {
    glm::vec3 c(s.center_radius);
    b.extend(c - s.center_radius.w), b.extend(c + s.center_radius.w);
  }
  return b;
}

uint Scene::add_material(const Material& m) {
  materials.push_back(m);
  return uint(materials.size() - 1);
}

void Scene::add_triangle(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, uint material) {
  triangles.push_back(Triangle{glm::vec4(p0, 0.0f), glm::vec4(p1, 0.0f), glm::vec4(p2, 0.0f),
                               glm::uvec4(material, kNoLight, 0u, 0u)});
}

void Scene::add_sphere(glm::vec3 center, float radius, uint material) {
  spheres.push_back(Sphere{glm::vec4(center, radius), glm::uvec4(material, kNoLight, 0u, 0u)});
}

namespace {
Material base_material(glm::vec3 color, uint kind) {
  Material m{};
  m.base_color = glm::vec4(color, 1.0f);
  m.params = glm::vec4(0.0f, 1.0f, 0.0f, 1.5f);
  m.kind = glm::uvec4(kind, 0u, 0u, 0u);
  return m;
}
}  // namespace

Material make_diffuse(glm::vec3 albedo, glm::vec3 emission, bool double_sided) {
  Material m = base_material(albedo, kMaterialDiffuse);
  m.emission = glm::vec4(emission, double_sided ? 1.0f : 0.0f);
  return m;
}

Material make_metal(glm::vec3 f0, float roughness) {
  Material m = base_material(f0, roughness > 0.0f ? kMaterialConductor : kMaterialMirror);
  m.params = glm::vec4(1.0f, roughness * roughness, 0.0f, 1.5f);
  return m;
}

Material make_glass(glm::vec3 tint, float ior) {
  Material m = base_material(tint, kMaterialGlass);
  m.params = glm::vec4(0.0f, 0.0f, 1.0f, ior);
  return m;
}

Material make_gltf_material(glm::vec3 base, float metallic, float roughness, float transmission,
                            float ior, glm::vec3 emission, bool double_sided) {
  Material m;
  if (transmission > 0.0f) {
    m = make_glass(base, ior);
  } else if (metallic >= 1.0f) {
    m = make_metal(base, roughness);
  } else if (metallic <= 0.0f) {
    m = make_diffuse(base);
  } else {
    m = base_material(base, kMaterialMixed);
    m.params = glm::vec4(metallic, roughness * roughness, 0.0f, ior);
  }
  m.params.z = transmission;
  m.emission = glm::vec4(emission, double_sided ? 1.0f : 0.0f);
  return m;
}

bool is_emissive(const Material& m) {
  return m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f;
}

Camera make_camera(const Scene& scene, float aspect) {
  CameraDesc desc;
  if (scene.camera) {
    desc = *scene.camera;
  } else {
    // Frame the bounding sphere from +Z with the default field of view.
    Bounds b = scene.bounds();
    glm::vec3 center = b.empty() ? glm::vec3(0.0f) : 0.5f * (b.lo + b.hi);
    float radius = b.empty() ? 1.0f : glm::max(0.5f * glm::length(b.hi - b.lo), 1e-6f);
    float half = 0.5f * desc.yfov * glm::min(aspect, 1.0f);
    float distance = radius / std::sin(half);
    desc.to_world = glm::mat4(1.0f);
    desc.to_world[3] = glm::vec4(center + glm::vec3(0.0f, 0.0f, distance), 1.0f);
  }
  glm::vec3 origin(desc.to_world[3]);
  glm::vec3 forward = glm::normalize(-glm::vec3(desc.to_world[2]));
  glm::vec3 up0 = glm::vec3(desc.to_world[1]);
  glm::vec3 right = glm::normalize(glm::cross(forward, up0));
  glm::vec3 up = glm::cross(right, forward);

  Camera c{};
  c.origin = glm::vec4(origin, 1.0f);
  c.forward = glm::vec4(forward, 0.0f);
  c.right = glm::vec4(right, 0.0f);
  c.up = glm::vec4(up, 0.0f);
  if (desc.kind == kCameraOrthographic) {
    c.extent = glm::vec4(desc.xmag, desc.ymag, 0.0f, 0.0f);
  } else {
    float t = std::tan(0.5f * desc.yfov);
    c.extent = glm::vec4(t * aspect, t, 0.0f, 0.0f);
  }
  c.kind = glm::uvec4(desc.kind, 0u, 0u, 0u);
  return c;
}

}  // namespace pt
