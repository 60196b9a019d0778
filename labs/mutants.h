// The known-wrong answers to labs 2-6 (docs/labs/teachers.md, "Grading by mutation"): the
// classic mistakes of the estimators of the article's Eq. (3)-(5), of the BVH's slab test
// after it and of stage5's MIS weights, each written as a student would write it. In the
// check build (cmake/Labs.cmake, PT_LAB_CHECK), PT_LAB_MUTANT=NAME puts mutant NAME in place
// of the reference, and CI's lab_mutant_NAME entries (tests/CMakeLists.txt) pass only if the
// lab's tests then fail (tools/expect_lab_failure.sh): a lab whose tests let one of these
// through would grade nothing. Held back from the labs' handouts (tools/make_lab_handout.py):
// each one is the answer with one thing wrong.
// C++ only; included inside a kernel's namespace by labs/check_definitions.h. Each
// mutant_F below has the parameters of the kernel function F and returns the selected
// mutant's value, or `on` false when no mutant of F is selected.
#define PT_LAB_MUTANTS 1

template <class T>
struct Mutated {
  bool on = false;
  T value = T();
};

// A mutant's value, turned into the Mutated<> of the function's own return type (a test
// compiles the kernel with float as double: tests/stability/test_float_double.cpp).
template <class T>
struct MutantValue {
  T value;
  template <class U>
  operator Mutated<U>() const {
    return Mutated<U>{true, U(value)};
  }
};

template <class T>
MutantValue<T> mutated(T value) {
  return MutantValue<T>{value};
}

bool is_mutant(int lab, const char* name) {
  return pt::lab::mutant_is(lab, name);
}

// ---- Lab 2: the uniform estimator of Eq. (3) and the roulette --------------------------

Mutated<vec3> mutant_sample_uniform_hemisphere(vec2 u) {
  float phi = 2.0f * kPi * u.y;
  // The circle's radius forgotten: (cos phi, sin phi, z) is no unit vector.
  if (is_mutant(2, "uniform_no_radius")) return mutated(vec3(cos(phi), sin(phi), u.x));
  // theta uniform in [0, pi/2] instead of cos theta: the samples crowd the pole.
  if (is_mutant(2, "uniform_theta_uniform")) {
    float theta = 0.5f * kPi * u.x;
    return mutated(vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)));
  }
  return {};
}

Mutated<float> mutant_uniform_hemisphere_pdf() {
  // The cosine sampler's normaliser 1 / pi: the hemisphere's solid angle taken as pi.
  if (is_mutant(2, "uniform_pdf_one_over_pi")) return mutated(1.0f / kPi);
  return {};
}

Mutated<vec3> mutant_uniform_bounce_weight(vec3 f, vec3 wi) {
  // Erratum 1: the factor 1 / (2 pi N) as the article prints it, multiplying by the pdf.
  if (is_mutant(2, "bounce_printed_factor")) return mutated(f * (wi.z / (2.0f * kPi)));
  if (is_mutant(2, "bounce_no_cosine")) return mutated(f * (2.0f * kPi));
  if (is_mutant(2, "bounce_no_pdf")) return mutated(f * wi.z);
  return {};
}

Mutated<float> mutant_russian_roulette(vec3 beta, uint mode) {
  float p = mode == kRouletteFixed ? 0.5f : min(1.0f, max_component(beta));
  // Erratum 3: the printed text's "1/2 multipliers": the survivor multiplied by p, not 1 / p.
  if (is_mutant(2, "roulette_times_p")) return mutated(sample_1d() < p ? p : 0.0f);
  // The survivor not reweighted at all.
  if (is_mutant(2, "roulette_unweighted")) return mutated(sample_1d() < p ? 1.0f : 0.0f);
  return {};
}

// ---- Lab 3: the cosine-weighted sampler of Eq. (4) -------------------------------------

Mutated<vec3> mutant_sample_cosine_hemisphere(vec2 u) {
  // The disk's radius taken as u.x, not sqrt(u.x): the disk is not sampled uniformly.
  if (is_mutant(3, "cosine_linear_radius")) {
    float phi = 2.0f * kPi * u.y;
    return mutated(vec3(u.x * cos(phi), u.x * sin(phi), sqrt(max(0.0f, 1.0f - u.x * u.x))));
  }
  return {};
}

Mutated<float> mutant_cosine_hemisphere_pdf(float cos_theta) {
  if (is_mutant(3, "cosine_pdf_uniform")) return mutated(1.0f / (2.0f * kPi));  // the uniform sampler's pdf
  if (is_mutant(3, "cosine_pdf_no_pi")) return mutated(max(cos_theta, 0.0f));  // not normalised
  return {};
}

// ---- Lab 4: the direct light of Eq. (5) and the emission rule --------------------------

// The mistakes of the triangle light, made the same way in the sampler and its pdf (a
// student who misreads the formula misreads it in both): each leaves a factor out of
// pdf = d^2 / (cos_y A) x P(light), or lights the back of a one-sided emitter.
bool light_mistake() {
  return is_mutant(4, "light_no_cos_y") || is_mutant(4, "light_no_distance") || is_mutant(4, "light_no_area") ||
         is_mutant(4, "light_no_pick") || is_mutant(4, "light_both_sides");
}

float mistaken_light_pdf(float dist, float cos_y, float area, float pick) {
  float pdf = is_mutant(4, "light_no_distance") ? 1.0f : dist * dist;
  pdf /= is_mutant(4, "light_no_cos_y") ? 1.0f : cos_y;
  pdf /= is_mutant(4, "light_no_area") ? 1.0f : area;
  return pdf * (is_mutant(4, "light_no_pick") ? 1.0f : pick);
}

