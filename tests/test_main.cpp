// Catch2's main for the CPU test executable, and its check that every test of a ctest group
// (PT_TEST_GROUP_TAGS: [stage1] ... [stage6], [sampling], [bvh], [mis]; tests/CMakeLists.txt)
// carries the tag of each stage whose CPU kernel it runs (docs/testing.md, section 8): the
// labs' grades, the stages' regression labels (ctest -L stage3) and the grader's choice of
// the kernels a submission rebuilds (labs/ungraded.h) rest on those tags. A test that runs a
// stage without its tag is named on stderr, and the run exits non-zero.
// Catch2's listener interface (its implementation: catch_runner.cpp).
#define CATCH_CONFIG_EXTERNAL_INTERFACES
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>

#include "common/scene/scene_loading.h"
#include "cpu/cpu_backend.h"
#include "stage1_raycast/kernels.h"
#include "tests/catch_runner.h"
#include "tests/support/test_render.h"

namespace {

int untagged_runs = 0;  // (test, stage) pairs without the tag

struct StageTags : Catch::TestEventListenerBase {
  using TestEventListenerBase::TestEventListenerBase;
  void testCaseStarting(Catch::TestCaseInfo const&) override { pt::clear_cpu_stages_run(); }
  void testCaseEnded(Catch::TestCaseStats const& stats) override {
    const std::uint32_t ran = pt::cpu_stages_run();
    const std::vector<std::string>& tags = stats.testInfo.lcaseTags;
    auto tagged = [&](const std::string& tag) { return std::find(tags.begin(), tags.end(), tag) != tags.end(); };
    const std::string groups = "," PT_TEST_GROUP_TAGS ",";
    auto a_group = [&](const std::string& tag) { return groups.find("," + tag + ",") != std::string::npos; };
    if (std::none_of(tags.begin(), tags.end(), a_group)) return;  // in no group: it grades no lab
    for (int k = 1; k <= 9; ++k) {
      const std::string tag = "stage" + std::to_string(k);
      if ((ran >> (k - 1) & 1u) && !tagged(tag)) {
        std::fprintf(stderr, "test \"%s\" runs %s's CPU kernel but is not tagged [%s]: add the tag\n",
                     stats.testInfo.name.c_str(), tag.c_str(), tag.c_str());
        ++untagged_runs;
      }
    }
  }
};

}  // namespace

CATCH_REGISTER_LISTENER(StageTags)

// The check's own test (hidden: ctest's pt_tests_untagged_stage_caught runs it and expects the
// run to fail, naming the test): checked as a group's test (PT_TEST_GROUP_TAGS holds its
// tag), it renders with stage1's CPU kernel and has no [stage1].
TEST_CASE("stage tags: a test that renders with stage1 but lacks its tag", "[.][untagged_stage]") {
  pt::Scene scene = pt::make_builtin_scene("cornell");
  pt::RenderResult r = pt::test::render_on("cpu", stage1::kernels(), scene, pt::test::settings(8, 6, 1, 1));
  CHECK(r.film.spp() == 1);
}

// The crash probe (hidden: grade_lab_fast runs it by name, tools/grade_lab_checks/fast.py): two
// threads die of SIGSEGV at once, as a student's wrong index does in the parallel render; the
// program must still die of SIGSEGV and say in which test (catch_runner.cpp).
TEST_CASE("grader: two threads die of SIGSEGV at once", "[.][crash_probe]") {
  std::atomic<int> ready{0};
  auto die = [&ready] {
    ready.fetch_add(1);
    while (ready.load() < 2) std::this_thread::yield();
    std::raise(SIGSEGV);
  };
  std::thread a(die), b(die);
  a.join();
  b.join();
}

int main(int argc, char* argv[]) {
  const int result = pt::test::run_catch(argc, argv);
  if (untagged_runs > 0) {
    std::fprintf(stderr, "%d test(s) ran a stage without its tag (docs/testing.md, section 8)\n", untagged_runs);
    return result != 0 ? result : 1;
  }
  return result;
}
