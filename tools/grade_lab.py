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
     tests that cannot reach the student's functions (EXCLUDED below), in a process group of
     their own, killed after --timeout seconds (TIMEOUT); a signal is CRASH.
One line per student on stdout:
  NAME: PASS | FAIL <criterion -> first line of its reason>; ... | COMPILE ERROR <first line>
  | TIMEOUT <where> | CRASH <signal> <where>
A failing test that checks only the project's convention (CONVENTION below; none at present:
the samplers' tests accept every convention) is marked "(convention)", apart from a wrong
estimator. OUT/grades.csv and OUT/grades.xml (JUnit, one testcase per
student) hold the same verdicts; OUT/logs/ each student's build log, test log and Catch2 XML.
Exit status: 0 when grading ran (whatever the verdicts), 1 when the lab build fails without any
student's code (the repository's own labs/labLAB.glsl), 2 for bad usage.
Student code runs as the teacher's user: grade in an account or container that holds nothing
else of value."""
import argparse
import csv
import fcntl
import filecmp
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from xml.sax.saxutils import escape, quoteattr

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)

# The tests of each lab's groups (tests/CMakeLists.txt, PT_TEST_GROUPS) that do not grade the
# student's functions, as Catch2 exclusions (-# adds [#file] tags):
#   lab 2: the GGX tests ([ggx]), the lobe energy ([energy]) and the mixed material's choice
#          never call the uniform hemisphere sampler (bsdf.glsl samples cosine and GGX lobes);
#   labs 2-4: pt_compare's tests of a stage ([compare]) render both of their sides with the
#          student's stage, so they grade pt_compare, not the student;
#   labs 2-3: the sampler checks' own mutation tests ([mutants]) never call the student's code;
#   lab 5: the BVH build ([#test_bvh]), the CPU's SIMD walk (cpu/wide_bvh_walk.cpp compiles
#          the reference box_slab.glsl, [#test_wide_bvh]), the summary line ([cli]), the
#          icosphere ([scene]) and the storage-buffer limit ([reliability]);
#   lab 6: the spherical triangles and the light sample by solid angle ([solid_angle]), which
#          neither weigh a sample nor ask light_pdf.
EXCLUDED = {
    1: [],
    2: ["[ggx]", "[energy]", '"sampling: a mixed material*"', "[compare]", "[mutants]"],
    3: ["[ggx]", "[compare]", "[mutants]"],
    4: ["[compare]"],
    5: ["[#test_bvh]", "[#test_wide_bvh]", "[cli]", "[scene]", "[reliability]"],
    6: ["[solid_angle]"],
}
# Tests that check the project's convention rather than the estimator. None now: the
# hemisphere samplers are graded by their mapping's density, which holds for every
# convention (tests/common/kernel/test_sampling.cpp), so a sampler with another mapping of u
# passes. A convention test added later goes here, and its failures are marked apart.
CONVENTION = set()
TEST_TARGET = "pt_tests"
BUILD_TIMEOUT = 3600  # seconds: the first build of a lab takes ~7 min on 2 cores
USAGE = "usage: tools/grade_lab.py LAB SUBMISSIONS_DIR [--out DIR] [--timeout SECONDS] [--jobs N] [--work DIR]"


def die(message, status):
    print(f"grade_lab: {message}", file=sys.stderr)
    sys.exit(status)


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2
        die(f"{message} ({USAGE})", 2)


def parse_args(argv):
    p = Parser(prog="tools/grade_lab.py", add_help=True, usage=USAGE)
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


# ---------------------------------------------------------------- the work copy and its build

def sync_tree(src, dest, skip):
    """Makes dest a copy of the repository src without .git, out/ and build folders (build*/ and
    any folder that holds a CMakeCache.txt). Rewrites only the files whose content differs, so
    that the build after it recompiles only what changed. Returns how many files it wrote or
    removed."""
    keep, changed = set(), 0
    for root, dirs, files in os.walk(src):
        rel = os.path.relpath(root, src)
        dirs[:] = sorted(d for d in dirs if d not in (".git", "__pycache__")
                         and not (rel == "." and (d.startswith("build") or d == "out"))
                         and os.path.realpath(os.path.join(root, d)) not in skip
                         and not os.path.isfile(os.path.join(root, d, "CMakeCache.txt")))
        os.makedirs(os.path.join(dest, rel), exist_ok=True)
        for f in files:
            s, d = os.path.join(root, f), os.path.normpath(os.path.join(dest, rel, f))
            keep.add(d)
            if not os.path.isfile(d) or not filecmp.cmp(s, d, shallow=False):
                shutil.copyfile(s, d)
                shutil.copymode(s, d)
                changed += 1
    for root, dirs, files in os.walk(dest):
        for f in files:
            if os.path.normpath(os.path.join(root, f)) not in keep:
                os.remove(os.path.join(root, f))
                changed += 1
    return changed


def make_tokens(text):
    """The words of a make rule or depfile: backslash-newlines joined, '\\ ' kept in a name."""
    text = text.replace("\\\n", " ")
    return [t.replace("\\ ", " ") for t in re.findall(r"(?:\\ |[^\s])+", text)]


def dependency_graph(build):
    """prerequisite -> the outputs made from it, from CMake's Makefile rules (build.make) and the
    compilers' depfiles (*.o.d). Paths inside the build folder are relative to it, others absolute."""
    def node(path, cwd):
        p = os.path.normpath(path if os.path.isabs(path) else os.path.join(cwd, path))
        return os.path.relpath(p, build) if p.startswith(build + os.sep) else p

    users = {}
    for root, _, files in os.walk(build):
        for f in files:
            path = os.path.join(root, f)
            if f == "build.make":
                lines = open(path, encoding="utf-8", errors="replace").read().replace("\\\n", " ").splitlines()
                for line in lines:
                    if not line or line[0] in "\t#" or ":" not in line or line.startswith("."):
                        continue
                    m = re.match(r"^((?:\\ |[^\s:])+)\s*:(?!=)(.*)$", line)
                    if not m:
                        continue
                    target = node(make_tokens(m.group(1))[0], build)
                    for dep in make_tokens(m.group(2)):
                        users.setdefault(node(dep, build), set()).add(target)
            elif f.endswith(".o.d"):
                tokens = make_tokens(open(path, encoding="utf-8", errors="replace").read())
                if not tokens or not tokens[0].endswith(":"):
                    continue
                # gcc runs in the target's folder, the part of the path before CMakeFiles/.
                cwd = path.split(os.sep + "CMakeFiles" + os.sep)[0]
                target = os.path.relpath(path[:-2], build)
                for dep in tokens[1:]:
                    if dep.endswith(":"):  # -MP phony rules
                        continue
                    users.setdefault(node(dep, cwd), set()).add(target)
    return users


