// The CPU entry point of a stage's kernel: binds the host arrays (a KernelScene,
// kernel_scene.h) to the kernel globals of kernel_bindings.h and runs render_pixel() over
// rows. Included INSIDE the kernel's namespace by kernel_end.h, after the integrator, so
// each stage gets its own.

// Binds the scene and the parameters of the next pass (called on one thread).
inline void cpu_bind(const pt::KernelScene& scene, const pt::FrameParams& pass) {
  triangles = scene.triangles;
  spheres = scene.spheres;
  materials = scene.materials;
  point_lights = scene.point_lights;
  counters = scene.counters;
  lights = scene.lights;
  light_alias = scene.light_alias;
  light_runs = scene.light_runs;
  light_run_count = scene.light_run_count;
  triangle_light_count = scene.triangle_light_count;
  triangle_soa = scene.triangle_soa;
  triangle_soa_stride = scene.triangle_soa_stride;
  sphere_soa = scene.sphere_soa;
  sphere_soa_stride = scene.sphere_soa_stride;
  sphere_soa_count = scene.sphere_soa_count;
  bvh_nodes = scene.bvh_nodes;
  bvh_indices = scene.bvh_indices;
  wide_bvh = scene.bvh_nodes != nullptr ? scene.wide_bvh : nullptr;  // the same tree, wide (wide_bvh.h)
  triangle_attributes = scene.triangle_attributes;
  material_textures = scene.material_textures;
  textures = scene.textures;
  texels = scene.texels;
  triangle_shading = scene.triangle_shading;
  env_texels = scene.environment_radiance;
  env_tables = scene.environment_tables;
  params = pass;
#ifdef PT_CPU_RUNTIME_FEATURES
  kSceneFeatures = scene.features;  // kernel_bindings.h
#endif
}

// Renders rows [y0, y1) of the pass into out[y * width + x] (called on many threads).
inline void cpu_render_rows(uint y0, uint y1, glm::vec4* out) {
  for (uint y = y0; y < y1; y++) {
    for (uint x = 0u; x < params.width; x++) out[y * params.width + x] = render_pixel(x, y);
  }
}

pt::CpuKernel cpu_kernel() {
  return pt::CpuKernel{&cpu_bind, &cpu_render_rows};
}
