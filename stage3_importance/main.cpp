// stage3_importance: Eq. (4) of the article, path tracing with BRDF importance sampling
// (each direction drawn in proportion to the BRDF, each contribution divided by its pdf).
// Parse, load, render, write: common/app/app.cpp run_stage(); the algorithm is integrator.glsl.
#include "common/app/app.h"
#include "common/kernel/scene_types.h"
#include "gpu/gpu_backend.h"
#include "stage3_importance/kernels.h"

int main(int argc, char** argv) {
  pt::StageInfo stage{"stage3_importance", "BRDF importance sampling, Eq. (4): f Lin cos / pdf", 64};
  stage.has_roulette = true;
  stage.default_roulette = pt::kRouletteThroughput;  // bounded variance at any albedo
  return pt::run_stage(argc, argv, stage, stage3::kernels(), pt::gpu::create_backend);
}
