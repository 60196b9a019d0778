#!/usr/bin/env python3
"""Test of tools/grade_lab.py (grading a class's lab submissions; tooling for teachers, not a
part of the article): bad usage exits 2 with one line; then labs 2 and 4 are graded on fixture
submissions made here from the reference functions, which are renamed and called by wrappers,
so that no line of their bodies is quoted here (the handout ships this file without them).
Each submission must get its verdict line; the other reference file of the lab (lab 2's
roulette, lab 4's emission rule) is appended to each as it is. Lab 2
(common/kernel/uniform_hemisphere.glsl, russian_roulette.glsl):
  a_correct          the reference                                  PASS
  b_syntax_error     a wrapper less a semicolon, graded right       COMPILE ERROR at labs/lab2.glsl
                     after a correct one (issue 24: the stale
                     binaries of a_correct passed)
  c_pdf_2pi          pdf = 2 pi instead of 1 / (2 pi)               FAIL, the furnace among the criteria
  d_theta_uniform    theta uniform instead of cos(theta)            FAIL, the chi-square among the criteria
  e_convention/      u.x and u.y swapped: another convention,       PASS (the project fixes no
    lab2.glsl        right in distribution                          convention: docs/monte_carlo.md)
  f_endless_loop     while (true) {} in the sampler                 TIMEOUT
  g_crash            a read far out of the materials' bounds        CRASH SIGSEGV
  h_empty/           a folder without lab2.glsl                     COMPILE ERROR no lab2.glsl
  m_NAME             each other known-wrong answer of labs/mutants.h FAIL, not put down to a
                     (d_theta_uniform is the eighth), the renamed     convention
                     reference wrapped to make it
and grades.csv and grades.xml hold one row and one testcase per submission. Lab 4
(common/kernel/triangle_light.glsl, emission_rule.glsl):
  a_correct          the reference                                  PASS
  b_pdf_doubled      the sample's pdf twice the right one           FAIL, the mean of 1/pdf among the criteria
  c_pdf_mismatch     triangle_light_pdf twice the sample's pdf      FAIL, the held-back test among them
  m_NAME             each known-wrong answer of labs/mutants.h       FAIL, not put down to a
                     (checked against the file's list)               convention
The mutants of labs 3, 5 and 6, whose builds this test does not make, are graded by mutation
in the check build only (the lab_mutant_NAME entries of tests/CMakeLists.txt).
usage: tools/test_grade_lab.py [WORK]   (ctest entry grade_lab; WORK: lab 2's build, and WORK_lab4
lab 4's, kept between runs so that only the first run builds each lab from nothing, ~7 min
each on 2 cores; PT_GRADE_TEST_TIMEOUT: seconds for one lab 2 submission's tests, default 90
(lab 4's, without an endless loop among them, have 300); PT_GRADE_TEST_LABS: the labs to
grade, default "2,4")"""
import csv
import os
import re
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
TOOL = os.path.join(HERE, "grade_lab.py")
# Seconds for one lab 2 submission's tests: the correct submission's take about 17 s on 2
# cores (20 tests, every test that runs stage2 being tagged [stage2]); 90 leaves room for a
# busy machine.
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
    its last #endif, `wrappers`: a submission built from the reference without quoting a line
    of its bodies, which the handout leaves out (tools/make_lab_handout.py)."""
    text = open(os.path.join(REPO, rel), encoding="utf-8").read()
    for signature, name in renames.items():
        if signature not in text:
            expect(False, f"{rel} has '{signature}'")
        text = text.replace(signature, signature.replace(signature.split("(")[0].split()[-1], name), 1)
    at = text.rindex("#endif")
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


def lab2_fixtures(folder):
    rel = "common/kernel/uniform_hemisphere.glsl"
    renames = {"vec3 sample_uniform_hemisphere(vec2 u)": "reference_sampler",
               "float uniform_hemisphere_pdf()": "reference_pdf"}

    def variant(sampler="return reference_sampler(u);", pdf="return reference_pdf();"):
        return with_wrappers(rel, renames, f"vec3 sample_uniform_hemisphere(vec2 u) {{\n  {sampler}\n}}\n\n"
                                           f"float uniform_hemisphere_pdf() {{\n  {pdf}\n}}\n")

    write(folder, {
        "a_correct.glsl": reference(rel),
        "b_syntax_error.glsl": variant(sampler="return reference_sampler(u)"),
        "c_pdf_2pi.glsl": variant(pdf="return 2.0f * kPi;"),
        # The reference's cos(theta) is u.x: feeding it cos of a uniform angle makes theta uniform.
        "d_theta_uniform.glsl": variant(sampler="return reference_sampler(vec2(cos(0.5f * kPi * u.x), u.y));"),
        "e_convention/lab2.glsl": variant(sampler="return reference_sampler(vec2(u.y, u.x));"),
        "f_endless_loop.glsl": variant(sampler="while (true) {\n  }\n  return reference_sampler(u);"),
        # A read far past the end of the scene's materials: SIGSEGV on the CPU (the read decides
        # the sample: 0 * x is not folded away without -ffast-math).
        "g_crash.glsl": variant(sampler="return reference_sampler(u + vec2(0.0f * materials[100000000 + int(u.y)].metallic));"),
        "h_empty/README.txt": "lab2.glsl was forgotten\n",
        # Lab 2's other known-wrong answers (labs/mutants.h; d_theta_uniform is its
        # uniform_theta_uniform), each the renamed reference wrapped to make that mistake.
        "m_uniform_no_radius.glsl": variant(sampler="vec3 v = reference_sampler(u);\n  "
                                                    "float r = max(length(vec2(v.x, v.y)), 1e-30f);\n  "
                                                    "return vec3(v.x / r, v.y / r, v.z);"),
        "m_uniform_pdf_one_over_pi.glsl": variant(pdf="return 1.0f / kPi;"),
    }, also=reference("common/kernel/russian_roulette.glsl"))
    # The bounce weight: the printed factor (erratum 1), the cosine or the pdf left out.
    weight = {"vec3 uniform_bounce_weight(vec3 f, vec3 wi)": "reference_weight"}

    def bounce(body):
        return with_wrappers(rel, weight, f"vec3 uniform_bounce_weight(vec3 f, vec3 wi) {{\n  {body}\n}}\n")

    write(folder, {
        "m_bounce_printed_factor.glsl": bounce("return reference_weight(f, wi) / (4.0f * kPi * kPi);"),
        "m_bounce_no_cosine.glsl": bounce("return reference_weight(f, wi) / max(wi.z, 1e-30f);"),
        "m_bounce_no_pdf.glsl": bounce("return reference_weight(f, wi) / (2.0f * kPi);"),
    }, also=reference("common/kernel/russian_roulette.glsl"))
    # The roulette's survivor weight, 1 / p: made p, or 1.
    roulette = {"float russian_roulette(vec3 beta, uint mode)": "reference_roulette"}

    def survivor(value):
        return with_wrappers("common/kernel/russian_roulette.glsl", roulette,
                             "float russian_roulette(vec3 beta, uint mode) {\n  float r = reference_roulette(beta, mode);\n"
                             f"  return r > 0.0f ? {value} : 0.0f;\n}}\n")

    write(folder, {
        "m_roulette_times_p.glsl": survivor("1.0f / r"),
        "m_roulette_unweighted.glsl": survivor("1.0f"),
    }, also=reference(rel))


def lab4_fixtures(folder):
    rel = "common/kernel/triangle_light.glsl"
    renames = {"LightSample sample_triangle_light(uint index, vec3 p, vec2 u, float pick)": "reference_sample",
               "float triangle_light_pdf(uint index, vec3 wi, float dist)": "reference_pdf"}

    def variant(sample="return reference_sample(index, p, u, pick);", pdf="return reference_pdf(index, wi, dist);",
                helpers=""):
        return with_wrappers(rel, renames, helpers +
                             f"LightSample sample_triangle_light(uint index, vec3 p, vec2 u, float pick) {{\n  {sample}\n}}\n\n"
                             f"float triangle_light_pdf(uint index, vec3 wi, float dist) {{\n  {pdf}\n}}\n")

    write(folder, {
        "a_correct.glsl": reference(rel),
        "b_pdf_doubled.glsl": variant(sample="return reference_sample(index, p, u, 2.0f * pick);"),
        # Only the pdf of a given direction is wrong: stage4 never calls it, the tests do, the
        # held-back one ([held_back], not in the handout) among them.
        "c_pdf_mismatch.glsl": variant(pdf="return 2.0f * reference_pdf(index, wi, dist);"),
    }, also=reference("common/kernel/emission_rule.glsl"))
    # Lab 4's known-wrong answers (labs/mutants.h): a factor of the pdf d^2 / (cos_y area) x
    # P(light) left out in the sample and in triangle_light_pdf alike (with_pdf() multiplies
    # a sample's pdf by what was left out and divides its weight by it), or only in the pdf;
    # the back of a one-sided light lit; the barycentric weights unfolded; the emission rule.
    helpers = """
