// The scene on the host: flat arrays of triangles, spheres, materials and point lights,
// plus the camera as the file describes it (docs/README.md, "Scene and kernels").
// Loaded from glTF (gltf_loader.cpp) or built in (builtin_scenes.cpp).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/base/huge_pages.h"
#include "common/kernel/scene_types.h"
#include "common/scene/environment.h"

namespace pt {

// A camera as glTF gives it; the image aspect is only known at render time.
struct CameraDesc {
  uint kind = kCameraPerspective;  // kCameraPerspective or kCameraOrthographic
  glm::mat4 to_world{1.0f};        // the camera node's world transform (looks down -Z)
  float yfov = 0.6911f;            // perspective: vertical field of view, radians
  float xmag = 1.0f, ymag = 1.0f;  // orthographic: half-extents of the view
  float aspect_ratio = 0.0f;       // perspective: the file's aspectRatio (width / height), 0 when not given
  float clip_start = 0.0f;         // nothing nearer than this along the view axis is seen (builtin
                                   // scenes only: glTF's znear is not read)
};

// One of a glTF file's cameras as the default scene places it (--camera N|NAME picks one).
struct SceneCamera {
  CameraDesc desc;
  int index = -1;    // the file's cameras[] index
  std::string name;  // the camera's name ("" when it has none)
  std::string node;  // the name of the node that places it, else "nodes[i]"
};

struct Bounds {
  glm::vec3 lo{1e30f}, hi{-1e30f};
  void extend(glm::vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  bool empty() const { return lo.x > hi.x; }
};

struct Scene {
  std::string name;                      // file path or builtin:NAME
  HugeVector<Triangle> triangles;        // world space (on huge pages: common/base/huge_pages.h)
  std::vector<Sphere> spheres;           // world space
  std::vector<Material> materials;       // indexed by Triangle/Sphere .material
  std::vector<PointLight> point_lights;  // KHR_lights_punctual point lights
  HugeVector<Light> lights;              // the light table: build_light_table()
  // Its alias table (lights.glsl pick_light_entry), one cell per light (scene_types.h LightAlias).
  HugeVector<LightAlias> light_alias;
  // The triangle lights (the table's first entries) as runs of consecutive triangles, at most
  // kMaxLightRuns of them, else none (scene_types.h LightRun; build_light_runs).
  std::vector<LightRun> light_runs;
  uint triangle_light_count = 0;  // the entries the runs cover
  double light_power = 0.0;              // the table's total power (luminance), same place
  std::optional<CameraDesc> camera;      // none: frame the bounds (make_camera)
  std::vector<SceneCamera> cameras;      // a glTF file's cameras in the order met; camera is
                                         // the first until select_camera picks another
  int degenerate_triangles = 0;          // skipped at load (zero area or not finite)
  std::optional<Bounds> region;          // where the scene's content is, when its shapes'
                                         // bounds overstate it (smallpt's walls are spheres
                                         // of radius 1e5): bounds() returns it, so the
                                         // spawn offset and framing use the room's size
  // Textures and vertex colours (common/kernel/texture.glsl): both arrays empty, or
  // material_textures parallel to materials and triangle_attributes to triangles
  // (uses_textures(); add_material and add_triangle keep them parallel).
  std::vector<MaterialTextures> material_textures;
  std::vector<TriangleAttributes> triangle_attributes;
  std::vector<Texture> textures;  // the texture table
  std::vector<uint> texels;       // every texture's texels, 8-bit RGBA packed in a uint
  // Shading normals (common/kernel/shading_normal.glsl): empty, or parallel to triangles
  // (add_triangle keeps it so); read only for triangles flagged kTriangleShadingNormals.
  std::vector<TriangleShading> triangle_shading;
  // The environment map (--env; common/scene/environment.h), or none: then the sky is
  // --sky's uniform colour. Set after loading (load_stage_scene); shared, never changed.
  std::shared_ptr<const Environment> environment;

