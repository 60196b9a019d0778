#!/usr/bin/env python3
"""Grades a folder of lab submissions in one command (docs/labs/teachers.md). Tooling for
teachers, not a part of the article: the labs (docs/labs/README.md) ask a student for the
function that carries one of the article's Eq. (2) to (5), lab 5's slab test, or lab 6's MIS
weights of stage5_mis, and the project's own tests grade it; this script runs those tests on
every submission of a class.

usage: tools/grade_lab.py LAB SUBMISSIONS_DIR [--out DIR] [--timeout SECONDS] [--jobs N] [--work DIR]

A submission is a file NAME.glsl (the student's labs/labLAB.glsl) or a folder NAME/ that holds
labLAB.glsl (or labs/labLAB.glsl). For each, in the order of the names:
  1. its file becomes labs/labLAB.glsl of a copy of this repository (WORK/src), and every
     output of the lab build (WORK/build, configured with -DPT_LAB=LAB) that depends on that
     file is deleted first: objects, SPIR-V headers, the libraries and programs linked from
     them, pt_tests among them. The dependencies are the build's own (the compilers' depfiles
     and CMake's rules), so a submission that does not compile leaves no test program at all,
     never the previous student's (issue 24: that one passed `ctest -L lab2`);
  2. pt_tests is rebuilt; a failed build is COMPILE ERROR, with the first compiler line;
  3. the lab's tests run: the Catch2 specs of the ctest entries labelled labLAB, less the
     tests that cannot reach the student's functions (EXCLUDED, grading/lab_tests.py), in a
     process group of their own, killed after --timeout seconds (TIMEOUT); a signal is CRASH.
One line per student on stdout:
  NAME: PASS | FAIL <criterion -> first line of its reason>; ... | COMPILE ERROR <first line>
  | TIMEOUT <where> | CRASH <signal> <where>
A failing test that checks only the project's convention (CONVENTION, grading/lab_tests.py;
none at present: the samplers' tests accept every convention) is marked "(convention)", apart
from a wrong estimator. OUT/grades.csv and OUT/grades.xml (JUnit, one testcase per student)
hold the same verdicts; OUT/logs/ each student's build log, test log and Catch2 XML.
Exit status: 0 when grading ran (whatever the verdicts), 1 when the lab build fails without any
student's code (the repository's own labs/labLAB.glsl), 2 for bad usage.
Student code runs as the teacher's user: grade in an account or container that holds nothing
else of value. This script reads the command line and runs the steps; tools/grading/ does them."""
import argparse
import os
import re
import shutil
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from grading import TEST_TARGET, USAGE, die  # noqa: E402
from grading.reports import fresh_logs, write_reports  # noqa: E402
from grading.submission import Grade, find_submissions, grade_one  # noqa: E402
from grading.work_build import lock_work, put_lab_file, set_up  # noqa: E402


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2
        die(f"{message} ({USAGE})", 2)


def parse_args(argv):
    p = Parser(prog="tools/grade_lab.py", add_help=True, usage=USAGE[len("usage: "):])
    p.add_argument("lab", nargs="?", help="the lab number, 1-6")
    p.add_argument("submissions", nargs="?", help="a folder of NAME.glsl files or NAME/ folders")
    p.add_argument("--out", help="where grades.csv, grades.xml and logs/ go (default WORK/grades)")
    p.add_argument("--timeout", type=float, default=300.0, help="seconds for one submission's tests (default 300)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 2, help="compiler jobs (default: all cores)")
    p.add_argument("--work", help="the lab build's folder, kept between runs (default build-grade-labLAB in the repository)")
    a = p.parse_args(argv)
    if a.lab is None or a.submissions is None:
        die(f"missing the {'lab number and the ' if a.lab is None else ''}submissions folder ({USAGE})", 2)
    if not re.fullmatch(r"[1-6]", a.lab):
        die(f"the lab is '{a.lab}': give 1, 2, 3, 4, 5 or 6 ({USAGE})", 2)
    a.lab = int(a.lab)
    if not os.path.isdir(a.submissions):
        die(f"no folder '{a.submissions}' of submissions ({USAGE})", 2)
    if a.timeout <= 0 or a.jobs < 1:
        die(f"--timeout and --jobs must be positive ({USAGE})", 2)
    return a


def checked_submissions(a, out):
    """The submissions of the folder (find_submissions); exits when there are none, or two of one name."""
    submissions = find_submissions(a.submissions, a.lab, {a.work, out})
    names = [name for name, _ in submissions]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        die(f"two submissions are called '{twice[0]}' in '{a.submissions}' (NAME.glsl and NAME/): keep one", 2)
    if not submissions:
        die(f"no submissions in '{a.submissions}': expected NAME.glsl files or NAME/ folders holding lab{a.lab}.glsl", 2)
    return submissions


def main(argv):
    a = parse_args(argv)
    a.work = os.path.realpath(a.work or os.path.join(REPO, f"build-grade-lab{a.lab}"))
    out = os.path.realpath(a.out or os.path.join(a.work, "grades"))
    submissions = checked_submissions(a, out)
    cmake, ctest = shutil.which("cmake"), shutil.which("ctest")
    if not cmake or not ctest:
        die("cmake and ctest are needed (./tutorial test installs them)", 1)
    src, build = os.path.join(a.work, "src"), os.path.join(a.work, "build")
    os.makedirs(a.work, exist_ok=True)
    lock = lock_work(a.work)  # noqa: F841 (held while this process runs)
    logs = fresh_logs(out)
    start = time.monotonic()
    lab_file, original, setup = set_up(REPO, a, out, logs, cmake, ctest, len(submissions))
    ctx = {"args": a, "src": src, "build": build, "logs": logs, "lab_file": lab_file, "cmake": cmake,
           "test_bin": os.path.join(build, "bin", TEST_TARGET), "specs": setup["specs"], "tests": setup["tests"]}
    print(f"grade_lab: set up in {time.monotonic() - start:.0f} s; {len(ctx['tests'])} tests per submission "
          f"({ctx['specs'][0]})", file=sys.stderr)

    grades = []
    try:
        for name, path in submissions:
            g = Grade(name, path)
            grade_one(g, ctx)
            grades.append(g)
            print(g.line(), flush=True)
    finally:
        # Leave the work copy as the repository has it, and no student's binaries behind.
        put_lab_file(build, lab_file, original)
        elapsed = time.monotonic() - start
        write_reports(out, a.lab, grades, elapsed)
    print(f"grade_lab: {len(grades)} submission(s) graded in {elapsed:.0f} s; {os.path.join(out, 'grades.csv')}, "
          f"{os.path.join(out, 'grades.xml')}, logs in {logs}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:  # the running build or tests are killed with their group (run_group)
        die("interrupted: the grades of the students graded so far are in --out", 130)
