// stage2_montecarlo: Eq. (3) of the article, Monte Carlo path tracing with one uniformly
// sampled direction per bounce and Russian roulette. Parse, load, render, write:
// common/app/app.cpp run_stage(); the algorithm is integrator.glsl.
#include "common/app/app.h"
#include "common/kernel/scene_types.h"
#include "gpu/gpu_backend.h"
#include "stage2_montecarlo/kernels.h"

int main(int argc, char** argv) {
  pt::StageInfo stage{"stage2_montecarlo", "Monte Carlo path tracing, Eq. (3), uniform hemisphere sampling", 64};
  stage.has_roulette = true;
  stage.default_roulette = pt::kRouletteFixed;  // the article's p = 1/2
  return pt::run_stage(argc, argv, stage, stage2::kernels(), pt::gpu::create_backend);
}
