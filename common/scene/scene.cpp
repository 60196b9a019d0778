// Scene helpers: material rules of the contract (README.md), bounds, and the kernel camera.
#include "common/scene/scene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "common/base/error.h"
#include "common/base/srgb.h"

namespace pt {

Bounds Scene::bounds() const {
  if (region) return *region;
  Bounds b;
  for (const Triangle& t : triangles) {
    b.extend(t.p0), b.extend(t.p1), b.extend(t.p2);
  }
  for (const Sphere& s : spheres) {
    b.extend(s.center - s.radius), b.extend(s.center + s.radius);
  }
  return b;
}

uint Scene::add_material(const Material& m) {
  materials.push_back(m);
  if (!material_textures.empty()) material_textures.push_back(no_material_textures());
  return uint(materials.size() - 1);
}

void Scene::add_triangle(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, uint material) {
  triangles.push_back(Triangle{p0, material, p1, kNoLight, p2, 0u});
  if (!triangle_attributes.empty()) triangle_attributes.push_back(no_triangle_attributes());
}

void Scene::add_sphere(glm::vec3 center, float radius, uint material) {
  spheres.push_back(Sphere{center, radius, material, kNoLight, 0u, 0u});
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
void add_icosphere(Scene& s, glm::vec3 center, float radius, int n, uint material, bool inward) {
  const float g = 1.6180340f;  // the golden ratio: the icosahedron's corners (0, +-1, +-g) cycled
  const glm::vec3 v[12] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  s.triangles.reserve(s.triangles.size() + 20 * std::size_t(n) * std::size_t(n));
  for (const auto& f : faces) {
    glm::vec3 a = v[f[0]], b = v[f[1]], c = v[f[2]];
    if ((glm::dot(glm::cross(b - a, c - a), a + b + c) < 0.0f) != inward) std::swap(b, c);
    // The grid point (i, j) of the face, i + j <= n. On an edge one weight is 0, and adding
    // 0 is exact, so the two faces of the edge compute its points to the same floats.
    auto point = [&](int i, int j) {
      glm::vec3 p = a * (float(n - i - j) / float(n)) + b * (float(i) / float(n)) + c * (float(j) / float(n));
      return center + radius * glm::normalize(p);
    };
    for (int j = 0; j < n; j++) {
      for (int i = 0; i + j < n; i++) {
        s.add_triangle(point(i, j), point(i + 1, j), point(i, j + 1), material);
        if (i + j + 1 < n) s.add_triangle(point(i + 1, j), point(i + 1, j + 1), point(i, j + 1), material);
      }
    }
  }
}

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
  m.base_color = color;
  m.metallic = 0.0f, m.alpha = 1.0f, m.transmission = 0.0f, m.ior = 1.5f;
  m.kind = kind;
  return m;
}
}  // namespace

Material make_diffuse(glm::vec3 albedo, glm::vec3 emission, bool double_sided) {
  Material m = base_material(albedo, kMaterialDiffuse);
  m.emission = emission;
  m.double_sided = double_sided ? 1u : 0u;
  return m;
}

PointLight make_point_light(glm::vec3 position, glm::vec3 intensity) {
  return PointLight{position, kPunctualPoint, intensity, 0.0f, glm::vec3(0.0f), 0.0f};
}

PointLight make_spot_light(glm::vec3 position, glm::vec3 direction, glm::vec3 intensity, float inner, float outer) {
  return PointLight{position, kPunctualSpot, intensity, std::cos(outer), glm::normalize(direction), std::cos(inner)};
}

PointLight make_directional_light(glm::vec3 direction, glm::vec3 irradiance) {
  return PointLight{glm::vec3(0.0f), kPunctualDirectional, irradiance, 0.0f, glm::normalize(direction), 0.0f};
}

Material make_metal(glm::vec3 f0, float roughness) {
  Material m = base_material(f0, roughness > 0.0f ? kMaterialConductor : kMaterialMirror);
  m.metallic = 1.0f, m.alpha = roughness * roughness, m.transmission = 0.0f, m.ior = 1.5f;
  return m;
}

