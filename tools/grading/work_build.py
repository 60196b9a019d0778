"""The work copy of the repository and its lab build, for tools/grade_lab.py (grading a class's
lab submissions; tooling for teachers, not a part of the article). WORK/src is a copy of the
repository, rewritten only where a file differs, and WORK/src/build its build with -DPT_LAB=LAB
-DPT_LAB_GRADING=ON, kept between runs (a child of the copy, as a checkout's build folder is of
the checkout, so that a compiler cache finds the same relative paths: compiler_cache.py). Before a submission is built, every output of that
build made from labs/labLAB.glsl is deleted (depends.py), so a submission that does not compile
leaves no test program at all, never the previous student's (issue 24). The first build, with
the repository's own labs/labLAB.glsl, is configured again with only the test files that hold
one of the lab's tests, and with the student's code in the CPU kernels of the stages those tests
run only (their tags; the other stages' kernels get traps, labs/ungraded.h); it and the list of
those tests are kept in WORK/setup.json."""
import fcntl
import filecmp
import json
import os
import re
import shutil
import sys

from . import BUILD_TIMEOUT, TEST_TARGET, USAGE, die
from .shards import tests_by_file
from .lab_tests import lab_specs, tag_specs, test_files, test_names, test_stages, test_tags
from .depends import delete_dependents
from .hidden import placeholders
from .sandbox import BUILD_LIMITS, NOBODY


def work_paths(work):
    """(the work copy, its lab build) of WORK."""
    return os.path.join(work, "src"), os.path.join(work, "src", "build")


def lock_work(work):
    """The open lock file of WORK, locked: one grader at a time per work folder. Keep it open."""
    lock = open(os.path.join(work, "lock"), "w")
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        die(f"another tools/grade_lab.py is using {work}: wait for it, or give this one another --work", 1)
    return lock


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
        if root == dest:  # the lab build (work_paths) and any other build folder of the copy
            dirs[:] = [d for d in dirs if not d.startswith("build")]
        for f in files:
            if os.path.normpath(os.path.join(root, f)) not in keep:
                os.remove(os.path.join(root, f))
                changed += 1
    return changed


def snapshot(build):
    """{path relative to build: (size, mtime)} of every file of the build folder."""
    state = {}
    for root, _, files in os.walk(build):
        for f in files:
            path = os.path.join(root, f)
            try:
                st = os.lstat(path)
            except OSError:
                continue
            state[os.path.relpath(path, build)] = (st.st_size, st.st_mtime_ns)
    return state


# What a build writes besides its outputs: make's and CMake's bookkeeping, the compilers'
# depfiles, and the ctest entries that tools/discover_test_groups.py writes after pt_tests.
BOOKKEEPING = re.compile(r"(\.o\.d|\.d|compiler_depend\.(make|internal|ts)|depend\.make|progress\.(make|marks)|"
                         r"CMakeFiles/Progress/.*|\.ninja_.*|pt_tests_groups\.cmake|.*_groups.*\.cmake)$")


def unexpected_writes(before, after, outputs):
    """The files that a build changed or made (after against before) that are neither the
    outputs made from the student's file nor the build's bookkeeping: what code run during
    the build (the test program lists its tests after it links) wrote on its own."""
    changed = [p for p, st in after.items() if before.get(p) != st]
    return sorted(p for p in changed if p not in outputs and not BOOKKEEPING.search(p))


def undo_writes(build, paths):
    """Deletes the files of paths (the build makes again what it needs of them); False when one
    of them is CMake's own configuration, which a build does not remake."""
    for rel in paths:
        if re.search(r"(^|/)(CMakeCache\.txt|Makefile|Makefile2|build\.make|flags\.make|link\.txt|.*\.cmake)$", rel):
            return False
        try:
            os.remove(os.path.join(build, rel))
        except OSError:
            pass
    return True


ERROR_LINE = re.compile(r"(:\d+(:\d+)?: (fatal )?error:)|(^ERROR: )|(undefined reference to)|(: error:)")


def first_error(log_path, src):
    """The first compiler, glslang or linker error line of a build log, with the work copy's
    paths shortened to the repository's (labs/lab2.glsl:14:3: error: ...)."""
    return first_error_of(open(log_path, encoding="utf-8", errors="replace").read(), src)


def first_error_of(text, src):
    """first_error of the text of a log."""
    lines = text.splitlines()
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


