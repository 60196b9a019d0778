#!/usr/bin/env python3
"""Makes the students' copy of lab N (docs/labs/README.md; labs 1-4 follow the article's
Eq. 2 to 5, lab 5 the BVH after it, lab 6 stage5_mis's multiple importance sampling): the
repository without .git and build folders, in which
  - the reference code of the functions lab N asks for (the files its build replaces by
    labs/labN.glsl, see cmake/Labs.cmake) is removed from their bodies, and the chapters'
    excerpts of them too, so the answer is not handed out with the question;
  - other copies of that answer, marked in the source as a region between a line holding
    [lab N answer] and one holding [/lab N answer] (cpu/wide_bvh_walk_lanes.h: lab 5's slab test
    on SIMD lanes), are cut, markers included;
  - the teacher's held-back tests, every Catch2 TEST_CASE in tests/ tagged [held_back] (with
    the comment lines just above it; a file whose every test is held back keeps only its
    opening comment), are removed: they grade the class (tools/grade_lab.py builds the
    teacher's tree), but the students never see them (docs/labs/teachers.md);
  - the known-wrong answers of labs/mutants.h (each is an answer with one thing wrong) are
    removed too, down to the file's opening comment (the check build then has no mutants);
    these two steps are in handout_held_back.py;
  - the comments of the reference files, which name the formulas, are cut (a one-line note
    opens each instead), and in the docs every piece of code (a `span` or a line of a code
    block) that quotes a statement of the reference bodies which no other source file holds
    is replaced by a note (issue 47: the errata and the stage2 chapter quoted lab 2's weight).
usage: tools/make_lab_handout.py N DEST     (DEST must not exist yet)"""
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import docs_check  # noqa: E402
from handout_held_back import HELD_BACK_FILES, strip_held_back, strip_held_back_files  # noqa: E402,F401

# What a function of each return type returns in the handout in place of its body; lab N's
# build never compiles it (it compiles labs/labN.glsl instead).
DEFAULTS = {"vec2": "vec2(0.0f)", "vec3": "vec3(0.0f)", "float": "0.0f", "bool": "false", "LightSample": "no_light()"}
# The files whose functions each lab asks for: what its build replaces by labs/labN.glsl
# (cmake/Labs.cmake; lab 1: stage1's integrator, pt_add_stage's LAB option).
REFERENCE_FILES = {
    1: ["stage1_raycast/integrator.glsl"],
    2: ["common/kernel/uniform_hemisphere.glsl", "common/kernel/russian_roulette.glsl"],
    3: ["common/kernel/cosine_hemisphere.glsl"],
    4: ["common/kernel/triangle_light.glsl", "common/kernel/emission_rule.glsl"],
    5: ["common/kernel/box_slab.glsl"],
    6: ["common/kernel/mis.glsl"],
}
DEFINITION = re.compile(r"^(\w+)\s+(\w+)\s*\(.*\{\s*$")
# Regions of other files that hold a copy of lab N's answer; the files they may be in.
REGION_START = re.compile(r"\[lab (\d) answer\]")
REGION_END = re.compile(r"\[/lab (\d) answer\]")
SOURCE_ENDINGS = (".glsl", ".comp", ".h", ".cpp")

def strip_sources(dest, lab):
    """Replaces the body of every function of lab N's reference files; returns their (path, name)."""
    names = []
    for rel in REFERENCE_FILES[lab]:
        path = os.path.join(dest, rel)
        lines = docs_check.read_lines(path)
        out = []
        i = 0
        while i < len(lines):
            out.append(lines[i])
            m = DEFINITION.match(lines[i])
            end = docs_check.block_end(lines, i) if m else None
            if not m or end is None:
                i += 1
                continue
            if m.group(1) not in DEFAULTS:
                raise SystemExit(f"make_lab_handout: {rel}:{i + 1}: no default for a function returning {m.group(1)}")
            names.append((rel, m.group(2)))
            out.append(f"  // The reference code is not in the lab {lab} handout: write {m.group(2)} in "
                       f"labs/lab{lab}.glsl (docs/labs/lab{lab}.md).")
            out.append(f"  return {DEFAULTS[m.group(1)]};")
            out.append(lines[end])
            i = end + 1
        with open(path, "w", encoding="utf-8") as fh:
            fh.write("\n".join(out))
    return names