Material make_glass(glm::vec3 tint, float ior) {
  Material m = base_material(tint, kMaterialGlass);
  m.metallic = 0.0f, m.alpha = 0.0f, m.transmission = 1.0f, m.ior = ior;
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
    m.metallic = metallic, m.alpha = roughness * roughness, m.transmission = 0.0f, m.ior = ior;
  }
  m.transmission = transmission;
  m.emission = emission;
  m.double_sided = double_sided ? 1u : 0u;
  return m;
}

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// The mean linear RGB of a texture whose texels are sRGB: the emissive texture's share of a
// light's power (what the texture averages to where its uv cover it evenly).
glm::dvec3 srgb_texture_mean(const Scene& scene, uint index) {
  const Texture& t = scene.textures[index];
  double lut[256];
  for (int i = 0; i < 256; i++) lut[i] = srgb_to_linear(i / 255.0);
  glm::dvec3 sum(0.0);
  const std::size_t n = std::size_t(t.width) * t.height;
  for (std::size_t i = 0; i < n; i++) {
    uint v = scene.texels[t.offset + i];
    sum += glm::dvec3(lut[v & 255u], lut[v >> 8 & 255u], lut[v >> 16 & 255u]);
  }
  return n ? sum / double(n) : glm::dvec3(0.0);
}

// The emission a triangle light's power counts: the material's, times the mean of its
// emissive texture (texture.glsl multiplies the two at every point).
glm::vec3 mean_emission(const Scene& scene, uint material, std::vector<std::optional<glm::dvec3>>& means) {
  glm::vec3 e = scene.materials[material].emission;
  if (!uses_textures(scene)) return e;
  uint tex = scene.material_textures[material].emissive;
  if (tex == kNoTexture) return e;
  if (means.size() < scene.textures.size()) means.resize(scene.textures.size());
  if (!means[tex]) means[tex] = srgb_texture_mean(scene, tex);
  return glm::vec3(glm::dvec3(e) * *means[tex]);
}
// A punctual light's power, by which the light table picks it (any positive number would
// be unbiased; the closer to the light's share of the light, the less noise). A point
// light sends I into 4 pi sr; a spot light into its cone, up to halfway along the falloff
// (the cone of angle between the inner and outer, 2 pi (1 - cos)); a directional light
// lights the scene's cross-section, pi r^2 for the radius r of its bounding sphere.
double punctual_power(const Scene& scene, const PointLight& l) {
  double i = luminance(l.intensity);
  if (l.kind == kPunctualSpot) return 2.0 * M_PI * (1.0 - 0.5 * (double(l.cos_inner) + double(l.cos_outer))) * i;
  if (l.kind == kPunctualDirectional) {
    Bounds b = scene.bounds();
    double r = b.empty() ? 1.0 : 0.5 * double(glm::length(b.hi - b.lo));
    return M_PI * r * r * i;
  }
  return 4.0 * M_PI * i;
}
}  // namespace