def build_target(cmake, build, jobs, target):
    """The command that builds target (the lab's tests) in build with jobs compilers."""
    return [cmake, "--build", build, "--target", target, "-j", str(jobs)]


def sealed_build(box, cmake, build, src, jobs, target, log_path, cache):
    """Builds target in the sandbox (build writable, src read-only, the references hidden; the
    compiler cache read-only when it is used); the log in log_path. Returns (return code, timed out)."""
    r = box.run(build_target(cmake, build, jobs, target), build, [build], [src] + cache.readonly(), box.hidden_in_build,
                BUILD_LIMITS, BUILD_TIMEOUT, env=cache.setup_env(build))
    with open(log_path, "ab") as fh:
        fh.write(r.stdout + r.stderr)
    return r.rc, r.timed_out


def build_is_new(build, a):
    """True when the lab build is not configured yet; exits when it is the build of another lab."""
    cache = os.path.join(build, "CMakeCache.txt")
    if not os.path.isfile(cache):
        return True
    configured = re.search(r"^PT_LAB:STRING=(\S*)", open(cache, encoding="utf-8", errors="replace").read(), re.M)
    if not configured or configured.group(1) != str(a.lab):
        die(f"{a.work} holds the build of another lab ({configured.group(1) if configured else '?'}): "
            f"give lab {a.lab} a --work of its own ({USAGE})", 2)
    return False


# The setup's format: a WORK/setup.json of another one (an older grader's build, configured
# without PT_LAB_GRADING) is built again.
SETUP_FORMAT = 4  # 3: "by_file", the lab's tests by test file (shards.py); 4: "stages", PT_LAB_GRADED_STAGES


def kept_setup(stamp, lab, fresh, changed):
    """The setup of the last run (WORK/setup.json) when neither the build nor the repository
    changed since, else None (and the stale file removed)."""
    setup = None
    if not fresh and not changed and os.path.isfile(stamp):
        setup = json.load(open(stamp, encoding="utf-8"))
        setup = setup if setup.get("lab") == lab and setup.get("format") == SETUP_FORMAT else None
    if setup is None and os.path.exists(stamp):
        os.remove(stamp)
    return setup


def lab_target(build):
    """(the target that holds the lab's tests, the lab's Catch2 tags or None, the test files it
    compiles or None): pt_lab_tests, its tags and files when the lab build defines it
    (tests/CMakeLists.txt writes pt_lab_tests.json), else pt_tests, whose ctest entries then
    give the tests."""
    path = os.path.join(build, "pt_lab_tests.json")
    if os.path.isfile(path):
        info = json.load(open(path, encoding="utf-8"))
        return info["target"], info["tags"], info.get("files")
    return TEST_TARGET, None, None


def configure(a, box, cmake, src, build, setup_log, files, stages):
    """Configures the lab build in the sandbox: the grader's (PT_LAB_GRADING), one general CPU
    kernel per stage, pt_lab_tests made of files (test files without .cpp; [] for all), the
    student's code in the CPU kernels of stages only (["stage2"]; None for every stage: the
    others get the traps of labs/ungraded.h, cmake/Labs.cmake), ccache as the launcher when
    the set-up uses the cache (a.cache)."""
    graded = "" if stages is None else (";".join(stages) or "none")
    r = box.run([cmake, "-S", src, "-B", build, "-G", "Unix Makefiles", "-DCMAKE_BUILD_TYPE=Release",
                 f"-DPT_LAB={a.lab}", "-DPT_LAB_GRADING=ON", "-DPT_CPU_GENERAL_ONLY=ON",
                 "-DPT_LAB_TEST_FILES=" + ";".join(files), "-DPT_LAB_GRADED_STAGES=" + graded] + a.cache.configure_args(),
                build, [build], [src], box.hidden_in_build, BUILD_LIMITS, BUILD_TIMEOUT)
    with open(setup_log, "ab") as fh:
        fh.write(r.stdout + r.stderr)
    if r.rc != 0:
        die(f"the lab build does not configure: see {setup_log}", 1)
    return lab_target(build)