def strip_reference_comments(dest, lab):
    """Cuts every comment line of lab N's reference files; a one-line note opens each instead."""
    for rel in REFERENCE_FILES[lab]:
        path = os.path.join(dest, rel)
        lines = docs_check.read_lines(path)
        keep = [line for line in lines if not line.lstrip().startswith("//")
                or line.lstrip().startswith("// The reference code is not in the lab")]
        keep = [re.sub(r"\s*//.*$", "", line) if "#endif" in line else line for line in keep]
        with open(path, "w", encoding="utf-8") as fh:
            fh.write("\n".join([f"// In the lab {lab} handout the functions of this file are yours to write, in "
                                f"labs/lab{lab}.glsl (docs/labs/lab{lab}.md)."] + keep))


def squeeze(text):
    return re.sub(r"\s+", "", text)


def answer_statements(root, lab):
    """The statements of lab N's reference bodies (squeezed, without 'return', a declaration's
    left side or ';') that are long enough to be telling, name a variable or function, and that
    no other source file of the kernel and stages holds: what the docs must not quote."""
    statements = set()
    for rel in REFERENCE_FILES[lab]:
        lines = docs_check.read_lines(os.path.join(root, rel))
        for i, line in enumerate(lines):
            end = docs_check.block_end(lines, i) if DEFINITION.match(line) else None
            for body_line in (lines[i + 1:end] if end is not None else []):
                code = body_line.split("//")[0].strip().rstrip(";")
                code = re.sub(r"^(return\s+|(\w+\s+)?\w+\s*=\s*)", "", code)
                names = [n for n in re.findall(r"\b[A-Za-z_]\w*", code) if not re.fullmatch(r"k[A-Z]\w*", n)]
                if len(squeeze(code)) >= 12 and names:  # a constant alone (1 / (2 pi)) says no more than the lab page
                    statements.add(squeeze(code))
    elsewhere = ""
    for rel in source_files(root):
        if rel not in REFERENCE_FILES[lab] and not rel.startswith(("tests/", "labs/")):
            elsewhere += squeeze(open(os.path.join(root, rel), encoding="utf-8", errors="replace").read())
    return sorted(s for s in statements if s not in elsewhere)


def strip_doc_quotes(dest, lab, statements):
    """Replaces each `span` and code-block line of the docs that holds one of statements by a
    note; returns the files changed."""
    note = f"(lab {lab}'s answer: not in its handout)"
    changed = []
    for md in docs_check.markdown_files(dest):
        text = open(md, encoding="utf-8").read()
        lines, out, fenced = text.split("\n"), [], False
        for line in lines:
            if docs_check.FENCE.match(line):
                fenced = not fenced
            elif fenced and any(s in squeeze(line) for s in statements):
                line = re.match(r"\s*", line).group(0) + "// " + note
            elif not fenced:
                line = re.sub(r"`[^`]+`", lambda m: note if any(s in squeeze(m.group(0)) for s in statements)
                              else m.group(0), line)
            out.append(line)
        if out != lines:
            with open(md, "w", encoding="utf-8") as fh:
                fh.write("\n".join(out))
            changed.append(os.path.relpath(md, dest))
    return changed


def source_files(dest, top=""):
    """The project's source files under dest/top, as paths relative to dest (not in .git, out/
    or a build folder, as the handout's copy leaves them out)."""
    found = []
    for root, dirs, files in os.walk(os.path.join(dest, top)):
        dirs[:] = sorted(d for d in dirs if not (d in (".git", "out") or d.startswith("build")))
        found += [os.path.relpath(os.path.join(root, f), dest) for f in sorted(files) if f.endswith(SOURCE_ENDINGS)]
    return found


