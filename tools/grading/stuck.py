"""Which of the lab's functions a timed-out test program was running, for tools/grade_lab.py
(grading a class's lab submissions; tooling for teachers, not a part of the article): before
the sandbox is killed, gdb (if installed) prints the stacks of its processes, and the first
frame that names a function of the lab's file (labs/labN.glsl, the stub's definitions) says
where the endless loop is. The grader's build keeps the lab's functions out of line on the CPU
(PT_LAB_GRADING, cmake/Labs.cmake; lab 1's integrator too, cmake/PtStage.cmake), so that they
have frames of their own. Where none is found (gdb missing), nothing is said."""
import os
import re
import shutil
import subprocess

DEFINITION = re.compile(r"^\s*[A-Za-z_]\w*\s+([A-Za-z_]\w*)\s*\([^;]*\)\s*\{", re.M)


def lab_functions(stub_text):
    """The names of the functions the lab's stub defines."""
    return DEFINITION.findall(stub_text)


def descendants(pid):
    """pid's processes and all their descendants (from /proc's parent links)."""
    children = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as fh:
                    ppid = int(fh.read().rsplit(")", 1)[1].split()[1])
                children.setdefault(ppid, []).append(int(entry))
            except (OSError, IndexError, ValueError):
                pass
    found, todo = [], [pid]
    while todo:
        p = todo.pop()
        found.append(p)
        todo += children.get(p, [])
    return found


def finder(names, programs):
    """An on_timeout(pid) for Sandbox.run: the first of names found in a stack of one of the
    processes under pid whose program is one of programs (basenames), as 'NAME()', or None."""
    gdb = shutil.which("gdb")
    if not gdb or not names:
        return None
    pattern = re.compile(r"\b(" + "|".join(map(re.escape, names)) + r")\b")

    def on_timeout(pid):
        for p in descendants(pid):
            try:
                program = os.path.basename(os.readlink(f"/proc/{p}/exe"))
            except OSError:
                continue
            if program not in programs:
                continue
            try:
                out = subprocess.run([gdb, "-nx", "-batch", "-p", str(p), "-ex", "thread apply all bt 40"],
                                     capture_output=True, text=True, timeout=30).stdout
            except (OSError, subprocess.TimeoutExpired):
                continue
            for line in out.splitlines():
                if line.startswith("#"):
                    m = pattern.search(line)
                    if m:
                        return f"{m.group(1)}()"
        return None

    return on_timeout
