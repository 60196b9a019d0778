// stage1_raycast: the article's simplest algorithm, raycasting (Eq. 2: Lout = Le). The
// program reads the options, loads the scene, chooses a backend, renders and writes the
// image; the algorithm itself is integrator.glsl, compiled for both backends by the build.
#include "common/app/app.h"
#include "cpu/cpu_backend.h"
#include "gpu/gpu_backend.h"
#include "stage1_raycast/kernels.h"

int main(int argc, char** argv) {
  const pt::Stage stage{pt::StageInfo{.name = "stage1_raycast",
                                      .summary = "raycasting, Eq. (2): Lout = Le",
                                      .default_spp = 1,
                                      .every_surface_emits = true},
                        stage1::kernels(),
                        {pt::make_cpu_backend, pt::gpu::create_backend, pt::gpu::vulkan_devices}};
  return pt::run_guarded(stage.info.name, [&] {
    std::optional<pt::Options> options = pt::read_options(argc, argv, stage);
    if (!options) return 0;                  // --help was printed
    const pt::OutputFile out(options->out);  // checked now, written after the render
    pt::Scene scene = pt::load_stage_scene(*options, stage);
    std::unique_ptr<pt::Backend> backend = pt::choose_backend(*options, stage);
    pt::RenderResult result = pt::render_frame(backend, scene, *options, stage);
    return pt::write_result(out, *options, *backend, scene, result, stage);
  });
}
