#!/usr/bin/env python3
"""Keeps the book true to the code: README.md, the stage folders' README.md and docs/, the
chapters beside the article's Eq. 1-5, so the docs cannot drift from what the program
computes.

Four things are checked in every Markdown file:

1. Code excerpts. A line
       <!-- excerpt: PATH#NAME -->
   followed by a fenced code block means: the block is the code of NAME in PATH (relative to
   the repository root). NAME is either a marked region of the source,
       // [excerpt NAME]   ...   // [/excerpt]      (any comment leader: //, #)
   or, without such markers, the function (or struct) definition named NAME: the line
   `Type NAME(` (or `Class::NAME(`), the comment lines just above it, and everything down
   to the `}` at the definition's indentation.
2. Line references. A link  [`SYMBOL`:N](REL/PATH#LN)  says that SYMBOL is defined at line N
   of the file; both numbers must be the line of SYMBOL's definition (see find_symbol,
   docs_source.py).
3. Images and relative links: every ![..](x), <img src="x"> and [..](x) that is not a URL
   must name a file or folder that exists.
4. Quoted numbers. A number followed by  <!-- numbers: PATH KEY -->  is the value of KEY in
   PATH: a picture's metadata (spp, seconds, mean.R), a CSV cell, a file's number (see
   docs_numbers.py); --update writes the file's value into the docs.

Besides, the reading path that docs/start_here.md lists must be at most 15,000 words
(docs_path.py); --check and --update print its length.

  tools/docs_check.py --check    (the ctest entry docs_check) lists every drifted excerpt,
                                 wrong line and missing file, one per line; exit 1 if any
  tools/docs_check.py --update   rewrites excerpts and line numbers from the source
                                 (missing files cannot be fixed this way and are listed)
  --root DIR                     the repository to check (default: this script's parent)
"""
import argparse
import os
import re
import sys

# Finding code in the sources; docs_check.X names them for make_lab_handout.py and the tests.
from docs_source import (block_end, dedent, definition_line, excerpt_text, find_symbol,  # noqa: F401
                         marked_region, read_lines)
from docs_numbers import check_numbers  # noqa: E402
from docs_path import check_reading_path  # noqa: E402

FENCE = re.compile(r"^(```+|~~~+)")
EXCERPT = re.compile(r"^<!-- excerpt: ([^#\s]+)#([A-Za-z_][\w:]*) -->\s*$")
LINE_REF = re.compile(r"\[`([A-Za-z_][\w:]*)`:(\d+)\]\(([^)\s#]+)#L(\d+)\)")
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
IMG_TAG = re.compile(r"<img\s[^>]*src=\"([^\"]+)\"")
LANG = {".glsl": "glsl", ".comp": "glsl", ".cpp": "cpp", ".h": "cpp", ".py": "python",
        ".cmake": "cmake", ".txt": "cmake", ".sh": "sh"}
# Files that other parts of the project write and that may not exist on every branch yet:
# a link to one of them that is missing is reported as a warning, not an error. Empty on
# main, where every such file exists: a missing link target is an error.
PENDING = set()


class Problems:
    def __init__(self):
        self.errors = []
        self.warnings = []


def markdown_files(root):
    """README.md, the stage folders' README.md files, and everything under docs/."""
    files = [os.path.join(root, "README.md")]
    files += sorted(os.path.join(root, d, "README.md") for d in os.listdir(root)
                    if d.startswith("stage") and os.path.isfile(os.path.join(root, d, "README.md")))
    for base, dirs, names in os.walk(os.path.join(root, "docs")):
        dirs.sort()
        files += [os.path.join(base, n) for n in sorted(names) if n.endswith(".md")]
    # docs/results/notes.md, stage_chapters_notes.md and cycles_notes.md are fragments that bench/report.py
    # copies into docs/results.md: their links are relative to docs/, and they are checked there.
    fragments = {os.path.normpath(os.path.join(root, "docs", "results", n))
                 for n in ("notes.md", "stage_chapters_notes.md", "cycles_notes.md")}
    return [f for f in files if os.path.isfile(f) and os.path.normpath(f) not in fragments]


