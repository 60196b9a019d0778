// The GPU entry point every stage's kernel ends with: one invocation per pixel of the rows
// [params.options.w, params.options.w + rows of this dispatch), and the check that the
// driver ran the pixel's loops to their end (gpu_backend.cpp redoes a pass that it cut).
#ifndef PT_GPU_KERNEL_MAIN_GLSL
#define PT_GPU_KERNEL_MAIN_GLSL

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

void main() {
  uint x = gl_GlobalInvocationID.x;
  uint y = gl_GlobalInvocationID.y + params.options.w;
  if (x >= params.image.x || y >= params.image.y) return;
  pass_output[y * params.image.x + x] = render_pixel(x, y);
  // lavapipe (Mesa's llvmpipe) silently ends every loop of an invocation once 65535 loop
  // iterations have run in all of them together (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS):
  // bounces x triangles tested x samples of the pass. After that a loop runs once at most,
  // so a loop that must run image.w + 1 times tells whether the pixel's loops were cut.
  uint probe = 0u;
  for (uint i = 0u; i <= params.image.w; i++) probe++;
  if (probe != params.image.w + 1u) atomicAdd(counters[kCounterLoopLimit], 1u);
}

#endif  // PT_GPU_KERNEL_MAIN_GLSL
