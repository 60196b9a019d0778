#!/usr/bin/env python3
"""Test of tools/grade_lab.py (grading a class's lab submissions; tooling for teachers, not a
part of the article): bad usage exits 2 with one line; then lab 2 is graded on fixture
submissions made here from the reference functions (common/kernel/uniform_hemisphere.glsl),
and each must get its verdict line:
  a_correct          the reference                                  PASS
  b_syntax_error     the reference less a semicolon, graded right   COMPILE ERROR at labs/lab2.glsl
                     after a correct one (issue 24: the stale
                     binaries of a_correct passed)
  c_pdf_2pi          pdf = 2 pi instead of 1 / (2 pi)               FAIL, the furnace among the criteria
  d_theta_uniform    theta uniform instead of cos(theta)            FAIL, the chi-square among the criteria
  e_convention/      u.x and u.y swapped: right in distribution,    FAIL (convention) only
    lab2.glsl        but the project's inverse does not undo it
  f_endless_loop     while (true) {} in the sampler                 TIMEOUT
  g_crash            a read far out of the materials' bounds        CRASH SIGSEGV
  h_empty/           a folder without lab2.glsl                     COMPILE ERROR no lab2.glsl
and grades.csv and grades.xml hold one row and one testcase per submission.
usage: tools/test_grade_lab.py [WORK]   (ctest entry grade_lab; WORK: the lab build, kept between
runs so that only the first run builds lab 2 from nothing, ~7 min on 2 cores;
PT_GRADE_TEST_TIMEOUT: seconds for one submission's tests, default 30)"""
import csv
import os
import re
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
TOOL = os.path.join(HERE, "grade_lab.py")
# Seconds for one submission's tests: the correct submission's take 2.4 s on 2 cores.
TIMEOUT = os.environ.get("PT_GRADE_TEST_TIMEOUT", "30")


def expect(cond, what, output=""):
    if not cond:
        print("FAILED: " + what)
        if output:
            print(output)
        sys.exit(1)
    print("ok: " + what)


def fixtures(folder):
    reference = open(os.path.join(REPO, "common", "kernel", "uniform_hemisphere.glsl"), encoding="utf-8").read()
    z_line, pdf_line, phi_line = "  float z = u.x;\n", "  return 1.0f / (2.0f * kPi);\n", "  float phi = 2.0f * kPi * u.y;\n"
    for line in (z_line, pdf_line, phi_line):
        expect(line in reference, f"the reference sampler has the line '{line.strip()}' the fixtures change")

    def variant(old, new):
        return reference.replace(old, new, 1)

    files = {
        "a_correct.glsl": reference,
        "b_syntax_error.glsl": variant(z_line, "  float z = u.x\n"),
        "c_pdf_2pi.glsl": variant(pdf_line, "  return 2.0f * kPi;\n"),
        "d_theta_uniform.glsl": variant(z_line, "  float z = cos(0.5f * kPi * u.x);\n"),
        "e_convention/lab2.glsl": variant(phi_line, "  float phi = 2.0f * kPi * u.x;\n").replace(z_line, "  float z = u.y;\n", 1),
        "f_endless_loop.glsl": variant(z_line, "  while (true) {\n  }\n" + z_line),
        # A read far past the end of the scene's materials: SIGSEGV on the CPU (the read decides
        # z: 0 * x is not folded away without -ffast-math).
        "g_crash.glsl": variant(z_line, "  float z = u.x + 0.0f * materials[100000000 + int(u.y)].metallic;\n"),
        "h_empty/README.txt": "lab2.glsl was forgotten\n",
    }
    for rel, text in files.items():
        os.makedirs(os.path.dirname(os.path.join(folder, rel)), exist_ok=True)
        with open(os.path.join(folder, rel), "w", encoding="utf-8") as fh:
            fh.write(text)


def main():
    if len(sys.argv) > 2:
        print("usage: tools/test_grade_lab.py [WORK]", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="grade_lab_test_") as tmp:
        work = sys.argv[1] if len(sys.argv) == 2 else os.path.join(tmp, "work")
        subs, out = os.path.join(tmp, "submissions"), os.path.join(tmp, "out")
        os.makedirs(subs)
        for args, what in (([], "no arguments"), (["2"], "no submissions folder"), (["7", subs], "lab 7"),
                           (["2", os.path.join(tmp, "missing")], "a missing folder"), (["2", subs], "an empty folder")):
            r = subprocess.run([sys.executable, TOOL] + args, capture_output=True, text=True)
            expect(r.returncode == 2 and r.stdout == "" and len(r.stderr.strip().splitlines()) == 1
                   and r.stderr.startswith("grade_lab: "), f"bad usage ({what}) exits 2 with one line", r.stderr)
        fixtures(subs)
        start = time.monotonic()
        r = subprocess.run([sys.executable, TOOL, "2", subs, "--out", out, "--work", work, "--timeout", TIMEOUT],
                           capture_output=True, text=True)
        print(f"grading took {time.monotonic() - start:.0f} s")
        print(r.stdout + r.stderr)
        expect(r.returncode == 0, "grade_lab.py ran and exits 0")
        lines = dict(line.split(": ", 1) for line in r.stdout.splitlines())
        expected = {
            "a_correct": r"PASS",
            "b_syntax_error": r"COMPILE ERROR labs/lab2\.glsl:\d+(:\d+)?: error: .*",
            "c_pdf_2pi": r"FAIL (?!\(convention\)).*stage2: furnace box.*->.*",
            "d_theta_uniform": r"FAIL .*sampling: uniform and cosine hemisphere samples fit their pdfs \(chi-square\) -> .*",
            "e_convention": r"FAIL \(convention\) sampling: the inverses undo the samplers -> [^;]*",
            "f_endless_loop": r"TIMEOUT after \S+ s in \".*\"",
            "g_crash": r"CRASH SIGSEGV in \".*\"",
            "h_empty": r"COMPILE ERROR no lab2\.glsl in the submission",
        }
        expect(list(lines) == sorted(expected), "one line per submission, in the order of the names")
        for name, pattern in expected.items():
            expect(re.fullmatch(pattern, lines.get(name, "")) is not None, f"{name}: {pattern}", lines.get(name, ""))
        rows = list(csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8")))
        for row in rows:
            print(f"{row['name']}: {row['verdict']}, build {row['build_seconds']} s, tests {row['test_seconds']} s")
        expect([(row["name"], row["verdict"]) for row in rows] ==
               [(n, re.match(r"PASS|FAIL|COMPILE ERROR|TIMEOUT|CRASH", expected[n]).group(0)) for n in sorted(expected)],
               "grades.csv: one row per submission with its verdict")
        expect([row["convention_only"] for row in rows if row["name"] in ("c_pdf_2pi", "e_convention")] == ["no", "yes"],
               "grades.csv: the convention mistake is told from the wrong estimator")
        suite = ET.parse(os.path.join(out, "grades.xml")).getroot().find("testsuite")
        cases = {c.get("name"): c for c in suite.iter("testcase")}
        expect(sorted(cases) == sorted(expected) and suite.get("tests") == "8" and suite.get("failures") == "3"
               and suite.get("errors") == "4", "grades.xml: one JUnit testcase per submission, 3 failures, 4 errors")
        expect(cases["a_correct"].find("failure") is None and cases["a_correct"].find("error") is None
               and cases["e_convention"].find("failure").get("type") == "FAIL convention"
               and cases["g_crash"].find("error").get("type") == "CRASH", "grades.xml: each testcase's outcome and type")
    return 0


if __name__ == "__main__":
    sys.exit(main())
