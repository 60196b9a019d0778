#!/usr/bin/env python3
"""Test of tools/grade_lab.py (grading a class's lab submissions; tooling for teachers, not a
part of the article). Two parts:
  --fast (ctest entry grade_lab_fast, in ./tutorial test; seconds, no lab build): a submission
    rebuilds only what #includes its file and what is made from that (not the GPU kernels,
    whose rules name every labs/*.glsl), with the setup's time stamp on it; bad usage exits
    2 with one line; without bubblewrap the grader says so in one line and grades nothing; the
    source check accepts every honest fixture below and REFUSES each malicious one with its
    reason; the sandbox keeps a command from writing outside its folder, from the network and
    from the project tree, cuts off 1 GB of output, and hands the grader a report pipe that
    no file write reaches; a report with text besides Catch2's is not taken; every row of each
    lab page's table "If a test fails" names a test of that lab (PT_TESTS --list-test-names-only);
    grades.csv quotes a field that holds the separator. Exit 77 (skipped) for the sandbox part
    where bubblewrap cannot run.
  (default; ctest entry grade_lab, label grading; minutes) labs 2 and 4 graded on fixture
    submissions made here from the reference functions, which are renamed and called by
    wrappers, so that no line of their bodies is quoted here (the handout ships this file
    without them). Each submission must get its verdict line; the other reference file of the
    lab (lab 2's roulette, lab 4's emission rule) is appended to each as it is. Lab 2
    (common/kernel/uniform_hemisphere.glsl, russian_roulette.glsl):
  a_correct          the reference                                  PASS
  b_syntax_error     a wrapper less a semicolon, graded right       COMPILE ERROR at labs/lab2.glsl
                     after a correct one (issue 24)
  c_pdf_2pi          pdf = 2 pi instead of 1 / (2 pi)               FAIL, the pdf test named, suspect
  d_theta_uniform    theta uniform instead of cos(theta)            FAIL, the chi-square named, suspect
  e_convention/      u.x and u.y swapped: another convention,       PASS
    lab2.glsl        right in distribution
  f_endless_loop     a loop on an unsigned i >= 0 in the sampler    TIMEOUT in sample_uniform_hemisphere(),
                                                                     with g++'s warning on it
  g_crash            a read far out of the materials' bounds        CRASH SIGSEGV
  h_empty/           a folder without lab2.glsl                     COMPILE ERROR no lab2.glsl
  m_NAME             each other known-wrong answer of labs/mutants.h FAIL with a suspect
  r_includes_reference  #includes the reference files                REFUSED
  r_writes_outside   no pdf, and C++ behind #ifdef __cplusplus that  REFUSED (with the source check
                     plants files in the work copy, the repository   off: FAIL, every write stopped by
                     and the build and copies the reference          the sandbox, nothing planted)
  r_rewrites_report  no pdf, and C++ that writes a passing report   REFUSED (check off: FAIL or
                     into every file and fd it can at exit          REFUSED, never PASS)
  r_prints_1gb       the reference, and C++ that prints 1 GB        REFUSED (check off: REFUSED,
                                                                     the pipe's cap)
and a summary line, grades.csv and grades.xml with one row and one testcase per submission.
Lab 4 (common/kernel/triangle_light.glsl, emission_rule.glsl): a_correct PASS, b_pdf_doubled and
c_pdf_mismatch FAIL (the latter through the held-back test), each mutant FAIL.
usage: tools/test_grade_lab.py --fast [PT_TESTS]
       tools/test_grade_lab.py [WORK]   (WORK: lab 2's build, and WORK_lab4 lab 4's, kept between
       runs; PT_GRADE_TEST_TIMEOUT: seconds for one lab 2 submission's tests, default 90;
       PT_GRADE_TEST_LABS: the labs to grade, default "2,4")"""
import csv
import os
import re
import shutil
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


