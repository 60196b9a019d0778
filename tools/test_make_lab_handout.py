#!/usr/bin/env python3
"""Test of tools/make_lab_handout.py (the students' copy of a lab; the labs follow the
article's Eq. 2 to 5, lab 5 the BVH after it, lab 6 stage5_mis's MIS). For each lab:
  - the handout carries no answer: the reference functions keep only a comment and a return,
    no chapter shows their code, and no file of the handout (code, docs, tests, tools) holds
    the body of any function of the lab's reference files, nor a [lab N answer] region of
    the teacher's tree (whitespace and // comments aside), no doc quotes a statement of those
    bodies that no other source file holds (issue 47), and the reference files keep none of
    their comments (which named the formulas); every function the student's labs/labN.glsl
    defines has its reference among those functions;
  - the teacher's held-back tests (Catch2 tag [held_back]; the teacher's tree must hold one)
    are in no handout, nor the known-wrong answers of labs/mutants.h;
  - the handout's docs pass docs_check, the lab's stage and stage4 still compile to SPIR-V in
    that lab's build (configured with -DPT_LAB=N), and so do the files the tool cut a region
    from, and (in lab 4's build) the test files it cut held-back tests from.
Refuses an existing DEST.
usage: tools/test_make_lab_handout.py CMAKE   (ctest entry lab_handout)"""
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import docs_check  # noqa: E402
import make_lab_handout as tool  # noqa: E402

# The stage each lab's build is checked with (besides stage4): lab 5's slab test serves every stage.
STAGES = ("stage1_raycast", "stage2_montecarlo", "stage3_importance", "stage4_direct_indirect", "stage1_raycast",
          "stage5_mis")
# The lab whose handout build also compiles the test files that held-back tests were cut from.
COMPILE_TESTS_IN = 4
# What the handout must leave out, as docs/labs/README.md and teachers.md define it (written
# out here rather than taken from the tool, so that the test judges the tool).
DEFINITION = re.compile(r"^(\w+)\s+(\w+)\s*\(.*\{\s*$")
REGION_START = re.compile(r"\[lab (\d) answer\]")
REGION_END = re.compile(r"\[/lab (\d) answer\]")
TEST_CASE = re.compile(r"^(TEST_CASE|TEST_CASE_METHOD|SCENARIO)\s*\(")
HELD_BACK = "[held_back]"
SOURCE_ENDINGS = (".glsl", ".comp", ".h", ".cpp")


def expect(cond, what, output=""):
    if not cond:
        print("FAILED: " + what)
        if output:
            print(output)
        sys.exit(1)
    print("ok: " + what)


def squeeze(lines):
    """Code without // comments and whitespace, as one string: how a copy is recognised."""
    return "".join(re.sub(r"\s+", "", line.split("//")[0]) for line in lines)


def text_files(root):
    """(path relative to root, text) of every UTF-8 file of a tree."""
    for base, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__")
        for f in sorted(files):
            try:
                yield os.path.relpath(os.path.join(base, f), root), open(os.path.join(base, f), encoding="utf-8").read()
            except (UnicodeDecodeError, OSError):
                continue


def source_files(root, top=""):
    """The source files under root/top (not in .git, out/ or a build folder), relative to root."""
    found = []
    for base, dirs, files in os.walk(os.path.join(root, top)):
        dirs[:] = sorted(d for d in dirs if not (d in (".git", "out") or d.startswith("build")))
        found += [os.path.relpath(os.path.join(base, f), root) for f in sorted(files) if f.endswith(SOURCE_ENDINGS)]
    return found


def functions(path):
    """name -> body lines of every top-level definition of a reference file."""
    lines = docs_check.read_lines(path)
    found = {}
    for i, line in enumerate(lines):
        m = DEFINITION.match(line)
        end = docs_check.block_end(lines, i) if m else None
        if end is not None:
            found[m.group(2)] = lines[i + 1:end]
    return found


def answer(root, lab):
    """What lab N's handout must not hold, from the teacher's tree: {what: squeezed code}."""
    bodies = {}
    for rel in tool.REFERENCE_FILES[lab]:
        for name, body in functions(os.path.join(root, rel)).items():
            bodies[f"{rel}#{name}"] = squeeze(body)
    for rel in source_files(root):
        lines, start = docs_check.read_lines(os.path.join(root, rel)), None
        for i, line in enumerate(lines):
            if (REGION_START.search(line) or [None, None])[1] == str(lab):
                start = i + 1
            elif start is not None and REGION_END.search(line):
                bodies[f"{rel}:{start} [lab {lab} answer]"] = squeeze(lines[start:i])
                start = None
    return {what: code for what, code in bodies.items() if code}


