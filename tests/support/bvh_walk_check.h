// The check of a BVH walk against the brute force, for the walks compiled as C++ (the plain
// one, tests/common/kernel/test_bvh_traversal.cpp; the GPU's, test_gpu_bvh_walk.cpp): rays at
// random scenes, each hit compared bit for bit. Not part of the article: test machinery.
// Included INSIDE a test file's anonymous namespace, after its `kernel` namespace, so that
// `kernel::` names that file's own copy of the kernel code (no include guard, on purpose).

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_hit(const kernel::Hit& a, const kernel::Hit& b) {
  return same_bits(a.t, b.t) && same_bits(a.b1, b.b1) && same_bits(a.b2, b.b2) && a.prim == b.prim && a.kind == b.kind;
}

void bind(const pt::Scene& s, const pt::Bvh& bvh) {
  kernel::triangles = s.triangles.data();
  kernel::spheres = s.spheres.data();
  kernel::triangle_soa = nullptr;
  kernel::params.triangle_count = uint(s.triangles.size());
  kernel::params.sphere_count = 0u;
  kernel::params.accel = pt::kAccelBvh;
  kernel::bvh_nodes = bvh.nodes.empty() ? nullptr : bvh.nodes.data();
  kernel::bvh_indices = bvh.indices.empty() ? nullptr : bvh.indices.data();
}

struct Tally {
  std::uint64_t rays = 0, hits = 0, mismatches = 0, ties = 0;
};

// The BVH's hit against the loop in index order, for one ray and bound t_max.
void compare(kernel::Ray ray, float t_max, Tally& tally) {
  kernel::Hit none = kernel::Hit(t_max, 0.0f, 0.0f, 0u, pt::kPrimNone);
  kernel::RayShear rs = kernel::make_ray_shear(ray.dir);
  kernel::Hit brute = kernel::nearest_triangle_in_order(ray, rs, none);
  kernel::Hit fast = kernel::nearest_triangle_bvh(ray, rs, none);
  tally.rays++;
  tally.hits += brute.kind == pt::kPrimTriangle;
  // The any-hit walk of shadow rays: a hit exactly when the brute force finds one.
  if (kernel::bvh_nodes != nullptr && kernel::occluded_bvh(ray, rs, t_max) != (brute.kind != pt::kPrimNone)) {
    tally.mismatches++;
    UNSCOPED_INFO("occluded_bvh differs from the brute force: t_max " << t_max << ", brute kind " << brute.kind);
  }
  if (!same_hit(brute, fast)) {
    tally.mismatches++;
    UNSCOPED_INFO("mismatch: brute t " << brute.t << " prim " << brute.prim << " kind " << brute.kind << "; bvh t "
                                       << fast.t << " prim " << fast.prim << " kind " << fast.kind);
  }
  if (brute.kind == pt::kPrimTriangle) {  // another triangle at the same distance: a tie
    for (uint i = 0; i < kernel::params.triangle_count; i++) {
      kernel::Hit h = kernel::hit_triangle(ray, rs, i, none);
      if (i != brute.prim && h.kind == pt::kPrimTriangle && same_bits(h.t, brute.t)) {
        tally.ties++;
        break;
      }
    }
  }
}

// Rays at a scene: towards random points of random triangles (edges and vertices too),
// along the axes (zero direction components), in random directions, and bounded at the
// brute force's own hit distance (a hit at exactly t_max is not taken).
void shoot(const pt::Scene& s, std::mt19937& rng, int count, Tally& tally) {
  pt::Bounds b = s.bounds();
  glm::vec3 center = b.empty() ? glm::vec3(0.0f) : 0.5f * b.lo + 0.5f * b.hi;
  float size = b.empty() ? 1.0f : std::max(glm::length(b.hi - b.lo), 1e-30f);
  for (int r = 0; r < count; r++) {
    glm::vec3 origin, dir;
    pt::test::random_test_ray(s, rng, r, center, size, origin, dir);
    if (!(glm::length(dir) > 0.0f)) continue;
    kernel::Ray ray(origin, glm::normalize(dir));
    compare(ray, kernel::kInfinity, tally);
    kernel::RayShear rs = kernel::make_ray_shear(ray.dir);
    kernel::Hit first = kernel::nearest_triangle_in_order(ray, rs, kernel::Hit(kernel::kInfinity, 0, 0, 0u, 0u));
    if (first.kind == pt::kPrimTriangle) compare(ray, first.t, tally);
  }
}

void check(const pt::Scene& s, std::mt19937& rng, int rays, const char* what, std::uint64_t min_ties = 0) {
  pt::Bvh bvh = pt::build_bvh(s.triangles);
  bind(s, bvh);
  Tally tally;
  shoot(s, rng, rays, tally);
  INFO(what << ": " << s.triangles.size() << " triangles, " << tally.rays << " rays, " << tally.hits << " hits, "
            << tally.ties << " ties");
  CHECK(tally.mismatches == 0);
  CHECK(tally.ties >= min_ties);
}


// 24 random scenes of 2 to 577 triangles (tests/support/random_scenes.h), 600 rays each.
void check_random_scenes() {
  std::mt19937 rng(777);
  for (int scene = 0; scene < 24; scene++) {
    pt::Scene s;
    const float scale = pt::test::add_random_triangles(s, rng, scene, 2 + scene * 25);
    INFO("scene " << scene << ", scale " << scale);
    check(s, rng, 600, "random");
  }
}

// Triangles on the plane z = 0 with small integer vertices: every hit of a ray straight
// down from an integer height has an exact t, so overlapping triangles tie. The large ones
// come first (low indices) and sit in other leaves than the small ones they cover, so the
// traversal often meets the higher index first.
pt::Scene coplanar_overlaps() {
  pt::Scene s;
  uint m = s.add_material(pt::make_diffuse(glm::vec3(0.5f)));
  for (int size = 64; size >= 1; size /= 2) {
    for (int x = 0; x < 64; x += size) {
      for (int y = 0; y < 64; y += size) {
        s.add_triangle({float(x), float(y), 0}, {float(x + size), float(y), 0}, {float(x), float(y + size), 0}, m);
      }
    }
  }
  return s;
}

// Rays straight down at coplanar_overlaps(): over a thousand ties, each won by the lower index.
void check_coplanar_ties(const pt::Scene& s) {
  pt::Bvh bvh = pt::build_bvh(s.triangles);
  bind(s, bvh);
  std::mt19937 rng(99);
  Tally tally;
  for (int r = 0; r < 3000; r++) {
    glm::vec3 origin(float(rng() % 256) * 0.25f, float(rng() % 256) * 0.25f, float(1 + rng() % 8));
    compare(kernel::Ray(origin, glm::vec3(0, 0, -1)), kernel::kInfinity, tally);
  }
  INFO(tally.rays << " rays, " << tally.hits << " hits, " << tally.ties << " ties");
  CHECK(tally.mismatches == 0);
  CHECK(tally.ties > 1000);
}

// All triangles at one point, one triangle, none, a plane of copies, sizes 1e-6 to 1e6.
void check_degenerate_scenes() {
  std::mt19937 rng(4242);
  for (const pt::test::DegenerateScene& d : pt::test::degenerate_scenes(rng)) check(d.scene, rng, d.rays, d.name, d.min_ties);
}
