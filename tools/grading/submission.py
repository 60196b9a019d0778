"""The students' submissions and the grade of each, for tools/grade_lab.py (grading a class's
lab submissions; tooling for teachers, not a part of the article). A submission is a file
NAME.glsl or a folder NAME/ that holds labLAB.glsl (or labs/labLAB.glsl). Grading one checks
that it is GLSL only (source_check.py; else REFUSED), puts it in place of the work copy's
labs/labLAB.glsl (with what depends on it deleted), rebuilds the lab's tests in the sandbox
(a failure is COMPILE ERROR, with the first error and the warnings on the student's file),
runs them in the sandbox, reads their report over a pipe the grader holds, and turns it into
one plain verdict: PASS, FAIL, COMPILE ERROR, TIMEOUT, CRASH or REFUSED."""
import os
import re
import shutil
import sys
from concurrent.futures import ThreadPoolExecutor

from . import BUILD_TIMEOUT, die
from .hints import sentence, suspect_for
from .lab_tests import CONVENTION, read_report, running_test, short, signal_name
from .compiler_cache import SUBMISSION_ENV
from .sandbox import BUILD_LIMITS, FOLDER_CAP, MiB, TEST_LIMITS
from .reports import folder_size, keep_pictures
from .shards import merge_reports, merge_results, plan, read_durations, record_durations, shard_specs
from .source_check import check_source
from .depends import put_lab_file
from .glsl_check import glsl_check
from .work_build import build_target, first_error, first_error_of, snapshot, undo_writes, unexpected_writes

VERDICTS = ["PASS", "FAIL", "COMPILE ERROR", "TIMEOUT", "CRASH", "REFUSED"]


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
        self.verdict, self.detail, self.suspect = "", "", ""
        self.warnings, self.failed, self.convention_only = [], [], False
        self.passed = self.total = 0
        self.build_s = self.test_s = 0.0
        self.build_cpu = self.test_cpu = 0.0  # user + system seconds

    def line(self):
        text = f"{self.name}: {self.verdict}" + (f" {self.detail}" if self.detail else "")
        if self.suspect:
            text += f" (suspect: {self.suspect})"
        if self.warnings:
            text += " (warning: " + "; ".join(self.warnings) + ")"
        return text


def summary(grades):
    """'PASS 4, FAIL 4, COMPILE ERROR 2, TIMEOUT 1, REFUSED 1': every verdict but a CRASH that
    did not happen, in this order."""
    counts = {v: sum(1 for g in grades if g.verdict == v) for v in VERDICTS}
    return ", ".join(f"{v} {counts[v]}" for v in VERDICTS if counts[v] or v != "CRASH")


def grade_one(g, ctx):
    """Grades g's submission in the lab build of ctx: sets its verdict, detail and counts."""
    lab = ctx["args"].lab
    if g.submission is None:
        g.verdict, g.detail = "COMPILE ERROR", f"no lab{lab}.glsl in the submission"
        return
    with open(g.submission, "rb") as fh:
        code = fh.read(2 * MiB)
    why = None if ctx["args"].unchecked_source else check_source(code, f"labs/lab{lab}.glsl", ctx["references"], ctx["src"])
    if why:
        g.verdict, g.detail = "REFUSED", why
        return
    outputs = install(g, ctx, code)
    if not build_submission(g, ctx, outputs):
        return
    run_tests(g, ctx)


def install(g, ctx, code):
    """g's file as the work copy's labs/labLAB.glsl, with no output of the build left that
    depends on it (exits when the test program survives: no grade would be safe)."""
    outputs = put_lab_file(ctx["build"], ctx["lab_file"], code, ctx["lab_stamp"])
    if os.path.exists(ctx["test_bin"]):
        a = ctx["args"]
        die(f"{ctx['test_bin']} survived the deletion of what depends on labs/lab{a.lab}.glsl: the build's "
            f"dependencies were not understood, so no grade would be safe; delete {a.work} and run again", 1)
    return outputs


def write_log(path, *parts):
    with open(path, "wb") as fh:
        for part in parts:
            fh.write(part)


def student_warnings(log_text, lab):
    """The compilers' warnings on the student's file, each once, shortest form first seen."""
    seen = []
    for line in log_text.splitlines():
        m = re.search(rf"(labs/lab{lab}\.glsl:\d+(?::\d+)?: warning: .*)", line)
        if not m:
            m = re.search(rf"WARNING: \S*(labs/lab{lab}\.glsl:\d+): (.*)", line)
            text = f"{m.group(1)}: warning: {m.group(2)}" if m else None
        else:
            text = m.group(1)
        if text:
            text = short(text, 200)
            if text not in seen:
                seen.append(text)
    return seen[:3]


