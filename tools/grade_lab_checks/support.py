"""What the checks of tools/test_grade_lab.py share (tooling for teachers, not a part of the
article): expect(), the paths of the repository and the grader, and writing submissions made
from the reference files."""
import os
import re
import sys

from grading.work_build import work_paths  # noqa: F401 (the work copy and lab build of a work folder)

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # tools/
REPO = os.path.dirname(HERE)
TOOL = os.path.join(HERE, "grade_lab.py")
# Seconds for one lab 2 submission's tests: the correct submission's 32 tests take about 14 s
# on 2 quiet cores in two shards side by side (docs/labs/teachers.md, "Measured time"); 90
# leaves room for a busy machine.
TIMEOUT = os.environ.get("PT_GRADE_TEST_TIMEOUT", "90")


def expect(cond, what, output=""):
    if not cond:
        print("FAILED: " + what)
        if output:
            print(output)
        sys.exit(1)
    print("ok: " + what)


def written_mutants(folder, lab, also=()):
    """The mutants the fixtures wrote into folder (m_NAME.glsl), checked against lab's in
    labs/mutants.h (`also`: those written under another name), so that a mutant added there
    is not left out here."""
    mine = sorted(f[2:-len(".glsl")] for f in os.listdir(folder) if f.startswith("m_") and f.endswith(".glsl"))
    listed = re.findall(r'is_mutant\(([0-9]), "([a-z_0-9]+)"\)', open(os.path.join(REPO, "labs", "mutants.h")).read())
    expect(sorted(set(m for l, m in listed if l == str(lab))) == sorted(mine + list(also)),
           f"the fixtures write each of lab {lab}'s mutants in labs/mutants.h")
    return mine


def with_wrappers(rel, renames, wrappers):
    """The reference file `rel` with its functions renamed (signature -> new name) and, before
    its last #endif (or at its end), `wrappers`: a submission built from the reference without quoting a line
    of its bodies, which the handout leaves out (tools/make_lab_handout.py)."""
    text = open(os.path.join(REPO, rel), encoding="utf-8").read()
    for signature, name in renames.items():
        if signature not in text:
            expect(False, f"{rel} has '{signature}'")
        text = text.replace(signature, signature.replace(signature.split("(")[0].split()[-1], name), 1)
    at = text.rindex("#endif") if "#endif" in text else len(text)  # stage1's integrator has no guard
    return text[:at] + wrappers + "\n" + text[at:]


def reference(rel):
    return open(os.path.join(REPO, rel), encoding="utf-8").read()


def write(folder, files, also=""):
    """Writes each submission; a .glsl file gets `also` (the lab's other reference file) appended."""
    for rel, text in files.items():
        if rel.endswith(".glsl"):
            text += "\n" + also
        os.makedirs(os.path.dirname(os.path.join(folder, rel)), exist_ok=True)
        with open(os.path.join(folder, rel), "w", encoding="utf-8") as fh:
            fh.write(text)
