#!/usr/bin/env python3
"""Test of tools/make_lab_handout.py (the students' copy of a lab; the labs follow the
article's Eq. 2 to 5, lab 5 the BVH after it, lab 6 stage5_mis's MIS): for each lab, the reference functions in
the handout keep only a comment and a return, no chapter shows their code, the handout's docs still pass
docs_check, and the lab's stage and stage4 still compile to SPIR-V in that lab's build
(configured with -DPT_LAB=N). Refuses an existing DEST.
usage: tools/test_make_lab_handout.py CMAKE   (ctest entry lab_handout)"""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import docs_check  # noqa: E402

# The stage each lab's build is checked with (besides stage4): lab 5's slab test serves every stage.
STAGES = ("stage1_raycast", "stage2_montecarlo", "stage3_importance", "stage4_direct_indirect", "stage1_raycast",
          "stage5_mis")


def expect(cond, what, output=""):
    if not cond:
        print("FAILED: " + what)
        if output:
            print(output)
        sys.exit(1)
    print("ok: " + what)


def main():
    if len(sys.argv) != 2:
        print("usage: tools/test_make_lab_handout.py CMAKE", file=sys.stderr)
        return 2
    cmake = sys.argv[1]
    tool = os.path.join(HERE, "make_lab_handout.py")
    with tempfile.TemporaryDirectory(prefix="lab_handout_test_") as tmp:
        existing = os.path.join(tmp, "existing")
        os.mkdir(existing)
        r = subprocess.run([sys.executable, tool, "2", existing], capture_output=True, text=True)
        expect(r.returncode == 2 and "already exists" in r.stderr and os.listdir(existing) == [],
               "an existing destination is refused and left alone", r.stderr)
        for lab in range(1, len(STAGES) + 1):
            dest = os.path.join(tmp, f"lab{lab}")
            r = subprocess.run([sys.executable, tool, str(lab), dest], capture_output=True, text=True)
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
            r = subprocess.run([sys.executable, os.path.join(dest, "tools", "docs_check.py"), "--check"],
                               capture_output=True, text=True)
            expect(r.returncode == 0, f"lab {lab}: the handout's docs pass docs_check", r.stdout + r.stderr)
            # The lab's own stage, and stage4, in the lab's build: configure, then the SPIR-V only.
            build = os.path.join(tmp, f"build{lab}")
            r = subprocess.run([cmake, "-S", dest, "-B", build, f"-DPT_LAB={lab}"], capture_output=True, text=True)
            expect(r.returncode == 0, f"lab {lab}: the handout configures with -DPT_LAB={lab}", r.stdout + r.stderr)
            for stage in sorted({STAGES[lab - 1], STAGES[3]}):
                r = subprocess.run([cmake, "--build", build, "--target", f"{stage}_spirv"], capture_output=True, text=True)
                expect(r.returncode == 0, f"lab {lab}: {stage} compiles to SPIR-V in lab mode", r.stdout + r.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
