// stage6_variance_aware: beyond the article, stage5's MIS with variance-aware weights from a
// pilot and a roulette after emission (docs/stage6_variance_aware.md). The program reads the
// options, loads the scene, chooses a backend, renders and writes the image; the algorithm is
// integrator.glsl, compiled for both backends by the build, and the pilot that runs before
// the render is pilot.cpp (the stage's before-render step: common/render/backend.h).
#include "common/app/app.h"
#include "cpu/cpu_backend.h"
#include "gpu/gpu_backend.h"
#include "stage6_variance_aware/kernels.h"

int main(int argc, char** argv) {
  const pt::Stage stage{pt::StageInfo{.name = "stage6_variance_aware",
                                      .summary = "beyond the article: MIS weighed by a pilot, roulette after emission",
                                      .default_spp = 64,
                                      .has_roulette = true,
                                      .default_roulette = pt::kRouletteThroughput,
                                      .throughput_p = "p = the square root of the path weight, glass's 1/eta^2 "
                                                      "taken out; drawn before a ray, applied after its emission",
                                      .sees_point_lights = true},
                        stage6::kernels(),
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