# C++ that a lab file can hide from GLSL behind #ifdef __cplusplus: the attacks of issue 47.
# The file is included inside the kernel's namespace, so the system calls are declared here
# under names of their own (asm labels), with C linkage.
ATTACK_DECLARATIONS = r"""
#ifdef __cplusplus
extern "C" int grade_attack_open(const char*, int, ...) __asm__("open");
extern "C" long grade_attack_write(int, const void*, unsigned long) __asm__("write");
extern "C" long grade_attack_read(int, void*, unsigned long) __asm__("read");
extern "C" int grade_attack_close(int) __asm__("close");
"""
ATTACK_END = "#endif\n"


def plant_attack(targets, reference, copy_to):
    """C++ that, as the program starts, writes a file at each of targets and copies reference to copy_to."""
    paths = ", ".join(f'"{t}"' for t in targets)
    return ATTACK_DECLARATIONS + f"""struct GradeAttackPlant {{
  GradeAttackPlant() {{
    const char* targets[] = {{{paths}}};
    for (const char* t : targets) {{
      int fd = grade_attack_open(t, 01 | 0100 | 01000, 0644);
      if (fd >= 0) {{ grade_attack_write(fd, "planted\\n", 8); grade_attack_close(fd); }}
    }}
    char buf[1 << 16];
    int in = grade_attack_open("{reference}", 0);
    int out = grade_attack_open("{copy_to}", 01 | 0100 | 01000, 0644);
    long n = in >= 0 ? grade_attack_read(in, buf, sizeof buf) : -1;
    if (n > 0 && out >= 0) grade_attack_write(out, buf, (unsigned long)n);
  }}
}};
static GradeAttackPlant grade_attack_plant;
""" + ATTACK_END


def report_attack(files):
    """C++ that, at exit, writes a passing Catch2 report into each of files and every fd from 1 to 63."""
    paths = ", ".join(f'"{f}"' for f in files)
    fake = ('<?xml version=\\"1.0\\" encoding=\\"UTF-8\\"?>\\n<Catch name=\\"pt_tests\\">\\n'
            '<OverallResults successes=\\"20\\" failures=\\"0\\" expectedFailures=\\"0\\"/>\\n</Catch>\\n')
    return ATTACK_DECLARATIONS + f"""struct GradeAttackReport {{
  ~GradeAttackReport() {{
    static const char fake[] = "{fake}";
    const char* files[] = {{{paths}}};
    for (const char* f : files) {{
      int fd = grade_attack_open(f, 01 | 0100 | 01000, 0644);
      if (fd >= 0) {{ grade_attack_write(fd, fake, sizeof fake - 1); grade_attack_close(fd); }}
    }}
    for (int fd = 1; fd < 64; ++fd) grade_attack_write(fd, fake, sizeof fake - 1);
  }}
}};
static GradeAttackReport grade_attack_report;
""" + ATTACK_END


PRINT_ATTACK = ATTACK_DECLARATIONS + """struct GradeAttackPrint {
  GradeAttackPrint() {
    static char block[1 << 16];
    for (unsigned i = 0; i < sizeof block; ++i) block[i] = 'x';
    for (int k = 0; k < (1 << 14); ++k) grade_attack_write(1, block, sizeof block);  // 1 GiB
  }
};
static GradeAttackPrint grade_attack_print;
""" + ATTACK_END

REFERENCES_2 = ["common/kernel/uniform_hemisphere.glsl", "common/kernel/russian_roulette.glsl"]


def plants(work):
    """Where r_writes_outside tries to write, and where it copies the reference to."""
    return ([os.path.join(work, "src", "tools", "grading", "planted_by_student.py"),
             os.path.join(REPO, "tools", "grading", "planted_by_student.py"),
             os.path.join(work, "build", "bin", "planted_by_student"), "/planted_by_student"],
            os.path.join(work, "build", "copied_reference.glsl"))