def delete_dependents(build, lab_file):
    """Deletes every output of the build that depends on lab_file; returns how many existed."""
    users = dependency_graph(build)
    seen, todo = set(), [os.path.normpath(lab_file)]
    while todo:
        for out in users.get(todo.pop(), ()):
            if out not in seen:
                seen.add(out)
                todo.append(out)
    deleted = 0
    for out in seen:
        path = os.path.join(build, out)
        if not os.path.isabs(out) and os.path.isfile(path):  # only what the build made
            os.remove(path)
            deleted += 1
    return deleted


def run_group(cmd, log_path, timeout, cwd=None, env=None):
    """Runs cmd in a new process group with its output in log_path; kills the whole group after
    timeout seconds (and any of its processes left behind). Returns (returncode, timed_out)."""
    with open(log_path, "wb") as log:
        p = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, cwd=cwd,
                             env=env, start_new_session=True)
        timed_out = False
        try:
            p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
        finally:
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            p.wait()
    return p.returncode, timed_out


ERROR_LINE = re.compile(r"(:\d+(:\d+)?: (fatal )?error:)|(^ERROR: )|(undefined reference to)|(: error:)")


def first_error(log_path, src):
    """The first compiler, glslang or linker error line of a build log, with the work copy's
    paths shortened to the repository's (labs/lab2.glsl:14:3: error: ...)."""
    lines = open(log_path, encoding="utf-8", errors="replace").read().splitlines()
    at = next((i for i, l in enumerate(lines) if ERROR_LINE.search(l)), None)
    pick = None if at is None else lines[at]
    if pick is not None and pick.rstrip().endswith(":") and at + 1 < len(lines):
        pick += " " + lines[at + 1].strip()  # glslang names the function on the next line
    if pick is None:
        pick = next((l for l in lines if re.search(r"error", l, re.I) and "***" not in l), None)
    if pick is None:
        pick = lines[-1] if lines else "the build failed without a message"
    pick = " ".join(pick.replace(src + os.sep, "").split())
    # glslang's "ERROR: FILE:LINE: 'x' : message" in the compilers' form "FILE:LINE: error: 'x' : message"
    return re.sub(r"^ERROR: (\S+?:\d+): ", r"\1: error: ", pick)


