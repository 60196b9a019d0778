// --accel bvh against --accel none (the BVH of common/scene/bvh.h, the acceleration
// structure that follows the article's GPU section): every stage renders the same image,
// bit for bit, on the CPU, since the traversal finds exactly the brute force's hits.
#include <catch2/catch.hpp>

#include "common/scene/scene_loading.h"
#include "stage1_raycast/kernels.h"
#include "stage2_montecarlo/kernels.h"
#include "stage3_importance/kernels.h"
#include "stage4_direct_indirect/kernels.h"
#include "tests/support/test_render.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("bvh: every stage's CPU image with --accel bvh is --accel none's, bit for bit",
          "[stage1][stage2][stage3][stage4][bvh]") {
  for (const StageKernels& kernels : {stage1::kernels(), stage2::kernels(), stage3::kernels(), stage4::kernels()}) {
    for (const char* name : {"cornell", "every_feature"}) {
      Scene scene = make_builtin_scene(name);
      RenderSettings s = settings(40, 30, 4, 31);
      s.roulette = kRouletteThroughput;
      s.accel = kAccelNone;
      RenderResult none = render_on("cpu", kernels, scene, s);
      s.accel = kAccelBvh;
      RenderResult bvh = render_on("cpu", kernels, scene, s);
      INFO(kernels.name << ", scene " << name);
      CHECK_FALSE(none.bvh.has_value());
      REQUIRE(bvh.bvh.has_value());
      CHECK(bvh.bvh->nodes > 1);
      CHECK(bvh.bvh->triangles == scene.triangles.size());
      REQUIRE(bvh.film.spp() == 4);
      CHECK(bvh.film.sums() == none.film.sums());
    }
  }
}
