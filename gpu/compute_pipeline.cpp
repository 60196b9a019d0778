// Compute pipeline and descriptor set (see compute_pipeline.h).
#include "gpu/compute_pipeline.h"

#include <algorithm>

namespace pt::gpu {

namespace {
VkDescriptorType binding_type(uint32_t binding) {
  if (binding == kBvhNodesBinding) return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  return binding == kParamsBinding || binding == kUniformTrianglesBinding ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                                                            : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}
}  // namespace

UniformTriangles uniform_triangles(const VulkanContext& context, std::span<const Triangle> triangles) {
  const VkDeviceSize range = std::min<VkDeviceSize>(context.properties().limits.maxUniformBufferRange, 65536);
  const uint32_t capacity = uint32_t(range / sizeof(Triangle)) - 1u;
  const bool fits = !triangles.empty() && triangles.size() <= capacity;
  UniformTriangles u{Buffer(context, (fits ? capacity + 1u : 1u) * sizeof(Triangle), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT),
                     fits ? capacity : 0u};
  if (fits) u.buffer.write(triangles.data(), triangles.size_bytes());
  return u;
}

KernelProgram::KernelProgram(const VulkanContext& context, std::span<const uint32_t> spirv, uint32_t features,
                             uint32_t uniform_triangles)
    : device_(context.device()) {
  try {
    // The layout of gpu/kernel_bindings.glsl: what kind of buffer sits at each binding.
    VkDescriptorSetLayoutBinding bindings[kBindingCount];
    for (uint32_t i = 0; i < kBindingCount; i++) {
      bindings[i] = VkDescriptorSetLayoutBinding{i, binding_type(i), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    }
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = kBindingCount;
    set_info.pBindings = bindings;
    check(vkCreateDescriptorSetLayout(device_, &set_info, nullptr, &set_layout_), "creating a descriptor set layout");

    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout_;
    check(vkCreatePipelineLayout(device_, &layout_info, nullptr, &layout_), "creating a pipeline layout");

    // The kernel: SPIR-V that glslangValidator made at build time.
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = spirv.size_bytes();
    module_info.pCode = spirv.data();
    check(vkCreateShaderModule(device_, &module_info, nullptr, &module_), "loading the kernel");

    VkComputePipelineCreateInfo pipe_info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipe_info.stage = VkPipelineShaderStageCreateInfo{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pipe_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipe_info.stage.module = module_;
    pipe_info.stage.pName = "main";
    // The scene's features and where its triangles are read, fixed before the driver
    // compiles the kernel.
    const uint32_t constants[2] = {features, uniform_triangles};
    VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(uint32_t)}, {1, sizeof(uint32_t), sizeof(uint32_t)}};
    VkSpecializationInfo specialization{2, entries, sizeof constants, constants};
    pipe_info.stage.pSpecializationInfo = &specialization;
    pipe_info.layout = layout_;
    check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipe_info, nullptr, &pipeline_),
          "compiling the kernel");
  } catch (...) {
    release();
    throw;
  }
}

KernelProgram::~KernelProgram() { release(); }

void KernelProgram::release() {
  if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
  if (module_) vkDestroyShaderModule(device_, module_, nullptr);
  if (layout_) vkDestroyPipelineLayout(device_, layout_, nullptr);
  if (set_layout_) vkDestroyDescriptorSetLayout(device_, set_layout_, nullptr);
  pipeline_ = VK_NULL_HANDLE, module_ = VK_NULL_HANDLE, layout_ = VK_NULL_HANDLE, set_layout_ = VK_NULL_HANDLE;
}

ComputePipeline::ComputePipeline(const VulkanContext& context, std::span<const uint32_t> spirv, uint32_t features,
                                 uint32_t uniform_triangles)
    : ComputePipeline(context, std::make_shared<const KernelProgram>(context, spirv, features, uniform_triangles)) {}

ComputePipeline::ComputePipeline(const VulkanContext& context, std::shared_ptr<const KernelProgram> program)
    : device_(context.device()), program_(std::move(program)) {
  // One descriptor set of the program's layout, from a pool of its own.
  VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBindingCount - 3},
                                   {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2},
                                   {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1}};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 3;
  pool_info.pPoolSizes = sizes;
  check(vkCreateDescriptorPool(device_, &pool_info, nullptr, &pool_), "creating a descriptor pool");
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool_;
  alloc.descriptorSetCount = 1;
  const VkDescriptorSetLayout set_layout = program_->set_layout();
  alloc.pSetLayouts = &set_layout;
  VkResult allocated = vkAllocateDescriptorSets(device_, &alloc, &set_);
  if (allocated != VK_SUCCESS) vkDestroyDescriptorPool(device_, pool_, nullptr);
  check(allocated, "allocating a descriptor set");
}

ComputePipeline::~ComputePipeline() {
  if (pool_) vkDestroyDescriptorPool(device_, pool_, nullptr);
}

void ComputePipeline::bind_buffers(const Buffer* const (&buffers)[kBindingCount]) {
  VkDescriptorBufferInfo infos[kBindingCount];
  VkWriteDescriptorSet writes[kBindingCount];
  VkBufferView views[kBindingCount];
  for (uint32_t i = 0; i < kBindingCount; i++) {
    infos[i] = VkDescriptorBufferInfo{buffers[i]->handle(), 0, VK_WHOLE_SIZE};
    writes[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set_;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = binding_type(i);
    if (writes[i].descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) {
      views[i] = buffers[i]->texel_view();
      writes[i].pTexelBufferView = &views[i];
    } else {
      writes[i].pBufferInfo = &infos[i];
    }
  }
  vkUpdateDescriptorSets(device_, kBindingCount, writes, 0, nullptr);
}

void ComputePipeline::record_dispatch(VkCommandBuffer cmd, uint32_t groups_x, uint32_t groups_y) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, program_->pipeline());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, program_->layout(), 0, 1, &set_, 0, nullptr);
  vkCmdDispatch(cmd, groups_x, groups_y, 1);
}

}  // namespace pt::gpu
