#!/usr/bin/env python3
"""Test of tools/grade_lab.py (grading a class's lab submissions; tooling for teachers, not a
part of the article). Two parts:
  --fast (ctest entry grade_lab_fast, in ./tutorial test; seconds, no lab build; the checks
    are in grade_lab_fast_checks.py): a submission
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
  (default; ctest entry grade_lab, label grading; minutes) labs 2 and 4 graded on fixture
    submissions made from the reference functions (grade_lab_fixtures.py), which are renamed
    and called by wrappers, so that no line of their bodies is quoted there (the handout
    ships the reference files without them). Each submission must get its verdict line; the other reference file of the
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
c_pdf_mismatch FAIL (the latter through the held-back test), each mutant FAIL.
usage: tools/test_grade_lab.py --fast [PT_TESTS]
       tools/test_grade_lab.py [WORK]   (WORK: lab 2's build, and WORK_lab4 lab 4's, kept between
       runs; PT_GRADE_TEST_TIMEOUT: seconds for one lab 2 submission's tests, default 90;
       PT_GRADE_TEST_LABS: the labs to grade, default "2,4")"""
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

from grade_lab_fast_checks import bad_usage, fast
from grade_lab_fixtures import REPO, TOOL, expect, lab2_fixtures, lab4_fixtures, plants, written_mutants

# Seconds for one lab 2 submission's tests: the correct submission's take about 17 s on 2
# cores (20 tests, every test that runs stage2 being tagged [stage2]); 90 leaves room for a
# busy machine.
TIMEOUT = os.environ.get("PT_GRADE_TEST_TIMEOUT", "90")


def grade(lab, subs, out, work, timeout, extra=()):
    """Grades the folder; returns ({name: verdict line}, the summary line)."""
    start = time.monotonic()
    r = subprocess.run([sys.executable, TOOL, str(lab), subs, "--out", out, "--work", work, "--timeout", timeout]
                       + list(extra), capture_output=True, text=True)
    print(f"grading lab {lab} took {time.monotonic() - start:.0f} s")
    print(r.stdout + r.stderr)
    expect(r.returncode == 0, f"grade_lab.py ran lab {lab} and exits 0")
    for row in csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8")):
        print(f"{row['name']}: {row['verdict']}, build {row['build_seconds']} s, tests {row['test_seconds']} s")
    lines = r.stdout.splitlines()
    return dict(line.split(": ", 1) for line in lines[:-1]), (lines[-1] if lines else "")


def check_lines(lines, expected):
    expect(list(lines) == sorted(expected), "one line per submission, in the order of the names")
    for name, pattern in expected.items():
        expect(re.fullmatch(pattern, lines.get(name, "")) is not None, f"{name}: {pattern}", lines.get(name, ""))


def check_summary(summary, expected):
    """The summary line counts the verdicts of expected (name: pattern)."""
    verdicts = [re.match(r"PASS|FAIL|COMPILE ERROR|TIMEOUT|CRASH|REFUSED", p).group(0) for p in expected.values()]
    want = ", ".join(f"{v} {verdicts.count(v)}" for v in ("PASS", "FAIL", "COMPILE ERROR", "TIMEOUT", "CRASH", "REFUSED")
                     if verdicts.count(v) or v != "CRASH")
    expect(summary == want, f"the summary line is '{want}'", summary)


def nothing_planted(work):
    targets, copy_to = plants(work)
    left = [t for t in targets + [copy_to] if os.path.exists(t)]
    expect(not left, "the submission that writes outside its folder planted nothing", ", ".join(left))
    for t in left:  # so that the next run starts clean
        os.remove(t)


def no_pictures_in_repository():
    expect(not os.path.exists(os.path.join(REPO, "test_pictures")), "nothing written into the repository (test_pictures/)")


# A FAIL line: the test in quotes, its check with the numbers, then the suspect.
FAIL = r'FAIL "[^"]+": (its check .+ failed with|an exception|FAIL|a fatal error).+ \(suspect: .+\)'


