"""The fixture submissions of tools/test_grade_lab.py for the labs of one or two short functions
(labs 1, 3, 5 and 6; tooling for teachers, not a part of the article): for each, the correct
file, one that does not compile, each known-wrong answer of labs/mutants.h, and the other kinds
of issue 47 (an endless loop, a crash, an empty folder, the attacks), written as a student would, from the reference file with its functions renamed and called by wrappers, so
that no line of their bodies is quoted here (the handout ships this file)."""
from grade_lab_checks.fixtures import CRASH, LOOP, other_kinds
from grade_lab_checks.support import reference, with_wrappers, write


def lab1_fixtures(folder, work=None, out=None):
    """Lab 1 (stage1's Li, Eq. 2) has no mutants in labs/mutants.h: its wrong answers here are a
    dimmed image and a black sky; and the other kinds (other_kinds)."""
    rel = "stage1_raycast/integrator.glsl"

    def variant(body):
        return with_wrappers(rel, {"vec3 Li(Ray ray)": "reference_Li"}, f"vec3 Li(Ray ray) {{\n  {body}\n}}\n")

    dimmed = variant("return 0.5f * reference_Li(ray);")
    write(folder, {
        "a_correct.glsl": reference(rel),
        "b_syntax_error.glsl": variant("return reference_Li(ray)"),
        "c_dimmed.glsl": dimmed,
        # What --sky (or the environment) gives a ray that meets nothing, left black.
        "c_black_sky.glsl": variant("if (intersect_scene(ray, kInfinity).kind == kPrimNone) return vec3(0.0f);\n"
                                    "  return reference_Li(ray);"),
        **other_kinds(1, rel, variant(LOOP.format(x="ray.dir.x") + "  return reference_Li(ray) + vec3(0.0f * acc);"),
                      variant("return reference_Li(ray) + vec3(" + CRASH.format(c="ray.dir.x > 0.0f") + ");"),
                      dimmed, work, out),
    })


def lab3_fixtures(folder, work=None, out=None):
    """Lab 3's submissions: the correct one, one that does not compile, and each of its
    known-wrong answers (labs/mutants.h), written as a student would."""
    rel = "common/kernel/cosine_hemisphere.glsl"
    renames = {"vec3 sample_cosine_hemisphere(vec2 u)": "reference_sampler",
               "float cosine_hemisphere_pdf(float cos_theta)": "reference_pdf"}

    def variant(sampler="return reference_sampler(u);", pdf="return reference_pdf(cos_theta);"):
        return with_wrappers(rel, renames, f"vec3 sample_cosine_hemisphere(vec2 u) {{\n  {sampler}\n}}\n\n"
                                           f"float cosine_hemisphere_pdf(float cos_theta) {{\n  {pdf}\n}}\n")

    write(folder, {
        "a_correct.glsl": reference(rel),
        "b_syntax_error.glsl": variant(pdf="return reference_pdf(cos_theta)"),
        # The disk's radius u.x instead of sqrt(u.x) (the reference's radius is sqrt of its u.x);
        # the uniform sampler's pdf (lab 2's function); the pdf not normalised by pi.
        "m_cosine_linear_radius.glsl": variant(sampler="return reference_sampler(vec2(u.x * u.x, u.y));"),
        "m_cosine_pdf_uniform.glsl": variant(pdf="return uniform_hemisphere_pdf();"),
        "m_cosine_pdf_no_pi.glsl": variant(pdf="return reference_pdf(cos_theta) * kPi;"),
        **other_kinds(3, rel, variant(sampler=LOOP.format(x="u.x") + "  return reference_sampler(u + vec2(0.0f * acc));"),
                      variant(sampler="return reference_sampler(u + vec2(" + CRASH.format(c="u.y > 2.0f") + "));"),
                      variant(pdf="return reference_pdf(cos_theta) * kPi;"), work, out),
    })


