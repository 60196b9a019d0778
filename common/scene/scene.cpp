// Scene helpers: material rules of the contract (README.md), bounds, and the kernel camera.
#include "common/scene/scene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace pt {

Bounds Scene::bounds() const {
  if (region) return *region;
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

// A quad p0 p1 p2 p3 (counter-clockwise seen from its front) as two triangles.
void add_quad(Scene& s, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, uint material) {
  s.add_triangle(p0, p1, p2, material);
  s.add_triangle(p0, p2, p3, material);
}

// An axis-aligned box of half-size `half` turned by `angle` about +Y, faces outwards.
void add_box(Scene& s, glm::vec3 center, glm::vec3 half, float angle, uint material) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), center) * glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0));
  auto p = [&](float x, float y, float z) { return glm::vec3(m * glm::vec4(x * half.x, y * half.y, z * half.z, 1.0f)); };
  add_quad(s, p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1), material);      // +z
  add_quad(s, p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1), material);  // -z
  add_quad(s, p(1, -1, 1), p(1, -1, -1), p(1, 1, -1), p(1, 1, 1), material);      // +x
  add_quad(s, p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1), material);  // -x
  add_quad(s, p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1), material);      // +y
  add_quad(s, p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1), material);  // -y
}

// The inside of the cube [-h, h]^3, every face turned inwards.
void add_room(Scene& s, float h, uint floor, uint ceiling, uint back, uint left, uint right, int front) {
  add_quad(s, {-h, -h, h}, {h, -h, h}, {h, -h, -h}, {-h, -h, -h}, floor);   // y = -h, facing +y
  add_quad(s, {-h, h, -h}, {h, h, -h}, {h, h, h}, {-h, h, h}, ceiling);     // y = +h, facing -y
  add_quad(s, {-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h}, back);    // z = -h, facing +z
  add_quad(s, {-h, -h, h}, {-h, -h, -h}, {-h, h, -h}, {-h, h, h}, left);    // x = -h, facing +x
  add_quad(s, {h, -h, -h}, {h, -h, h}, {h, h, h}, {h, h, -h}, right);       // x = +h, facing -x
  if (front >= 0) add_quad(s, {h, -h, h}, {-h, -h, h}, {-h, h, h}, {h, h, h}, uint(front));  // facing -z
}

// A camera on `position` looking straight down (-y), image up = -z.
CameraDesc orthographic_down(glm::vec3 position, float half) {
  CameraDesc cam;
  cam.kind = kCameraOrthographic;
  cam.xmag = half, cam.ymag = half;
  cam.to_world = glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0), glm::vec4(position, 1));
  return cam;
}

// An orthographic camera on the +z axis looking down -z.
CameraDesc orthographic_front(float z, float half) {
  CameraDesc cam;
  cam.kind = kCameraOrthographic;
  cam.xmag = half, cam.ymag = half;
  cam.to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, z));
  return cam;
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

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
}  // namespace

void build_light_table(Scene& scene) {
  scene.lights.clear();
  std::vector<double> power;
  for (std::size_t i = 0; i < scene.triangles.size(); i++) {
    Triangle& t = scene.triangles[i];
    const Material& m = scene.materials[t.info.x];
    if (!is_emissive(m)) continue;
    double area = 0.5 * glm::length(glm::cross(glm::vec3(t.p1 - t.p0), glm::vec3(t.p2 - t.p0)));
    double sides = m.emission.w > 0.0f ? 2.0 : 1.0;
    t.info.y = uint(scene.lights.size());
    scene.lights.push_back(Light{glm::uvec4(kLightTriangle, uint(i), 0u, 0u), glm::vec4(0.0f)});
    power.push_back(M_PI * area * sides * luminance(glm::vec3(m.emission)));
  }
  for (std::size_t i = 0; i < scene.spheres.size(); i++) {
    Sphere& s = scene.spheres[i];
    const Material& m = scene.materials[s.info.x];
    if (!is_emissive(m)) continue;
    double r = s.center_radius.w;
    s.info.y = uint(scene.lights.size());
    scene.lights.push_back(Light{glm::uvec4(kLightSphere, uint(i), 0u, 0u), glm::vec4(0.0f)});
    power.push_back(M_PI * 4.0 * M_PI * r * r * luminance(glm::vec3(m.emission)));
  }
  for (std::size_t i = 0; i < scene.point_lights.size(); i++) {
    scene.lights.push_back(Light{glm::uvec4(kLightPoint, uint(i), 0u, 0u), glm::vec4(0.0f)});
    power.push_back(4.0 * M_PI * luminance(glm::vec3(scene.point_lights[i].intensity)));
  }
  double total = 0.0;
  for (double p : power) total += p;
  scene.light_power = total;
  double cumulative = 0.0;
  for (std::size_t i = 0; i < scene.lights.size(); i++) {
    // Lights of zero luminance (pure blue, say) still get a small share, so none is missed.
    double p = total > 0.0 ? power[i] / total : 1.0 / double(power.size());
    p = std::max(p, 1e-6);
    cumulative += p;
    scene.lights[i].pick = glm::vec4(float(p), float(cumulative), 0.0f, 0.0f);
  }
  // Normalise so that the last cumulative value is exactly 1.
  for (Light& l : scene.lights) l.pick.x /= float(cumulative), l.pick.y /= float(cumulative);
  if (!scene.lights.empty()) scene.lights.back().pick.y = 1.0f;
}