vec3 mutant_normal(uint index) {
  Triangle t = triangles[index];
  return normalize(cross(vec3(t.p1 - t.p0), vec3(t.p2 - t.p0)));
}

float mutant_area(uint index) {
  Triangle t = triangles[index];
  return 0.5f * length(cross(vec3(t.p1 - t.p0), vec3(t.p2 - t.p0)));
}

float mutant_pick(uint index) {
  return light_pick_probability(triangles[index].light);
}

LightSample with_pdf(LightSample s, float factor) {
  if (s.pdf > 0.0f) {
    s.pdf *= factor;
    s.weight /= factor;
  }
  return s;
}

// wi mirrored through the plane of triangle `index`.
vec3 mutant_mirror(uint index, vec3 wi) {
  vec3 n = mutant_normal(index);
  return wi - 2.0f * dot(wi, n) * n;
}
"""

    def mistake(sample_factor, pdf_factor):
        return variant(helpers=helpers, sample=f"LightSample s = reference_sample(index, p, u, pick);\n  return with_pdf(s, {sample_factor});",
                                 pdf=f"float r = reference_pdf(index, wi, dist);\n  return r > 0.0f ? r * {pdf_factor} : 0.0f;")

    emission = {"bool counts_emission(uint depth, bool after_delta)": "reference_counts"}

    def rule(body):
        return with_wrappers("common/kernel/emission_rule.glsl", emission,
                             f"bool counts_emission(uint depth, bool after_delta) {{\n  {body}\n}}\n")

    write(folder, {
        "m_light_no_cos_y.glsl": mistake("abs(dot(s.wi, mutant_normal(index)))", "abs(dot(wi, mutant_normal(index)))"),
        "m_light_no_distance.glsl": mistake("1.0f / (s.dist * s.dist)", "(1.0f / (dist * dist))"),
        "m_light_no_area.glsl": mistake("mutant_area(index)", "mutant_area(index)"),
        "m_light_no_pick.glsl": mistake("1.0f / pick", "(1.0f / mutant_pick(index))"),
        "m_light_pdf_no_pick.glsl": mistake("1.0f", "(1.0f / mutant_pick(index))"),
        "m_light_both_sides.glsl": variant(helpers=helpers,
            sample="LightSample s = reference_sample(index, p, u, pick);\n  if (s.pdf > 0.0f) return s;\n"
                   "  // p mirrored through the light's plane sees its front: the same point, distance and cos_y.\n"
                   "  vec3 n = mutant_normal(index);\n"
                   "  LightSample m = reference_sample(index, p - 2.0f * dot(p - vec3(triangles[index].p0), n) * n, u, pick);\n"
                   "  m.wi = mutant_mirror(index, m.wi);\n  return m;",
            pdf="float r = reference_pdf(index, wi, dist);\n"
                "  return r > 0.0f ? r : reference_pdf(index, mutant_mirror(index, wi), dist);"),
        # u turned into the numbers for which the reference's barycentric weights are u's own.
        "m_light_unfolded_barycentric.glsl": variant(
            sample="float s = u.x + u.y;\n  return reference_sample(index, p, vec2(s * s, s > 0.0f ? u.y / s : 0.0f), pick);"),
    }, also=reference("common/kernel/emission_rule.glsl"))
    write(folder, {
        "m_emission_always.glsl": rule("return reference_counts(depth, after_delta) || true;"),
        "m_emission_camera_only.glsl": rule("return reference_counts(depth, false);"),
    }, also=reference(rel))


def grade(lab, subs, out, work, timeout):
    """Grades the folder; returns {name: verdict line}."""
    start = time.monotonic()
    r = subprocess.run([sys.executable, TOOL, str(lab), subs, "--out", out, "--work", work, "--timeout", timeout],
                       capture_output=True, text=True)
    print(f"grading lab {lab} took {time.monotonic() - start:.0f} s")
    print(r.stdout + r.stderr)
    expect(r.returncode == 0, f"grade_lab.py ran lab {lab} and exits 0")
    for row in csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8")):
        print(f"{row['name']}: {row['verdict']}, build {row['build_seconds']} s, tests {row['test_seconds']} s")
    return dict(line.split(": ", 1) for line in r.stdout.splitlines())


def check_lines(lines, expected):
    expect(list(lines) == sorted(expected), "one line per submission, in the order of the names")
    for name, pattern in expected.items():
        expect(re.fullmatch(pattern, lines.get(name, "")) is not None, f"{name}: {pattern}", lines.get(name, ""))


def lab2(subs, out, work):
    lab2_fixtures(subs)
    mutants = written_mutants(subs, 2, also=["uniform_theta_uniform"])  # that one is d_theta_uniform
    lines = grade(2, subs, out, work, TIMEOUT)
    expected = {
        "a_correct": r"PASS",
        "b_syntax_error": r"COMPILE ERROR labs/lab2\.glsl:\d+(:\d+)?: error: .*",
        "c_pdf_2pi": r"FAIL (?!\(convention\)).*stage2: furnace box.*->.*",
        "d_theta_uniform": r"FAIL .*sampling: uniform and cosine hemisphere samples fit their pdfs \(chi-square\) -> .*",
        "e_convention": r"PASS",
        "f_endless_loop": r"TIMEOUT after \S+ s in \".*\"",
        "g_crash": r"CRASH SIGSEGV in \".*\"",
        "h_empty": r"COMPILE ERROR no lab2\.glsl in the submission",
    }
    for mutant in mutants:  # each known-wrong answer fails, and not as a convention
        expected["m_" + mutant] = r"FAIL (?!\(convention\)).* -> .*"
    check_lines(lines, expected)
    rows = list(csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8")))
    expect([(row["name"], row["verdict"]) for row in rows] ==
           [(n, re.match(r"PASS|FAIL|COMPILE ERROR|TIMEOUT|CRASH", expected[n]).group(0)) for n in sorted(expected)],
           "grades.csv: one row per submission with its verdict")
    expect([row["convention_only"] for row in rows] == ["no"] * len(rows),
           "grades.csv: no failure is put down to a convention (the project fixes none)")
    suite = ET.parse(os.path.join(out, "grades.xml")).getroot().find("testsuite")
    cases = {c.get("name"): c for c in suite.iter("testcase")}
    expect(sorted(cases) == sorted(expected) and suite.get("tests") == str(len(expected))
           and suite.get("failures") == str(2 + len(mutants)) and suite.get("errors") == "4",
           "grades.xml: one JUnit testcase per submission, a failure for each wrong answer, 4 errors")
    expect(all(cases[n].find("failure") is None and cases[n].find("error") is None for n in ("a_correct", "e_convention"))
           and cases["c_pdf_2pi"].find("failure").get("type") == "FAIL"
           and cases["g_crash"].find("error").get("type") == "CRASH", "grades.xml: each testcase's outcome and type")


def lab4(subs, out, work):
    os.makedirs(subs)
    lab4_fixtures(subs)
    mutants = written_mutants(subs, 4)
    expected = {
        "a_correct": r"PASS",
        "b_pdf_doubled": r"FAIL .*light sampling: the mean of 1/pdf is the solid angle .* -> .*",
        "c_pdf_mismatch": r"FAIL .*light sampling: triangle_light_pdf is d\^2 / \(cos_y area\) times the pick.* -> .*",
    }
    for mutant in mutants:
        expected["m_" + mutant] = r"FAIL (?!\(convention\)).* -> .*"
    check_lines(grade(4, subs, out, work, "300"), expected)  # no endless loop among them


def main():
    if len(sys.argv) > 2:
        print("usage: tools/test_grade_lab.py [WORK]", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="grade_lab_test_") as tmp:
        work = sys.argv[1] if len(sys.argv) == 2 else os.path.join(tmp, "work")
        subs, out = os.path.join(tmp, "submissions"), os.path.join(tmp, "out")
        os.makedirs(subs)
        for args, what in (([], "no arguments"), (["2"], "no submissions folder"), (["7", subs], "lab 7"),
                           (["2", os.path.join(tmp, "missing")], "a missing folder"), (["2", subs], "an empty folder")):
            r = subprocess.run([sys.executable, TOOL] + args, capture_output=True, text=True)
            expect(r.returncode == 2 and r.stdout == "" and len(r.stderr.strip().splitlines()) == 1
                   and r.stderr.startswith("grade_lab: "), f"bad usage ({what}) exits 2 with one line", r.stderr)
        labs = os.environ.get("PT_GRADE_TEST_LABS", "2,4").split(",")
        if "2" in labs:
            lab2(subs, out, work)
        if "4" in labs:
            lab4(os.path.join(tmp, "submissions_lab4"), os.path.join(tmp, "out_lab4"), work + "_lab4")
    return 0



if __name__ == "__main__":
    sys.exit(main())
