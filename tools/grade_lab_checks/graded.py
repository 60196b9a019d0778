"""The slow part of tools/test_grade_lab.py (ctest entry grade_lab; tooling for teachers, not a
part of the article): every lab graded by tools/grade_lab.py on the fixture submissions,
each verdict line, the summary, grades.csv and grades.xml checked."""
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

from grade_lab_checks.fixtures import REFERENCES_2, lab2_fixtures, lab4_fixtures, plants
from grade_lab_checks.fixtures_small import lab1_fixtures, lab3_fixtures, lab5_fixtures, lab6_fixtures
from grade_lab_checks.support import REPO, TIMEOUT, TOOL, expect, written_mutants, work_paths


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
        # The grader's build keeps the lab's functions out of line: the endless loop's line names it.
        **other_kinds_expected(2, REFERENCES_2[0], "sample_uniform_hemisphere"),
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
    graded_kernels(work, 2, [f"stage{k}" for k in range(1, 6)], ["stage6_variance_aware"])
    other_kinds_after(2, lab2_fixtures, REFERENCES_2[0], subs, out, work, TIMEOUT)


def graded_kernels(work, lab, stages, ungraded, includer="stage2_montecarlo"):
    """The set-up built the student's code into the CPU kernels of stages (the tags of the lab's
    tests) only: the kernels of the ungraded stage folders have the traps (labs/ungraded.h) and
    do not include labs/labLAB.glsl, so no submission rebuilt them; includer's kernel does."""
    setup = json.load(open(os.path.join(work, "setup.json"), encoding="utf-8"))
    expect(setup.get("stages") == stages, f"lab {lab}'s set-up names the stages its tests run: {stages}",
           setup.get("stages"))
    build = work_paths(work)[1]
    for folder in ungraded:
        kernel = open(os.path.join(build, folder, "cpu_kernel_v0.cpp"), encoding="utf-8").read()
        expect('#define PT_LAB_UNGRADED_KERNEL "' + folder.split("_")[0] + '"' in kernel,
               f"{folder}'s CPU kernel is built with the traps")
        depfile = os.path.join(build, "CMakeFiles", f"pt_{folder}.dir", folder, "cpu_kernel_v0.cpp.o.d")
        expect(os.path.isfile(depfile) and f"labs/lab{lab}.glsl" not in open(depfile, encoding="utf-8").read(),
               f"{folder}'s CPU kernel does not include labs/lab{lab}.glsl")
    depfile = os.path.join(build, "CMakeFiles", f"pt_{includer}.dir", includer, "cpu_kernel_v0.cpp.o.d")
    expect(f"labs/lab{lab}.glsl" in open(depfile, encoding="utf-8").read(), f"{includer}'s CPU kernel includes the student's file")


def sandbox_alone(lab, fixtures, reference_file, subs, out, work, timeout):
    """The attacks on lab `lab` again with the source check off (--unchecked-source): the
    sandbox alone must keep them from passing, planting files or flooding the grader."""
    os.makedirs(subs)
    fixtures(subs, work, out)
    for f in os.listdir(subs):
        if not f.startswith("r_"):
            path = os.path.join(subs, f)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
    lines, summary = grade(lab, subs, out, work, timeout, ["--unchecked-source"])
    check_lines(lines, {
        "r_includes_reference": rf"COMPILE ERROR .*{re.escape(reference_file)}.*reference solution.*",
        # No code runs during the build of pt_lab_tests, and the tests see the build read-only:
        # every write fails, and its estimator (no pdf) is graded.
        "r_writes_outside": FAIL,
        "r_rewrites_report": r"(FAIL|REFUSED) .*",
        "r_prints_1gb": r"REFUSED .*printed more than \d+ MB.*",
    })
    nothing_planted(work)
    no_pictures_in_repository()


# The labs of one or two short functions: their fixtures, the wrong answers that are not
# mutants of labs/mutants.h (each FAIL), a stage whose CPU kernel includes the lab's file, and
# the stages the lab's tests run (their tags; the other stages' kernels get the traps).
STAGE_FOLDERS = ["stage1_raycast", "stage2_montecarlo", "stage3_importance", "stage4_direct_indirect", "stage5_mis",
                 "stage6_variance_aware"]
# Then the lab's reference file and the function its endless loop is in.
SMALL_LABS = {
    3: (lab3_fixtures, [], "stage2_montecarlo", range(1, 6), "common/kernel/cosine_hemisphere.glsl", "sample_cosine_hemisphere"),
    5: (lab5_fixtures, [], "stage2_montecarlo", range(1, 5), "common/kernel/box_slab.glsl", "box_span"),
    6: (lab6_fixtures, [], "stage5_mis", range(1, 6), "common/kernel/mis.glsl", "power_heuristic"),
}


