#!/usr/bin/env python3
"""Test of tools/docs_check.py (the check that keeps the book beside the article true to the
code): on a temporary copy of the repository, the checker passes as it is, then fails and
names the excerpt, the line reference or the image that was made to drift, and --update
repairs what can be repaired; a reading path grown past 15,000 words fails it too. The real repository is never modified.
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

        # 3b. A number quoted about a picture drifts from its metadata (docs_numbers.py).
        check_quoted_numbers(root, tmp)

        # 4. A picture the docs show is missing.
        md3, m3 = first_match(root, re.compile(r"!\[[^\]]*\]\(([^)\s]+)\)"))
        expect(m3 is not None, "the docs show at least one picture")
        image = os.path.normpath(os.path.join(os.path.dirname(md3), m3.group(1)))
        os.remove(image)
        rc, out = run_check(root)
        expect(rc == 1 and f"{os.path.relpath(image, root)} does not exist" in out,
               f"--check fails and names the missing picture {os.path.relpath(image, root)}", out)

        # 5. The reading path of docs/start_here.md grows past its limit (docs_path.py).
        test_reading_path(root)
    return 0


def test_reading_path(root):
    import docs_path
    items = docs_path.reading_path(root)
    expect(items, "docs/start_here.md lists a reading path")
    rc, out = run_check(root)
    expect(re.search(r"reading path: \d+ words in \d+ files \(limit 15000\)", out) is not None,
           "--check reports the reading path's word count", out)
    required = [rel for rel, optional in items if not optional]
    optional = [rel for rel, opt in items if opt]
    total = sum(docs_path.words(os.path.join(root, rel)) for rel in required)
    if optional:  # an optional file may grow without bound
        with open(os.path.join(root, optional[0]), "a", encoding="utf-8") as f:
            f.write("\n" + "word " * (docs_path.PATH_LIMIT + 1))
        rc, out = run_check(root)
        expect("reading path has" not in out, "an optional file of the path is not held to the limit", out)
    with open(os.path.join(root, required[-1]), "a", encoding="utf-8") as f:
        f.write("\n" + "word " * (docs_path.PATH_LIMIT - total + 1))
    rc, out = run_check(root)
    expect(rc == 1 and f"the reading path has {docs_path.PATH_LIMIT + 1} words, more than {docs_path.PATH_LIMIT}" in out,
           "--check fails when the reading path is one word over its limit", out)


def write_png(path, pixels, text):
    """A small 8-bit RGB PNG: PIXELS rows of (r, g, b), TEXT {key: value} as tEXt chunks."""
    import struct
    import zlib

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\0" + bytes(v for px in row for v in px) for row in pixels)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", len(pixels[0]), len(pixels), 8, 2, 0, 0, 0))
    data += b"".join(chunk(b"tEXt", k.encode() + b"\0" + v.encode()) for k, v in text.items())
    data += chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(data)


def check_quoted_numbers(root, tmp):
    """A marked number must equal its file's value at the docs' precision: on the repository's
    own markers, then each kind of source on small files made here."""
    import docs_numbers
    md, m = first_match(root, docs_numbers.MARKER)
    expect(m is not None, "the docs mark at least one quoted number")
    lines = docs_check.read_lines(md)
    n = next(i for i, line in enumerate(lines) if docs_numbers.MARKER.search(line))
    quoted = list(docs_numbers.NUMBER.finditer(lines[n][:docs_numbers.MARKER.search(lines[n]).start()]))[-1]
    wrong = "9" + quoted.group(0)
    original = lines[n]
    lines[n] = original[:quoted.start()] + wrong + original[quoted.end():]
    with open(md, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    rc, out = run_check(root)
    expect(rc == 1 and f"the docs say {m.group(1).split()[-1]} {wrong}," in out,
           f"--check fails when {os.path.relpath(md, root)} quotes {wrong} for {quoted.group(0)}", out)
    rc, out = run_check(root, "--update")
    expect(rc == 0 and docs_check.read_lines(md)[n] == original, "--update writes the file's value back", out)

    d = os.path.join(tmp, "numbers")
    os.makedirs(d)
    write_png(os.path.join(d, "a.png"), [[(10, 20, 30), (20, 20, 30)]], {"pt:spp": "576", "pt:seconds": "8.136478"})
    with open(os.path.join(d, "t.csv"), "w", encoding="utf-8") as f:
        f.write("scene,stage,spp,rel_rmse\nbox,s4,1,0.5\nbox,s4,4,0.25\nbox,s5,4,3.29209e-05\n")

    def check(text):
        problems = docs_check.Problems()
        page = os.path.join(d, "page.md")
        out = docs_numbers.check_numbers(d, page, [text], True, problems)
        docs_numbers.check_numbers(d, page, [text], False, problems)
        return problems.errors, out[0]
    cases = [  # (text, the error expected or None, what it shows)
        ("576 spp, 8.136 s <!-- numbers: a.png spp seconds -->", None, "spp and seconds equal to the metadata pass"),
        ("8.1 s <!-- numbers: a.png seconds -->", None, "a number rounded to fewer decimals passes"),
        ("577 spp <!-- numbers: a.png spp -->", "the docs say spp 577, a.png says 576", "an spp that differs fails"),
        ("8.4 s <!-- numbers: a.png seconds -->", "the docs say seconds 8.4, a.png says 8.1", "seconds that differ fail"),
        ("R 15.0 <!-- numbers: a.png mean.R -->", None, "a channel mean computed from the pixels passes"),
        ("R 15.5 <!-- numbers: a.png mean.R -->", "says 15.0", "a channel mean that differs fails"),
        ("0.25 <!-- numbers: t.csv scene=box stage=s4 spp=4 rel_rmse -->", None, "a CSV cell picked by filters passes"),
        ("0.25 <!-- numbers: t.csv stage=s4 spp=max rel_rmse -->", None, "spp=max picks the last checkpoint"),
        ("3.3e-5 <!-- numbers: t.csv stage=s5 rel_rmse -->", None, "a number in e-notation passes"),
        ("2.0 <!-- numbers: t.csv spp=1 rel_rmse[stage=s4]/rel_rmse[spp=4,stage=s4] -->", None, "a ratio of two cells passes"),
        ("0.3 <!-- numbers: t.csv stage=s4 rel_rmse -->", "2 rows match", "filters that pick two rows fail"),
        ("1 <!-- numbers: a.png pt:seed -->", "has no attribute pt:seed", "a missing attribute fails"),
        ("8.136 <!-- numbers: a.png spp seconds -->", "names 2 value(s) but 1 number(s)", "a marker with too few numbers fails"),
        ("5 <!-- numbers: missing.png spp -->", "does not exist", "a missing file fails"),
    ]
    for text, error, what in cases:
        errors, updated = check(text)
        if error is None:
            expect(not errors and updated == text, what, "\n".join(errors))
        else:
            expect(any(error in e for e in errors), what, "\n".join(errors) or "(no error)")
    expect(check("577 spp <!-- numbers: a.png spp -->")[1] == "576 spp <!-- numbers: a.png spp -->",
           "--update rewrites a drifted number from the metadata")


if __name__ == "__main__":
    sys.exit(main())