def first_build(a, box, cmake, ctest, lab_file, setup_log, stamp):
    """Configures the lab build, builds its tests with the repository's own labs/labLAB.glsl (the
    handout's stub; a failure there is not a student's), both in the sandbox, and lists the
    lab's tests; then configures it again with only the test files that hold one of them, and
    the student's code only in the kernels of the stages they run, so that a submission's
    build compiles no other. Returns the setup {lab, target, specs, tests, by_file, stages},
    written to stamp."""
    src, build = work_paths(a.work)
    os.makedirs(build, exist_ok=True)
    box.owner_of_writable(build)
    target, tags, files = configure(a, box, cmake, src, build, setup_log, [], None)
    delete_dependents(build, lab_file)
    specs, tests, stages = None, None, None
    while True:
        rc, timed_out = sealed_build(box, cmake, build, src, a.jobs, target, setup_log, a.cache)
        if rc != 0 or timed_out:
            die(f"the lab build fails with the repository's own labs/lab{a.lab}.glsl, before any submission: "
                f"{first_error(setup_log, src)} (see {setup_log})", 1)
        specs = specs or (tag_specs(tags, a.lab) if tags else lab_specs(ctest, build, a.lab))
        names = test_names(build, specs, target)
        if tests is not None and names != tests:
            die(f"lab {a.lab}'s test program lost tests when built of the files that hold them only: {setup_log}", 1)
        tests = names
        listed = test_tags(build, specs, target)
        needed = ["test_main"] + test_files(build, specs, target, listed) if files else None
        run = test_stages(listed) if files else None
        if (not needed or sorted(needed) == sorted(files)) and run == stages:
            break
        # Again with only those files, the student's code only in those stages' kernels.
        target, tags, files = configure(a, box, cmake, src, build, setup_log, needed, run)
        stages = run
    if not tests:
        die(f"lab {a.lab}'s specs {specs} select no test of {target}", 1)
    # The tests by file, for the shards a submission's tests run in (shards.py); none when
    # the files' lists do not hold each test once (then one run holds them all).
    by_file = tests_by_file(os.path.join(build, "bin", target), specs, test_files(build, specs, target, listed))
    if sorted(n for names in by_file.values() for n in names) != sorted(tests):
        by_file = {}
    setup = {"lab": a.lab, "format": SETUP_FORMAT, "target": target, "specs": specs, "tests": tests, "by_file": by_file,
             "stages": stages}
    with open(stamp, "w", encoding="utf-8") as fh:
        json.dump(setup, fh, indent=1)
    return setup


def set_up(repo, a, box, out, logs, cmake, ctest, count, hidden):
    """Brings the work copy up to date with repo, sets the sandbox's placeholders of the files
    hidden from every build (hidden: repository-relative) and, the first time and whenever the
    repository changed since, builds the lab once (first_build). Returns (the work copy's
    labs/labLAB.glsl, its content, its time stamp, the setup {lab, specs, tests})."""
    src, build = work_paths(a.work)
    changed = sync_tree(repo, src, {a.work, out})
    box.hidden_in_build = placeholders(a.work, src, hidden, "a reference solution")
    lab_file = os.path.join(src, "labs", f"lab{a.lab}.glsl")
    original = open(lab_file, "rb").read()
    lab_stamp = os.stat(lab_file).st_mtime_ns  # every submission's file gets it (depends.put_lab_file)
    fresh = build_is_new(build, a)
    stamp = os.path.join(a.work, "setup.json")
    setup = kept_setup(stamp, a.lab, fresh, changed)
    print(f"grade_lab: lab {a.lab}, {count} submission(s); the lab build is {build}"
          + (" (new: its first build takes about 2 min on 2 idle cores)" if fresh else "")
          + (", unchanged since the last run" if setup else ""), file=sys.stderr, flush=True)
    if setup is None and (a.cache.enabled or a.cache.why_not):
        print("grade_lab: " + (a.cache.why_not or f"the set-up reads compiled objects from ccache's cache "
                               f"{a.cache.settings['cache_dir']}, read-only"), file=sys.stderr, flush=True)
    if os.path.isfile(os.path.join(a.work, "build", "CMakeCache.txt")):
        print(f"grade_lab: {os.path.join(a.work, 'build')} is an older grader's lab build, no longer used "
              f"(the build is {build} now): delete it to free its space", file=sys.stderr, flush=True)
    if not fresh and box.as_nobody and os.stat(build).st_uid != NOBODY:
        box.owner_of_writable(build)  # a build made unsealed (or by an older grader): the sandbox's now
    if setup is None:
        setup = first_build(a, box, cmake, ctest, lab_file, os.path.join(logs, "_setup.log"), stamp)
    return lab_file, original, lab_stamp, setup