def lab2_fixtures(folder, work=None, out=None):
    """Lab 2's submissions. work and out (the grading run's folders) aim the attacks."""
    work, out = work or "/nonexistent", out or "/nonexistent"
    rel = "common/kernel/uniform_hemisphere.glsl"
    renames = {"vec3 sample_uniform_hemisphere(vec2 u)": "reference_sampler",
               "float uniform_hemisphere_pdf()": "reference_pdf"}

    def variant(sampler="return reference_sampler(u);", pdf="return reference_pdf();"):
        return with_wrappers(rel, renames, f"vec3 sample_uniform_hemisphere(vec2 u) {{\n  {sampler}\n}}\n\n"
                                           f"float uniform_hemisphere_pdf() {{\n  {pdf}\n}}\n")

    weight = {"vec3 uniform_bounce_weight(vec3 f, vec3 wi)": "reference_weight"}

    def bounce(body):
        return with_wrappers(rel, weight, f"vec3 uniform_bounce_weight(vec3 f, vec3 wi) {{\n  {body}\n}}\n")

    no_pdf = bounce("return reference_weight(f, wi) / (2.0f * kPi);")
    targets, copy_to = plants(work)
    write(folder, {
        "a_correct.glsl": reference(rel),
        "b_syntax_error.glsl": variant(sampler="return reference_sampler(u)"),
        "c_pdf_2pi.glsl": variant(pdf="return 2.0f * kPi;"),
        # The reference's cos(theta) is u.x: feeding it cos of a uniform angle makes theta uniform.
        "d_theta_uniform.glsl": variant(sampler="return reference_sampler(vec2(cos(0.5f * kPi * u.x), u.y));"),
        "e_convention/lab2.glsl": variant(sampler="return reference_sampler(vec2(u.y, u.x));"),
        # A count down on an unsigned i that never ends (g++ warns: always true).
        "f_endless_loop.glsl": variant(sampler="float acc = 0.0f;\n  for (uint i = 4u; i >= 0u; --i) {\n"
                                               "    acc += u.x;\n  }\n  return reference_sampler(u + vec2(0.0f * acc));"),
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
        # The attacks: each would pass, or plant its files, if the grader let it.
        "r_includes_reference.glsl": "".join(f'#include "{r}"\n' for r in REFERENCES_2),
        "r_writes_outside.glsl": no_pdf + plant_attack(targets, os.path.join(work, "src", rel), copy_to),
        "r_rewrites_report.glsl": no_pdf + report_attack([os.path.join(out, "logs", "r_rewrites_report.tests.xml"),
                                                          os.path.join(work, "build", "report.xml")]),
        "r_prints_1gb.glsl": reference(rel) + PRINT_ATTACK,
    }, also=reference("common/kernel/russian_roulette.glsl"))
    # The bounce weight: the printed factor (erratum 1), the cosine or the pdf left out.
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


def grade(lab, subs, out, work, timeout, extra=()):
    """Grades the folder; returns ({name: verdict line}, the summary line)."""
    start = time.monotonic()
    r = subprocess.run([sys.executable, TOOL, str(lab), subs, "--out", out, "--work", work, "--timeout", timeout]
                       + list(extra), capture_output=True, text=True)
    print(f"grading lab {lab} took {time.monotonic() - start:.0f} s")
    print(r.stdout + r.stderr)
    expect(r.returncode == 0, f"grade_lab.py ran lab {lab} and exits 0")
    for row in csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8")):
        print(f"{row['name']}: {row['verdict']}, build {row['build_seconds']} s, tests {row['test_seconds']} s")
    lines = r.stdout.splitlines()
    return dict(line.split(": ", 1) for line in lines[:-1]), (lines[-1] if lines else "")


def check_lines(lines, expected):
    expect(list(lines) == sorted(expected), "one line per submission, in the order of the names")
    for name, pattern in expected.items():
        expect(re.fullmatch(pattern, lines.get(name, "")) is not None, f"{name}: {pattern}", lines.get(name, ""))


