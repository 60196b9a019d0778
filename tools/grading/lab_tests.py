"""The lab's tests, for tools/grade_lab.py (grading a class's lab submissions; tooling for
teachers, not a part of the article): which of pt_tests's Catch2 tests grade lab LAB (the
ctest entries labelled labLAB, less EXCLUDED), and reading the Catch2 XML report of a run,
finished or cut short by a kill, into the test cases that passed or failed, with the first
line of why each failed."""
import json
import os
import signal
import subprocess
import xml.etree.ElementTree as ET

from . import TEST_TARGET, die

# The tests of each lab's groups (tests/CMakeLists.txt, PT_TEST_GROUPS) that do not grade the
# student's functions, as Catch2 exclusions (-# adds [#file] tags):
#   lab 2: the GGX tests ([ggx]), the lobe energy ([energy]) and the mixed material's choice
#          never call the uniform hemisphere sampler (bsdf.glsl samples cosine and GGX lobes);
#   labs 2-4: pt_compare's tests of a stage ([compare]) render both of their sides with the
#          student's stage, so they grade pt_compare, not the student;
#   labs 2-3: the sampler checks' own mutation tests ([mutants]) never call the student's code;
#   lab 5: the BVH build ([#test_bvh]), the CPU's SIMD walk (cpu/wide_bvh_walk.cpp compiles
#          the reference box_slab.glsl, [#test_wide_bvh]), the summary line ([cli]), the
#          icosphere ([scene]) and the storage-buffer limit ([reliability]);
#   lab 6: the spherical triangles and the light sample by solid angle ([solid_angle]), which
#          neither weigh a sample nor ask light_pdf.
EXCLUDED = {
    1: [],
    2: ["[ggx]", "[energy]", '"sampling: a mixed material*"', "[compare]", "[mutants]"],
    3: ["[ggx]", "[compare]", "[mutants]"],
    4: ["[compare]"],
    5: ["[#test_bvh]", "[#test_wide_bvh]", "[cli]", "[scene]", "[reliability]"],
    6: ["[solid_angle]"],
}
# Tests that check the project's convention rather than the estimator. None now: the
# hemisphere samplers are graded by their mapping's density, which holds for every
# convention (tests/common/kernel/test_sampling.cpp), so a sampler with another mapping of u
# passes. A convention test added later goes here, and its failures are marked apart.
CONVENTION = set()


def lab_specs(ctest, build, lab):
    """The Catch2 specs of the ctest entries labelled labN, with EXCLUDED's tests left out."""
    r = subprocess.run([ctest, "--test-dir", build, "-L", f"^lab{lab}$", "--show-only=json-v1"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        die(f"ctest cannot list lab {lab}'s tests in {build}: {r.stderr.strip()}", 1)
    specs = []
    for test in json.loads(r.stdout).get("tests", []):
        command = test.get("command", [])
        if len(command) == 2 and os.path.basename(command[0]) == TEST_TARGET:
            specs.append(command[1] + "".join("~" + e for e in EXCLUDED[lab]))
        elif command:
            die(f"lab {lab}'s ctest entry '{test.get('name')}' does not run {TEST_TARGET} with one spec: "
                f"tools/grade_lab.py does not know how to grade it", 1)
    if not specs:
        die(f"no ctest entry is labelled lab{lab} in {build}", 1)
    return [",".join(specs)]  # one argument: Catch2 ORs the comma-separated specs (several arguments AND)


def test_names(build, specs):
    """The names of the tests of the lab build's test program that specs select."""
    listing = subprocess.run([os.path.join(build, "bin", TEST_TARGET), "-#", "--list-test-names-only"] + specs,
                             capture_output=True, text=True)
    return [l for l in listing.stdout.splitlines() if l.strip()]


def short(text, limit=240):
    line = " ".join(text.strip().splitlines()[0].split()) if text.strip() else ""
    return line if len(line) <= limit else line[:limit - 3] + "..."


def failure_reason(case):
    """The first line of why a Catch2 <TestCase> failed: its first failed assertion (with the
    INFO just before it), exception, FAIL message or fatal condition."""
    infos = []
    for el in case.iter():
        if el.tag == "Info":
            infos.append(el.text or "")
        elif el.tag == "Expression":
            if el.get("success") == "false":
                orig = (el.findtext("Original") or "").strip()
                expanded = (el.findtext("Expanded") or "").strip()
                reason = f"{el.get('type', 'CHECK')}({short(orig)})"
                if expanded and expanded != orig:
                    reason += f" with {short(expanded)}"
                exc = el.find("Exception")
                if exc is not None:
                    reason += f": exception {short(exc.text or '')}"
                if infos and short(infos[-1]):
                    reason += f" [{short(infos[-1], 160)}]"
                return reason
            infos = []
        elif el.tag in ("Exception", "FatalErrorCondition", "Failure") and el is not case:
            return f"{el.tag}: {short(el.text or '')}"
    return "failed (no assertion recorded)"


def read_catch_xml(path):
    """(finished test cases as (name, success, reason), the name of a test case left unfinished).
    A report cut short by a kill is read as far as it goes."""
    parser = ET.XMLPullParser(events=("start", "end"))
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            parser.feed(fh.read())
    except (OSError, ET.ParseError):
        pass
    cases, running = [], None
    try:
        for event, el in parser.read_events():
            if el.tag != "TestCase":
                continue
            if event == "start":
                running = el.get("name")
            else:
                result = el.find("OverallResult")
                ok = result is not None and result.get("success") == "true"
                cases.append((el.get("name"), ok, "" if ok else failure_reason(el)))
                running = None
    except ET.ParseError:
        pass
    return cases, running


def signal_name(rc):
    try:
        return signal.Signals(-rc).name
    except ValueError:
        return f"signal {-rc}"
