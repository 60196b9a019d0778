// stage5_mis: beyond the article, multiple importance sampling of light and BSDF
// samples (Veach 1997). The program reads the options, loads the scene, chooses a backend,
// renders and writes the image; the algorithm itself is integrator.glsl, compiled for both
// backends by the build.
#include "common/app/app.h"
#include "cpu/cpu_backend.h"
#include "gpu/gpu_backend.h"
#include "stage5_mis/kernels.h"

int main(int argc, char** argv) {
  const pt::Stage stage{pt::StageInfo{.name = "stage5_mis",
                                      .summary = "beyond the article: MIS of light and BSDF samples",
                                      .default_spp = 64,
                                      .has_roulette = true,
                                      .default_roulette = pt::kRouletteThroughput,
                                      .sees_point_lights = true},
                        stage5::kernels(),
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
