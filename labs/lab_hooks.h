// The C++ side of the lab hooks (docs/labs/README.md; labs/lab_support.glsl): which lab's
// stub replaces the real function, and the loud failure of a stub the student has not yet
// written. Labs 1-4 follow the article's four algorithms (Eq. 2, 3, 4 and 5), lab 5 the BVH
// that comes after it, lab 6 stage5_mis's multiple importance sampling.
//   PT_LAB=N (CMake -DPT_LAB=N, the student's build): lab N's stub, fixed at compile time.
//   PT_LAB_CHECK (CMake -DPT_LAB_CHECK=ON, the CI's check build): the stub of lab
//   $PT_LAB_STUB, chosen at run time, so one build checks all six labs; or the known-wrong
//   answer $PT_LAB_MUTANT (labs/mutants.h).
//   PT_LAB_GRADING with PT_LAB_GRADED_STAGES (the grader's build, tools/grade_lab.py): the
//   stages whose tests are not lab N's get traps in place of lab N's functions (ungraded).
#pragma once

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#ifndef PT_LAB
#define PT_LAB 0
#endif

namespace pt::lab {

// The lab whose stubs are in use: 0 for none (the normal build).
inline int selected() {
#if PT_LAB != 0
  return PT_LAB;
#elif defined(PT_LAB_CHECK)
  static const int lab = [] {
    const char* s = std::getenv("PT_LAB_STUB");
    return s ? std::atoi(s) : 0;
  }();
  return lab;
#else
  return 0;
#endif
}

// A stub's result: NaN, and one line on stderr the first time any stub of this lab runs.
inline float not_written(int lab, const char* function) {
  static std::atomic<bool> said[7] = {};
  if (lab >= 0 && lab < 7 && !said[lab].exchange(true)) {
    std::fprintf(stderr, "lab %d: %s is not written yet: write it in labs/lab%d.glsl (docs/labs/lab%d.md)\n", lab,
                 function, lab, lab);
  }
  return std::numeric_limits<float>::quiet_NaN();
}

// The grader's trap (labs/ungraded.h): lab `lab`'s function ran in the CPU kernel of a stage
// that the grader built without the student's code, because none of the lab's tests is
// tagged with that stage. Says so on stderr and aborts: a grade never rests on the reference.
[[noreturn]] inline void ungraded(int lab, const char* function, const char* stage) {
  std::fprintf(stderr,
               "grade_lab: lab %d's %s ran in %s's CPU kernel, which the grader built without the student's code: "
               "the test that runs %s must carry the tag [%s] (docs/testing.md, section 8)\n",
               lab, function, stage, stage, stage);
  std::abort();
}

// The check build's known-wrong answers (labs/mutants.h): whether PT_LAB_MUTANT names
// mutant `name` of lab `lab`, said once on stderr the first time it is used, so that
// tools/expect_lab_failure.sh knows the mutant ran.
inline bool mutant_is(int lab, const char* name) {
  static const char* const chosen = [] {
    const char* s = std::getenv("PT_LAB_MUTANT");
    return s ? s : "";
  }();
  if (chosen[0] == '\0' || std::strcmp(chosen, name) != 0) return false;
  static std::atomic<bool> said{false};
  if (!said.exchange(true)) {
    std::fprintf(stderr, "lab %d: mutant %s runs in place of the reference (labs/mutants.h)\n", lab, name);
  }
  return true;
}

}  // namespace pt::lab
