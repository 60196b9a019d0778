// The GPU entry point every stage's kernel.comp ends with: one invocation per pixel of
// the rows [params.first_row, params.first_row + rows of this dispatch); see gpu/.
#ifndef PT_KERNEL_MAIN_GLSL
#define PT_KERNEL_MAIN_GLSL

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

void main() {
  uint x = gl_GlobalInvocationID.x;
  uint y = gl_GlobalInvocationID.y + params.first_row;
  if (x >= params.width || y >= params.height) return;
  pass_output[y * params.width + x] = render_pixel(x, y);
}

#endif  // PT_KERNEL_MAIN_GLSL
