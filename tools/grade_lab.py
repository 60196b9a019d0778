#!/usr/bin/env python3
"""Grades a folder of lab submissions in one command (docs/labs/teachers.md). Tooling for
teachers, not a part of the article: the labs (docs/labs/README.md) ask a student for the
function that carries one of the article's Eq. (2) to (5), lab 5's slab test, or lab 6's MIS
weights of stage5_mis, and the project's own tests grade it; this script runs those tests on
every submission of a class, sealed.

usage: tools/grade_lab.py LAB SUBMISSIONS_DIR [--out DIR] [--timeout SECONDS] [--jobs N] [--work DIR] [--unsealed]
       [--compiler-cache]

A submission is a file NAME.glsl (the student's labs/labLAB.glsl) or a folder NAME/ that holds
labLAB.glsl (or labs/labLAB.glsl). For each, in the order of the names:
  1. the file must be GLSL only: the kernel's #includes and include guards, no other
     preprocessor line (no C++ hidden from GLSL behind #ifdef __cplusplus), no #include of a
     reference solution; else REFUSED (grading/source_check.py);
  2. it becomes labs/labLAB.glsl of a copy of this repository (WORK/src), and every output of
     the lab build (WORK/src/build, -DPT_LAB=LAB) that depends on it is deleted first, so a
     submission that does not compile leaves no test program at all (issue 24);
  3. pt_tests is rebuilt inside bubblewrap (grading/sandbox.py): the system and WORK/src
     read-only, the lab's reference solutions replaced by placeholders, no network, a private
     /tmp, limits on CPU time, memory, processes and file size; a failure is COMPILE ERROR;
  4. the lab's tests run inside bubblewrap as well, the build read-only too, the held-back
     tests' sources hidden, WORK/run/NAME the one folder they may write; their Catch2 report
     comes over a pipe the grader holds (no file the tests could rewrite), and stdout and
     stderr over pipes read up to a cap. After --timeout seconds: TIMEOUT, naming the lab
     function that was running when gdb can see it.
One line per student on stdout, as each finishes (stderr: the progress, [k/n]):
  NAME: PASS | FAIL "<test>": <its first failed check, with the numbers> (suspect: <mistake>)
  | COMPILE ERROR <file:line: message> | TIMEOUT <where> | CRASH <signal> | REFUSED <why>
with the compiler's warnings on the student's file after it, then a summary line
(PASS 4, FAIL 4, COMPILE ERROR 2, TIMEOUT 1, REFUSED 1). The suspects come from the lab
page's table "If a test fails" (docs/labs/labLAB.md). OUT/grades.csv and OUT/grades.xml (JUnit)
hold the same verdicts; OUT/logs/ each student's build log, test log, report and pictures.
Without a usable bubblewrap the grader says so in one line and grades nothing, unless
--unsealed (student code then runs as the grader's user: only in a throwaway account).
Exit status: 0 when grading ran (whatever the verdicts), 1 when the lab build fails without any
student's code or no sandbox is available, 2 for bad usage."""
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
from grading.hints import read_hints  # noqa: E402
from grading.reports import fresh_logs, write_reports  # noqa: E402
from grading.sandbox import Sandbox, probe  # noqa: E402
from grading.stuck import finder, lab_functions  # noqa: E402
from grading.submission import Grade, find_submissions, grade_one, summary  # noqa: E402
from grading.depends import put_lab_file  # noqa: E402
from grading.compiler_cache import compiler_cache  # noqa: E402
from grading.hidden import held_back_tests, placeholders  # noqa: E402
from grading.work_build import lock_work, set_up, work_paths  # noqa: E402
from make_lab_handout import HELD_BACK_FILES, REFERENCE_FILES  # noqa: E402


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
    p.add_argument("--unsealed", action="store_true",
                   help="grade without the sandbox when bubblewrap cannot run (student code runs as you)")
    # For the grader's own test: skip the check that a lab file is GLSL only, so that the
    # sandbox alone is tried against C++ hidden behind #ifdef __cplusplus.
    p.add_argument("--unchecked-source", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--compiler-cache", action="store_true",
                   help="the set-up reads the libraries' objects from your ccache cache, read-only (after "
                        "./tutorial test's build, about half of a set-up; the work folder inside the checkout)")
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


# The stage programs that the tests start: where an endless loop may be, besides the test program.
STAGES = {"stage1_raycast", "stage2_montecarlo", "stage3_importance", "stage4_direct_indirect", "stage5_mis"}