def build_submission(g, ctx, outputs):
    """Rebuilds the lab's tests with g's file, sealed; False (and the verdict) when it does not
    build, or when code run during the build (the test program lists its tests after it links)
    wrote files of the build folder that are not outputs of the student's file (outputs)."""
    box, build = ctx["sandbox"], ctx["build"]
    before = snapshot(build)
    r = box.run(build_target(ctx["cmake"], build, ctx["args"].jobs, ctx["target"]), build, [build], [ctx["src"]],
                box.hidden_in_build, BUILD_LIMITS, BUILD_TIMEOUT, env=SUBMISSION_ENV)
    g.build_s, g.build_cpu = r.seconds, r.cpu_seconds
    build_log = os.path.join(ctx["logs"], f"{g.name}.build.log")
    write_log(build_log, r.stdout, r.stderr)
    text = (r.stdout + r.stderr).decode("utf-8", errors="replace")
    g.warnings = student_warnings(text, ctx["args"].lab)
    planted = unexpected_writes(before, snapshot(build), outputs)
    if planted and not undo_writes(build, planted):
        die(f"{g.name}'s build rewrote the build's configuration ({planted[0]}): delete {ctx['work']} and run again", 1)
    if planted:
        g.verdict = "REFUSED"
        g.detail = (f"code run during its build wrote {len(planted)} file(s) it does not make: "
                    + ", ".join(planted[:3]) + (", ..." if len(planted) > 3 else ""))
    elif r.over_cap:
        g.verdict, g.detail = "REFUSED", f"its build printed more than {BUILD_LIMITS.stdout_cap // MiB} MB"
    elif r.timed_out:
        g.verdict, g.detail = "COMPILE ERROR", f"the build took over {BUILD_TIMEOUT} s"
    elif r.rc != 0 or not os.path.isfile(ctx["test_bin"]):
        g.verdict, g.detail = "COMPILE ERROR", first_error(build_log, ctx["src"])
        g.warnings = [w for w in g.warnings if w not in g.detail]
    else:
        return glsl_compiles(g, ctx, build_log)
    return False


def glsl_compiles(g, ctx, build_log):
    """True when g's file compiles as GLSL too (glsl_check.py); else False and COMPILE ERROR
    with glslang's first error. Its output is added to the build log."""
    r = glsl_check(ctx)
    if r is None:
        return True
    g.build_s += r.seconds
    g.build_cpu += r.cpu_seconds
    with open(build_log, "ab") as fh:
        fh.write(r.stdout + r.stderr)
    text = (r.stdout + r.stderr).decode("utf-8", errors="replace")
    g.warnings += [w for w in student_warnings(text, ctx["args"].lab) if w not in g.warnings][:3 - len(g.warnings)]
    if r.rc == 0 and not r.timed_out and not r.over_cap:
        return True
    g.verdict = "COMPILE ERROR"
    g.detail = ("glslangValidator did not finish (time or output over its limit)" if r.timed_out or r.over_cap
                else first_error_of(text, ctx["src"]))
    g.warnings = [w for w in g.warnings if w not in g.detail]
    return False


def fresh_run_folder(g, ctx):
    """WORK/run/NAME, empty: the one folder the tests may write (their pictures)."""
    run = os.path.join(ctx["work"], "run", g.name)
    shutil.rmtree(run, ignore_errors=True)
    os.makedirs(run)
    ctx["sandbox"].owner_of_writable(run)
    return run


def run_tests(g, ctx):
    """Runs the lab's tests on g's build in the sandbox (the build read-only, the held-back
    tests' sources hidden, WORK/run/NAME the only folder it may write), as --jobs shards side
    by side (shards.py), and judges them."""
    box, by_file = ctx["sandbox"], ctx.get("by_file") or {}
    run = fresh_run_folder(g, ctx)
    env = {"PT_TEST_PICTURES": os.path.join(run, "test_pictures")}
    groups = plan(by_file, read_durations(ctx["durations"], ctx["args"].lab), ctx["args"].jobs) if by_file else [None]

    def shard(k, files):
        specs = ctx["specs"] if files is None else shard_specs(ctx["specs"], files)
        cmd = [ctx["test_bin"], "-#", "-d", "yes", "-r", "xml", "-o", "{report}"] + specs
        # The test each shard started last (tests/catch_runner.cpp writes it unbuffered): a crash's name.
        running = os.path.join(run, f"running.{k}.txt")
        r = box.run(cmd, run, [run], [ctx["src"], ctx["build"]], box.hidden_in_tests, TEST_LIMITS,
                    ctx["args"].timeout, env={**env, "PT_TEST_RUNNING_FILE": running}, report=True,
                    on_timeout=ctx.get("on_timeout"))
        r.running_test = running_test(running, ctx["tests"])
        return r

    with ThreadPoolExecutor(len(groups)) as pool:
        results = list(pool.map(shard, range(len(groups)), groups))
    reports = [read_report(r.report, ctx["tests"] if files is None else [n for f in files for n in by_file[f]])
               for r, files in zip(results, groups)]
    r, rep = merge_results(results), merge_reports(reports, ctx["tests"])
    g.test_s, g.test_cpu = r.seconds, r.cpu_seconds
    write_log(os.path.join(ctx["logs"], f"{g.name}.tests.log"), r.stdout, r.stderr)
    for k, one in enumerate(results, 1):  # NAME.tests.xml, or NAME.tests.K.xml for shard K of several
        write_log(os.path.join(ctx["logs"], f"{g.name}.tests{'' if len(results) == 1 else f'.{k}'}.xml"), one.report)
    written = folder_size(run)
    keep_pictures(run, ctx["logs"], g.name)
    shutil.rmtree(run, ignore_errors=True)
    judge(g, ctx, r, rep, written)
    if g.verdict == "PASS":
        record_durations(ctx["durations"], rep.durations)