def check_summary(summary, expected):
    """The summary line counts the verdicts of expected (name: pattern)."""
    verdicts = [re.match(r"PASS|FAIL|COMPILE ERROR|TIMEOUT|CRASH|REFUSED", p).group(0) for p in expected.values()]
    want = ", ".join(f"{v} {verdicts.count(v)}" for v in ("PASS", "FAIL", "COMPILE ERROR", "TIMEOUT", "CRASH", "REFUSED")
                     if verdicts.count(v) or v != "CRASH")
    expect(summary == want, f"the summary line is '{want}'", summary)


def nothing_planted(work):
    targets, copy_to = plants(work)
    left = [t for t in targets + [copy_to] if os.path.exists(t)]
    expect(not left, "the submission that writes outside its folder planted nothing", ", ".join(left))
    for t in left:  # so that the next run starts clean
        os.remove(t)


def no_pictures_in_repository():
    expect(not os.path.exists(os.path.join(REPO, "test_pictures")), "nothing written into the repository (test_pictures/)")


# A FAIL line: the test in quotes, its check with the numbers, then the suspect.
FAIL = r'FAIL "[^"]+": (its check .+ failed with|an exception|FAIL|a fatal error).+ \(suspect: .+\)'


def lab2(subs, out, work):
    lab2_fixtures(subs, work, out)
    mutants = written_mutants(subs, 2, also=["uniform_theta_uniform"])  # that one is d_theta_uniform
    lines, summary = grade(2, subs, out, work, TIMEOUT)
    expected = {
        "a_correct": r"PASS",
        "b_syntax_error": r"COMPILE ERROR labs/lab2\.glsl:\d+(:\d+)?: error: .*",
        "c_pdf_2pi": (r'FAIL "sampling: each hemisphere sampler\'s pdf is the density of its mapping[^"]*": '
                      r'its check .*\d.* \(suspect: .*uniform_hemisphere_pdf.*\)'),
        "d_theta_uniform": r'FAIL "sampling: [^"]*": its check .*\d.* \(suspect: .*\)',
        "e_convention": r"PASS",
        # The grader's build keeps the lab's functions out of line: the line names the one that loops.
        "f_endless_loop": (r"TIMEOUT in sample_uniform_hemisphere\(\) after \S+ s.* "
                           r"\(warning: labs/lab2\.glsl:\d+(:\d+)?: warning: comparison .* always true.*\)"),
        "g_crash": r"CRASH SIGSEGV in \".*\"",
        "h_empty": r"COMPILE ERROR no lab2\.glsl in the submission",
        "r_includes_reference": r"REFUSED labs/lab2\.glsl:1: includes the reference solution common/kernel/uniform_hemisphere\.glsl",
        "r_writes_outside": r"REFUSED labs/lab2\.glsl:\d+: the preprocessor line '#ifdef __cplusplus': .*",
        "r_rewrites_report": r"REFUSED labs/lab2\.glsl:\d+: the preprocessor line '#ifdef __cplusplus': .*",
        "r_prints_1gb": r"REFUSED labs/lab2\.glsl:\d+: the preprocessor line '#ifdef __cplusplus': .*",
    }
    for mutant in mutants:  # each known-wrong answer fails, with a suspect
        expected["m_" + mutant] = FAIL
    check_lines(lines, expected)
    check_summary(summary, expected)
    rows = list(csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8")))
    expect([(row["name"], row["verdict"]) for row in rows] ==
           [(n, re.match(r"PASS|FAIL|COMPILE ERROR|TIMEOUT|CRASH|REFUSED", expected[n]).group(0)) for n in sorted(expected)],
           "grades.csv: one row per submission with its verdict")
    suite = ET.parse(os.path.join(out, "grades.xml")).getroot().find("testsuite")
    cases = {c.get("name"): c for c in suite.iter("testcase")}
    expect(sorted(cases) == sorted(expected) and suite.get("tests") == str(len(expected))
           and suite.get("failures") == str(2 + len(mutants)) and suite.get("errors") == "8",
           "grades.xml: one JUnit testcase per submission, a failure for each wrong answer, 8 errors")
    expect(all(cases[n].find("failure") is None and cases[n].find("error") is None for n in ("a_correct", "e_convention"))
           and cases["c_pdf_2pi"].find("failure").get("type") == "FAIL"
           and cases["r_prints_1gb"].find("error").get("type") == "REFUSED", "grades.xml: each testcase's outcome and type")
    expect(os.path.isfile(os.path.join(out, "logs", "a_correct.pictures", "uniform_hemisphere.png")),
           "the histogram of a submission is kept in logs/NAME.pictures/")
    nothing_planted(work)
    no_pictures_in_repository()


def lab2_sandbox_alone(subs, out, work):
    """The attacks again with the source check off (--unchecked-source): the sandbox alone
    must keep them from passing, planting files or flooding the grader."""
    os.makedirs(subs)
    lab2_fixtures(subs, work, out)
    for f in os.listdir(subs):
        if not f.startswith("r_"):
            path = os.path.join(subs, f)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
    lines, summary = grade(2, subs, out, work, TIMEOUT, ["--unchecked-source"])
    check_lines(lines, {
        "r_includes_reference": r"COMPILE ERROR .*common/kernel/uniform_hemisphere\.glsl.*reference solution.*",
        # No code runs during the build of pt_lab_tests, and the tests see the build read-only:
        # every write fails, and its estimator (no pdf) is graded.
        "r_writes_outside": FAIL,
        "r_rewrites_report": r"(FAIL|REFUSED) .*",
        "r_prints_1gb": r"REFUSED .*printed more than \d+ MB.*",
    })
    nothing_planted(work)
    no_pictures_in_repository()


def lab4(subs, out, work):
    os.makedirs(subs)
    lab4_fixtures(subs)
    mutants = written_mutants(subs, 4)
    expected = {"a_correct": r"PASS", "b_pdf_doubled": FAIL, "c_pdf_mismatch": FAIL}
    for mutant in mutants:
        expected["m_" + mutant] = FAIL
    lines, summary = grade(4, subs, out, work, "300")  # no endless loop among them
    check_lines(lines, expected)
    check_summary(summary, expected)
    failed = {row["name"]: row["failed_tests"].split("\n")
              for row in csv.DictReader(open(os.path.join(out, "grades.csv"), encoding="utf-8"))}
    expect("light sampling: the mean of 1/pdf is the solid angle a triangle or a sphere subtends" in failed["b_pdf_doubled"],
           "b_pdf_doubled fails the mean of 1/pdf", repr(failed["b_pdf_doubled"]))
    expect(any(n.startswith("light sampling: triangle_light_pdf is d^2 / (cos_y area) times the pick")
               for n in failed["c_pdf_mismatch"]), "c_pdf_mismatch fails the held-back test", repr(failed["c_pdf_mismatch"]))


def bad_usage(tmp):
    subs = os.path.join(tmp, "empty")
    os.makedirs(subs)
    for args, what in (([], "no arguments"), (["2"], "no submissions folder"), (["7", subs], "lab 7"),
                       (["2", os.path.join(tmp, "missing")], "a missing folder"), (["2", subs], "an empty folder")):
        r = subprocess.run([sys.executable, TOOL] + args, capture_output=True, text=True)
        expect(r.returncode == 2 and r.stdout == "" and len(r.stderr.strip().splitlines()) == 1
               and r.stderr.startswith("grade_lab: "), f"bad usage ({what}) exits 2 with one line", r.stderr)


def no_sandbox_refused(tmp):
    """With no bwrap on PATH the grader says so in one line, exits 1 and grades nothing."""
    bin_dir, subs = os.path.join(tmp, "bin_without_bwrap"), os.path.join(tmp, "one")
    os.makedirs(bin_dir)
    os.makedirs(subs)
    for tool in ("cmake", "ctest", "prlimit", "setpriv"):
        if shutil.which(tool):
            os.symlink(shutil.which(tool), os.path.join(bin_dir, tool))
    write(subs, {"alice.glsl": reference("common/kernel/uniform_hemisphere.glsl")})
    r = subprocess.run([sys.executable, TOOL, "2", subs, "--work", os.path.join(tmp, "work_unused")],
                       capture_output=True, text=True, env={**os.environ, "PATH": bin_dir})
    expect(r.returncode == 1 and r.stdout == "" and len(r.stderr.strip().splitlines()) == 1
           and "bubblewrap" in r.stderr and "--unsealed" in r.stderr,
           "without bubblewrap: one line that says so and names --unsealed, exit 1, nothing graded", r.stderr)


def source_checks(tmp):
    """The honest fixtures pass the source check; each attack is refused, with its reason."""
    from grading.source_check import check_source
    from make_lab_handout import REFERENCE_FILES
    refs = sorted({r for rels in REFERENCE_FILES.values() for r in rels})
    subs = os.path.join(tmp, "fixtures")
    os.makedirs(subs)
    lab2_fixtures(subs)
    found = {}
    for entry in sorted(os.listdir(subs)):
        path = os.path.join(subs, entry, "lab2.glsl") if os.path.isdir(os.path.join(subs, entry)) else os.path.join(subs, entry)
        if os.path.isfile(path):
            found[entry.replace(".glsl", "")] = check_source(open(path, "rb").read(), "labs/lab2.glsl", refs, REPO)
    refused = {n: why for n, why in found.items() if why}
    expect(sorted(refused) == ["r_includes_reference", "r_prints_1gb", "r_rewrites_report", "r_writes_outside"],
           "the source check refuses the four attacks and nothing else", repr(refused))
    expect(refused["r_includes_reference"] == "labs/lab2.glsl:1: includes the reference solution "
                                              "common/kernel/uniform_hemisphere.glsl", "it names the reference included")
    expect(all("'#ifdef __cplusplus'" in refused[n] for n in ("r_prints_1gb", "r_rewrites_report", "r_writes_outside")),
           "it names the C++ hidden from GLSL", repr(refused))
    for code, what in ((b'#ifndef GL_SPIRV\n#define GL_SPIRV\nint x;\n#endif\n', "a guard on a name GLSL defines"),
                       (b"#define CHECK(x) (void)0\n", "a #define of a test macro"),
                       (b'%:include "common/kernel/box_slab.glsl"\n', "a digraph #include"),
                       (b'#  include </etc/passwd>\n', "an #include <...>"),
                       (b'#include "../../tests/common/kernel/test_light_sampling.cpp"\n', "an #include of a test")):
        expect(check_source(code, "labs/lab2.glsl", refs, REPO) is not None, f"the source check refuses {what}")


def sandbox_checks(tmp):
    """The sandbox's walls, tried with small commands."""
    from grading.sandbox import Limits, MiB, Sandbox, memory_limit, probe
    why = probe()
    if why:
        print(f"SKIPPED: the sandbox cannot run here: {why}")
        return False
    run = os.path.join(tmp, "run")
    os.makedirs(run)
    box = Sandbox(True, REPO, {}, {})
    box.owner_of_writable(run)
    limits = Limits(20, memory_limit(), 64, 4 * MiB, 2 * MiB, 2 * MiB)
    outside = os.path.join(tmp, "outside.txt")
    script = (f"echo in > {run}/inside.txt; echo out > {outside}; echo repo > {REPO}/planted_by_sandbox_test; "
              f"ls {REPO} >/dev/null 2>&1 && echo SEES_REPO; echo tmp > /tmp/t && echo TMP_OK; "
              f"python3 -c \"import socket; socket.create_connection(('1.1.1.1', 80), timeout=3)\" 2>/dev/null "
              f"&& echo NET_OK; echo '<fake/>' > {run}/report.xml; echo real > {{report}}; exit 0")
    r = box.run(["bash", "-c", script], run, [run], [], {}, limits, 60, report=True)
    out = r.stdout.decode()
    expect(os.path.isfile(os.path.join(run, "inside.txt")), "the sandbox writes its own folder")
    expect(not os.path.exists(outside) and not os.path.exists(os.path.join(REPO, "planted_by_sandbox_test")),
           "the sandbox writes nothing outside its folder", out)
    expect("SEES_REPO" not in out and "TMP_OK" in out and "NET_OK" not in out,
           "the sandbox sees no project tree and no network, and has a /tmp of its own", out)
    expect(r.report == b"real\n", "the report comes over the grader's pipe, whatever files the sandbox writes",
           repr(r.report))
    r = box.run(["bash", "-c", "head -c 1073741824 /dev/zero"], run, [run], [], {}, limits, 60)
    expect(r.over_cap == "stdout" and len(r.stdout) == limits.stdout_cap and r.seconds < 30,
           "1 GB on stdout is cut off at the cap and the command killed", f"{r.over_cap} {len(r.stdout)} {r.seconds}")
    r = box.run(["bash", "-c", "head -c 10000000 /dev/zero > big"], run, [run], [], {}, limits, 60)
    expect(r.rc != 0 and os.path.getsize(os.path.join(run, "big")) <= limits.file_size,
           "a file over the size limit is cut off", f"rc {r.rc}")
    r = box.run(["bash", "-c", "while :; do :; done"], run, [run], [], {}, limits, 2, on_timeout=lambda pid: "spin()")
    expect(r.timed_out and r.running_function == "spin()" and r.seconds < 10,
           "an endless loop is killed at the deadline, after on_timeout said where it was")
    return True


def report_checks():
    """A report with text besides Catch2's, or a test the lab does not run, is not taken."""
    from grading.lab_tests import read_report
    doc = ('<?xml version="1.0" encoding="UTF-8"?>\n<Catch name="pt_tests">\n  <Group name="pt_tests">\n'
           '    <TestCase name="a; b, c" tags="[x]">\n      <OverallResult success="true"/>\n    </TestCase>\n'
           '    <TestCase name="d" tags="[x]">\n      <Expression success="false" type="CHECK">\n'
           '        <Original>mean == 2</Original>\n        <Expanded>1.013 == 2</Expanded>\n      </Expression>\n'
           '      <OverallResult success="false"/>\n    </TestCase>\n  </Group>\n</Catch>\n')
    rep = read_report(doc.encode(), ["a; b, c", "d"])
    expect(rep.whole and rep.problem is None and rep.cases[0][:2] == ("a; b, c", True)
           and rep.cases[1][2] == "its check mean == 2 failed with 1.013 == 2", "a whole report is read", repr(rep.cases))
    expect(read_report((doc + doc).encode(), ["a; b, c", "d"]).problem is not None, "two reports are refused")
    expect(read_report(("hello\n" + doc).encode(), ["a; b, c", "d"]).problem is not None, "text before it is refused")
    expect(read_report(doc.encode(), ["a; b, c"]).problem is not None, "a test the lab does not run is refused")
    cut = read_report(doc[:doc.index("<OverallResult success=\"false")].encode(), ["a; b, c", "d"])
    expect(not cut.whole and cut.running == "d" and cut.problem is None, "a report cut short names the running test")


def hint_tables(pt_tests):
    """Every lab page has the table, and each of its rows names a test of the lab's program."""
    from grading.hints import matches, read_hints
    names = []
    if pt_tests:
        listing = subprocess.run([pt_tests, "--list-test-names-only"], capture_output=True, text=True)
        names = [n.strip() for n in listing.stdout.splitlines() if n.strip()]
    for lab in range(1, 7):
        hints = read_hints(REPO, lab)
        expect(len(hints) >= 2, f"docs/labs/lab{lab}.md has the table 'If a test fails'")
        for pattern, suspect in hints:
            expect(not names or any(matches(pattern, n) for n in names),
                   f"lab {lab}: the row '{pattern[:60]}' names a test of pt_tests")


def csv_quoting(tmp):
    from grading.reports import write_csv
    from grading.submission import Grade
    g = Grade("alice", "/x/alice.glsl")
    g.verdict, g.detail, g.failed, g.suspect = "FAIL", '"t; u, v": its check a, b failed', ["t; u, v", "w"], "x, y"
    write_csv(tmp, [g])
    rows = list(csv.reader(open(os.path.join(tmp, "grades.csv"), encoding="utf-8", newline="")))
    expect(len(rows) == 2 and rows[1][:4] == ["alice", "FAIL", g.detail, "x, y"] and rows[1][7] == "t; u, v\nw",
           "grades.csv keeps a field with ',' ';' and quotes whole (Python's csv module)", repr(rows))


def rebuilt_outputs(tmp):
    """A submission rebuilds what #includes the lab file (its depfiles) and what is made from
    that, not the GPU kernels that name every labs/*.glsl in a glob rule; the file gets the
    setup's time stamp, so that make does not remake those either."""
    from grading.depends import dependents, put_lab_file
    build, lab = os.path.join(tmp, "deps", "build"), os.path.join(tmp, "deps", "src", "labs", "lab2.glsl")
    os.makedirs(os.path.join(build, "CMakeFiles", "k.dir"))
    os.makedirs(os.path.dirname(lab))
    with open(os.path.join(build, "CMakeFiles", "k.dir", "build.make"), "w") as fh:
        fh.write(f"k_spirv.h: {lab}\n\nCMakeFiles/k.dir/k.cpp.o: k_spirv.h\n\nlibk.a: CMakeFiles/k.dir/k.cpp.o\n"
                 f"libk.a: CMakeFiles/k.dir/cpu.cpp.o\n\nbin/stage: libk.a\n")
    with open(os.path.join(build, "CMakeFiles", "k.dir", "cpu.cpp.o.d"), "w") as fh:
        fh.write(f"CMakeFiles/k.dir/cpu.cpp.o: /src/cpu.cpp \\\n {lab}\n")
    with open(os.path.join(build, "CMakeFiles", "k.dir", "k.cpp.o.d"), "w") as fh:
        fh.write(f"CMakeFiles/k.dir/k.cpp.o: /src/k.cpp {os.path.join(build, 'k_spirv.h')}\n")
    outputs = put_lab_file(build, lab, b"vec3 f() { return vec3(0.0f); }\n", 1_000_000_000)
    expect(sorted(outputs) == ["CMakeFiles/k.dir/cpu.cpp.o", "bin/stage", "libk.a"] and os.stat(lab).st_mtime_ns == 1_000_000_000,
           "a submission rebuilds the objects that include its file and what they make, not the GPU kernels", repr(outputs))
    expect(dependents(build, lab) == set(outputs), "dependents() is what put_lab_file deletes")


def fast(pt_tests):
    sys.path.insert(0, HERE)
    with tempfile.TemporaryDirectory(prefix="grade_lab_fast_") as tmp:
        rebuilt_outputs(tmp)
        bad_usage(tmp)
        no_sandbox_refused(tmp)
        source_checks(tmp)
        report_checks()
        hint_tables(pt_tests)
        csv_quoting(tmp)
        sealed = sandbox_checks(tmp)
    return 0 if sealed else 77


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == "--fast":
        return fast(sys.argv[2] if len(sys.argv) > 2 else None)
    if len(sys.argv) > 2:
        print("usage: tools/test_grade_lab.py --fast [PT_TESTS] | [WORK]", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="grade_lab_test_") as tmp:
        work = sys.argv[1] if len(sys.argv) == 2 else os.path.join(tmp, "work")
        subs, out = os.path.join(tmp, "submissions"), os.path.join(tmp, "out")
        os.makedirs(subs)
        bad_usage(tmp)
        labs = os.environ.get("PT_GRADE_TEST_LABS", "2,4").split(",")
        if "2" in labs:
            lab2(subs, out, work)
            lab2_sandbox_alone(os.path.join(tmp, "attacks"), os.path.join(tmp, "out_attacks"), work)
        if "4" in labs:
            lab4(os.path.join(tmp, "submissions_lab4"), os.path.join(tmp, "out_lab4"), work + "_lab4")
    return 0


if __name__ == "__main__":
    sys.exit(main())
