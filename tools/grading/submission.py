"""The students' submissions and the grade of each, for tools/grade_lab.py (grading a class's
lab submissions; tooling for teachers, not a part of the article). A submission is a file
NAME.glsl or a folder NAME/ that holds labLAB.glsl (or labs/labLAB.glsl). Grading one puts its
file in place of the work copy's labs/labLAB.glsl (with what depends on it deleted), rebuilds
pt_tests (a failure is COMPILE ERROR, with the first compiler line), runs the lab's tests in a
process group killed after --timeout seconds (TIMEOUT; a signal is CRASH) and reads their
Catch2 report into PASS or FAIL with the first line of each failed test's reason."""
import os
import re
import sys
import time

from . import BUILD_TIMEOUT, die, run_group
from .lab_tests import CONVENTION, read_catch_xml, signal_name
from .work_build import cmake_build, first_error, put_lab_file


def find_submissions(folder, lab, skip):
    """(name, path of the student's file or None), sorted by name; skips what is not a submission
    (and the folders in skip: --out and --work, should they be in the folder)."""
    found = []
    for entry in sorted(os.listdir(folder)):
        path = os.path.join(folder, entry)
        if entry.startswith(".") or os.path.realpath(path) in skip:
            continue
        if os.path.isdir(path):
            candidates = [os.path.join(path, f"lab{lab}.glsl"), os.path.join(path, "labs", f"lab{lab}.glsl")]
            found.append((entry, next((c for c in candidates if os.path.isfile(c)), None)))
        elif entry.endswith(".glsl"):
            found.append((entry[:-len(".glsl")], path))
        else:
            print(f"grade_lab: skipping '{path}': not NAME.glsl nor a folder", file=sys.stderr)
    return found


class Grade:
    def __init__(self, name, submission):
        self.name, self.submission = name, submission
        self.verdict, self.detail = "", ""
        self.failed, self.convention_only = [], False
        self.passed = self.total = 0
        self.build_s = self.test_s = 0.0

    def line(self):
        return f"{self.name}: {self.verdict}" + (f" {self.detail}" if self.detail else "")


def grade_one(g, ctx):
    """Grades g's submission in the lab build of ctx: sets its verdict, detail and counts."""
    if g.submission is None:
        g.verdict, g.detail = "COMPILE ERROR", f"no lab{ctx['args'].lab}.glsl in the submission"
        return
    install(g, ctx)
    if not build_submission(g, ctx):
        return
    rc, timed_out = run_tests(g, ctx)
    judge(g, ctx, rc, timed_out)


def install(g, ctx):
    """g's file as the work copy's labs/labLAB.glsl, with no output of the build left that
    depends on it (exits when pt_tests survives: no grade would be safe)."""
    a = ctx["args"]
    with open(g.submission, "rb") as fh:
        code = fh.read()
    put_lab_file(ctx["build"], ctx["lab_file"], code)
    if os.path.exists(ctx["test_bin"]):
        die(f"{ctx['test_bin']} survived the deletion of what depends on labs/lab{a.lab}.glsl: the build's "
            f"dependencies were not understood, so no grade would be safe; delete {a.work} and run again", 1)


def build_submission(g, ctx):
    """Rebuilds pt_tests with g's file; False (and COMPILE ERROR) when it does not build."""
    build_log = os.path.join(ctx["logs"], f"{g.name}.build.log")
    t0 = time.monotonic()
    rc, timed_out = cmake_build(ctx["cmake"], ctx["build"], ctx["args"].jobs, build_log)
    g.build_s = time.monotonic() - t0
    if timed_out or rc != 0 or not os.path.isfile(ctx["test_bin"]):
        g.verdict = "COMPILE ERROR"
        g.detail = (f"the build took over {BUILD_TIMEOUT} s" if timed_out
                    else first_error(build_log, ctx["src"]))
        return False
    return True