Mutated<LightSample> mutant_sample_triangle_light(uint index, vec3 p, vec2 u, float pick) {
  // u used as barycentric weights as they come: half of the points fall outside the triangle.
  bool unfolded = is_mutant(4, "light_unfolded_barycentric");
  if (!unfolded && !light_mistake()) return {};
  Triangle tri = triangles[index];
  vec3 p0 = tri.p0;
  vec3 p1 = tri.p1;
  vec3 p2 = tri.p2;
  float su = sqrt(u.x);
  float b1 = unfolded ? u.x : su * (1.0f - u.y);
  float b2 = unfolded ? u.y : su * u.y;
  vec3 y = (1.0f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
  vec3 c = cross(p1 - p0, p2 - p0);
  float area = 0.5f * length(c);
  vec3 d = y - p;
  float dist = length(d);
  vec3 wi = d / dist;
  float cos_y = dot(-wi, normalize(c));
  if (materials[tri.material].double_sided != 0u || is_mutant(4, "light_both_sides")) cos_y = abs(cos_y);
  if (!(cos_y > 0.0f) || !(dist > 0.0f)) return mutated(no_light());
  float pdf = mistaken_light_pdf(dist, cos_y, area, pick);
  return mutated(LightSample(wi, dist, triangle_emission(index, b1, b2) / pdf, pdf));
}

Mutated<float> mutant_triangle_light_pdf(uint index, vec3 wi, float dist) {
  bool no_pick_here = is_mutant(4, "light_pdf_no_pick");  // the pdf alone forgets P(light)
  if (!no_pick_here && !light_mistake()) return {};
  Triangle tri = triangles[index];
  if (tri.light == kNoLight) return mutated(0.0f);
  vec3 c = cross(vec3(tri.p1 - tri.p0), vec3(tri.p2 - tri.p0));
  float cos_y = dot(-wi, normalize(c));
  if (materials[tri.material].double_sided != 0u || is_mutant(4, "light_both_sides")) cos_y = abs(cos_y);
  if (!(cos_y > 0.0f)) return mutated(0.0f);
  float pick = no_pick_here ? 1.0f : light_pick_probability(tri.light);
  return mutated(mistaken_light_pdf(dist, cos_y, 0.5f * length(c), pick));
}

Mutated<bool> mutant_counts_emission(uint depth, bool after_delta) {
  (void)after_delta;  // each mistake below ignores it
  // Every hit's emission, as stage3 counts it: what light sampling found is counted twice.
  if (is_mutant(4, "emission_always")) return mutated(true);
  // Only the camera ray's: a light seen in a mirror or through glass is lost.
  if (is_mutant(4, "emission_camera_only")) return mutated(depth == 0u);
  return {};
}

// ---- Lab 5: the slab test of the BVH ---------------------------------------------------

// inverse_direction has none: 1 / dir left unclamped is no mistake beside the reference's
// box_span, whose comparisons all fail on the 0 x inf = NaN of a box face and so keep the
// interval they had (CI showed the lab's tests pass with it, and rightly).

Mutated<vec2> mutant_box_span(Ray ray, vec3 inv_dir, vec3 lo, vec3 hi, float t_max) {
  bool no_swap = is_mutant(5, "slab_no_swap");  // near and far not swapped for a negative direction
  bool no_pad = is_mutant(5, "slab_no_pad");    // the box not grown by the triangle test's rounding
  if (!no_swap && !no_pad) return {};
  vec3 t0 = (lo - ray.origin) * inv_dir;
  vec3 t1 = (hi - ray.origin) * inv_dir;
  vec3 near = no_swap ? t0 : min(t0, t1);
  vec3 far = no_swap ? t1 : max(t0, t1);
  float t_enter = max(0.0f, max(near.x, max(near.y, near.z)));
  float t_exit = min(t_max, min(far.x, min(far.y, far.z)));
  return mutated(vec2(t_enter, t_exit));
}

// ---- Lab 6: the MIS weights of stage5 --------------------------------------------------

Mutated<float> mutant_power_heuristic(float mine, float other) {
  // Both strategies weighted 1: what both find is counted twice.
  if (is_mutant(6, "mis_weight_one")) return mutated(mine > 0.0f ? 1.0f : 0.0f);
  // The squares over the square of the sum: the two weights no longer add up to 1.
  if (is_mutant(6, "mis_unnormalised")) {
    return mutated(mine > 0.0f ? mine * mine / ((mine + other) * (mine + other)) : 0.0f);
  }
  return {};
}

Mutated<float> mutant_triangle_light_pdf_by_solid_angle(uint index, vec3 p, vec3 wi, float dist) {
  if (!is_mutant(6, "mis_pdf_no_pick") && !is_mutant(6, "mis_pdf_by_area")) return {};
  Triangle tri = triangles[index];
  if (tri.light == kNoLight || !triangle_lights_point(tri, p)) return mutated(0.0f);
  // The area sampler's pdf, although the light sample was drawn by solid angle.
  if (is_mutant(6, "mis_pdf_by_area")) return mutated(triangle_light_pdf(index, wi, dist));
  SphericalTriangle t = spherical_triangle(p, vec3(tri.p0), vec3(tri.p1), vec3(tri.p2));
  if (!sample_by_solid_angle(t)) return mutated(triangle_light_pdf(index, wi, dist));
  return mutated(1.0f / t.area);  // P(light) forgotten
}