def check_excerpts(root, md, lines, update, problems):
    rel = os.path.relpath(md, root)
    out = []
    i = 0
    while i < len(lines):
        line = lines[i]
        out.append(line)
        m = EXCERPT.match(line)
        if not m:
            i += 1
            continue
        path, name = m.group(1), m.group(2)
        code, error = excerpt_text(root, path, name)
        fence_at = i + 1
        if fence_at >= len(lines) or not FENCE.match(lines[fence_at]):
            problems.errors.append(f"{rel}:{i + 1}: excerpt {path}#{name} is not followed by a ``` code block")
            i += 1
            continue
        end = fence_at + 1
        while end < len(lines) and not lines[end].startswith(FENCE.match(lines[fence_at]).group(1)):
            end += 1
        if end >= len(lines):
            problems.errors.append(f"{rel}:{fence_at + 1}: the code block of excerpt {path}#{name} is not closed")
            return lines
        if error:
            problems.errors.append(f"{rel}:{i + 1}: excerpt {path}#{name}: {error}")
            out += lines[fence_at:end + 1]
        else:
            current = lines[fence_at + 1:end]
            if current != code:
                if update:
                    problems.warnings.append(f"{rel}:{i + 1}: excerpt {path}#{name} updated")
                else:
                    problems.errors.append(f"{rel}:{i + 1}: excerpt {path}#{name} differs from the source "
                                           f"(run tools/docs_check.py --update)")
            lang = LANG.get(os.path.splitext(path)[1], "")
            out.append("```" + lang)
            out += code if update else current
            out.append("```")
        i = end + 1
    return out


def check_line_refs(root, md, lines, update, problems):
    rel = os.path.relpath(md, root)
    base = os.path.dirname(md)
    cache = {}

    def fix(m, lineno):
        symbol, shown, target, anchor = m.group(1), int(m.group(2)), m.group(3), int(m.group(4))
        path = os.path.normpath(os.path.join(base, target))
        where = os.path.relpath(path, root)
        if not os.path.isfile(path):
            problems.errors.append(f"{rel}:{lineno}: {where} (line reference of {symbol}) does not exist")
            return m.group(0)
        if path not in cache:
            cache[path] = read_lines(path)
        i = find_symbol(cache[path], symbol)
        if i is None:
            problems.errors.append(f"{rel}:{lineno}: {symbol} is not defined in {where}")
            return m.group(0)
        if shown == i + 1 and anchor == i + 1:
            return m.group(0)
        if update:
            problems.warnings.append(f"{rel}:{lineno}: {symbol} in {where}: line {shown} -> {i + 1}")
            return f"[`{symbol}`:{i + 1}]({target}#L{i + 1})"
        problems.errors.append(f"{rel}:{lineno}: {symbol} is at {where}:{i + 1}, the docs say {shown}"
                               f"{'' if shown == anchor else f' and link to line {anchor}'}"
                               f" (run tools/docs_check.py --update)")
        return m.group(0)

    return [LINE_REF.sub(lambda m, n=n: fix(m, n), line) for n, line in enumerate(lines, 1)]


def check_links(root, md, lines, problems):
    rel = os.path.relpath(md, root)
    base = os.path.dirname(md)
    in_code = False
    for n, line in enumerate(lines, 1):
        if FENCE.match(line):
            in_code = not in_code
            continue
        if in_code:
            continue
        for target in LINK.findall(line) + IMG_TAG.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                continue
            path = target.split("#")[0]
            full = os.path.normpath(os.path.join(base, path))
            if os.path.exists(full):
                continue
            where = os.path.relpath(full, root)
            if where in PENDING:
                problems.warnings.append(f"{rel}:{n}: {where} does not exist yet (written by another part of the project)")
            else:
                problems.errors.append(f"{rel}:{n}: link or image {target} -> {where} does not exist")


def run(root, update):
    problems = Problems()
    number_files = {}  # the pictures and tables that quoted numbers come from, each read once
    for md in markdown_files(root):
        lines = read_lines(md)
        new = check_excerpts(root, md, lines, update, problems)
        new = check_line_refs(root, md, new, update, problems)
        new = check_numbers(root, md, new, update, problems, number_files)
        check_links(root, md, new, problems)
        if update and new != lines:
            with open(md, "w", encoding="utf-8") as f:
                f.write("\n".join(new))
    return problems


def main():
    parser = argparse.ArgumentParser(description="Check (or update) the code excerpts, line references "
                                                 "and links of README.md and docs/.")
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", action="store_true", help="report drift; exit 1 if any")
    mode.add_argument("--update", action="store_true", help="rewrite excerpts and line numbers from the source")
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                        help="the repository root (default: the parent of tools/)")
    args = parser.parse_args()
    if not os.path.isfile(os.path.join(args.root, "README.md")):
        print(f"docs_check: {args.root} has no README.md: give the repository root with --root", file=sys.stderr)
        return 2
    problems = run(args.root, args.update)
    path_report = check_reading_path(args.root, problems)  # docs/start_here.md's path, in words
    if path_report:
        print("docs_check: " + path_report)
    for w in problems.warnings:
        print("note: " + w)
    for e in problems.errors:
        print("error: " + e, file=sys.stderr)
    if problems.errors:
        print(f"docs_check: {len(problems.errors)} problem(s)", file=sys.stderr)
        return 1
    print("docs_check: excerpts, line references, links and quoted numbers agree with the source")
    return 0


if __name__ == "__main__":
    sys.exit(main())