float sky_pick_probability(const Scene& scene, glm::vec3 sky) {
  float sky_lum = luminance(sky);
  if (!(sky_lum > 0.0f)) return 0.0f;
  if (scene.lights.empty()) return 1.0f;
  double lights = scene.light_power;
  // The sky's power into the scene: radiance times pi times the bounding sphere's disk.
  Bounds b = scene.bounds();
  double r = b.empty() ? 1.0 : 0.5 * glm::length(b.hi - b.lo);
  double sky_power = M_PI * sky_lum * M_PI * r * r;
  return float(std::clamp(sky_power / (sky_power + lights), 0.05, 0.95));
}

uint scene_feature_mask(const Scene& scene, glm::vec3 sky) {
  uint mask = 0u;
  if (!scene.triangles.empty()) mask |= kFeatureTriangles;
  if (!scene.spheres.empty()) mask |= kFeatureSpheres;
  auto add_material = [&](const Material& m) {
    switch (m.kind.x) {
      case kMaterialDiffuse: mask |= kFeatureDiffuse; break;
      case kMaterialMirror: mask |= kFeatureMirror; break;
      case kMaterialConductor:  // below kGgxMirrorAlpha the kernels scatter it as a mirror
        mask |= kFeatureConductor | (m.params.y < kGgxMirrorAlpha ? kFeatureMirror : 0u);
        break;
      case kMaterialGlass: mask |= kFeatureGlass; break;
      default:  // mixed: the diffuse lobe, and the conductor's (a mirror when alpha is 0)
        mask |= kFeatureMixed | kFeatureDiffuse | (m.params.y >= kGgxMirrorAlpha ? kFeatureConductor : kFeatureMirror);
    }
  };
  for (const Triangle& t : scene.triangles) add_material(scene.materials[t.info.x]);
  for (const Sphere& s : scene.spheres) add_material(scene.materials[s.info.x]);
  for (const Light& l : scene.lights) {
    if (l.info.x == kLightTriangle) mask |= kFeatureTriangleLights;
    if (l.info.x == kLightSphere) mask |= kFeatureSphereLights;
  }
  if (!scene.point_lights.empty()) mask |= kFeaturePointLights;
  if (sky.x > 0.0f || sky.y > 0.0f || sky.z > 0.0f) mask |= kFeatureSky;
  return mask;
}

std::string feature_names(uint mask) {
  struct Name {
    uint bit;
    const char* name;
  };
  const Name groups[3][5] = {
      {{kFeatureTriangles, "triangles"}, {kFeatureSpheres, "spheres"}},
      {{kFeatureDiffuse, "diffuse"}, {kFeatureMirror, "mirror"}, {kFeatureConductor, "GGX conductor"},
       {kFeatureGlass, "glass"}, {kFeatureMixed, "mixed"}},
      {{kFeatureTriangleLights, "emissive triangles"}, {kFeatureSphereLights, "emissive spheres"},
       {kFeaturePointLights, "point lights"}, {kFeatureSky, "sky"}}};
  std::string s;
  for (int g = 0; g < 3; g++) {
    std::string part;
    for (const Name& n : groups[g]) {
      if (n.name && (mask & n.bit)) part += (part.empty() ? "" : ", ") + std::string(n.name);
    }
    s += (g ? "; " : "") + (part.empty() ? std::string("none") : part);
  }
  return s;
}

std::string scene_features(const Scene& scene, glm::vec3 sky) {
  return feature_names(scene_feature_mask(scene, sky));
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