def quoted_statements(root, lab):
    """The statements of lab N's reference bodies, squeezed and without 'return', a declared
    name or ';', that name a variable or function, are 12 characters or more, and appear in no
    other source file of the kernel and stages: the pieces a doc must not quote (issue 47)."""
    found = set()
    for rel in tool.REFERENCE_FILES[lab]:
        for body in functions(os.path.join(root, rel)).values():
            for line in body:
                code = re.sub(r"^(return\s+|(\w+\s+)?\w+\s*=\s*)", "", line.split("//")[0].strip().rstrip(";"))
                if len(squeeze([code])) >= 12 and any(not re.fullmatch(r"k[A-Z]\w*", n)
                                                      for n in re.findall(r"\b[A-Za-z_]\w*", code)):
                    found.add(squeeze([code]))
    others = "".join(squeeze(docs_check.read_lines(os.path.join(root, rel))) for rel in source_files(root)
                     if rel not in tool.REFERENCE_FILES[lab] and not rel.startswith(("tests/", "labs/")))
    return {s for s in found if s not in others}


def leaks(root, handout, lab):
    """Where the handout of lab N still holds its answer (the teacher's tree is root)."""
    bodies = answer(root, lab)
    statements = quoted_statements(root, lab)
    found_comments = []
    for rel in tool.REFERENCE_FILES[lab]:
        comments = [line.strip() for line in docs_check.read_lines(os.path.join(handout, rel))
                    if line.strip().startswith("//")]
        kept = [c for c in comments[1:] if not c.startswith("// The reference code is not in the lab")]
        if kept:
            found_comments.append(f"{rel} keeps a comment of the reference: '{kept[0][:60]}'")
    student = set(functions(os.path.join(root, "labs", f"lab{lab}.glsl")))
    references = {what.split("#")[1] for what in bodies if "#" in what}
    found = [f"labs/lab{lab}.glsl asks for {name}, which no reference file of lab {lab} defines"
             for name in sorted(student - references)] + found_comments
    for rel, text in text_files(handout):
        code = squeeze(text.split("\n"))
        found += [f"{rel} holds {what}" for what, body in bodies.items() if body in code]
        if rel.endswith(".md"):
            found += [f"{rel} quotes lab {lab}'s statement #{k}" for k, st in enumerate(sorted(statements)) if st in code]
        if rel.endswith(SOURCE_ENDINGS) and str(lab) in {m.group(1) for m in REGION_START.finditer(text)}:
            found.append(f"{rel} keeps a [lab {lab} answer] region")
    return found


def held_back_tests(root):
    """(file, test name) of every test case tagged [held_back] under root/tests."""
    tests = []
    for rel in source_files(root, "tests"):
        lines = docs_check.read_lines(os.path.join(root, rel))
        for i, line in enumerate(lines):
            if TEST_CASE.match(line):
                header = " ".join(lines[i:i + 3])
                name = re.search(r'"((?:[^"\\]|\\.)*)"', header)
                if HELD_BACK in header.split("{")[0] and name:
                    tests.append((rel, name.group(1)))
    return tests


