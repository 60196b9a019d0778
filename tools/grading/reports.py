"""The reports of a grading run, for tools/grade_lab.py (grading a class's lab submissions;
tooling for teachers, not a part of the article): OUT/logs/, emptied before the run, which
then holds each student's build log, test log, Catch2 XML and the tests' pictures; OUT/grades.csv, one row per
student; OUT/grades.xml, JUnit, one testcase per student (FAIL a failure, the other verdicts
but PASS an error)."""
import csv
import os
import shutil
import time
from xml.sax.saxutils import escape, quoteattr

from .sandbox import MiB


def fresh_logs(out):
    """OUT/logs, made or emptied; returns its path."""
    logs = os.path.join(out, "logs")
    os.makedirs(logs, exist_ok=True)
    for stale in os.listdir(logs):
        os.remove(os.path.join(logs, stale))
    return logs


CSV_COLUMNS = ["name", "verdict", "detail", "suspect", "warnings", "tests_passed", "tests_total", "failed_tests",
               "convention_only", "build_seconds", "test_seconds", "submission"]


def write_csv(out, grades):
    """OUT/grades.csv by Python's csv module: a field that holds a comma, a quote or a newline
    is quoted, so test names with ';' or ',' stay one field."""
    with open(os.path.join(out, "grades.csv"), "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(CSV_COLUMNS)
        for g in grades:
            w.writerow([g.name, g.verdict, g.detail, g.suspect, " | ".join(g.warnings), g.passed, g.total,
                        "\n".join(g.failed), "yes" if g.convention_only else "no", f"{g.build_s:.1f}",
                        f"{g.test_s:.1f}", g.submission or ""])


def write_junit(out, lab, grades, elapsed):
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


def write_reports(out, lab, grades, elapsed):
    """OUT/grades.csv and OUT/grades.xml for the grades so far."""
    write_csv(out, grades)
    write_junit(out, lab, grades, elapsed)


def folder_size(path):
    total = 0
    for root, _, files in os.walk(path):
        for f in files:
            try:
                total += os.lstat(os.path.join(root, f)).st_size
            except OSError:
                pass
    return total


def keep_pictures(run, logs, name):
    """The tests' pictures (PNG files up to 4 MB) copied to logs/NAME.pictures/."""
    kept = 0
    for root, _, files in os.walk(run):
        for f in files:
            path = os.path.join(root, f)
            if f.endswith(".png") and not os.path.islink(path) and os.path.getsize(path) <= 4 * MiB:
                os.makedirs(os.path.join(logs, f"{name}.pictures"), exist_ok=True)
                shutil.copyfile(path, os.path.join(logs, f"{name}.pictures", f))
                kept += 1
    return kept
