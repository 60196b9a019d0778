// pt_bench's speed section on the GPU (see speed_gpu.h): the two ray-casting kernels on
// one Vulkan device with gpu/'s buffers and pipelines, each a single dispatch over all the
// rays (64 rays per workgroup), recorded once and submitted again and again. Article: the
// raycasting step (Eq. 2), its brute-force closest-hit search, as the GPU runs it.
#include "bench/speed_gpu.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <thread>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/vulkan_context.h"
#include "intersect_raycast_spirv.h"
#include "naive_raycast_spirv.h"

namespace pt::bench {

namespace {

constexpr uint32_t kRaysPerGroup = 64;  // both kernels' local_size_x

// One kernel's pipeline and its recorded dispatch over every ray.
class RayKernel {
 public:
  RayKernel(const gpu::VulkanContext& context, std::span<const uint32_t> spirv, uint features,
            const gpu::Buffer* const (&buffers)[gpu::kBindingCount], uint32_t groups, uint32_t uniform_triangles = 0)
      : context_(context), pipeline_(context, spirv, features, uniform_triangles) {
    VkDevice dev = context.device();
    pipeline_.bind_buffers(buffers);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = context.command_pool();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    gpu::check(vkAllocateCommandBuffers(dev, &alloc, &cmd_), "allocating a command buffer");
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    gpu::check(vkCreateFence(dev, &fence_info, nullptr, &fence_), "creating a fence");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    gpu::check(vkBeginCommandBuffer(cmd_, &begin), "recording commands");
    pipeline_.record_dispatch(cmd_, groups, 1);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    gpu::check(vkEndCommandBuffer(cmd_), "recording commands");
  }
  ~RayKernel() {
    vkDeviceWaitIdle(context_.device());
    vkDestroyFence(context_.device(), fence_, nullptr);
    vkFreeCommandBuffers(context_.device(), context_.command_pool(), 1, &cmd_);
  }
  RayKernel(const RayKernel&) = delete;
  RayKernel& operator=(const RayKernel&) = delete;

  // Submits the dispatch and waits for it; adds its wall and process CPU seconds. The
  // first run is a warm-up (the driver may finish compiling then) and is not counted.
  void run() {
    VkDevice dev = context_.device();
    std::clock_t cpu0 = std::clock();
    auto t0 = std::chrono::steady_clock::now();
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    gpu::check(vkResetFences(dev, 1, &fence_), "resetting a fence");
    gpu::check(vkQueueSubmit(context_.queue(), 1, &submit, fence_), "running a kernel");
    gpu::check(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "running a kernel");
    if (!warm_) {
      warm_ = true;
      return;
    }
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    cpu += double(std::clock() - cpu0) / CLOCKS_PER_SEC;
    runs++;
  }

  double wall = 0.0, cpu = 0.0;  // seconds of the counted runs
  std::uint64_t runs = 0;

 private:
  const gpu::VulkanContext& context_;
  gpu::ComputePipeline pipeline_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  bool warm_ = false;
};

}  // namespace

GpuRayRates gpu_rays_per_second(const Scene& scene, std::span<const glm::vec3> origins,
                                std::span<const glm::vec3> dirs, double seconds) {
  gpu::VulkanContext context("");
  const std::size_t count = origins.size();
  // The rays as pairs of vec4 (origin, direction), as both kernels read them.
  std::vector<glm::vec4> rays(2 * count);
  for (std::size_t i = 0; i < count; i++) rays[2 * i] = glm::vec4(origins[i], 1.0f), rays[2 * i + 1] = glm::vec4(dirs[i], 0.0f);
  auto storage = [&](const void* data, std::size_t bytes) {
    gpu::Buffer b(context, std::max<std::size_t>(bytes, 64), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (data) b.write(data, bytes);
    return b;
  };
  gpu::Buffer triangles = storage(scene.triangles.data(), scene.triangles.size() * sizeof(Triangle));
  gpu::Buffer ray_buffer = storage(rays.data(), rays.size() * sizeof(glm::vec4));
  gpu::Buffer naive_out = storage(nullptr, count * sizeof(float));
  gpu::Buffer renderer_out = storage(nullptr, count * sizeof(glm::vec4));
  gpu::Buffer unused = storage(nullptr, 64);
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
      &triangles, &unused, &unused, &ray_buffer, &naive_params, &naive_out, &unused, &unused, &unused_uniform, &unused, &unused};
  const gpu::Buffer* renderer_bindings[gpu::kBindingCount] = {
      &triangles, &unused, &unused, &ray_buffer, &renderer_params, &renderer_out, &unused, &unused, &uniform.buffer, &unused, &unused};
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
