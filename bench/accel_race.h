// pt_bench's acceleration section (accel.cpp): the race of the search methods over one
// ray set, passes in turn on all cores so that they see the same load, and the CSV row
// (docs/results/accel.csv) with the console line that each method's result becomes.
// Not part of the article: the machinery of the benchmark (issue 17).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bench/accel.h"

namespace pt::bench {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One method on one ray set: its speed and what it found.
struct Result {
  Result(std::string m, std::string d) : method(std::move(m)), device(std::move(d)) {}
  std::string method, device, note;
  bool measured = false;
  double wall = 0.0, cpu = 0.0;  // seconds of the counted passes (cpu: summed over threads)
  std::uint64_t rays = 0, passes = 0;
  std::vector<float> t;                     // per ray of the set (kMiss: no hit)
  std::vector<std::size_t> subset;          // the rays traced, when not all of them
  std::function<void(bool counted)> pass;   // one pass over its rays
};

// The methods' passes in turn until each has run `seconds` and kMinPasses (3) passes (after one
// uncounted warm-up pass each, which also leaves the distances): all see the same load
// from other jobs, and a burst of load falls on more than one pass.
void race(std::vector<Result*> methods, double seconds);

// A pass of a CPU method over its rays on all cores.
std::function<void(bool)> cpu_pass(Result& r, const RaySet& rays, std::function<void()> setup,
                                   std::function<void(const std::size_t*, std::size_t, std::size_t, float*)> trace);

// docs/results/accel.csv, one row per method and ray set.
struct Csv {
  std::ofstream out;
  // Writes one method's row; `reference` is the CPU BVH's result on the same rays.
  void row(const char* set, int level, std::size_t triangles, const Result& r, const Result& reference);
};

}  // namespace pt::bench
