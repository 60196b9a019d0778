"""The fixture submissions of tools/test_grade_lab.py (tooling for teachers, not a part of the
article): lab 2's, the attacks of issue 47 among them, and lab 4's, each made from the
reference files without quoting a line of their bodies (labs 1, 3, 5 and 6: fixtures_small.py)."""
import os

from grade_lab_checks.support import REPO, reference, with_wrappers, write


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
             os.path.join(work, "src", "build", "bin", "planted_by_student"), "/planted_by_student"],
            os.path.join(work, "src", "build", "copied_reference.glsl"))


def attacks(rel, references, wrong, work, out):
    """The attacks of issue 47 on a lab whose reference file is rel (references: all of the
    lab's): each would pass, or plant its files, if the grader let it. wrong: a wrong answer
    (a whole lab file) that the attacks which write carry, so that only the attack could pass it."""
    targets, copy_to = plants(work)
    return {
        "r_includes_reference.glsl": "".join(f'#include "{r}"\n' for r in references),
        "r_writes_outside.glsl": wrong + plant_attack(targets, os.path.join(work, "src", rel), copy_to),
        "r_rewrites_report.glsl": wrong + report_attack([os.path.join(out, "logs", "r_rewrites_report.tests.xml"),
                                                         os.path.join(work, "src", "build", "report.xml")]),
        "r_prints_1gb.glsl": reference(rel) + PRINT_ATTACK,
    }


# A count down on an unsigned i that never ends (g++ warns: always true), and a read far past
# the end of the scene's materials (SIGSEGV on the CPU; the read decides the result: 0 * x is
# not folded away without -ffast-math), each put before a call of the reference as the lab's
# own function: LOOP.format(x=a float of the call's arguments) and CRASH.format(c=a bool of them).
LOOP = "float acc = 0.0f;\n  for (uint i = 4u; i >= 0u; --i) {{\n    acc += {x};\n  }}\n"
CRASH = "0.0f * materials[100000000 + int({c})].metallic"


def other_kinds(lab, rel, endless, crash, wrong, work, out, references=None):
    """The submissions of every kind besides the lab's answers (issue 47): an endless loop, a
    crash, a folder without the file, and the attacks (fixtures.attacks; references: the lab's
    reference files, default [rel]), aimed at work and out (the grading run's folders; None:
    nowhere). endless, crash, wrong: whole lab files."""
    work, out = work or "/nonexistent", out or "/nonexistent"
    return {"f_endless_loop.glsl": endless, "g_crash.glsl": crash, "h_empty/README.txt": f"lab{lab}.glsl was forgotten\n",
            **attacks(rel, references or [rel], wrong, work, out)}


def lab2_fixtures(folder, work=None, out=None):
    """Lab 2's submissions. work and out (the grading run's folders) aim the attacks."""
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
    write(folder, {
        "a_correct.glsl": reference(rel),
        "b_syntax_error.glsl": variant(sampler="return reference_sampler(u)"),
        "c_pdf_2pi.glsl": variant(pdf="return 2.0f * kPi;"),
        # The reference's cos(theta) is u.x: feeding it cos of a uniform angle makes theta uniform.
        "d_theta_uniform.glsl": variant(sampler="return reference_sampler(vec2(cos(0.5f * kPi * u.x), u.y));"),
        "e_convention/lab2.glsl": variant(sampler="return reference_sampler(vec2(u.y, u.x));"),
        # Lab 2's other known-wrong answers (labs/mutants.h; d_theta_uniform is its
        # uniform_theta_uniform), each the renamed reference wrapped to make that mistake.
        "m_uniform_no_radius.glsl": variant(sampler="vec3 v = reference_sampler(u);\n  "
                                                    "float r = max(length(vec2(v.x, v.y)), 1e-30f);\n  "
                                                    "return vec3(v.x / r, v.y / r, v.z);"),
        "m_uniform_pdf_one_over_pi.glsl": variant(pdf="return 1.0f / kPi;"),
        **other_kinds(2, rel, variant(sampler=LOOP.format(x="u.x") + "  return reference_sampler(u + vec2(0.0f * acc));"),
                      variant(sampler="return reference_sampler(u + vec2(" + CRASH.format(c="u.y > 2.0f") + "));"),
                      no_pdf, work, out, REFERENCES_2),
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


def lab4_fixtures(folder, work=None, out=None):
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
        **other_kinds(4, rel, variant(sample=LOOP.format(x="u.x") + "  return reference_sample(index, p, u + vec2(0.0f * acc), pick);"),
                      variant(sample="return reference_sample(index, p, u + vec2(" + CRASH.format(c="u.y > 2.0f") + "), pick);"),
                      variant(sample="return reference_sample(index, p, u, 2.0f * pick);"), work, out),
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
