#!/usr/bin/env python3
"""Writes the ctest entries of pt_tests by Catch2 tag (tests/CMakeLists.txt runs it after
each build of pt_tests; ctest reads the file it writes). Tooling for the test suite, not a
part of the article.

A test tagged with several groups (a test that runs stage3 and stage4 carries [stage3] and
[stage4]) must run once in the whole suite, yet under every label of its groups: ctest -L
stage3 is stage3's regression test, ctest -L lab4 grades lab 4. So the entries are the
combinations of group tags that occur: each entry runs the tests tagged with exactly its
groups (the other groups' tags excluded), with the labels of all of them. A test of one
group keeps the entry pt_tests_GROUP; one of stage3 and stage4 is in pt_tests_stage3_stage4.

usage: tools/discover_test_groups.py PT_TESTS OUT.cmake SKIP_SPEC GROUP:LABS...
  GROUP:LABS   a Catch2 tag and the labs it grades (stage3:lab3, sampling:lab2,lab3, bvh:lab5)
  SKIP_SPEC    appended to every entry's spec ("" or "~[large]")
"""
import os
import subprocess
import sys


def listing(binary):
    """(name, set of tags) of every test pt_tests lists (hidden ones are not listed)."""
    r = subprocess.run([binary, "--list-tests"], capture_output=True, text=True)
    # Catch2 v2 exits with the number of tests it listed; the listing ends "N test cases".
    if r.returncode < 0 or not r.stdout.rstrip().endswith("test cases"):
        raise SystemExit(f"discover_test_groups: {binary} --list-tests failed (exit {r.returncode}): {r.stderr.strip()}")
    tests = []
    for line in r.stdout.splitlines():
        if line.startswith("      ") and tests:  # the tags of the test above
            tags = line.strip()
            tests[-1][1].update(t.strip("[") for t in tags.split("]") if t.strip("["))
        elif line.startswith("  ") and not line.startswith("   "):
            tests.append((line[2:], set()))
    return tests


def cmake_quote(text):
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("$", "\\$") + '"'


def main(argv):
    if len(argv) < 4:
        print(__doc__.split("usage: ")[1].split("\n")[0], file=sys.stderr)
        return 2
    binary, out, skip, pairs = argv[0], argv[1], argv[2], argv[3:]
    groups = [p.split(":")[0] for p in pairs]
    labs = {p.split(":")[0]: [lab for lab in p.split(":")[1].split(",") if lab] for p in pairs}
    skipped = {t.strip("~[") for t in skip.split("]") if t.strip("~[")}
    combinations = set()
    for name, tags in listing(binary):
        mine = tuple(g for g in groups if g in tags)
        if mine and not (tags & skipped):
            combinations.add(mine)
    lines = [f"# Written by tools/discover_test_groups.py from {binary} --list-tests: one entry per",
             "# combination of group tags that occurs (tests/CMakeLists.txt)."]
    for combo in sorted(combinations, key=lambda c: [groups.index(g) for g in c]):
        name = "pt_tests_" + "_".join(combo)
        spec = "".join(f"[{g}]" for g in combo) + "".join(f"~[{g}]" for g in groups if g not in combo) + skip + "~[.]"
        labels = []
        for g in combo:
            labels += [lab for lab in labs[g] if lab not in labels]
            if g.startswith("stage") and g not in labels:
                labels.append(g)
        lines.append(f"add_test({name} {cmake_quote(binary)} {cmake_quote(spec)})")
        lines.append(f"set_tests_properties({name} PROPERTIES LABELS {cmake_quote(';'.join(labels))})")
    text = "\n".join(lines) + "\n"
    try:
        with open(out, encoding="utf-8") as fh:
            if fh.read() == text:
                return 0  # unchanged: ctest's file keeps its time stamp
    except OSError:
        pass
    with open(out + ".tmp", "w", encoding="utf-8") as fh:
        fh.write(text)
    os.replace(out + ".tmp", out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
