// stage1_raycast: Eq. (2) of the article, Lout = Le, rendered by raycasting.
// Parse, load, render, write: common/app/app.cpp run_stage(); the algorithm is integrator.glsl.
#include "common/app/app.h"
#include "gpu/gpu_backend.h"
#include "stage1_raycast/kernels.h"

int main(int argc, char** argv) {
  const pt::StageInfo stage{"stage1_raycast", "raycasting, Eq. (2): Lout = Le", 1};
  return pt::run_stage(argc, argv, stage, stage1::kernels(), pt::gpu::create_backend);
}