  Bounds bounds() const;  // `region` when set, else the shapes' bounds
  // Appends a material and returns its index.
  uint add_material(const Material& m);
  void add_triangle(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, uint material);
  void add_sphere(glm::vec3 center, float radius, uint material);
};

// Shape builders for built-in scenes: a quad p0 p1 p2 p3 (counter-clockwise seen from its
// front) as two triangles; a box turned by `angle` about +Y, faces outwards; the inside
// of the cube [-h, h]^3 with each face turned inwards (front < 0: no front wall).
void add_quad(Scene& s, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, uint material);
void add_box(Scene& s, glm::vec3 center, glm::vec3 half, float angle, uint material);
void add_room(Scene& s, float h, uint floor, uint ceiling, uint back, uint left, uint right, int front);
// A sphere tessellated as an icosahedron whose 20 faces are each cut into n x n triangles
// (20 n^2 in all) with their corners pushed out to the sphere; faces outwards, or inwards
// when `inward`. Watertight: a vertex on an edge two faces share is the same float triple
// in both, so a ray cannot slip between them.
void add_icosphere(Scene& s, glm::vec3 center, float radius, int n, uint material, bool inward = false);

// Orthographic cameras of half-extent `half`: looking straight down (-y, image up = -z)
// from `position`, or looking down -z from (0, 0, z).
CameraDesc orthographic_down(glm::vec3 position, float half);
CameraDesc orthographic_front(float z, float half);

// Material constructors following the contract (README.md)'s rules.
Material make_diffuse(glm::vec3 albedo, glm::vec3 emission = glm::vec3(0.0f), bool double_sided = false);
Material make_metal(glm::vec3 f0, float roughness);  // roughness 0: mirror, else GGX alpha = r^2
Material make_glass(glm::vec3 tint, float ior);
// Rough glass (kMaterialRoughGlass, rough_dielectric.glsl): alpha = roughness^2, at least
// kGgxMirrorAlpha. make_gltf_material makes it for transmission with roughness > 0.
Material make_rough_glass(glm::vec3 tint, float ior, float roughness);
// The full glTF metallic-roughness rule (transmission wins, then metallic 0 / 1 / between).
// Built-in scenes' simple materials: metallic 0 is Lambert (no specular layer).
Material make_gltf_material(glm::vec3 base, float metallic, float roughness, float transmission,
                            float ior, glm::vec3 emission, bool double_sided);

// A glTF file's material, as the specification's Appendix B defines it (docs/gltf_material.md).
struct GltfPbr {
  glm::vec3 base{1.0f};                      // baseColorFactor (rgb)
  float metallic = 1.0f;                     // metallicFactor
  float roughness = 1.0f;                    // roughnessFactor
  float transmission = 0.0f;                 // KHR_materials_transmission's factor
  float ior = 1.5f;                          // KHR_materials_ior
  float specular = 1.0f;                     // KHR_materials_specular's specularFactor
  glm::vec3 specular_color{1.0f};            // its specularColorFactor
  glm::vec3 emission{0.0f};                  // emissiveFactor x emissive strength
  bool double_sided = false;                 // doubleSided
  bool textured_metallic_roughness = false;  // a metallic-roughness texture varies the two
  bool textured_transmission = false;        // a transmissionTexture scales the transmission
};
// Transmission 1 wins (glass, as make_gltf_material), unless a transmissionTexture varies
// it on a material that is not a pure metal (then it is kMaterialDielectric). A pure metal (metallic 1, not
// varied by a texture) is make_metal's conductor, whatever a transmission below 1; a
// material without a specular layer (specular 0) and without transmission
// make_gltf_material's; every other one is kMaterialDielectric, whose `transmission`
// between 0 and 1 adds glass (docs/gltf_material.md, "Partial transmission"): the metal
// with probability metallic, else a GGX layer of F0 = min(((ior - 1) / (ior + 1))^2 x
// specular_color, 1) and weight `specular` over a Lambert base.
Material make_gltf_pbr_material(const GltfPbr& p);

// KHR_lights_punctual lights (common/kernel/scene_types.h PointLight): intensity in W/sr,
// a spot's cone angles in radians (0 <= inner <= outer <= pi/2; inner == outer: a hard-edged cone), a directional light's
// irradiance in W/m^2; `direction` is where the light travels, made unit here.
PointLight make_point_light(glm::vec3 position, glm::vec3 intensity);
PointLight make_spot_light(glm::vec3 position, glm::vec3 direction, glm::vec3 intensity, float inner, float outer);
PointLight make_directional_light(glm::vec3 direction, glm::vec3 irradiance);

// The kernel camera for an image of the given aspect (width / height). With no camera in
// the scene, frame_bounds places one.
Camera make_camera(const Scene& scene, float aspect);

// The camera a model viewer would place: a perspective camera with the default field of
// view, raised above the bounds' centre and turned 45 degrees about +Y (a three-quarter
// view from +X+Z, looking down at 30 degrees, image up +Y), as close as it can be with
// every corner of the bounds inside the image of the given aspect (with a 5% margin).
CameraDesc frame_bounds(const Bounds& bounds, float aspect);

// --camera N|NAME: makes the file's camera with index N (cameras[N]), or the one whose own
// name or node name is NAME, the scene's camera. Throws pt::Error(2) naming the cameras
// there are when none matches.
void select_camera(Scene& scene, const std::string& request);

// Fills scene.lights with every emissive triangle and sphere and every point light, each
// with the probability of being picked in proportion to its power (stage4), and sets
// the primitives' light indices. load_scene() calls it.
void build_light_table(Scene& scene);
// Fills scene.light_alias from scene.lights' pick probabilities (build_light_table calls
// it): cell k picks light k or its alias with probabilities that add up, over the cells, to
// each light's pick.
void build_light_alias(Scene& scene);
// Fills scene.light_runs and triangle_light_count from scene.lights (build_light_table
// calls it).
void build_light_runs(Scene& scene);
// The most runs of consecutive emitting triangles that the CPU's hint searches (a few
// cache lines); a scene with more gets none, and its light samples no hint.
constexpr std::size_t kMaxLightRuns = 64;

// The probability that light sampling picks the sky rather than the table: the sky's
// power through the scene's bounding sphere against the lights' power (0 without a sky,
// 1 without lights).
float sky_pick_probability(const Scene& scene, glm::vec3 sky);

// What the scene uses (issue: model only what a scene requires): shapes, material kinds,
// light kinds and the sky, e.g. "triangles; diffuse, glass; emissive triangles, sky".
uint scene_feature_mask(const Scene& scene, glm::vec3 sky);  // kFeature* bits
std::string feature_names(uint mask);  // "triangles; diffuse; emissive triangles"
std::string scene_features(const Scene& scene, glm::vec3 sky);  // both of the above

// Whether the material emits light (any emission component above zero).
bool is_emissive(const Material& m);

// Whether the scene has textures or vertex colours (kFeatureTextures): its
// material_textures and triangle_attributes are filled.
bool uses_textures(const Scene& scene);
// The textures of a material that has none: every slot kNoTexture, identity transforms.
MaterialTextures no_material_textures();
// Flags the triangles whose material has an alpha mask (alphaMode MASK: alpha_cutoff > 0)
// with kTriangleMasked, and clears the flag of the others: after the scene's materials and
// textures are set (the glTF loader and the built-in scenes call it). Whether a triangle
// is flagged (kFeatureAlphaMask).
void mark_alpha_masked(Scene& scene);
bool uses_alpha_mask(const Scene& scene);
// What a backend binds as material_textures[] for a scene without textures whose kernel
// has texture code (a CPU variant, --all-features): entries that read nothing (enabled 0).
std::vector<MaterialTextures> neutral_material_textures(std::size_t materials);
// The attributes of a triangle without TEXCOORD_0 or COLOR_0: uv (0, 0), colour 1.
TriangleAttributes no_triangle_attributes();
// The shading frame of a flat triangle: its face normal at every corner, a tangent
// orthogonal to it (handedness 1). Whether the scene has shading normals: some triangle is
// flagged kTriangleShadingNormals (kFeatureShadingNormals).
TriangleShading flat_shading(const Triangle& t);
bool uses_shading_normals(const Scene& scene);
// Texel (x, y) of texture t, each channel in [0, 1] (as stored: sRGB channels not decoded).
glm::vec4 texel_value(const Scene& scene, const Texture& t, uint x, uint y);

}  // namespace pt
