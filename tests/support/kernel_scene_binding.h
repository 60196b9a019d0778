// For tests that call kernel functions on the CPU directly (light sampling, spherical
// triangles): bind a scene's arrays and the light-sampling parameters to the kernel's
// globals (cpu/kernel_bindings.h), as the CPU backend does for a render. Include it inside
// the test's own kernel namespace, after the kernel code; no include guard, since each test
// file's namespace gets its own copy.
inline void bind_scene(const ::pt::Scene& s, glm::vec3 sky = glm::vec3(0.0f)) {
  // Textures (common/kernel/texture.glsl): the scene's, or neutral material entries.
  static thread_local std::vector<::pt::MaterialTextures> neutral;
  neutral = ::pt::neutral_material_textures(s.materials.size());
  const bool textured = ::pt::uses_textures(s);
  triangle_attributes = textured ? s.triangle_attributes.data() : nullptr;
  material_textures = textured ? s.material_textures.data() : neutral.data();
  textures = textured ? s.textures.data() : nullptr;
  texels = textured ? s.texels.data() : nullptr;
  triangle_shading = ::pt::uses_shading_normals(s) ? s.triangle_shading.data() : nullptr;
  env_texels = s.environment ? s.environment->radiance.data() : nullptr;
  env_tables = s.environment ? s.environment->table.data() : nullptr;
  params.env_width = s.environment ? s.environment->width : 0u;
  params.env_height = s.environment ? s.environment->height : 0u;
  const glm::vec2 turn = s.environment ? ::pt::environment_turn(*s.environment) : glm::vec2(1.0f, 0.0f);
  params.env_cos = turn.x, params.env_sin = turn.y;
  triangles = s.triangles.data();
  spheres = s.spheres.data();
  materials = s.materials.data();
  point_lights = s.point_lights.data();
  lights = s.lights.data();
  light_alias = s.light_alias.data();
  light_runs = s.light_runs.data();
  light_run_count = uint(s.light_runs.size());
  triangle_light_count = s.triangle_light_count;
  params.triangle_count = uint(s.triangles.size());
  params.sphere_count = uint(s.spheres.size());
  params.material_count = uint(s.materials.size());
  params.point_light_count = uint(s.point_lights.size());
  params.light_count = uint(s.lights.size());
  params.sky = sky;
  params.sky_pick = ::pt::sky_pick_probability(s, sky);
}
