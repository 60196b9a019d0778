// The Vulkan compute backend (see gpu_backend.h): the scene arrays in storage buffers (and
// the triangles in a uniform buffer too when they fit: gpu/kernel_bindings.glsl, triangle_at),
// one pass = a few dispatches of 8x8 workgroups over row ranges, each short enough for a
// desktop GPU's watchdog, timed with timestamp queries, then the output read back.
#include "gpu/gpu_backend.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>
#include <memory>
#include <stdexcept>
#include <vector>

#include "common/base/error.h"
#include "common/render/memory.h"
#include "common/render/render.h"
#include "common/scene/bvh.h"
#include "common/scene/environment.h"
#include "common/scene/scene.h"
#include "gpu/compute_pipeline.h"
#include "gpu/device_limits.h"
#include "gpu/device_session.h"
#include "gpu/fault.h"
#include "gpu/loop_limit.h"

namespace pt::gpu {

namespace {

constexpr uint32_t kGroupSize = 8;                      // kernel_main.glsl's local size
constexpr uint64_t kPixelSamplesPerDispatch = 1u << 22;  // about 4 million camera samples
constexpr uint64_t kFenceTimeoutNs = 120'000'000'000;    // a dispatch that takes 2 minutes is hung

class GpuBackend : public Backend, public DeviceMemoryLimits {
 public:
  GpuBackend(const StageKernels& kernels, std::shared_ptr<DeviceSession> session)
      : session_(std::move(session)), context_(session_->context()), kernels_(kernels) {
    VkDevice dev = context_.device();
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = context_.command_pool();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(dev, &alloc, &cmd_), "allocating a command buffer");
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(dev, &fence_info, nullptr, &fence_), "creating a fence");
    if (context_.has_timestamps()) {
      VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      q.queryType = VK_QUERY_TYPE_TIMESTAMP;
      q.queryCount = 2;
      check(vkCreateQueryPool(dev, &q, nullptr, &queries_), "creating a timestamp query pool");
    }
    params_ = Buffer(context_, sizeof(FrameParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    counters_ = Buffer(context_, kGpuCounterCount * sizeof(uint), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  }

  ~GpuBackend() override {
    VkDevice dev = context_.device();
    vkDeviceWaitIdle(dev);
    if (queries_) vkDestroyQueryPool(dev, queries_, nullptr);
    if (fence_) vkDestroyFence(dev, fence_, nullptr);
    // The device may serve other backends after this one (DeviceSession).
    if (cmd_) vkFreeCommandBuffers(dev, context_.command_pool(), 1, &cmd_);
  }

  std::string kind() const override { return "gpu"; }
  std::string device_name() const override { return context_.device_name(); }
  BeforeRender before_render() const override { return kernels_.before_render; }

  void set_scene(const Scene& scene, uint features, const Bvh* bvh) override {
    one_sample_ = false;  // a new scene may fit the loop budget again
    // Only what the kernel specialised to `features` reads is uploaded.
    bool spheres = (features & kFeatureSpheres) != 0u, lights = kernels_.uses_light_table;
    upload(triangles_, scene.triangles.data(), scene.triangles.size() * sizeof(Triangle), "the scene's triangles need");
    // The triangles again as a uniform buffer if they fit (gpu/kernel_bindings.glsl: triangle_at).
    UniformTriangles uniform = uniform_triangles(context_, scene.triangles);
    uniform_triangles_ = std::move(uniform.buffer);
    upload(spheres_, scene.spheres.data(), spheres ? scene.spheres.size() * sizeof(Sphere) : 0);
    upload(materials_, scene.materials.data(), scene.materials.size() * sizeof(Material));
    upload(point_lights_, scene.point_lights.data(), lights ? scene.point_lights.size() * sizeof(PointLight) : 0);
    upload(lights_, scene.lights.data(), lights ? scene.lights.size() * sizeof(Light) : 0);
    upload(light_alias_, scene.light_alias.data(), lights ? scene.light_alias.size() * sizeof(LightAlias) : 0);
    // The BVH, or placeholders when the render searches every triangle (params.accel).
    const bool has_bvh = bvh && !bvh->nodes.empty();
    upload(bvh_nodes_, has_bvh ? bvh->nodes.data() : nullptr, has_bvh ? bvh->nodes.size() * sizeof(BvhNode) : 0,
           "the BVH's nodes need", kTexels);
    upload(bvh_indices_, has_bvh ? bvh->indices.data() : nullptr, has_bvh ? bvh->indices.size() * sizeof(uint) : 0,
           "the BVH's triangle list needs");
    // Textures and vertex colours (common/kernel/texture.glsl), or placeholders without them.
    // A kernel with texture code (--all-features) and a scene without textures reads neutral
    // material entries (texture.glsl).
    const bool textured = (features & kFeatureTextures) && uses_textures(scene);
    upload(triangle_attributes_, scene.triangle_attributes.data(),
           textured ? scene.triangle_attributes.size() * sizeof(TriangleAttributes) : 0, "the vertex attributes need");
    const std::vector<MaterialTextures> neutral =
        (features & kFeatureTextures) && !textured ? neutral_material_textures(scene.materials.size())
                                                   : std::vector<MaterialTextures>();
    upload(material_textures_, textured ? scene.material_textures.data() : neutral.data(),
           (textured ? scene.material_textures.size() : neutral.size()) * sizeof(MaterialTextures));
    upload(textures_, scene.textures.data(), textured ? scene.textures.size() * sizeof(Texture) : 0);
    upload(texels_, scene.texels.data(), textured ? scene.texels.size() * sizeof(uint) : 0, "the textures need");
    const bool shaded = (features & kFeatureShadingNormals) && uses_shading_normals(scene);  // else a placeholder
    upload(triangle_shading_, scene.triangle_shading.data(),
           shaded ? scene.triangle_shading.size() * sizeof(TriangleShading) : 0, "the shading normals need");
    const Environment* env = (features & kFeatureEnvironment) ? scene.environment.get() : nullptr;
    upload(environment_radiance_, env ? env->radiance.data() : nullptr, env ? env->radiance.size() * sizeof(float) : 0,
           "the environment map needs");
    upload(environment_tables_, env ? env->table.data() : nullptr, env ? env->table.size() * sizeof(float) : 0,
           "the environment map's sampling tables need");
    // One pipeline per feature set, made on first use: the driver compiles the kernel with
    // the specialization constant kSceneFeatures fixed, and drops the code it excludes (once
    // per session: other backends on the same DeviceSession reuse the compiled program).
    std::unique_ptr<ComputePipeline>& pipeline = pipelines_[{features, uniform.constant}];
    if (!pipeline) {
      pipeline = std::make_unique<ComputePipeline>(context_, session_->program(kernels_.spirv, features, uniform.constant));
    }
    pipeline_ = pipeline.get();
  }

  // Before anything is built or allocated (common/render/memory.h): gpu/device_limits.h.
  void check_device_memory(const Scene& scene, uint features, std::uint64_t pixels, const Bvh* bvh) const override {
    check_scene_memory(context_, scene, features, pixels, bvh);
  }

  PassResult run_pass(const FrameParams& params, std::span<glm::vec4> out) override {
    // A lost device is never used again: its results could not be trusted.
    if (lost_) throw Error(kExitNoDevice, "Vulkan device '" + context_.device_name() + "' was lost earlier and is not retried");
    passes_++;
    ensure_output(VkDeviceSize(out.size_bytes()));
    if (!pipeline_) throw std::logic_error("run_pass before set_scene");
    if (!one_sample_ || params.sample_count <= 1) {
      PassResult result = run_dispatches(params, out);
      if (result.cut_short.empty() || params.sample_count <= 1) return result;
      // lavapipe's loop budget per invocation ran out (gpu/loop_limit.h): the pass is wrong.
      // From now on every invocation renders one sample, the pass again included.
      one_sample_ = true;
    }
    return run_one_sample_at_a_time(params, out, [&](const FrameParams& one) { return run_dispatches(one, out); });
  }

 private:
  // Runs the pass `params` over the whole image in dispatches of bounded work.
  PassResult run_dispatches(const FrameParams& params, std::span<glm::vec4> out) {
    const uint32_t width = params.width, height = params.height;
    const Buffer* buffers[kBindingCount] = {&triangles_, &spheres_,   &materials_, &point_lights_,     &params_,
                                            &output_,    &counters_, &lights_,    &uniform_triangles_,
                                            &bvh_nodes_, &bvh_indices_, &triangle_attributes_, &material_textures_,
                                            &textures_,  &texels_,   &triangle_shading_, &environment_radiance_,
                                            &environment_tables_, &light_alias_};
    pipeline_->bind_buffers(buffers);
    PassResult result;
    uint counters[kGpuCounterCount] = {};  // the kernels' (kNoPixel where they lower it), then the GPU's
    std::copy_n(result.counters, kCounterCount, counters);
    counters_.write(counters, sizeof counters);

    // Rows per dispatch: a bounded amount of work, a whole number of workgroups.
    const VkPhysicalDeviceLimits& limits = context_.properties().limits;
    uint64_t rows = kPixelSamplesPerDispatch / (uint64_t(width) * std::max(1u, params.sample_count));
    rows = std::clamp<uint64_t>(rows / kGroupSize * kGroupSize, kGroupSize,
                                uint64_t(limits.maxComputeWorkGroupCount[1]) * kGroupSize);
    const uint32_t groups_x = (width + kGroupSize - 1) / kGroupSize;
    if (groups_x > limits.maxComputeWorkGroupCount[0]) {
      throw Error(kExitNoDevice, "image width " + std::to_string(width) + " needs more workgroups than device '" +
                                     context_.device_name() + "' allows; render a narrower image or use --backend cpu");
    }
    for (uint32_t row0 = 0; row0 < height; row0 += uint32_t(rows)) {
      uint32_t n = uint32_t(std::min<uint64_t>(rows, height - row0));
      FrameParams chunk = params;
      chunk.first_row = row0;
      params_.write(&chunk, sizeof chunk);
      result.kernel_seconds += dispatch(groups_x, (n + kGroupSize - 1) / kGroupSize);
    }
    output_.read(out.data(), out.size_bytes());
    counters_.read(counters, sizeof counters);
    std::copy_n(counters, kCounterCount, result.counters);
    result.cut_short = loop_limit_message(counters[kCounterLoopLimit]);
    return result;
  }


  // The BVH's nodes, which the kernel reads as uvec4 texels (binding 9, gpu/kernel_bindings.glsl).
  static constexpr VkBufferUsageFlags kTexels = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;

  // Storage buffers never have size 0: an empty array still gets a small buffer.
  void upload(Buffer& buffer, const void* data, std::size_t bytes, const char* what = "the scene needs",
              VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
    check_range(context_, bytes, what);
    if (usage & VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT) check_texels(context_, bytes, what);
    buffer = Buffer(context_, std::max<std::size_t>((bytes + 15) / 16 * 16, 64), usage);
    if (bytes) buffer.write(data, bytes);
  }

  void ensure_output(VkDeviceSize bytes) {
    if (output_.size() == bytes) return;
    check_range(context_, bytes, "the image needs");
    output_ = Buffer(context_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  }

  // Records and submits one dispatch, waits for it; returns its kernel time.
  double dispatch(uint32_t groups_x, uint32_t groups_y) {
    VkDevice dev = context_.device();
    check(vkResetCommandBuffer(cmd_, 0), "resetting a command buffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd_, &begin), "recording commands");
    if (queries_) {
      vkCmdResetQueryPool(cmd_, queries_, 0, 2);
      vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    }
    pipeline_->record_dispatch(cmd_, groups_x, groups_y);
    if (queries_) vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
    // Make the shader's writes visible to the host's read of the output buffer.
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    check(vkEndCommandBuffer(cmd_), "recording commands");

    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    check(vkResetFences(dev, 1, &fence_), "resetting a fence");
    VkResult submitted = vkQueueSubmit(context_.queue(), 1, &submit, fence_);
    VkResult waited = submitted == VK_SUCCESS ? vkWaitForFences(dev, 1, &fence_, VK_TRUE, kFenceTimeoutNs) : submitted;
    if (fault().device_lost_pass == passes_) waited = VK_ERROR_DEVICE_LOST;  // PT_FAULT=device_lost:pass=N
    if (waited == VK_ERROR_DEVICE_LOST) {
      lost_ = true;
      throw Error(kExitNoDevice, "Vulkan device '" + context_.device_name() + "' was lost during pass " +
                                     std::to_string(passes_) + " (VK_ERROR_DEVICE_LOST) and is not retried");
    }
    if (waited == VK_TIMEOUT) {
      throw Error(kExitNoDevice, "the Vulkan device did not finish a pass within 2 minutes; use --backend cpu");
    }
    check(waited, "running the kernel");
    if (!queries_) return 0.0;
    uint64_t stamps[2];
    check(vkGetQueryPoolResults(dev, queries_, 0, 2, sizeof stamps, stamps, sizeof(uint64_t),
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "reading timestamps");
    return double(stamps[1] - stamps[0]) * double(context_.properties().limits.timestampPeriod) * 1e-9;
  }

  std::shared_ptr<DeviceSession> session_;  // first: it outlives the buffers below
  const VulkanContext& context_;
  StageKernels kernels_;
  std::map<std::pair<uint, uint32_t>, std::unique_ptr<ComputePipeline>> pipelines_;  // by features, kUniformTriangles
  ComputePipeline* pipeline_ = nullptr;                          // the current scene's
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
  std::uint64_t passes_ = 0;  // passes begun on this device (PT_FAULT counts them)
  bool lost_ = false;         // VK_ERROR_DEVICE_LOST seen: the device is not used again
  bool one_sample_ = false;   // the driver's loop budget ran out once: one sample per invocation
  Buffer triangles_, spheres_, materials_, point_lights_, params_, output_, counters_, lights_, uniform_triangles_;
  Buffer bvh_nodes_, bvh_indices_;  // bindings 9 and 10
  Buffer triangle_attributes_, material_textures_, textures_, texels_;  // bindings 11 to 14
  Buffer triangle_shading_;                                             // binding 15
  Buffer environment_radiance_, environment_tables_;                    // bindings 16 and 17
  Buffer light_alias_;                                                  // binding 18
};

}  // namespace

std::unique_ptr<Backend> create_backend(const StageKernels& kernels, const std::string& device) {
  return create_backend(kernels, std::make_shared<DeviceSession>(device));
}

std::unique_ptr<Backend> create_backend(const StageKernels& kernels, std::shared_ptr<DeviceSession> session) {
  return std::make_unique<GpuBackend>(kernels, std::move(session));
}

std::vector<VulkanDevice> vulkan_devices() {
  std::vector<VulkanDevice> list;
  for (const DeviceInfo& d : list_devices()) {
    VulkanDevice::Type type = VulkanDevice::Type::other;
    switch (d.type) {
      case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: type = VulkanDevice::Type::discrete; break;
      case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: type = VulkanDevice::Type::integrated; break;
      case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: type = VulkanDevice::Type::virtual_gpu; break;
      case VK_PHYSICAL_DEVICE_TYPE_CPU: type = VulkanDevice::Type::cpu; break;
      default: break;
    }
    list.push_back(VulkanDevice{d.name, type});
  }
  return list;
}

}  // namespace pt::gpu
