// The GPU entry point every stage's kernel.comp ends with: one invocation per pixel of
// the rows [params.options.w, params.options.w + rows of this dispatch); see gpu/.
#ifndef PT_KERNEL_MAIN_GLSL
#define PT_KERNEL_MAIN_GLSL

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

void main() {
  uint x = gl_GlobalInvocationID.x;
  uint y = gl_GlobalInvocationID.y + params.options.w;
  if (x >= params.image.x || y >= params.image.y) return;
  pass_output[y * params.image.x + x] = render_pixel(x, y);
}

#endif  // PT_KERNEL_MAIN_GLSL
