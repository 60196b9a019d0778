// pt_bench's acceleration section on the GPU backend (accel.h): the renderer's nearest-hit
// search through the BVH (bounded for shadow rays) and its any-hit search, gpu/bvh_walk.glsl
// as gpu/triangle_search.glsl calls it,
// over a buffer of rays, one invocation per ray (intersect_raycast.comp with params.accel =
// kAccelBvh and the BVH at bindings 9 and 10, as gpu_backend.cpp binds it for a render).
// On this machine the device is lavapipe, which runs on the same CPU cores.
#include <algorithm>
#include <deque>
#include <optional>

#include "bench/accel.h"
#include "bench/gpu_ray_kernel.h"
#include "intersect_raycast_spirv.h"

namespace pt::bench {

struct GpuBvhTracer::Impl {
  gpu::VulkanContext context{""};
  // Per scene: the buffers, then the kernel that binds them (destroyed first).
  std::deque<gpu::Buffer> buffers;  // a deque: references stay valid as it grows
  std::optional<gpu::UniformTriangles> uniform;
  std::optional<RayKernel> kernel;
  std::size_t ray_count = 0;
  gpu::Buffer* output = nullptr;
};

GpuBvhTracer::GpuBvhTracer() : impl_(new Impl) {}

GpuBvhTracer::~GpuBvhTracer() {
  impl_->kernel.reset();
}

std::string GpuBvhTracer::device() const {
  return impl_->context.device_name();
}

void GpuBvhTracer::set_scene(const Scene& scene, const Bvh& bvh, const RaySet& rays) {
  Impl& m = *impl_;
  m.kernel.reset();
  m.buffers.clear();
  m.uniform.reset();
  const std::size_t count = rays.size();
  m.ray_count = count;
  auto storage = [&](const void* data, std::size_t bytes,
                     VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) -> gpu::Buffer& {
    m.buffers.emplace_back(m.context, std::max<std::size_t>(bytes, 64), usage);
    if (data && bytes) m.buffers.back().write(data, bytes);
    return m.buffers.back();
  };
  // The rays as vec4 triples (origin; direction and bound; the search: 1 any hit, 0 the
  // nearest) in binding 3, as the kernel reads them: a shadow ray's bound is its search's
  // t_max, the others' infinity.
  std::vector<glm::vec4> packed(3 * count, glm::vec4(0.0f));
  for (std::size_t i = 0; i < count; i++) {
    packed[3 * i] = glm::vec4(rays.origins[i], 1.0f), packed[3 * i + 1] = glm::vec4(rays.dirs[i], rays.bound(i));
    packed[3 * i + 2] = glm::vec4(0.0f, 0.0f, 0.0f, rays.any_hit ? 1.0f : 0.0f);
  }
  gpu::Buffer& triangles = storage(scene.triangles.data(), scene.triangles.size() * sizeof(Triangle));
  gpu::Buffer& ray_buffer = storage(packed.data(), packed.size() * sizeof(glm::vec4));
  gpu::Buffer& output = storage(nullptr, count * sizeof(glm::vec4));
  // The nodes as the kernel reads them: texels of a uniform texel buffer (binding 9).
  gpu::Buffer& nodes = storage(bvh.nodes.data(), bvh.nodes.size() * sizeof(BvhNode),
                               VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
  gpu::Buffer& indices = storage(bvh.indices.data(), bvh.indices.size() * sizeof(uint));
  gpu::Buffer& unused = storage(nullptr, 64);
  m.output = &output;
  // The triangles again as a uniform buffer when they fit, as gpu_backend.cpp binds them.
  m.uniform.emplace(gpu::uniform_triangles(m.context, scene.triangles));
  FrameParams params{};
  params.width = uint(count), params.height = 1u, params.first_sample = 0u, params.sample_count = 1u;
  params.triangle_count = uint(scene.triangles.size());
  params.accel = kAccelBvh;
  m.buffers.emplace_back(m.context, sizeof(FrameParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  gpu::Buffer& params_buffer = m.buffers.back();
  params_buffer.write(&params, sizeof params);
  const gpu::Buffer* bindings[gpu::kBindingCount] = {&triangles, &unused, &unused, &ray_buffer, &params_buffer,
                                                     &output,    &unused, &unused, &m.uniform->buffer, &nodes,
                                                     &indices,   &unused, &unused, &unused, &unused, &unused,
                                                     &unused,    &unused, &unused};  // 11-14: textures, 15: shading normals, 16-17: environment, 18: light alias table
  const uint32_t groups = uint32_t((count + kRaysPerGroup - 1) / kRaysPerGroup);
  // Specialised to the scene's features, as the renderer specialises its kernels.
  m.kernel.emplace(m.context, intersect_raycast_spirv, scene_feature_mask(scene, glm::vec3(0.0f)), bindings, groups,
                   m.uniform->constant);
}

void GpuBvhTracer::run() {
  impl_->kernel->run();
}

double GpuBvhTracer::wall() const {
  return impl_->kernel->wall;
}

double GpuBvhTracer::cpu() const {
  return impl_->kernel->cpu;
}

std::uint64_t GpuBvhTracer::runs() const {
  return impl_->kernel->runs;
}

std::vector<float> GpuBvhTracer::distances() const {
  std::vector<glm::vec4> hits(impl_->ray_count);
  impl_->output->read(hits.data(), hits.size() * sizeof(glm::vec4));
  std::vector<float> t(hits.size());
  // The kernel writes kInfinity (intersect.glsl: the largest float) for a miss.
  for (std::size_t i = 0; i < hits.size(); i++) t[i] = hits[i].x >= 3.4e38f ? kMiss : hits[i].x;
  return t;
}

}  // namespace pt::bench
