// The GPU entry point every stage's kernel ends with: one invocation per pixel of the rows
// [params.first_row, params.first_row + rows of this dispatch), and the check that the
// driver ran the pixel's loops to their end (gpu_backend.cpp redoes a pass that it cut).
#ifndef PT_GPU_KERNEL_MAIN_GLSL
#define PT_GPU_KERNEL_MAIN_GLSL

// The GPU's own counter, after the kernels' kCounterCount (scene_types.h; gpu/loop_limit.h):
// the pixels whose loops the driver cut short in this pass.
const uint kCounterLoopLimit = kCounterCount;

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

void main() {
  uint x = gl_GlobalInvocationID.x;
  uint y = gl_GlobalInvocationID.y + params.first_row;
  if (x >= params.width || y >= params.height) return;
  pass_output[y * params.width + x] = render_pixel(x, y);
  // lavapipe (Mesa's llvmpipe) silently ends every loop of an invocation once 65535 loop
  // iterations have run in all of them together (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS):
  // bounces x triangles tested x samples of the pass. After that a loop runs once at most,
  // so a loop that must run sample_count + 1 times tells whether the pixel's loops were cut.
  uint probe = 0u;
  for (uint i = 0u; i <= params.sample_count; i++) probe++;
  if (probe != params.sample_count + 1u) atomicAdd(counters[kCounterLoopLimit], 1u);
}

#endif  // PT_GPU_KERNEL_MAIN_GLSL
