#!/usr/bin/env python3
"""Test of tools/grade_lab.py (grading a class's lab submissions; tooling for teachers, not a
part of the article). Two parts:
  --fast (ctest entry grade_lab_fast, in ./tutorial test; seconds, no lab build): a submission
    rebuilds only what #includes its file and what is made from that (not the GPU kernels,
    whose rules name every labs/*.glsl), with the setup's time stamp on it; bad usage exits
    2 with one line; without bubblewrap the grader says so in one line and grades nothing; the
    source check accepts every honest fixture below and REFUSES each malicious one with its
    reason; the sandbox keeps a command from writing outside its folder, from the network and
    from the project tree, cuts off 1 GB of output, and hands the grader a report pipe that
    no file write reaches; a report with text besides Catch2's is not taken; every row of each
    lab page's table "If a test fails" names a test of that lab (PT_TESTS --list-test-names-only);
    grades.csv quotes a field that holds the separator. Exit 77 (skipped) for the sandbox part
    where bubblewrap cannot run.
  (default; ctest entry grade_lab, label grading; minutes) every lab graded on fixture
    submissions made here from the reference functions, which are renamed and called by
    wrappers, so that no line of their bodies is quoted here (the handout ships this file
    without them). Each submission must get its verdict line; the other reference file of the
    lab (lab 2's roulette, lab 4's emission rule) is appended to each as it is. Lab 2
    (common/kernel/uniform_hemisphere.glsl, russian_roulette.glsl):
  a_correct          the reference                                  PASS
  b_syntax_error     a wrapper less a semicolon, graded right       COMPILE ERROR at labs/lab2.glsl
                     after a correct one (issue 24)
  c_pdf_2pi          pdf = 2 pi instead of 1 / (2 pi)               FAIL, the pdf test named, suspect
  d_theta_uniform    theta uniform instead of cos(theta)            FAIL, the chi-square named, suspect
  e_convention/      u.x and u.y swapped: another convention,       PASS
    lab2.glsl        right in distribution
  f_endless_loop     a loop on an unsigned i >= 0 in the sampler    TIMEOUT in sample_uniform_hemisphere(),
                                                                     with g++'s warning on it
  g_crash            a read far out of the materials' bounds        CRASH SIGSEGV
  h_empty/           a folder without lab2.glsl                     COMPILE ERROR no lab2.glsl
  m_NAME             each other known-wrong answer of labs/mutants.h FAIL with a suspect
  r_includes_reference  #includes the reference files                REFUSED
  r_writes_outside   no pdf, and C++ behind #ifdef __cplusplus that  REFUSED (with the source check
                     plants files in the work copy, the repository   off: FAIL, every write stopped by
                     and the build and copies the reference          the sandbox, nothing planted)
  r_rewrites_report  no pdf, and C++ that writes a passing report   REFUSED (check off: FAIL or
                     into every file and fd it can at exit          REFUSED, never PASS)
  r_prints_1gb       the reference, and C++ that prints 1 GB        REFUSED (check off: REFUSED,
                                                                     the pipe's cap)
and a summary line, grades.csv and grades.xml with one row and one testcase per submission.
Lab 4 (common/kernel/triangle_light.glsl, emission_rule.glsl): a_correct PASS, b_pdf_doubled and
c_pdf_mismatch FAIL (the latter through the held-back test), each mutant FAIL. Labs 3, 5 and 6
(grade_lab_checks/fixtures_small.py): a_correct PASS, b_syntax_error COMPILE ERROR, each mutant
FAIL. Lab 1, which has no mutants: a_correct, b_syntax_error, c_dimmed and c_black_sky FAIL.
Labs 1 and 3-6 also get lab 2's other kinds (fixtures.other_kinds): f_endless_loop TIMEOUT
(naming the lab's function where gdb is installed), g_crash CRASH, h_empty COMPILE ERROR, the
four attacks REFUSED, and graded again with the source check off. Each lab's set-up builds the
student's code into the kernels of the stages its tests run only.
  --lab1 WORK (ctest entry grade_lab_1, in ./tutorial test; about a minute after the Release
    build): lab 1 alone, its set-up reading the Release build's objects from ccache
    (--compiler-cache). Exit 77 (skipped) where bubblewrap cannot run.
usage: tools/test_grade_lab.py --fast [PT_TESTS]
       tools/test_grade_lab.py --lab1 WORK
       tools/test_grade_lab.py [WORK]   (WORK: lab 2's build, WORK_labN lab N's, kept between runs;
       PT_GRADE_TEST_TIMEOUT: seconds for one submission's tests (labs 1-3, 5, 6), default 90;
       PT_GRADE_TEST_LABS: the labs to grade, default "1,2,3,4,5,6")"""
import os
import sys
import tempfile

from grade_lab_checks.fast import bad_usage, fast  # the parts of this test: tools/grade_lab_checks/
from grade_lab_checks.graded import SMALL_LABS, lab1, lab2, lab4, small_lab
from grading.sandbox import probe


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == "--fast":
        return fast(sys.argv[2] if len(sys.argv) > 2 else None)
    if len(sys.argv) == 3 and sys.argv[1] == "--lab1":
        return lab1_in_suite(sys.argv[2])
    if len(sys.argv) > 2:
        print("usage: tools/test_grade_lab.py --fast [PT_TESTS] | --lab1 WORK | [WORK]", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="grade_lab_test_") as tmp:
        work = sys.argv[1] if len(sys.argv) == 2 else os.path.join(tmp, "work")
        subs, out = os.path.join(tmp, "submissions"), os.path.join(tmp, "out")
        os.makedirs(subs)
        bad_usage(tmp)
        labs = os.environ.get("PT_GRADE_TEST_LABS", "1,2,3,4,5,6").split(",")
        if "2" in labs:
            lab2(subs, out, work)
        if "1" in labs:
            lab1(os.path.join(tmp, "submissions_lab1"), os.path.join(tmp, "out_lab1"), work + "_lab1")
        if "4" in labs:
            lab4(os.path.join(tmp, "submissions_lab4"), os.path.join(tmp, "out_lab4"), work + "_lab4")
        for lab in sorted(SMALL_LABS):
            if str(lab) in labs:
                small_lab(lab, os.path.join(tmp, f"submissions_lab{lab}"), os.path.join(tmp, f"out_lab{lab}"), f"{work}_lab{lab}")
    return 0


def lab1_in_suite(work):
    """Lab 1 graded in ./tutorial test: a sealed grading run from set-up to report, end to end."""
    why = probe()
    if why:
        print(f"skipped: no sandbox here ({why})")
        return 77
    with tempfile.TemporaryDirectory(prefix="grade_lab_test_") as tmp:
        lab1(os.path.join(tmp, "submissions_lab1"), os.path.join(tmp, "out_lab1"), work, ["--compiler-cache"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