def test_env():
    """The environment of the tests: without the check build's switches or a seed offset."""
    return {k: v for k, v in os.environ.items() if k not in ("PT_LAB_STUB", "PT_LAB_MUTANT", "PT_TEST_SEED_OFFSET")}


def run_tests(g, ctx):
    """Runs the lab's tests on g's build, killed after --timeout seconds, with their Catch2 XML
    in logs/NAME.tests.xml. Returns (the return code, timed out)."""
    xml_path = os.path.join(ctx["logs"], f"{g.name}.tests.xml")
    test_log = os.path.join(ctx["logs"], f"{g.name}.tests.log")
    t0 = time.monotonic()
    rc, timed_out = run_group([ctx["test_bin"], "-#", "-r", "xml", "-o", xml_path] + ctx["specs"], test_log,
                              ctx["args"].timeout, env=test_env())
    g.test_s = time.monotonic() - t0
    return rc, timed_out


def catch_name(name):
    """A test's name as a Catch2 test spec that selects it alone: a backslash before the
    characters a spec gives a meaning (a comma separates specs, brackets hold tags)."""
    return "".join("\\" + c if c in ",[]\\\"" else c for c in name)


def crashed_in(g, ctx):
    """The test in which g's tests die of a signal: each test of the lab run alone, in the order
    of the run, until one dies (logs/NAME.crash.log holds the last one's output); None if none
    does. (Catch2 names the test in its report of the signal, but a report written to a file is
    buffered and a fatal signal may end the process before it is written out.)"""
    log = os.path.join(ctx["logs"], f"{g.name}.crash.log")
    for name in ctx["tests"]:
        rc, _ = run_group([ctx["test_bin"], "-#", catch_name(name)], log, ctx["args"].timeout, env=test_env())
        if rc < 0:
            return name
    return None


def judge(g, ctx, rc, timed_out):
    """g's verdict from the run of its tests: TIMEOUT, CRASH, PASS or FAIL."""
    cases, running = read_catch_xml(os.path.join(ctx["logs"], f"{g.name}.tests.xml"))
    g.total = len(ctx["tests"])
    g.passed = sum(1 for _, ok, _ in cases if ok)
    where = f" in \"{running}\"" if running else ""
    if timed_out:
        g.verdict, g.detail = "TIMEOUT", f"after {ctx['args'].timeout:g} s{where}"
        return
    if rc < 0:
        # Catch2 reports the signal in the test case it stopped, then dies of it; its XML file
        # may not have been written out that far, and then each test run alone says (crashed_in).
        fatal = next((n for n, ok, r in cases if r.startswith("FatalErrorCondition")), running)
        fatal = fatal or crashed_in(g, ctx)
        g.verdict, g.detail = "CRASH", signal_name(rc) + (f" in \"{fatal}\"" if fatal else "")
        return
    failed = [(n, r) for n, ok, r in cases if not ok]
    if rc == 0 and not failed and len(cases) == g.total:
        g.verdict = "PASS"
        return
    g.verdict = "FAIL"
    if not failed:
        g.failed = [f"pt_tests exited {rc} after {len(cases)} of {g.total} tests"]
        g.detail = g.failed[0]
        return
    explain_failures(g, failed, os.path.join(ctx["logs"], f"{g.name}.tests.log"))


def explain_failures(g, failed, test_log):
    """A FAIL's detail: the stubs the tests say are not written yet, then each failed test
    (marked when only a convention test) with the first line of its reason."""
    g.convention_only = all(n in CONVENTION for n, _ in failed)
    parts = []
    for n, r in failed:
        g.failed.append(n)
        parts.append(f"{'(convention) ' if n in CONVENTION else ''}{n} -> {r}")
    stub = sorted(set(re.findall(r"^lab \d+: (\w+) is not written yet", open(test_log, errors="replace").read(), re.M)))
    g.detail = (f"(not written: {', '.join(stub)}) " if stub else "") + "; ".join(parts)
