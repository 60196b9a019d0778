"""The teacher's held-back tests and known-wrong answers, removed from a lab's handout
(tools/make_lab_handout.py; docs/labs/teachers.md): every Catch2 TEST_CASE in tests/ tagged
[held_back] (with the comment lines just above it; a file whose every test is held back
keeps only its opening comment), and the files of HELD_BACK_FILES down to their opening
comment. They grade the class (tools/grade_lab.py builds the teacher's tree), but the
students never see them. Not part of the article: the machinery of the labs."""
import os
import re

import docs_check

# A held-back test: a Catch2 test case whose tags (up to the line that opens its body) hold [held_back].
TEST_CASE = re.compile(r"^(TEST_CASE|TEST_CASE_METHOD|SCENARIO)\s*\(")
HELD_BACK = "[held_back]"
# Files held back whole: the mutants, each an answer of some lab with one mistake in it.
HELD_BACK_FILES = ["labs/mutants.h"]


def strip_held_back(dest, tests):
    """Removes every test case tagged [held_back] from `tests` (the source files of tests/, as
    paths relative to dest); returns their (file, first line)."""
    removed = []
    for rel in tests:
        lines = docs_check.read_lines(os.path.join(dest, rel))
        out, i, cases, held = [], 0, 0, 0
        while i < len(lines):
            if not TEST_CASE.match(lines[i]):
                out.append(lines[i])
                i += 1
                continue
            cases += 1
            opens = i  # the line that opens the body: the test's name and tags are above it
            while opens < len(lines) and not lines[opens].rstrip().endswith("{"):
                opens += 1
            header = " ".join(lines[i:opens + 1])
            end = docs_check.block_end(lines, i) if opens < len(lines) else None
            if HELD_BACK not in header:
                out.append(lines[i])
                i += 1
                continue
            if end is None:
                raise SystemExit(f"make_lab_handout: {rel}:{i + 1}: a {HELD_BACK} test case without its closing '}}'")
            while out and out[-1].startswith("//"):  # the comment that describes it
                out.pop()
            while out and not out[-1].strip() and end + 1 < len(lines) and not lines[end + 1].strip():
                out.pop()  # one blank line between the neighbours, not two
            removed.append((rel, i + 1))
            held += 1
            i = end + 1
        if cases and held == cases:
            # Every test of the file is held back: its helpers go too, down to its opening comment.
            head = next((k for k, line in enumerate(lines) if not line.startswith("//")), len(lines))
            out = lines[:head] + [f"// This handout holds none of its tests (tools/make_lab_handout.py, "
                                  f"docs/labs/teachers.md).", ""]
        if out != lines:
            with open(os.path.join(dest, rel), "w", encoding="utf-8") as fh:
                fh.write("\n".join(out))
    return removed


def strip_held_back_files(dest):
    """Cuts each of HELD_BACK_FILES down to its opening comment; returns those it cut."""
    cut = []
    for rel in HELD_BACK_FILES:
        path = os.path.join(dest, rel)
        if not os.path.exists(path):
            continue
        lines = docs_check.read_lines(path)
        head = next((k for k, line in enumerate(lines) if not line.startswith("//")), len(lines))
        with open(path, "w", encoding="utf-8") as fh:
            fh.write("\n".join(lines[:head] + ["// This handout holds none of them (tools/make_lab_handout.py, "
                                                "docs/labs/teachers.md).", ""]))
        cut.append(rel)
    return cut