def judge(g, ctx, r, rep, written):
    """g's verdict from the sealed run of its tests (r: how it ended; rep: its report)."""
    g.total = len(ctx["tests"])
    g.passed = sum(1 for _, ok, _ in rep.cases if ok)
    # A signal: a negative return code, or bwrap's 128 + the signal (1 to 64; 255 is an exit).
    sig = -r.rc if r.rc < 0 else r.rc - 128 if r.rc > 128 else 0
    died = 0 < sig <= 64
    cap = {"stdout": TEST_LIMITS.stdout_cap, "stderr": TEST_LIMITS.stderr_cap, "report": TEST_LIMITS.stdout_cap}
    if r.over_cap == "report" and rep.running_failure and not rep.problem:
        # A wrong answer whose check fails in a loop (every pixel) fills the report: FAIL, with
        # the first failure of that test (never PASS: its report was cut short).
        g.verdict = "FAIL"
        failed = [(n, why) for n, ok, why in rep.cases if not ok]
        why = f"{rep.running_failure}, and so often that the report passed {cap['report'] // MiB} MB"
        explain_failures(g, ctx, rep, [(rep.running, why)] + failed, r)
    elif r.over_cap:
        g.verdict, g.detail = "REFUSED", f"the tests printed more than {cap[r.over_cap] // MiB} MB on {r.over_cap}"
    elif written > FOLDER_CAP:
        g.verdict, g.detail = "REFUSED", f"the tests wrote {written // MiB} MB into their folder (at most {FOLDER_CAP // MiB} MB)"
    elif rep.problem and not died:
        # (A program that died of a signal may have left its report cut mid-element: that is its
        # crash, below, never a REFUSED.)
        g.verdict, g.detail = "REFUSED", f"the test report is not the test program's own: {rep.problem}"
    elif r.timed_out or (died and sig == 24):  # SIGXCPU: the CPU-time limit
        g.verdict = "TIMEOUT"
        test = r.running_test or rep.running
        where = r.running_function or (f"test \"{test}\"" if test else None)
        g.detail = (f"in {where}" if where else "") + (
            f" after {ctx['args'].timeout:g} s" if r.timed_out else f" after {TEST_LIMITS.cpu_s} s of CPU time")
        g.detail = g.detail.strip()
        if r.running_function and test:
            g.detail += f" (test \"{test}\")"
        g.suspect = not_written(r)
    elif died and sig == 25:  # SIGXFSZ
        g.verdict, g.detail = "REFUSED", f"the tests wrote a file larger than {TEST_LIMITS.file_size // MiB} MB"
    elif died:
        # In which test: the one the program started last (the test runner, tests/catch_runner.cpp,
        # writes its name as it starts); else the report's unfinished one.
        g.verdict = "CRASH"
        where = r.running_test or rep.running
        g.detail = signal_name(-sig) + (" after its report ended" if rep.whole else f" in \"{where}\"" if where else "")
    else:
        failed = [(n, why) for n, ok, why in rep.cases if not ok]
        if not failed and rep.whole and r.rc == 0 and len(rep.cases) == g.total:
            g.verdict, g.warnings = "PASS", []
            return
        g.verdict = "FAIL"
        explain_failures(g, ctx, rep, failed, r)


def explain_failures(g, ctx, rep, failed, r):
    """A FAIL's detail: the most telling failed test (the lab page's table) with its first failed
    check and numbers, how many others failed, and the suspect; the stubs still in place."""
    if not failed:
        missing = g.total - len(rep.cases)
        g.detail = f"the test program ended (exit {r.rc}) with {missing} of the lab's {g.total} tests not run"
        g.failed = [g.detail]
        return
    g.failed = [n for n, _ in failed]
    g.convention_only = all(n in CONVENTION for n in g.failed)
    name, suspect = suspect_for(ctx["hints"], g.failed)
    why = dict(failed)[name]
    others = len(failed) - 1
    g.detail = sentence(name, why) + (f"; {others} more of the {g.total} tests failed" if others else "")
    g.suspect = not_written(r) or suspect or ""


def not_written(r):
    """The suspect when the lab's stubs ran: the functions they name, else ''."""
    said = (r.stderr + r.report).decode(errors="replace")
    stubs = sorted(set(re.findall(r"lab \d+: (\w+) is not written yet", said)))
    if not stubs:
        return ""
    return f"{', '.join(stubs)} {'is' if len(stubs) == 1 else 'are'} not written yet (the stub's line is still there)"
