"""The reading path's length: docs_check's count of the words a student reads in an afternoon
(not part of the article: machinery that keeps docs/start_here.md's path at most PATH_LIMIT
words, the book's promise that the path is finished in one sitting).

docs/start_here.md lists the path between two marker lines:

    <!-- reading-path -->
    1. [stage1_raycast.md](stage1_raycast.md): raycasting, Eq. (2)
    8. [stage5_mis.md](stage5_mis.md) (optional): beyond the article
    <!-- /reading-path -->

Each list item's first link is one file of the path (relative to start_here.md); an item
with "(optional)" right after its link is counted apart and not held to the limit. A file's
words are its whitespace-separated tokens, code blocks included (the reader reads them),
HTML comments (the excerpt markers) left out.
"""
import os
import re

PATH_FILE = os.path.join("docs", "start_here.md")
PATH_LIMIT = 15000
BEGIN, END = "<!-- reading-path -->", "<!-- /reading-path -->"
ITEM = re.compile(r"^\s*(?:\d+\.|[-*])\s+\[[^\]]*\]\(([^)\s#]+)[^)]*\)(\s*\(optional\))?")
COMMENT = re.compile(r"<!--.*?-->", re.S)


def words(path):
    with open(path, encoding="utf-8") as f:
        return len(COMMENT.sub(" ", f.read()).split())


def reading_path(root):
    """[(relative path from the root, optional?)] of the path, or None without a start page."""
    start = os.path.join(root, PATH_FILE)
    if not os.path.isfile(start):
        return None
    with open(start, encoding="utf-8") as f:
        lines = f.read().split("\n")
    items, inside = [], False
    for line in lines:
        if line.strip() == BEGIN:
            inside = True
        elif line.strip() == END:
            inside = False
        elif inside:
            m = ITEM.match(line)
            if m:
                full = os.path.normpath(os.path.join(os.path.dirname(start), m.group(1)))
                items.append((os.path.relpath(full, root), bool(m.group(2))))
    return items


def check_reading_path(root, problems):
    """Adds an error when the path is missing, names a missing file or is longer than
    PATH_LIMIT words; returns the line that reports its length (None without a start page)."""
    items = reading_path(root)
    if items is None:
        return None
    if not items:
        problems.errors.append(f"{PATH_FILE}: no reading path between {BEGIN} and {END}")
        return None
    required = optional = 0
    for rel, is_optional in items:
        full = os.path.join(root, rel)
        if not os.path.isfile(full):
            problems.errors.append(f"{PATH_FILE}: the reading path's {rel} does not exist")
            continue
        n = words(full)
        if is_optional:
            optional += n
        else:
            required += n
    files = sum(1 for _, o in items if not o)
    report = (f"reading path: {required} words in {files} files (limit {PATH_LIMIT}), "
              f"{optional} more optional")
    if required > PATH_LIMIT:
        problems.errors.append(f"{PATH_FILE}: the reading path has {required} words, more than {PATH_LIMIT}: "
                               f"move measurements, test lists and engineering to docs/reference/")
    return report