def main():
    if len(sys.argv) != 2:
        print("usage: tools/test_make_lab_handout.py CMAKE", file=sys.stderr)
        return 2
    cmake = sys.argv[1]
    script = os.path.join(HERE, "make_lab_handout.py")
    held_back = held_back_tests(REPO)
    expect(held_back, "the teacher's tree holds held-back tests ([held_back])")
    for lab in range(1, len(STAGES) + 1):
        expect(answer(REPO, lab), f"lab {lab}: the teacher's tree holds lab {lab}'s answer")
    with tempfile.TemporaryDirectory(prefix="lab_handout_test_") as tmp:
        existing = os.path.join(tmp, "existing")
        os.mkdir(existing)
        r = subprocess.run([sys.executable, script, "2", existing], capture_output=True, text=True)
        expect(r.returncode == 2 and "already exists" in r.stderr and os.listdir(existing) == [],
               "an existing destination is refused and left alone", r.stderr)
        for lab in range(1, len(STAGES) + 1):
            dest = os.path.join(tmp, f"lab{lab}")
            r = subprocess.run([sys.executable, script, str(lab), dest], capture_output=True, text=True)
            expect(r.returncode == 0, f"lab {lab}: the handout is made", r.stdout + r.stderr)
            removed = [item.split("#") for item in r.stdout.split("removed from ")[1].split(";")[0].split(", ")]
            for path, name in removed:
                lines = docs_check.read_lines(os.path.join(dest, path))
                start = docs_check.definition_line(lines, name)
                end = docs_check.block_end(lines, start)
                body = [l.strip() for l in lines[start + 1:end]]
                expect(len(body) == 2 and body[0].startswith("// The reference code is not") and body[1].startswith("return "),
                       f"lab {lab}: {path}#{name} keeps only a comment and a return", "\n".join(body))
                for md in docs_check.markdown_files(dest):
                    text = open(md, encoding="utf-8").read()
                    expect(f"<!-- excerpt: {path}#{name} -->" not in text,
                           f"lab {lab}: {os.path.relpath(md, dest)} shows no excerpt of {name}")
            found = leaks(REPO, dest, lab)
            expect(not found, f"lab {lab}: no file of the handout holds lab {lab}'s answer", "\n".join(found))
            left = {f"{rel}: {name}" for rel, name in held_back_tests(dest)}
            left |= {f"{rel}: {name}" for rel, name in held_back if os.path.isfile(os.path.join(dest, rel))
                     and f'"{name}"' in open(os.path.join(dest, rel), encoding="utf-8").read()}
            expect(not left, f"lab {lab}: the handout has none of the {len(held_back)} held-back test(s)",
                   "\n".join(sorted(left)))
            mutants = open(os.path.join(dest, "labs", "mutants.h"), encoding="utf-8").read()
            expect("is_mutant(" in open(os.path.join(REPO, "labs", "mutants.h"), encoding="utf-8").read()
                   and "is_mutant(" not in mutants, f"lab {lab}: the handout holds none of the mutants", mutants)
            r = subprocess.run([sys.executable, os.path.join(dest, "tools", "docs_check.py"), "--check"],
                               capture_output=True, text=True)
            expect(r.returncode == 0, f"lab {lab}: the handout's docs pass docs_check", r.stdout + r.stderr)
            # The lab's own stage, and stage4, in the lab's build: configure, then the SPIR-V only.
            # The test files one by one (no unity build), so that one of them compiles alone below.
            build = os.path.join(tmp, f"build{lab}")
            r = subprocess.run([cmake, "-S", dest, "-B", build, "-G", "Unix Makefiles", f"-DPT_LAB={lab}",
                                "-DPT_TEST_UNITY=OFF"],
                               capture_output=True, text=True)
            expect(r.returncode == 0, f"lab {lab}: the handout configures with -DPT_LAB={lab}", r.stdout + r.stderr)
            for stage in sorted({STAGES[lab - 1], STAGES[3]}):
                r = subprocess.run([cmake, "--build", build, "--target", f"{stage}_spirv"], capture_output=True, text=True)
                expect(r.returncode == 0, f"lab {lab}: {stage} compiles to SPIR-V in lab mode", r.stdout + r.stderr)
            # The files the tool cut code from besides the reference files still compile.
            cut = {what.split(":")[0]: "its answer region" for what in answer(REPO, lab) if "#" not in what}
            if lab == COMPILE_TESTS_IN:
                cut.update({rel: "its held-back tests" for rel, _ in held_back})
            for rel, what in sorted(cut.items()):
                for unit in compiled_units(dest, rel):
                    top, obj = unit.split("/", 1)  # the object's target in the Makefile of the build's top/
                    r = subprocess.run([cmake, "--build", os.path.join(build, top), "--target", obj + ".o"],
                                       capture_output=True, text=True)
                    expect(r.returncode == 0, f"lab {lab}: {rel} compiles without {what} ({unit})", r.stdout + r.stderr)
    return 0


def compiled_units(dest, rel):
    """The .cpp files of rel's folder that compile rel: rel itself when it is one; for a header,
    the files that #include it and those that #include them (cpu/wide_bvh_walk_lanes.h is in
    wide_bvh_walk.cpp, which the AVX2 and AVX-512 copies include)."""
    if rel.endswith(".cpp"):
        return [rel]
    folder = os.path.dirname(rel)
    units, todo = [], [rel]
    for _ in range(2):
        found = []
        for name in sorted(os.listdir(os.path.join(dest, folder))):
            path = os.path.join(folder, name)
            if name.endswith(".cpp") and any(f'#include "{t}"' in open(os.path.join(dest, path), encoding="utf-8").read()
                                             for t in todo):
                found.append(path)
        units += [u for u in found if u not in units]
        todo = found
    return units


if __name__ == "__main__":
    sys.exit(main())