def sandbox_for(a, src):
    """The Sandbox of this run: sealed unless --unsealed; exits when no sandbox can run here."""
    if not a.unsealed:
        why = probe()
        if why:
            die(f"no sandbox: {why}. Nothing was graded: student code would run as you, unsealed; "
                f"fix that, or grade in a throwaway account with --unsealed", 1)
    else:
        print("grade_lab: --unsealed: the students' code runs as you, without a sandbox", file=sys.stderr)
    references = sorted({rel for rels in REFERENCE_FILES.values() for rel in rels})
    box = Sandbox(not a.unsealed, src, {}, {})
    return box, references


def main(argv):
    a = parse_args(argv)
    a.work = os.path.realpath(a.work or os.path.join(REPO, f"build-grade-lab{a.lab}"))
    out = os.path.realpath(a.out or os.path.join(a.work, "grades"))
    submissions = checked_submissions(a, out)
    cmake, ctest = shutil.which("cmake"), shutil.which("ctest")
    if not cmake or not ctest:
        die("cmake and ctest are needed (./tutorial test installs them)", 1)
    src, build = work_paths(a.work)
    a.cache = compiler_cache(a.compiler_cache)
    os.makedirs(a.work, exist_ok=True)
    box, references = sandbox_for(a, src)
    lock = lock_work(a.work)  # noqa: F841 (held while this process runs)
    logs = fresh_logs(out)
    start = time.monotonic()
    # The lab's own references are hidden from the setup build too: the lab build never uses them.
    lab_file, original, lab_stamp, setup = set_up(REPO, a, box, out, logs, cmake, ctest, len(submissions),
                                       REFERENCE_FILES[a.lab] + HELD_BACK_FILES)
    box.hidden_in_tests = dict(box.hidden_in_build)
    box.hidden_in_tests.update(placeholders(a.work, src, held_back_tests(src), "a held-back test"))
    setup_s, setup_cpu = time.monotonic() - start, box.cpu_seconds
    ctx = {"args": a, "work": a.work, "src": src, "build": build, "logs": logs, "lab_file": lab_file,
           "lab_stamp": lab_stamp,
           "cmake": cmake, "target": setup.get("target", TEST_TARGET),
           "test_bin": os.path.join(build, "bin", setup.get("target", TEST_TARGET)),
           "specs": setup["specs"], "tests": setup["tests"], "by_file": setup.get("by_file"),
           "durations": os.path.join(a.work, "test_durations.json"), "sandbox": box, "references": references,
           "hints": read_hints(src, a.lab),
           "on_timeout": finder(lab_functions(original.decode(errors="replace")), {setup.get("target", TEST_TARGET)} | STAGES)}
    print(f"grade_lab: set up in {setup_s:.0f} s ({setup_cpu:.0f} s CPU); {len(ctx['tests'])} tests per submission, "
          f"{'sealed (bubblewrap)' if box.sealed else 'UNSEALED'}, --jobs {a.jobs}", file=sys.stderr, flush=True)

    grades = []
    try:
        for k, (name, path) in enumerate(submissions, 1):
            print(f"grade_lab: [{k}/{len(submissions)}] {name} ...", file=sys.stderr, flush=True)
            g = Grade(name, path)
            grade_one(g, ctx)
            grades.append(g)
            print(g.line(), flush=True)
            left = (time.monotonic() - start - setup_s) / k * (len(submissions) - k)
            print(f"grade_lab: [{k}/{len(submissions)}] {name}: {g.verdict}, built in {g.build_s:.1f} s ({g.build_cpu:.1f} s "
                  f"CPU), tested in {g.test_s:.1f} s ({g.test_cpu:.1f} s CPU)"
                  + (f"; about {left / 60:.0f} min left" if k < len(submissions) else ""), file=sys.stderr, flush=True)
    finally:
        # Leave the work copy as the repository has it, and no student's binaries behind.
        put_lab_file(build, lab_file, original, lab_stamp)
        elapsed = time.monotonic() - start
        write_reports(out, a.lab, grades, elapsed)
    print(summary(grades), flush=True)
    timed = [g for g in grades if g.build_s > 0]
    per = (f"; per submission built and tested {min(g.build_s + g.test_s for g in timed):.0f}-"
           f"{max(g.build_s + g.test_s for g in timed):.0f} s") if timed else ""
    print(f"grade_lab: {len(grades)} submission(s) graded in {elapsed:.0f} s (setup {setup_s:.0f} s{per}); "
          f"{os.path.join(out, 'grades.csv')}, {os.path.join(out, 'grades.xml')}, logs in {logs}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:  # the running build or tests are killed with their session (grading/sandbox.py)
        die("interrupted: the grades of the students graded so far are in --out", 130)