def lab5_fixtures(folder, work=None, out=None):
    rel = "common/kernel/box_slab.glsl"
    renames = {"vec3 inverse_direction(vec3 dir)": "reference_inverse",
               "vec2 box_span(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max)": "reference_span"}

    def variant(span="return reference_span(ray, inv_dir, lo, hi, t_max);"):
        return with_wrappers(rel, renames, "vec3 inverse_direction(vec3 dir) {\n  return reference_inverse(dir);\n}\n\n"
                                           f"vec2 box_span(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max) {{\n  {span}\n}}\n")

    # The slab test as a textbook writes it, without the rounding of the triangle test: with
    # near and far not swapped for a negative direction, or swapped but the box not grown.
    slabs = "vec3 t0 = (lo - ray.origin) * inv_dir;\n  vec3 t1 = (hi - ray.origin) * inv_dir;\n"
    no_swap = variant(slabs + "  return vec2(max(0.0f, max(t0.x, max(t0.y, t0.z))), min(t_max, min(t1.x, min(t1.y, t1.z))));")
    write(folder, {
        "a_correct.glsl": reference(rel),
        "b_syntax_error.glsl": variant("return reference_span(ray, inv_dir, lo, hi, t_max)"),
        "m_slab_no_swap.glsl": no_swap,
        "m_slab_no_pad.glsl": variant(slabs + "  vec3 near = min(t0, t1);\n  vec3 far = max(t0, t1);\n"
                                              "  return vec2(max(0.0f, max(near.x, max(near.y, near.z))), "
                                              "min(t_max, min(far.x, min(far.y, far.z))));"),
        **other_kinds(5, rel, variant(LOOP.format(x="t_max") + "  return reference_span(ray, inv_dir, lo, hi, t_max + 0.0f * acc);"),
                      variant("return reference_span(ray, inv_dir, lo, hi, t_max + " + CRASH.format(c="t_max < 0.0f") + ");"),
                      no_swap, work, out),
    })


def lab6_fixtures(folder, work=None, out=None):
    rel = "common/kernel/mis.glsl"
    renames = {"float power_heuristic(float mine, float other)": "reference_weight",
               "float triangle_light_pdf_by_solid_angle(uint index, vec3 p, vec3 wi, float dist)": "reference_pdf"}

    def variant(weight="return reference_weight(mine, other);", pdf="return reference_pdf(index, p, wi, dist);"):
        return with_wrappers(rel, renames, f"float power_heuristic(float mine, float other) {{\n  {weight}\n}}\n\n"
                                           "float triangle_light_pdf_by_solid_angle(uint index, vec3 p, vec3 wi, float dist) "
                                           f"{{\n  {pdf}\n}}\n")

    pdf = "float r = reference_pdf(index, p, wi, dist);\n  return r > 0.0f ? {} : 0.0f;"
    write(folder, {
        "a_correct.glsl": reference(rel),
        "b_syntax_error.glsl": variant(weight="return reference_weight(mine, other)"),
        # Both strategies weighted 1; the squares over the square of the sum; the light's pdf
        # without the probability of picking it; the area sampler's pdf for a solid-angle sample.
        "m_mis_weight_one.glsl": variant(weight="return reference_weight(mine, other) > 0.0f ? 1.0f : 0.0f;"),
        "m_mis_unnormalised.glsl": variant(
            weight="return mine > 0.0f ? mine * mine / ((mine + other) * (mine + other)) : 0.0f;"),
        "m_mis_pdf_no_pick.glsl": variant(pdf=pdf.format("r / light_pick_probability(triangles[index].light)")),
        "m_mis_pdf_by_area.glsl": variant(pdf=pdf.format("triangle_light_pdf(index, wi, dist)")),
        **other_kinds(6, rel, variant(weight=LOOP.format(x="mine") + "  return reference_weight(mine, other) + 0.0f * acc;"),
                      variant(weight="return reference_weight(mine, other) + " + CRASH.format(c="mine < 0.0f") + ";"),
                      variant(weight="return reference_weight(mine, other) > 0.0f ? 1.0f : 0.0f;"), work, out),
    })
