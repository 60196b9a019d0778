"""The parts of tools/grade_lab.py, which grades a folder of lab submissions in one command
(docs/labs/teachers.md; tooling for teachers, not a part of the article):
  sandbox.py      the sealed run (bubblewrap) of every command that compiles or runs a
                  student's code, its limits, and the pipes its output comes back over;
  source_check.py what a lab file may hold (GLSL, the kernel's #includes, include guards);
  work_build.py   the work copy of the repository, its lab build and the setup's first build;
  hidden.py       the placeholders of the files a submission must not see;
  compiler_cache.py  the set-up's read-only use of ccache's cache (--compiler-cache);
  depends.py      the deletion of every output that #includes labs/labLAB.glsl before a
                  submission is built (the GPU kernels stay the setup's);
  glsl_check.py   the student's file compiled once as GLSL (glslangValidator);
  lab_tests.py    which Catch2 tests grade a lab, and reading their XML report;
  hints.py        the lab page's "If a test fails" table: the FAIL line's sentence and suspect;
  stuck.py        which lab function a timed-out test program was running (gdb);
  submission.py   finding the submissions and grading one: check, build, tests, verdict;
  reports.py      OUT/grades.csv, OUT/grades.xml (JUnit) and the logs folder.
Here is what they share: the grader's one-line error exit and usage line, the test program's
target and the build's time limit."""
import sys

TEST_TARGET = "pt_tests"
BUILD_TIMEOUT = 3600  # seconds: the first build of a lab takes a few minutes on 2 cores
USAGE = ("usage: tools/grade_lab.py LAB SUBMISSIONS_DIR [--out DIR] [--timeout SECONDS] [--jobs N] [--work DIR] "
         "[--unsealed] [--compiler-cache]")


def die(message, status):
    print(f"grade_lab: {message}", file=sys.stderr)
    sys.exit(status)