void build_light_table(Scene& scene) {
  scene.lights.clear();
  std::vector<double> power;
  std::vector<std::optional<glm::dvec3>> texture_means;  // of the emissive textures met
  for (std::size_t i = 0; i < scene.triangles.size(); i++) {
    Triangle& t = scene.triangles[i];
    const Material& m = scene.materials[t.material];
    if (!is_emissive(m)) continue;
    double area = 0.5 * glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
    double sides = m.double_sided != 0u ? 2.0 : 1.0;
    t.light = uint(scene.lights.size());
    scene.lights.push_back(Light{kLightTriangle, uint(i), 0.0f, 0.0f});
    power.push_back(M_PI * area * sides * luminance(mean_emission(scene, t.material, texture_means)));
  }
  for (std::size_t i = 0; i < scene.spheres.size(); i++) {
    Sphere& s = scene.spheres[i];
    const Material& m = scene.materials[s.material];
    if (!is_emissive(m)) continue;
    double r = s.radius;
    s.light = uint(scene.lights.size());
    scene.lights.push_back(Light{kLightSphere, uint(i), 0.0f, 0.0f});
    power.push_back(M_PI * 4.0 * M_PI * r * r * luminance(m.emission));
  }
  for (std::size_t i = 0; i < scene.point_lights.size(); i++) {
    scene.lights.push_back(Light{kLightPoint, uint(i), 0.0f, 0.0f});
    power.push_back(punctual_power(scene, scene.point_lights[i]));
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
    scene.lights[i].pick = float(p), scene.lights[i].cumulative = float(cumulative);
  }
  // Normalise so that the last cumulative value is exactly 1.
  for (Light& l : scene.lights) l.pick /= float(cumulative), l.cumulative /= float(cumulative);
  if (!scene.lights.empty()) scene.lights.back().cumulative = 1.0f;
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
  std::vector<char> tex_seen;  // the textured materials already counted
  if (!scene.triangles.empty()) mask |= kFeatureTriangles;
  if (!scene.spheres.empty()) mask |= kFeatureSpheres;
  auto add_material = [&](const Material& m) {
    switch (m.kind) {
      case kMaterialDiffuse: mask |= kFeatureDiffuse; break;
      case kMaterialMirror: mask |= kFeatureMirror; break;
      case kMaterialConductor:  // below kGgxMirrorAlpha the kernels scatter it as a mirror
        mask |= kFeatureConductor | (m.alpha < kGgxMirrorAlpha ? kFeatureMirror : 0u);
        break;
      case kMaterialGlass: mask |= kFeatureGlass; break;
      default:  // mixed: the diffuse lobe, and the conductor's (a mirror when alpha is 0)
        mask |= kFeatureMixed | kFeatureDiffuse | (m.alpha >= kGgxMirrorAlpha ? kFeatureConductor : kFeatureMirror);
    }
  };
  // A metallic-roughness texture makes metallic and roughness vary over the surface
  // (texture.glsl: surface_material): every kind the range of its texels reaches counts.
  auto add_textured = [&](uint index) {
    const Material& m = scene.materials[index];
    uint tex = uses_textures(scene) ? scene.material_textures[index].metallic_roughness : kNoTexture;
    if (tex == kNoTexture || m.kind == kMaterialGlass) return add_material(m);
    if (tex_seen.size() < scene.materials.size()) tex_seen.resize(scene.materials.size(), 0);
    if (tex_seen[index]) return;
    tex_seen[index] = 1;
    const MaterialTextures& mt = scene.material_textures[index];
    const Texture& t = scene.textures[tex];
    auto channel = [](uint packed, int c) { return float(packed >> (8 * c) & 255u) / 255.0f; };
    float m_lo = mt.metallic_factor * channel(t.texel_min, 2), m_hi = mt.metallic_factor * channel(t.texel_max, 2);
    float r_lo = mt.roughness_factor * channel(t.texel_min, 1), r_hi = mt.roughness_factor * channel(t.texel_max, 1);
    // Between the extremes every value is reached (bilinear filtering): one in between too.
    float m_mid = 0.5f * (std::max(m_lo, 0.0f) + std::min(m_hi, 1.0f));
    for (float metallic : {m_lo, m_mid, m_hi}) {
      for (float roughness : {r_lo, r_hi}) {
        add_material(make_gltf_material(m.base_color, metallic, roughness, 0.0f, m.ior, m.emission, false));
      }
    }
  };
  for (const Triangle& t : scene.triangles) add_textured(t.material);
  for (const Sphere& s : scene.spheres) add_material(scene.materials[s.material]);
  if (uses_textures(scene)) mask |= kFeatureTextures;
  if (uses_alpha_mask(scene)) mask |= kFeatureAlphaMask;
  for (const Light& l : scene.lights) {
    if (l.kind == kLightTriangle) mask |= kFeatureTriangleLights;
    if (l.kind == kLightSphere) mask |= kFeatureSphereLights;
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
  const Name groups[3][7] = {
      {{kFeatureTriangles, "triangles"}, {kFeatureSpheres, "spheres"}},
      {{kFeatureDiffuse, "diffuse"}, {kFeatureMirror, "mirror"}, {kFeatureConductor, "GGX conductor"},
       {kFeatureGlass, "glass"}, {kFeatureMixed, "mixed"}, {kFeatureTextures, "textures"},
       {kFeatureAlphaMask, "alpha masks"}},
      {{kFeatureTriangleLights, "emissive triangles"}, {kFeatureSphereLights, "emissive spheres"},
       {kFeaturePointLights, "punctual lights"}, {kFeatureSky, "sky"}}};
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

bool uses_textures(const Scene& scene) {
  return !scene.material_textures.empty() && !scene.triangle_attributes.empty();
}

void mark_alpha_masked(Scene& scene) {
  const bool textured = uses_textures(scene);
  for (Triangle& t : scene.triangles) {
    bool masked = textured && scene.material_textures[t.material].alpha_cutoff > 0.0f;
    t.flags = masked ? t.flags | kTriangleMasked : t.flags & ~kTriangleMasked;
  }
}

bool uses_alpha_mask(const Scene& scene) {
  if (!uses_textures(scene)) return false;
  for (const Triangle& t : scene.triangles) {
    if (t.flags & kTriangleMasked) return true;
  }
  return false;
}

MaterialTextures no_material_textures() {
  const glm::vec3 s(1.0f, 0.0f, 0.0f), t(0.0f, 1.0f, 0.0f);  // the identity transform
  return MaterialTextures{s, kNoTexture, t, 1.0f, s, kNoTexture, t, 1.0f, s, kNoTexture, t, 1u, 1.0f, 0.0f, 0u, 0u};
}

std::vector<MaterialTextures> neutral_material_textures(std::size_t materials) {
  MaterialTextures none = no_material_textures();
  none.enabled = 0u;
  return std::vector<MaterialTextures>(std::max<std::size_t>(materials, 1), none);
}

TriangleAttributes no_triangle_attributes() {
  const glm::vec2 uv(0.0f);
  const glm::vec4 white(1.0f);
  return TriangleAttributes{uv, uv, uv, uv, white, white, white};
}

glm::vec4 texel_value(const Scene& scene, const Texture& t, uint x, uint y) {
  uint v = scene.texels[t.offset + std::size_t(y) * t.width + x];
  return glm::vec4(float(v & 255u), float(v >> 8 & 255u), float(v >> 16 & 255u), float(v >> 24)) / 255.0f;
}

CameraDesc frame_bounds(const Bounds& bounds, float aspect) {
  CameraDesc desc;  // perspective, the default yfov
  Bounds b = bounds;
  if (b.empty()) b.lo = glm::vec3(-1.0f), b.hi = glm::vec3(1.0f);
  const double azimuth = M_PI / 4.0, elevation = M_PI / 6.0;
  // The camera's frame: it looks along -back, towards the centre, with image up near +Y.
  const glm::dvec3 back(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                        std::cos(azimuth) * std::cos(elevation));
  const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), back));
  const glm::dvec3 up = glm::cross(back, right);
  const glm::dvec3 center = 0.5 * (glm::dvec3(b.lo) + glm::dvec3(b.hi));
  // A corner at (x, y) across and z towards the camera from the centre, seen from distance
  // D along `back`, is in the picture when |x| <= tx (D - z) and |y| <= ty (D - z).
  const double ty = std::tan(0.5 * double(desc.yfov)), tx = ty * double(aspect);
  const double margin = 1.05;
  double distance = 0.0, depth = 0.0;
  for (int corner = 0; corner < 8; corner++) {
    glm::dvec3 p((corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y, (corner & 4) ? b.hi.z : b.lo.z);
    glm::dvec3 o = p - center;
    double z = glm::dot(o, back);
    distance = std::max({distance, margin * std::abs(glm::dot(o, right)) / tx + z,
                         margin * std::abs(glm::dot(o, up)) / ty + z});
    depth = std::max(depth, z);
  }
  // The nearest corner stays in front of the camera (a flat scene seen edge-on has none).
  distance = std::max({distance, depth * 1.01, 1e-6 * std::max(1.0, glm::length(center))});
  glm::dmat4 to_world(1.0);
  to_world[0] = glm::dvec4(right, 0.0), to_world[1] = glm::dvec4(up, 0.0), to_world[2] = glm::dvec4(back, 0.0);
  to_world[3] = glm::dvec4(center + distance * back, 1.0);
  desc.to_world = glm::mat4(to_world);
  return desc;
}

