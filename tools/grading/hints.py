"""The plain verdict of a failed submission, for tools/grade_lab.py (grading a class's lab
submissions; tooling for teachers, not a part of the article): the first failing check in a
sentence, with its numbers, and the likely mistake, read from the lab page's table "If a test
fails" (docs/labs/labN.md: | if this test fails | suspect |), whose rows are in the order of
how telling a failure is: the first row whose test failed gives the sentence and the hint."""
import os
import re

ROW = re.compile(r"^\|\s*(.+?)\s*\|\s*(.+?)\s*\|\s*$")


def plain(cell):
    """A table cell without its Markdown: quotes, backticks, emphasis and links."""
    cell = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", cell)
    cell = cell.replace("`", "").replace("**", "")
    return cell.strip().strip('"').strip()


def read_hints(repo, lab):
    """[(test name or its start before '...', suspect)] of docs/labs/labN.md's table
    'If a test fails', in its order; [] when the page has none."""
    path = os.path.join(repo, "docs", "labs", f"lab{lab}.md")
    if not os.path.isfile(path):
        return []
    rows, inside = [], False
    for line in open(path, encoding="utf-8"):
        if line.startswith("## "):
            inside = line.strip().lower().startswith("## if a test fails")
            continue
        m = ROW.match(line.strip()) if inside else None
        if not m or set(m.group(1)) <= set("-: ") or m.group(1).lower().startswith("if this test fails"):
            continue
        rows.append((plain(m.group(1)), plain(m.group(2))))
    return rows


def matches(pattern, name):
    """A row's test: the whole name, or its start when the cell ends in '...' (or '…')."""
    for dots in ("...", "…"):
        if pattern.endswith(dots):
            return name.startswith(pattern[:-len(dots)].rstrip())
    return name == pattern


def suspect_for(hints, failed_names):
    """(the failed test the verdict names, the suspect or None): the first row of the table whose
    test failed, else the first failed test with no hint."""
    for pattern, suspect in hints:
        for name in failed_names:
            if matches(pattern, name):
                return name, suspect
    return (failed_names[0] if failed_names else None), None


def sentence(name, check):
    """The FAIL line's sentence: the test, then its first failed check with the numbers it saw."""
    return f"\"{name}\": {check}" if check else f"\"{name}\" failed"