def lab2(subs, out, work):
    lab2_fixtures(subs, work, out)
    mutants = written_mutants(subs, 2, also=["uniform_theta_uniform"])  # that one is d_theta_uniform
    lines, summary = grade(2, subs, out, work, TIMEOUT)
    expected = {
        "a_correct": r"PASS",
        "b_syntax_error": r"COMPILE ERROR labs/lab2\.glsl:\d+(:\d+)?: error: .*",
        "c_pdf_2pi": (r'FAIL "sampling: each hemisphere sampler\'s pdf is the density of its mapping[^"]*": '
                      r'its check .*\d.* \(suspect: .*uniform_hemisphere_pdf.*\)'),
        "d_theta_uniform": r'FAIL "sampling: [^"]*": its check .*\d.* \(suspect: .*\)',
        "e_convention": r"PASS",
        # The grader's build keeps the lab's functions out of line: the line names the one that loops.
        "f_endless_loop": (r"TIMEOUT in sample_uniform_hemisphere\(\) after \S+ s.* "
                           r"\(warning: labs/lab2\.glsl:\d+(:\d+)?: warning: comparison .* always true.*\)"),
        "g_crash": r"CRASH SIGSEGV in \".*\"",
        "h_empty": r"COMPILE ERROR no lab2\.glsl in the submission",
        "r_includes_reference": r"REFUSED labs/lab2\.glsl:1: includes the reference solution common/kernel/uniform_hemisphere\.glsl",
        "r_writes_outside": r"REFUSED labs/lab2\.glsl:\d+: the preprocessor line '#ifdef __cplusplus': .*",
        "r_rewrites_report": r"REFUSED labs/lab2\.glsl:\d+: the preprocessor line '#ifdef __cplusplus': .*",
        "r_prints_1gb": r"REFUSED labs/lab2\.glsl:\d+: the preprocessor line '#ifdef __cplusplus': .*",
    }
    for mutant in mutants:  # each known-wrong answer fails, with a suspect
        expected["m_" + mutant] = FAIL
    check_lines(lines, expected)
    check_summary(summary, expected)
    rows = list(csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8")))
    expect([(row["name"], row["verdict"]) for row in rows] ==
           [(n, re.match(r"PASS|FAIL|COMPILE ERROR|TIMEOUT|CRASH|REFUSED", expected[n]).group(0)) for n in sorted(expected)],
           "grades.csv: one row per submission with its verdict")
    suite = ET.parse(os.path.join(out, "grades.xml")).getroot().find("testsuite")
    cases = {c.get("name"): c for c in suite.iter("testcase")}
    expect(sorted(cases) == sorted(expected) and suite.get("tests") == str(len(expected))
           and suite.get("failures") == str(2 + len(mutants)) and suite.get("errors") == "8",
           "grades.xml: one JUnit testcase per submission, a failure for each wrong answer, 8 errors")
    expect(all(cases[n].find("failure") is None and cases[n].find("error") is None for n in ("a_correct", "e_convention"))
           and cases["c_pdf_2pi"].find("failure").get("type") == "FAIL"
           and cases["r_prints_1gb"].find("error").get("type") == "REFUSED", "grades.xml: each testcase's outcome and type")
    expect(os.path.isfile(os.path.join(out, "logs", "a_correct.pictures", "uniform_hemisphere.png")),
           "the histogram of a submission is kept in logs/NAME.pictures/")
    nothing_planted(work)
    no_pictures_in_repository()


def lab2_sandbox_alone(subs, out, work):
    """The attacks again with the source check off (--unchecked-source): the sandbox alone
    must keep them from passing, planting files or flooding the grader."""
    os.makedirs(subs)
    lab2_fixtures(subs, work, out)
    for f in os.listdir(subs):
        if not f.startswith("r_"):
            path = os.path.join(subs, f)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
    lines, summary = grade(2, subs, out, work, TIMEOUT, ["--unchecked-source"])
    check_lines(lines, {
        "r_includes_reference": r"COMPILE ERROR .*common/kernel/uniform_hemisphere\.glsl.*reference solution.*",
        # No code runs during the build of pt_lab_tests, and the tests see the build read-only:
        # every write fails, and its estimator (no pdf) is graded.
        "r_writes_outside": FAIL,
        "r_rewrites_report": r"(FAIL|REFUSED) .*",
        "r_prints_1gb": r"REFUSED .*printed more than \d+ MB.*",
    })
    nothing_planted(work)
    no_pictures_in_repository()


def lab4(subs, out, work):
    os.makedirs(subs)
    lab4_fixtures(subs)
    mutants = written_mutants(subs, 4)
    expected = {"a_correct": r"PASS", "b_pdf_doubled": FAIL, "c_pdf_mismatch": FAIL}
    for mutant in mutants:
        expected["m_" + mutant] = FAIL
    lines, summary = grade(4, subs, out, work, "300")  # no endless loop among them
    check_lines(lines, expected)
    check_summary(summary, expected)
    failed = {row["name"]: row["failed_tests"].split("\n")
              for row in csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8"))}
    expect("light sampling: the mean of 1/pdf is the solid angle a triangle or a sphere subtends" in failed["b_pdf_doubled"],
           "b_pdf_doubled fails the mean of 1/pdf", repr(failed["b_pdf_doubled"]))
    expect(any(n.startswith("light sampling: triangle_light_pdf is d^2 / (cos_y area) times the pick")
               for n in failed["c_pdf_mismatch"]), "c_pdf_mismatch fails the held-back test", repr(failed["c_pdf_mismatch"]))


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == "--fast":
        return fast(sys.argv[2] if len(sys.argv) > 2 else None)
    if len(sys.argv) > 2:
        print("usage: tools/test_grade_lab.py --fast [PT_TESTS] | [WORK]", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="grade_lab_test_") as tmp:
        work = sys.argv[1] if len(sys.argv) == 2 else os.path.join(tmp, "work")
        subs, out = os.path.join(tmp, "submissions"), os.path.join(tmp, "out")
        os.makedirs(subs)
        bad_usage(tmp)
        labs = os.environ.get("PT_GRADE_TEST_LABS", "2,4").split(",")
        if "2" in labs:
            lab2(subs, out, work)
            lab2_sandbox_alone(os.path.join(tmp, "attacks"), os.path.join(tmp, "out_attacks"), work)
        if "4" in labs:
            lab4(os.path.join(tmp, "submissions_lab4"), os.path.join(tmp, "out_lab4"), work + "_lab4")
    return 0


if __name__ == "__main__":
    sys.exit(main())
