"""The lab's tests, for tools/grade_lab.py (grading a class's lab submissions; tooling for
teachers, not a part of the article): which of pt_tests's Catch2 tests grade lab LAB (the
ctest entries labelled labLAB, less EXCLUDED), and reading the Catch2 XML report of a run,
which comes over a pipe the grader holds, finished or cut short by a kill, into the test
cases that passed or failed, each failure in words with the numbers its check saw; and the
test a run started last (PT_TEST_RUNNING_FILE, which names a crash)."""
import json
import os
import re
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
#   lab 5: the BVH build ([#test_bvh]), the CPU's SIMD walk (cpu/wide_bvh_walk_lanes.h holds its
#          own copy of the reference slab test, [#test_wide_bvh]), the summary line ([cli]), the
#          icosphere ([scene]) and the storage-buffer limit ([reliability]);
#   lab 4: the Cornell box's trade test, 27 of the 63 s of a correct submission's tests (one
#          core): it checks the film's error estimate against a long render of a scene with no
#          closed form, which the floor's trade test checks in closed form on the same stage,
#          and every mistake of labs/mutants.h fails another test first;
#   lab 6: the spherical triangles and the light sample by solid angle ([solid_angle]), which
#          neither weigh a sample nor ask light_pdf.
EXCLUDED = {
    1: [],
    2: ["[ggx]", "[energy]", '"sampling: a mixed material*"', "[compare]", "[mutants]"],
    3: ["[ggx]", "[compare]", "[mutants]"],
    4: ["[compare]", '"trade: the printed per-pixel error is within 20% of the measured one over 20 or 40 seeds*"'],
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


def tag_specs(tags, lab):
    """The Catch2 spec of the lab's group tags (pt_lab_tests.json), EXCLUDED's tests left out."""
    return [",".join(tag + "".join("~" + e for e in EXCLUDED[lab]) for tag in tags)]


def test_names(build, specs, target=TEST_TARGET):
    """The names of the tests of the lab build's test program that specs select (the program
    built from the repository's own lab file, before any submission)."""
    listing = subprocess.run([os.path.join(build, "bin", target), "-#", "--list-test-names-only"] + specs,
                             capture_output=True, text=True)
    return [l for l in listing.stdout.splitlines() if l.strip()]


def test_tags(build, specs, target):
    """The Catch2 tags of the tests specs select, with the [#file] ones."""
    listing = subprocess.run([os.path.join(build, "bin", target), "-#", "--list-tags"] + specs,
                             capture_output=True, text=True)
    return set(re.findall(r"\[(#?\w+)\]", listing.stdout))


def test_files(build, specs, target, tags=None):
    """The test files (Catch2's [#file] tags, without .cpp) that hold a test specs select
    (tags: test_tags's, if already listed)."""
    return sorted(t[1:] for t in (tags or test_tags(build, specs, target)) if t.startswith("#"))


def test_stages(tags):
    """The stages (["stage2", "stage4"]) whose CPU kernels the tests of test_tags run: their
    tags, which every test of a group that runs a stage carries (tests/test_main.cpp checks it)."""
    return sorted(t for t in tags if re.fullmatch(r"stage\d", t))


def short(text, limit=240):
    line = " ".join(text.split()) if text.strip() else ""
    return line if len(line) <= limit else line[:limit - 3] + "..."


def failure_reason(case):
    """Why a Catch2 <TestCase> failed, in words: its first failed check with the values it saw
    (and the INFO just before it), or its exception, FAIL message or fatal condition."""
    infos = []
    for el in case.iter():
        if el.tag == "Info":
            infos.append(el.text or "")
        elif el.tag == "Expression":
            fatal = el.find("FatalErrorCondition")
            if fatal is not None:  # Catch2 caught a signal here
                return f"a fatal error: {short(fatal.text or '', 200)}"
            if el.get("success") == "false":
                orig = short(el.findtext("Original") or "", 120)
                expanded = short(el.findtext("Expanded") or "", 160)
                reason = f"its check {orig} failed"
                if expanded and expanded != orig:
                    reason += f" with {expanded}"
                exc = el.find("Exception")
                if exc is not None:
                    reason += f" (exception: {short(exc.text or '', 160)})"
                if infos and short(infos[-1]):
                    reason += f" ({short(infos[-1], 200)})"
                return reason
            infos = []
        elif el.tag in ("Exception", "FatalErrorCondition", "Failure") and el is not case:
            what = {"Exception": "an exception", "FatalErrorCondition": "a fatal error", "Failure": "FAIL"}[el.tag]
            return f"{what}: {short(el.text or '', 200)}"
    return "it failed (no check recorded)"


class Report:
    """The Catch2 XML report of one run, read over the pipe the grader holds: the finished test
    cases as (name, passed, reason), the test left unfinished, whether the document is whole,
    and what is wrong with it when it is not the test program's report of the lab's tests."""

    def __init__(self):
        self.cases, self.running, self.whole, self.problem = [], None, False, None
        self.durations = {}  # seconds per finished test, where Catch2 gave them (-d yes)
        # Why the unfinished test had failed when the report was cut short, if it had: a check
        # failing in a loop over pixels fills the report's cap with its failures.
        self.running_failure = None


def read_report(data, expected):
    """The Report of the bytes the test program wrote on the report pipe. expected: the names of
    the lab's tests, in which every case must be, once."""
    rep = Report()
    text = data.decode("utf-8", errors="replace")
    start = text.find("<?xml")
    if text.strip() and (start < 0 or text[:start].strip()):
        rep.problem = "the report pipe holds text before Catch2's report"
    parser = ET.XMLPullParser(events=("start", "end"))
    ended, closing, current = False, False, None
    try:
        # Line by line, so that what follows the end of the first document is told apart.
        for piece in text[max(start, 0):].splitlines(keepends=True) + [None]:
            if piece is None:
                closing = True
                parser.close()
            else:
                parser.feed(piece)
            for event, el in parser.read_events():
                if el.tag == "Catch" and event == "end":
                    ended = True
                if el.tag != "TestCase":
                    continue
                if event == "start":
                    rep.running, current = el.get("name"), el
                else:
                    result = el.find("OverallResult")
                    ok = result is not None and result.get("success") == "true"
                    rep.cases.append((el.get("name"), ok, "" if ok else failure_reason(el)))
                    seconds = result.get("durationInSeconds") if result is not None else None
                    if seconds is not None:
                        try:
                            rep.durations[el.get("name")] = float(seconds)
                        except ValueError:
                            pass
                    rep.running = None
        rep.whole = ended
    except ET.ParseError as e:
        if ended:  # a second document, or text after the first
            rep.problem = f"the report pipe holds more than Catch2's report ({short(str(e), 80)})"
        elif not closing:  # not cut short: broken inside
            rep.problem = f"the report is not well-formed ({short(str(e), 80)})"
    if rep.running is not None and current is not None:  # the part of it that came
        why = failure_reason(current)
        rep.running_failure = None if why.startswith("it failed (no check") else why
    names = [n for n, _, _ in rep.cases]
    unknown = sorted(set(names) - set(expected))
    twice = sorted({n for n in names if names.count(n) > 1})
    if rep.problem is None and (unknown or twice):
        rep.problem = (f"the report names a test the lab does not run: \"{short(unknown[0], 80)}\"" if unknown
                       else f"the report holds \"{short(twice[0], 80)}\" twice")
    return rep


def running_test(path, tests):
    """The test named in path (PT_TEST_RUNNING_FILE) when it is one of the lab's tests, else None
    (the student's code could write anything there: it names a crash, never decides a verdict)."""
    try:
        with open(path, "rb") as fh:
            name = fh.read(4096).decode(errors="replace").rstrip("\n")
    except OSError:
        return None
    return name if name in tests else None


def signal_name(rc):
    try:
        return signal.Signals(-rc).name
    except ValueError:
        return f"signal {-rc}"
