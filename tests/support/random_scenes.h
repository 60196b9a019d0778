// Random triangle scenes for the BVH tests (the traversal of common/kernel/bvh.glsl and the
// CPU's wide walk, cpu/wide_bvh.h): the hard cases of a nearest-hit search in one soup.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "common/scene/scene.h"

namespace pt::test {

// `count` small triangles at a random scale from 1e-6 to 1e6 (moved off the origin in two
// scenes of three, by `index`), with slivers, zero-area triangles, exact copies (equal
// distances) and shared edges mixed in; returns the scale.
float add_random_triangles(Scene& s, std::mt19937& rng, int index, int count);

// An n x n grid of unit quads in the plane z = 5, every quad three times: ties everywhere.
void add_copied_grid(Scene& s, int n);

// `count` triangles from 1e-6 to 1e6 in size, each at a distance from the origin to match.
void add_spread_triangles(Scene& s, std::mt19937& rng, int count);

// Ray number `r` of a traversal test of `s` (within `size` of `center`, its bounds): from a
// random point toward a random point, three in four toward a triangle of the scene (on an
// edge for every fifth, at a vertex for every seventh), one in six along an axis (two
// direction components exactly 0). The direction is not normalised and may be zero.
void random_test_ray(const Scene& s, std::mt19937& rng, int r, glm::vec3 center, float size, glm::vec3& origin,
                     glm::vec3& dir);

// The degenerate scenes every traversal test runs, with how many rays each gets and how
// many ties at least those rays must meet: all triangles at one point (and one to hit), one
// triangle, none, a plane of copies, sizes 1e-6 to 1e6.
struct DegenerateScene {
  const char* name;
  Scene scene;
  int rays;
  std::uint64_t min_ties;
};
std::vector<DegenerateScene> degenerate_scenes(std::mt19937& rng);

}  // namespace pt::test
