// The Vulkan compute backend (see gpu_backend.h): the scene arrays in storage buffers (and
// the triangles in a uniform buffer too when they fit: gpu/kernel_bindings.glsl, triangle_at),
// one pass = a few dispatches of 8x8 workgroups over row ranges, each short enough for a
// desktop GPU's watchdog (each recorded, timed and waited for by dispatch.h), then the
// output read back. device_limits.h checks beforehand that the buffers fit the device.
#include "gpu/gpu_backend.h"

#include <algorithm>
#include <cmath>
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
#include "gpu/dispatch.h"

namespace pt::gpu {

namespace {

constexpr uint32_t kGroupSize = 8;                      // kernel_main.glsl's local size
constexpr uint64_t kPixelSamplesPerDispatch = 1u << 22;  // about 4 million camera samples

class GpuBackend : public Backend, public DeviceMemoryLimits {
 public:
  GpuBackend(const StageKernels& kernels, const std::string& device)
      : context_(device), kernels_(kernels), dispatcher_(context_) {
    params_ = Buffer(context_, sizeof(FrameParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    counters_ = Buffer(context_, sizeof(PassResult::counters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  }

  ~GpuBackend() override {
    vkDeviceWaitIdle(context_.device());
  }

  std::string kind() const override { return "gpu"; }
  std::string device_name() const override { return context_.device_name(); }

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
    upload(light_guide_, scene.light_guide.data(), lights ? scene.light_guide.size() * sizeof(uint) : 0);
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
    // the specialization constant kSceneFeatures fixed, and drops the code it excludes.
    std::unique_ptr<ComputePipeline>& pipeline = pipelines_[{features, uniform.constant}];
    if (!pipeline) pipeline = std::make_unique<ComputePipeline>(context_, kernels_.spirv, features, uniform.constant);
    pipeline_ = pipeline.get();
  }

  // Before anything is built or allocated (common/render/memory.h): each buffer that
  // set_scene() and run_pass() will make against the device's limits, as they check them,
  // and all of them together against its memory.
  void check_device_memory(const Scene& scene, uint features, std::uint64_t pixels, const Bvh* bvh) const override {
    check_render_memory(context_, scene, features, pixels, bvh);
  }

  PassResult run_pass(const FrameParams& params, std::span<glm::vec4> out) override {
    // A lost device is never used again: its results could not be trusted.
    if (dispatcher_.lost()) {
      throw Error(kExitNoDevice, "Vulkan device '" + context_.device_name() + "' was lost earlier and is not retried");
    }
    passes_++;
    ensure_output(VkDeviceSize(out.size_bytes()));
    if (!pipeline_) throw std::logic_error("run_pass before set_scene");
    if (!one_sample_ || params.sample_count <= 1) {
      PassResult result = run_dispatches(params, out);
      if (result.counters[kCounterLoopLimit] == 0 || params.sample_count <= 1) return result;
      // lavapipe's loop budget per invocation ran out (gpu/kernel_main.glsl): the pass is wrong.
      // From now on every invocation renders one sample, the pass again included.
      one_sample_ = true;
    }
    return run_one_sample_at_a_time(params, out);
  }

 private:
  // The pass as sample_count passes of one sample each (the same sample indices, so the same
  // samples), added up on the host as render_pixel() adds its samples: the radiance sums,
  // and the roots of the sums of squared luminance as the root of their squares' sum.
  PassResult run_one_sample_at_a_time(const FrameParams& params, std::span<glm::vec4> out) {
    std::vector<glm::dvec4> sum(out.size(), glm::dvec4(0.0));
    PassResult result;
    result.counters[kCounterNonFinitePixel] = kNoPixel;
    for (uint i = 0; i < params.sample_count; i++) {
      FrameParams one = params;
      one.first_sample = params.first_sample + i;
      one.sample_count = 1u;
      PassResult part = run_dispatches(one, out);
      for (std::size_t p = 0; p < out.size(); p++) {
        sum[p] += glm::dvec4(glm::dvec3(out[p]), double(out[p].w) * double(out[p].w));
      }
      result.kernel_seconds += part.kernel_seconds;
      for (uint c = 0; c < kCounterCount; c++) {
        result.counters[c] = c == kCounterNonFinitePixel ? std::min(result.counters[c], part.counters[c])
                                                         : result.counters[c] + part.counters[c];
      }
    }
    for (std::size_t p = 0; p < out.size(); p++) out[p] = glm::vec4(glm::dvec3(sum[p]), std::sqrt(sum[p].w));
    return result;
  }

  // Runs the pass `params` over the whole image in dispatches of bounded work.
  PassResult run_dispatches(const FrameParams& params, std::span<glm::vec4> out) {
    const uint32_t width = params.width, height = params.height;
    const Buffer* buffers[kBindingCount] = {&triangles_, &spheres_,   &materials_, &point_lights_,     &params_,
                                            &output_,    &counters_, &lights_,    &uniform_triangles_,
                                            &bvh_nodes_, &bvh_indices_, &triangle_attributes_, &material_textures_,
                                            &textures_,  &texels_,   &triangle_shading_, &environment_radiance_,
                                            &environment_tables_, &light_guide_};
    pipeline_->bind_buffers(buffers);
    PassResult result;
    result.counters[kCounterNonFinitePixel] = kNoPixel;
    counters_.write(result.counters, sizeof result.counters);

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
      result.kernel_seconds += dispatcher_.dispatch(*pipeline_, groups_x, (n + kGroupSize - 1) / kGroupSize, passes_);
    }
    output_.read(out.data(), out.size_bytes());
    counters_.read(result.counters, sizeof result.counters);
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

  VulkanContext context_;
  StageKernels kernels_;
  std::map<std::pair<uint, uint32_t>, std::unique_ptr<ComputePipeline>> pipelines_;  // by features, kUniformTriangles
  ComputePipeline* pipeline_ = nullptr;                          // the current scene's
  Dispatcher dispatcher_;      // records, submits and times each dispatch (dispatch.h)
  std::uint64_t passes_ = 0;  // passes begun on this device (PT_FAULT counts them)
  bool one_sample_ = false;   // the driver's loop budget ran out once: one sample per invocation
  Buffer triangles_, spheres_, materials_, point_lights_, params_, output_, counters_, lights_, uniform_triangles_;
  Buffer bvh_nodes_, bvh_indices_;  // bindings 9 and 10
  Buffer triangle_attributes_, material_textures_, textures_, texels_;  // bindings 11 to 14
  Buffer triangle_shading_;                                             // binding 15
  Buffer environment_radiance_, environment_tables_;                    // bindings 16 and 17
  Buffer light_guide_;                                                  // binding 18
};

}  // namespace

std::unique_ptr<Backend> create_backend(const StageKernels& kernels, const std::string& device) {
  return std::make_unique<GpuBackend>(kernels, device);
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
