#!/usr/bin/env python3
"""Test of tools/docs_check.py (the check that keeps the book beside the article true to the
code): on a temporary copy of the repository, the checker passes as it is, then fails and
names the excerpt, the line reference or the image that was made to drift, and --update
repairs what can be repaired. The real repository is never modified.
usage: tools/test_docs_check.py [--root DIR]   (ctest entry docs_check_catches_drift)"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import docs_check  # noqa: E402


def run_check(root, mode="--check"):
    r = subprocess.run([sys.executable, os.path.join(root, "tools", "docs_check.py"), mode, "--root", root],
                       capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def first_match(root, rx):
    for md in docs_check.markdown_files(root):
        for line in docs_check.read_lines(md):
            m = rx.search(line)
            if m:
                return md, m
    return None, None


def expect(cond, what, output=""):
    if not cond:
        print("FAILED: " + what)
        if output:
            print(output)
        sys.exit(1)
    print("ok: " + what)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--root", default=os.path.dirname(HERE))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="docs_check_test_") as tmp:
        root = os.path.join(tmp, "repo")
        shutil.copytree(args.root, root, ignore=shutil.ignore_patterns(".git", "build*", "out"))

        rc, out = run_check(root)
        expect(rc == 0, "the unchanged copy passes --check", out)

        # 1. An excerpt drifts: change the first line of its code in the source.
        md, m = first_match(root, docs_check.EXCERPT)
        expect(m is not None, "the docs have at least one code excerpt")
        path, name = m.group(1), m.group(2)
        src = os.path.join(root, path)
        code, error = docs_check.excerpt_text(root, path, name)
        expect(error is None and code, f"excerpt {path}#{name} is found in the source", error or "")
        lines = docs_check.read_lines(src)
        longest = max(code, key=len).strip()  # a line of the excerpt found once in the source
        target = next(i for i, l in enumerate(lines) if l.strip() == longest)
        lines[target] = lines[target] + "  // drifted"
        with open(src, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
        rc, out = run_check(root)
        expect(rc == 1 and f"excerpt {path}#{name} differs from the source" in out,
               f"--check fails and names the drifted excerpt {path}#{name}", out)

        # 2. A line reference drifts: a line inserted above the symbol it names.
        md2, m2 = first_match(root, docs_check.LINE_REF)
        expect(m2 is not None, "the docs have at least one line reference")
        symbol, target_rel = m2.group(1), m2.group(3)
        ref_file = os.path.normpath(os.path.join(os.path.dirname(md2), target_rel))
        with open(ref_file, encoding="utf-8") as f:
            text = f.read()
        with open(ref_file, "w", encoding="utf-8") as f:
            f.write("// an inserted line\n" + text)
        rc, out = run_check(root)
        expect(rc == 1 and re.search(re.escape(symbol) + r" is at .*:\d+, the docs say \d+", out) is not None,
               f"--check fails and names the moved symbol {symbol}", out)

        # 3. --update repairs both; --check passes again.
        rc, out = run_check(root, "--update")
        expect(rc == 0, "--update rewrites the excerpt and the line numbers", out)
        rc, out = run_check(root)
        expect(rc == 0, "--check passes after --update", out)

        # 4. A picture the docs show is missing.
        md3, m3 = first_match(root, re.compile(r"!\[[^\]]*\]\(([^)\s]+)\)"))
        expect(m3 is not None, "the docs show at least one picture")
        image = os.path.normpath(os.path.join(os.path.dirname(md3), m3.group(1)))
        os.remove(image)
        rc, out = run_check(root)
        expect(rc == 1 and f"{os.path.relpath(image, root)} does not exist" in out,
               f"--check fails and names the missing picture {os.path.relpath(image, root)}", out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
