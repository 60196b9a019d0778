#!/usr/bin/env python3
"""Makes the students' copy of lab N (docs/labs/README.md; labs 1-4 follow the article's
Eq. 2 to 5, lab 5 the BVH after it, lab 6 stage5_mis's multiple importance sampling): the repository without .git and build folders, in which
the reference code of the functions lab N asks for (the files its build replaces by
labs/labN.glsl, see cmake/Labs.cmake) is removed from their bodies, and the chapters'
excerpts of them too, so the answer is not handed out with the question.
usage: tools/make_lab_handout.py N DEST     (DEST must not exist yet)"""
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import docs_check  # noqa: E402

# What a function of each return type returns in the handout in place of its body; lab N's
# build never compiles it (it compiles labs/labN.glsl instead).
DEFAULTS = {"vec2": "vec2(0.0f)", "vec3": "vec3(0.0f)", "float": "0.0f", "LightSample": "no_light()"}
# The files whose functions each lab asks for: what its build replaces by labs/labN.glsl
# (cmake/Labs.cmake; lab 1: stage1's integrator, pt_add_stage's LAB option).
REFERENCE_FILES = {
    1: ["stage1_raycast/integrator.glsl"],
    2: ["common/kernel/uniform_hemisphere.glsl"],
    3: ["common/kernel/cosine_hemisphere.glsl"],
    4: ["common/kernel/triangle_light.glsl"],
    5: ["common/kernel/box_slab.glsl"],
    6: ["common/kernel/mis.glsl"],
}
DEFINITION = re.compile(r"^(\w+)\s+(\w+)\s*\(.*\{\s*$")


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
    # The shorter bodies move the lines below them: renumber the docs' line references.
    problems = docs_check.run(dest, update=True)
    if problems.errors:
        print("\n".join(problems.errors), file=sys.stderr)
        return 1
    print(f"make_lab_handout: {dest}: lab {lab}, reference code removed from {', '.join(p + '#' + n for p, n in names)}; "
          f"build it with -DPT_LAB={lab} and grade with ctest -L lab{lab}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
