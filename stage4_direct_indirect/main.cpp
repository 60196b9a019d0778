// stage4_direct_indirect: Eq. (5) of the article, direct light by light sampling (shadow
// rays to points sampled on the lights: soft shadows) plus indirect light by BRDF
// sampling. Parse, load, render, write: common/app/app.cpp run_stage(); the algorithm is
// integrator.glsl.
#include "common/app/app.h"
#include "common/kernel/scene_types.h"
#include "gpu/gpu_backend.h"
#include "stage4_direct_indirect/kernels.h"

int main(int argc, char** argv) {
  pt::StageInfo stage{"stage4_direct_indirect", "direct + indirect light, Eq. (5): light sampling", 64};
  stage.has_roulette = true;
  stage.default_roulette = pt::kRouletteThroughput;
  stage.sees_point_lights = true;
  return pt::run_stage(argc, argv, stage, stage4::kernels(), pt::gpu::create_backend);
}
