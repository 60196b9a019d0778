// pt_bench's speed section on the GPU (see speed_gpu.h): the two ray-casting kernels on
// one Vulkan device with gpu/'s buffers and pipelines, each a single dispatch over all the
// rays (64 rays per workgroup), recorded once and submitted again and again
// (gpu_ray_kernel.h). Article: the raycasting step (Eq. 2), its brute-force closest-hit
// search, as the GPU runs it.
#include "bench/speed_gpu.h"

#include <algorithm>
#include <thread>
#include <vector>

#include "bench/accel.h"  // kNoBound
#include "bench/gpu_ray_kernel.h"
#include "intersect_raycast_spirv.h"
#include "naive_raycast_spirv.h"

namespace pt::bench {

GpuRayRates gpu_rays_per_second(const Scene& scene, std::span<const glm::vec3> origins,
                                std::span<const glm::vec3> dirs, double seconds) {
  gpu::VulkanContext context("");
  const std::size_t count = origins.size();
  // The rays as three vec4 each (origin; direction and the search's bound, no bound here:
  // intersect.glsl's kInfinity; unused: a PointLight's 48 bytes), as both kernels read them.
  std::vector<glm::vec4> rays(3 * count, glm::vec4(0.0f));
  for (std::size_t i = 0; i < count; i++) {
    rays[3 * i] = glm::vec4(origins[i], 1.0f), rays[3 * i + 1] = glm::vec4(dirs[i], kNoBound);
  }
  auto storage = [&](const void* data, std::size_t bytes, VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
    gpu::Buffer b(context, std::max<std::size_t>(bytes, 64), usage);
    if (data) b.write(data, bytes);
    return b;
  };
  gpu::Buffer triangles = storage(scene.triangles.data(), scene.triangles.size() * sizeof(Triangle));
  gpu::Buffer ray_buffer = storage(rays.data(), rays.size() * sizeof(glm::vec4));
  gpu::Buffer naive_out = storage(nullptr, count * sizeof(float));
  gpu::Buffer renderer_out = storage(nullptr, count * sizeof(glm::vec4));
  // A placeholder for every binding the kernels do not read; binding 9 (the BVH's nodes) is a
  // uniform texel buffer, so it has a texel view too.
  gpu::Buffer unused = storage(nullptr, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
  gpu::Buffer unused_uniform(context, 64, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  // The triangles again as a uniform buffer if they fit, as gpu_backend.cpp binds them.
  gpu::UniformTriangles uniform = gpu::uniform_triangles(context, scene.triangles);
  // FrameParams for intersect_scene (triangle_count, and width: the ray count); the naive
  // kernel reads the same two counts from a uvec4 of its own.
  FrameParams params{};
  params.width = uint(count), params.height = 1u, params.first_sample = 0u, params.sample_count = 1u;
  params.triangle_count = uint(scene.triangles.size());
  gpu::Buffer renderer_params(context, sizeof(FrameParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  renderer_params.write(&params, sizeof params);
  glm::uvec4 counts(uint(scene.triangles.size()), uint(count), 0u, 0u);
  gpu::Buffer naive_params(context, 64, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  naive_params.write(&counts, sizeof counts);

  const uint32_t groups = uint32_t((count + kRaysPerGroup - 1) / kRaysPerGroup);
  const gpu::Buffer* naive_bindings[gpu::kBindingCount] = {
      &triangles, &unused, &unused, &ray_buffer, &naive_params, &naive_out, &unused, &unused, &unused_uniform, &unused, &unused,
      &unused,    &unused, &unused, &unused, &unused, &unused, &unused, &unused};  // 11-14: textures, 15: shading normals, 16-17: environment, 18: light alias table (none)
  const gpu::Buffer* renderer_bindings[gpu::kBindingCount] = {
      &triangles, &unused, &unused, &ray_buffer, &renderer_params, &renderer_out, &unused, &unused, &uniform.buffer, &unused, &unused,
      &unused,    &unused, &unused, &unused, &unused, &unused, &unused, &unused};
  // Specialised to the scene's features, as the renderer specialises its kernels.
  RayKernel naive(context, naive_raycast_spirv, 0u, naive_bindings, groups);
  RayKernel renderer(context, intersect_raycast_spirv, scene_feature_mask(scene, glm::vec3(0.0f)), renderer_bindings,
                     groups, uniform.constant);
  // Alternating, so that both see the same load from other jobs on the machine.
  while (naive.wall < seconds || renderer.wall < seconds) naive.run(), renderer.run();

  GpuRayRates r;
  r.device = context.device_name();
  unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  auto rate = [&](const RayKernel& k) {
    double rays_cast = double(count) * double(k.runs);
    return Rate{rays_cast / k.wall, rays_cast / k.cpu * cores};
  };
  r.naive = rate(naive), r.renderer = rate(renderer);
  // Both must find the same rays hitting the box (they differ only on edges and corners).
  std::vector<float> t(count);
  std::vector<glm::vec4> hits(count);
  naive_out.read(t.data(), count * sizeof(float));
  renderer_out.read(hits.data(), count * sizeof(glm::vec4));
  std::size_t mismatch = 0;
  for (std::size_t i = 0; i < count; i++) mismatch += (t[i] < 1e30f) != (hits[i].x < 1e30f);
  r.hit_mismatch = double(mismatch) / double(count);
  return r;
}

}  // namespace pt::bench
