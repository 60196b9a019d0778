// stage1_raycast: Eq. (2) of the article, Lout = Le, rendered by raycasting.
// Parse the command line, load the scene, render on the chosen backend, write the image.
#include <cstdio>

#include "common/app.h"
#include "common/image_output.h"
#include "common/scene_loading.h"
#include "gpu/gpu_backend.h"
#include "stage1_raycast/kernels.h"

static const pt::StageInfo kStage{"stage1_raycast", "raycasting, Eq. (2): Lout = Le", 1};

int main(int argc, char** argv) {
  return pt::guarded_main(kStage.name, [&] {
    std::optional<pt::Options> options = pt::parse_options(argc, argv, kStage);
    if (!options) return 0;  // --help
    pt::OutputFile out(options->out);  // checked now, written after the render
    pt::check_image_memory(options->width, options->height);
    pt::Scene scene = pt::load_scene(options->scene);
    if (!scene.point_lights.empty()) {
      std::fprintf(stderr, "%s: the scene's point lights are delta lights; only stage4 can see them\n", kStage.name);
    }
    auto backend = pt::make_backend(*options, stage1::kernels(), pt::gpu::create_backend);
    pt::RenderResult result = pt::render(*backend, scene, pt::render_settings(*options, kStage.name));
    out.write(result.film.mean_rgb(), options->width, options->height,
              pt::image_metadata(kStage.name, *options, *backend, result), options->exposure);
    std::printf("%s\n", pt::summary_line(kStage.name, *backend, result).c_str());
    return 0;
  });
}