def cmake_build(cmake, build, jobs, log_path):
    return run_group([cmake, "--build", build, "--target", TEST_TARGET, "-j", str(jobs)], log_path, BUILD_TIMEOUT)


# ---------------------------------------------------------------- the tests and their verdict

def lab_specs(ctest, build, lab):
    """The Catch2 specs of the ctest entries labelled labN, with EXCLUDED's tests left out."""
    r = subprocess.run([ctest, "--test-dir", build, "-L", f"^lab{lab}$", "--show-only=json-v1"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        die(f"ctest cannot list lab {lab}'s tests in {build}: {r.stderr.strip()}", 1)
    specs = []
    for test in json.loads(r.stdout).get("tests", []):
        command = test.get("command", [])
        if len(command) == 2 and os.path.basename(command[0]) == TEST_TARGET:
            specs.append(command[1] + "".join("~" + e for e in EXCLUDED[lab]))
        elif command:
            die(f"lab {lab}'s ctest entry '{test.get('name')}' does not run {TEST_TARGET} with one spec: "
                f"tools/grade_lab.py does not know how to grade it", 1)
    if not specs:
        die(f"no ctest entry is labelled lab{lab} in {build}", 1)
    return [",".join(specs)]  # one argument: Catch2 ORs the comma-separated specs (several arguments AND)


def short(text, limit=240):
    line = " ".join(text.strip().splitlines()[0].split()) if text.strip() else ""
    return line if len(line) <= limit else line[:limit - 3] + "..."


def failure_reason(case):
    """The first line of why a Catch2 <TestCase> failed: its first failed assertion (with the
    INFO just before it), exception, FAIL message or fatal condition."""
    infos = []
    for el in case.iter():
        if el.tag == "Info":
            infos.append(el.text or "")
        elif el.tag == "Expression":
            if el.get("success") == "false":
                orig = (el.findtext("Original") or "").strip()
                expanded = (el.findtext("Expanded") or "").strip()
                reason = f"{el.get('type', 'CHECK')}({short(orig)})"
                if expanded and expanded != orig:
                    reason += f" with {short(expanded)}"
                exc = el.find("Exception")
                if exc is not None:
                    reason += f": exception {short(exc.text or '')}"
                if infos and short(infos[-1]):
                    reason += f" [{short(infos[-1], 160)}]"
                return reason
            infos = []
        elif el.tag in ("Exception", "FatalErrorCondition", "Failure") and el is not case:
            return f"{el.tag}: {short(el.text or '')}"
    return "failed (no assertion recorded)"


def read_catch_xml(path):
    """(finished test cases as (name, success, reason), the name of a test case left unfinished).
    A report cut short by a kill is read as far as it goes."""
    parser = ET.XMLPullParser(events=("start", "end"))
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            parser.feed(fh.read())
    except (OSError, ET.ParseError):
        pass
    cases, running = [], None
    try:
        for event, el in parser.read_events():
            if el.tag != "TestCase":
                continue
            if event == "start":
                running = el.get("name")
            else:
                result = el.find("OverallResult")
                ok = result is not None and result.get("success") == "true"
                cases.append((el.get("name"), ok, "" if ok else failure_reason(el)))
                running = None
    except ET.ParseError:
        pass
    return cases, running


def signal_name(rc):
    try:
        return signal.Signals(-rc).name
    except ValueError:
        return f"signal {-rc}"


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
    a, src, build = ctx["args"], ctx["src"], ctx["build"]
    logs = ctx["logs"]
    if g.submission is None:
        g.verdict, g.detail = "COMPILE ERROR", f"no lab{a.lab}.glsl in the submission"
        return
    with open(g.submission, "rb") as fh:
        code = fh.read()
    with open(ctx["lab_file"], "wb") as fh:  # a new file, written now
        fh.write(code)
    delete_dependents(build, ctx["lab_file"])
    if os.path.exists(ctx["test_bin"]):
        die(f"{ctx['test_bin']} survived the deletion of what depends on labs/lab{a.lab}.glsl: the build's "
            f"dependencies were not understood, so no grade would be safe; delete {a.work} and run again", 1)
    t0 = time.monotonic()
    rc, timed_out = cmake_build(ctx["cmake"], build, a.jobs, os.path.join(logs, f"{g.name}.build.log"))
    g.build_s = time.monotonic() - t0
    if timed_out or rc != 0 or not os.path.isfile(ctx["test_bin"]):
        g.verdict = "COMPILE ERROR"
        g.detail = (f"the build took over {BUILD_TIMEOUT} s" if timed_out
                    else first_error(os.path.join(logs, f"{g.name}.build.log"), src))
        return
    xml_path = os.path.join(logs, f"{g.name}.tests.xml")
    test_log = os.path.join(logs, f"{g.name}.tests.log")
    env = {k: v for k, v in os.environ.items() if k not in ("PT_LAB_STUB", "PT_TEST_SEED_OFFSET")}
    t0 = time.monotonic()
    rc, timed_out = run_group([ctx["test_bin"], "-#", "-r", "xml", "-o", xml_path] + ctx["specs"], test_log,
                              a.timeout, env=env)
    g.test_s = time.monotonic() - t0
    cases, running = read_catch_xml(xml_path)
    g.total = len(ctx["tests"])
    g.passed = sum(1 for _, ok, _ in cases if ok)
    where = f" in \"{running}\"" if running else ""
    if timed_out:
        g.verdict, g.detail = "TIMEOUT", f"after {a.timeout:g} s{where}"
        return
    if rc < 0:
        # Catch2 reports the signal in the test case it stopped, then dies of it.
        fatal = next((n for n, ok, r in cases if r.startswith("FatalErrorCondition")), running)
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
    g.convention_only = all(n in CONVENTION for n, _ in failed)
    parts = []
    for n, r in failed:
        g.failed.append(n)
        parts.append(f"{'(convention) ' if n in CONVENTION else ''}{n} -> {r}")
    stub = sorted(set(re.findall(r"^lab \d+: (\w+) is not written yet", open(test_log, errors="replace").read(), re.M)))
    g.detail = (f"(not written: {', '.join(stub)}) " if stub else "") + "; ".join(parts)


# ---------------------------------------------------------------- the reports

def write_reports(out, lab, grades, elapsed):
    with open(os.path.join(out, "grades.csv"), "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["name", "verdict", "convention_only", "tests_passed", "tests_total", "failed_criteria", "detail",
                    "build_seconds", "test_seconds", "submission"])
        for g in grades:
            w.writerow([g.name, g.verdict, "yes" if g.convention_only else "no", g.passed, g.total, "; ".join(g.failed),
                        g.detail, f"{g.build_s:.1f}", f"{g.test_s:.1f}", g.submission or ""])
    failures = sum(1 for g in grades if g.verdict == "FAIL")
    errors = sum(1 for g in grades if g.verdict not in ("PASS", "FAIL"))
    xml = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<testsuites name="lab{lab}" tests="{len(grades)}" failures="{failures}" errors="{errors}" time="{elapsed:.1f}">',
           f'  <testsuite name="lab{lab}" tests="{len(grades)}" failures="{failures}" errors="{errors}" skipped="0" '
           f'time="{elapsed:.1f}" timestamp="{time.strftime("%Y-%m-%dT%H:%M:%S")}">']
    for g in grades:
        xml.append(f'    <testcase classname="lab{lab}" name={quoteattr(g.name)} time="{g.build_s + g.test_s:.1f}">')
        if g.verdict == "FAIL":
            kind = "FAIL convention" if g.convention_only else "FAIL"
            xml.append(f'      <failure type="{kind}" message={quoteattr(g.detail)}>{escape(chr(10).join(g.failed))}</failure>')
        elif g.verdict != "PASS":
            xml.append(f'      <error type="{g.verdict}" message={quoteattr(g.detail)}/>')
        xml.append(f"      <system-out>{escape(g.line())}</system-out>")
        xml.append("    </testcase>")
    xml += ["  </testsuite>", "</testsuites>", ""]
    with open(os.path.join(out, "grades.xml"), "w", encoding="utf-8") as fh:
        fh.write("\n".join(xml))