def strip_regions(dest, lab):
    """Cuts every [lab N answer] ... [/lab N answer] region; returns the files cut."""
    cut = []
    for rel in source_files(dest):
        lines = docs_check.read_lines(os.path.join(dest, rel))
        out, start = [], None
        for i, line in enumerate(lines):
            m, e = REGION_START.search(line), REGION_END.search(line)
            if m and int(m.group(1)) == lab:
                if start is not None:
                    raise SystemExit(f"make_lab_handout: {rel}:{i + 1}: a [lab {lab} answer] inside another")
                start = i
                indent = line[:len(line) - len(line.lstrip())]
                out.append(f"{indent}// Lab {lab}'s answer is cut from here in its handout (tools/make_lab_handout.py).")
            elif e and int(e.group(1)) == lab:
                if start is None:
                    raise SystemExit(f"make_lab_handout: {rel}:{i + 1}: [/lab {lab} answer] without its start")
                start = None
            elif start is None:
                out.append(line)
        if start is not None:
            raise SystemExit(f"make_lab_handout: {rel}:{start + 1}: [lab {lab} answer] is never closed")
        if out != lines:
            with open(os.path.join(dest, rel), "w", encoding="utf-8") as fh:
                fh.write("\n".join(out))
            cut.append(rel)
    return cut


def strip_docs(dest, lab, names):
    """Replaces the docs' excerpts of the removed functions by a note."""
    for md in docs_check.markdown_files(dest):
        lines = docs_check.read_lines(md)
        out = []
        i = 0
        while i < len(lines):
            m = docs_check.EXCERPT.match(lines[i])
            if m and (m.group(1), m.group(2)) in names and i + 1 < len(lines) and docs_check.FENCE.match(lines[i + 1]):
                end = i + 2
                while end < len(lines) and not docs_check.FENCE.match(lines[end]):
                    end += 1
                out += [lines[i + 1], f"// {m.group(2)}: not in the lab {lab} handout; you write it in "
                                      f"labs/lab{lab}.glsl", "```"]
                i = end + 1
                continue
            out.append(lines[i])
            i += 1
        if out != lines:
            with open(md, "w", encoding="utf-8") as fh:
                fh.write("\n".join(out))


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in [str(lab) for lab in REFERENCE_FILES]:
        print("usage: tools/make_lab_handout.py N DEST   (N = 1 to 6; DEST a new folder)", file=sys.stderr)
        return 2
    lab, dest = int(sys.argv[1]), sys.argv[2]
    if os.path.exists(dest):
        print(f"make_lab_handout: {dest} already exists; give a new folder so that nothing is overwritten",
              file=sys.stderr)
        return 2
    root = os.path.dirname(HERE)
    shutil.copytree(root, dest, ignore=shutil.ignore_patterns(".git", "build*", "out"))
    names = strip_sources(dest, lab)
    if not names:
        shutil.rmtree(dest)
        print(f"make_lab_handout: no function found in {', '.join(REFERENCE_FILES[lab])}", file=sys.stderr)
        return 1
    strip_docs(dest, lab, names)
    strip_doc_quotes(dest, lab, answer_statements(root, lab))
    strip_reference_comments(dest, lab)
    regions = strip_regions(dest, lab)
    held_back = strip_held_back(dest, source_files(dest, "tests"))
    held_back += [(rel, 1) for rel in strip_held_back_files(dest)]
    # The shorter bodies move the lines below them: renumber the docs' line references.
    problems = docs_check.run(dest, update=True)
    if problems.errors:
        print("\n".join(problems.errors), file=sys.stderr)
        return 1
    print(f"make_lab_handout: {dest}: lab {lab}, reference code removed from {', '.join(p + '#' + n for p, n in names)}; "
          f"answer regions cut from {', '.join(regions) or 'no other file'}; "
          f"{len(held_back)} held-back test(s) removed{': ' if held_back else ''}"
          f"{', '.join(f'{p}:{n}' for p, n in held_back)}; "
          f"build it with -DPT_LAB={lab} and grade with ctest -L lab{lab}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