void select_camera(Scene& scene, const std::string& request) {
  std::string there;  // the cameras there are, for the message
  for (const SceneCamera& c : scene.cameras) {
    bool by_index = !request.empty() && request.find_first_not_of("0123456789") == std::string::npos &&
                    request.size() < 10 && std::stoi(request) == c.index;
    if (by_index || (!c.name.empty() && c.name == request) || c.node == request) {
      scene.camera = c.desc;
      return;
    }
    there += (there.empty() ? "" : ", ") + std::to_string(c.index) + (c.name.empty() ? "" : " '" + c.name + "'") +
             " (node '" + c.node + "')";
  }
  if (scene.cameras.empty()) {
    throw Error(kExitBadOption, "--camera " + request + ": " + scene.name +
                                    " has no cameras of its own to choose from; leave --camera out");
  }
  throw Error(kExitBadOption, "--camera " + request + ": " + scene.name + " has no such camera; its cameras: " +
                                  there + " (give the index or a name)");
}

Camera make_camera(const Scene& scene, float aspect) {
  CameraDesc desc = scene.camera ? *scene.camera : frame_bounds(scene.bounds(), aspect);
  glm::vec3 origin(desc.to_world[3]);
  glm::vec3 forward = glm::normalize(-glm::vec3(desc.to_world[2]));
  glm::vec3 up0 = glm::vec3(desc.to_world[1]);
  glm::vec3 right = glm::normalize(glm::cross(forward, up0));
  glm::vec3 up = glm::cross(right, forward);

  Camera c{};
  c.origin = origin;
  c.forward = forward;
  c.right = right;
  c.up = up;
  if (desc.kind == kCameraOrthographic) {
    c.extent_x = desc.xmag, c.extent_y = desc.ymag;
  } else {
    float t = std::tan(0.5f * desc.yfov);
    c.extent_x = t * aspect, c.extent_y = t;
  }
  c.kind = desc.kind;
  return c;
}

}  // namespace pt
