"""The parts of tools/grade_lab.py, which grades a folder of lab submissions in one command
(docs/labs/teachers.md; tooling for teachers, not a part of the article):
  work_build.py   the work copy of the repository and its lab build, and the deletion of
                  every output that depends on labs/labLAB.glsl before a submission is built;
  lab_tests.py    which Catch2 tests grade a lab, and reading their XML report;
  submission.py   finding the submissions and grading one: build, tests, verdict;
  reports.py      OUT/grades.csv, OUT/grades.xml (JUnit) and the logs folder.
Here is what they share: the grader's one-line error exit and usage line, the test program's
target, the build's time limit, and running a command in a process group of its own that is
killed after a time limit."""
import os
import signal
import subprocess
import sys

TEST_TARGET = "pt_tests"
BUILD_TIMEOUT = 3600  # seconds: the first build of a lab takes ~7 min on 2 cores
USAGE = "usage: tools/grade_lab.py LAB SUBMISSIONS_DIR [--out DIR] [--timeout SECONDS] [--jobs N] [--work DIR]"


def die(message, status):
    print(f"grade_lab: {message}", file=sys.stderr)
    sys.exit(status)


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
