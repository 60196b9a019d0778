// Catch2's runner for the test programs (issue #51): its implementation is compiled once, in
// catch_runner.cpp, for pt_tests, pt_gpu_tests and the grader's pt_lab_tests, whose main()s
// (test_main.cpp, gpu/gpu_main.cpp) call it. Test machinery, not part of the article.
#pragma once

namespace pt::test {

// Runs the tests the command line selects (Catch2's Session); returns its exit status.
int run_catch(int argc, char* argv[]);

}  // namespace pt::test