def main(argv):
    a = parse_args(argv)
    a.work = os.path.realpath(a.work or os.path.join(REPO, f"build-grade-lab{a.lab}"))
    out = os.path.realpath(a.out or os.path.join(a.work, "grades"))
    submissions = find_submissions(a.submissions, a.lab, {a.work, out})
    names = [name for name, _ in submissions]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        die(f"two submissions are called '{twice[0]}' in '{a.submissions}' (NAME.glsl and NAME/): keep one", 2)
    if not submissions:
        die(f"no submissions in '{a.submissions}': expected NAME.glsl files or NAME/ folders holding lab{a.lab}.glsl", 2)
    cmake, ctest = shutil.which("cmake"), shutil.which("ctest")
    if not cmake or not ctest:
        die("cmake and ctest are needed (./tutorial test installs them)", 1)
    src, build = os.path.join(a.work, "src"), os.path.join(a.work, "build")
    os.makedirs(a.work, exist_ok=True)
    lock = open(os.path.join(a.work, "lock"), "w")
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        die(f"another tools/grade_lab.py is using {a.work}: wait for it, or give this one another --work", 1)
    logs = os.path.join(out, "logs")
    os.makedirs(logs, exist_ok=True)
    for stale in os.listdir(logs):
        os.remove(os.path.join(logs, stale))
    start = time.monotonic()

    # The work copy of the repository and its lab build. The first time, and whenever the
    # repository changed since, the build runs once with the repository's own labs/labN.glsl
    # (the handout's stub): a failure there is not a student's. Its list of the lab's tests is
    # kept in WORK/setup.json, so that a later run with an unchanged repository skips it.
    changed = sync_tree(REPO, src, {a.work, out})
    lab_file = os.path.join(src, "labs", f"lab{a.lab}.glsl")
    original = open(lab_file, "rb").read()
    cache = os.path.join(build, "CMakeCache.txt")
    fresh = not os.path.isfile(cache)
    if not fresh:
        configured = re.search(r"^PT_LAB:STRING=(\S*)", open(cache, encoding="utf-8", errors="replace").read(), re.M)
        if not configured or configured.group(1) != str(a.lab):
            die(f"{a.work} holds the build of another lab ({configured.group(1) if configured else '?'}): "
                f"give lab {a.lab} a --work of its own ({USAGE})", 2)
    stamp = os.path.join(a.work, "setup.json")
    setup = None
    if not fresh and not changed and os.path.isfile(stamp):
        setup = json.load(open(stamp, encoding="utf-8"))
        setup = setup if setup.get("lab") == a.lab else None
    if setup is None and os.path.exists(stamp):
        os.remove(stamp)
    print(f"grade_lab: lab {a.lab}, {len(submissions)} submission(s); the lab build is {build}"
          + (" (new: the first build takes ~7 min on 2 cores)" if fresh else "")
          + (", unchanged since the last run" if setup else ""), file=sys.stderr)
    setup_log = os.path.join(logs, "_setup.log")
    if setup is None:
        if fresh:
            rc, _ = run_group([cmake, "-S", src, "-B", build, "-G", "Unix Makefiles", "-DCMAKE_BUILD_TYPE=Release",
                               f"-DPT_LAB={a.lab}", "-DPT_CPU_GENERAL_ONLY=ON"], setup_log, BUILD_TIMEOUT)
            if rc != 0:
                die(f"the lab build does not configure: see {setup_log}", 1)
        delete_dependents(build, lab_file)
        rc, timed_out = cmake_build(cmake, build, a.jobs, setup_log)
        if rc != 0 or timed_out:
            die(f"the lab build fails with the repository's own labs/lab{a.lab}.glsl, before any submission: "
                f"{first_error(setup_log, src)} (see {setup_log})", 1)
        specs = lab_specs(ctest, build, a.lab)
        listing = subprocess.run([os.path.join(build, "bin", TEST_TARGET), "-#", "--list-test-names-only"] + specs,
                                 capture_output=True, text=True)
        setup = {"lab": a.lab, "specs": specs, "tests": [l for l in listing.stdout.splitlines() if l.strip()]}
        if not setup["tests"]:
            die(f"lab {a.lab}'s specs {specs} select no test of {TEST_TARGET}", 1)
        with open(stamp, "w", encoding="utf-8") as fh:
            json.dump(setup, fh, indent=1)
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
        with open(lab_file, "wb") as fh:
            fh.write(original)
        delete_dependents(build, lab_file)
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