def other_kinds_expected(lab, rel, loop_function):
    """The verdicts of the other kinds of submission (fixtures.other_kinds): the endless loop
    TIMEOUT (naming loop_function where gdb is installed) with g++'s warning, the crash, the
    empty folder, the attacks REFUSED by the source check."""
    preprocessor = rf"REFUSED labs/lab{lab}\.glsl:\d+: the preprocessor line '#ifdef __cplusplus': .*"
    named = rf"in {loop_function}\(\) " if shutil.which("gdb") else ""
    return {"f_endless_loop": (rf"TIMEOUT {named}after \S+ s.* "
                               rf"\(warning: labs/lab{lab}\.glsl:\d+(:\d+)?: warning: comparison .* always true.*\)"),
            "g_crash": r'CRASH SIGSEGV in ".*"',
            "h_empty": rf"COMPILE ERROR no lab{lab}\.glsl in the submission",
            "r_includes_reference": rf"REFUSED labs/lab{lab}\.glsl:1: includes the reference solution {re.escape(rel)}",
            "r_writes_outside": preprocessor, "r_rewrites_report": preprocessor, "r_prints_1gb": preprocessor}


def other_kinds_after(lab, fixtures, rel, subs, out, work, timeout):
    """After the grading run: nothing planted, nothing written into the repository; then the
    attacks again with the source check off (sandbox_alone)."""
    nothing_planted(work)
    no_pictures_in_repository()
    sandbox_alone(lab, fixtures, rel, subs + "_attacks", out + "_attacks", work, timeout)


def small_lab(lab, subs, out, work):
    """Lab 3, 5 or 6: the correct file passes, the one that does not compile says where, each
    wrong answer fails with a suspect; the student's code only in the kernels of the stages the
    lab's tests run."""
    fixtures, wrong, includer, stages, rel, loop_function = SMALL_LABS[lab]
    os.makedirs(subs)
    fixtures(subs, work, out)
    expected = {"a_correct": r"PASS", "b_syntax_error": rf"COMPILE ERROR labs/lab{lab}\.glsl:\d+(:\d+)?: error: .*"}
    for name in wrong + ["m_" + m for m in written_mutants(subs, lab)]:
        expected[name] = FAIL
    expected.update(other_kinds_expected(lab, rel, loop_function))
    lines, summary = grade(lab, subs, out, work, TIMEOUT)
    check_lines(lines, expected)
    check_summary(summary, expected)
    graded_kernels(work, lab, [f"stage{k}" for k in stages], STAGE_FOLDERS[max(stages):], includer)
    other_kinds_after(lab, fixtures, rel, subs, out, work, TIMEOUT)


# Lab 1's tests take about 1.5 s per submission on 2 quiet cores; its endless loop waits this long.
LAB1_TIMEOUT = "20"


def lab1(subs, out, work, extra=()):
    """Lab 1 with a submission of every kind (its run in ./tutorial test, ctest entry
    grade_lab_1; extra: the grader's options, --compiler-cache there): the correct file
    passes, the one that does not compile (right after it) says where, each wrong answer fails
    with a suspect, the endless loop times out (naming Li() where gdb is installed), the crash
    and the empty folder say so, the attacks are REFUSED by the source check and, with it off,
    by the sandbox; nothing is planted or written into the repository."""
    os.makedirs(subs)
    lab1_fixtures(subs, work, out)
    lines, summary = grade(1, subs, out, work, LAB1_TIMEOUT, extra)
    rel = "stage1_raycast/integrator.glsl"
    expected = {"a_correct": r"PASS", "b_syntax_error": r"COMPILE ERROR labs/lab1\.glsl:\d+(:\d+)?: error: .*",
                "c_dimmed": FAIL, "c_black_sky": FAIL, **other_kinds_expected(1, rel, "Li")}
    check_lines(lines, expected)
    check_summary(summary, expected)
    graded_kernels(work, 1, [f"stage{k}" for k in range(1, 6)], STAGE_FOLDERS[5:], "stage1_raycast")
    other_kinds_after(1, lab1_fixtures, rel, subs, out, work, LAB1_TIMEOUT)


def lab4(subs, out, work):
    os.makedirs(subs)
    lab4_fixtures(subs, work, out)
    mutants = written_mutants(subs, 4)
    rel = "common/kernel/triangle_light.glsl"
    expected = {"a_correct": r"PASS", "b_pdf_doubled": FAIL, "c_pdf_mismatch": FAIL,
                **other_kinds_expected(4, rel, "sample_triangle_light")}
    for mutant in mutants:
        expected["m_" + mutant] = FAIL
    lines, summary = grade(4, subs, out, work, TIMEOUT)
    check_lines(lines, expected)
    check_summary(summary, expected)
    failed = {row["name"]: row["failed_tests"].split("\n")
              for row in csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8"))}
    expect("light sampling: the mean of 1/pdf is the solid angle a triangle or a sphere subtends" in failed["b_pdf_doubled"],
           "b_pdf_doubled fails the mean of 1/pdf", repr(failed["b_pdf_doubled"]))
    expect(any(n.startswith("light sampling: triangle_light_pdf is d^2 / (cos_y area) times the pick")
               for n in failed["c_pdf_mismatch"]), "c_pdf_mismatch fails the held-back test", repr(failed["c_pdf_mismatch"]))
    graded_kernels(work, 4, [f"stage{k}" for k in range(1, 6)], ["stage6_variance_aware"])
    other_kinds_after(4, lab4_fixtures, rel, subs, out, work, TIMEOUT)
