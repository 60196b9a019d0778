// The race of pt_bench's acceleration section (accel_race.h): each method's passes over its
// rays on all cores, timed by the wall clock and by the threads' CPU time, and each result
// written as a CSV row beside a console line. Not part of the article: the machinery of the
// benchmark (issue 17).
#include "bench/accel_race.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <thread>

#include "bench/bench.h"

namespace pt::bench {

namespace {

using Clock = std::chrono::steady_clock;

// work(first, last) over [0, n) in chunks taken from a shared counter by every core;
// returns the CPU seconds the threads spent.
template <class F> double on_all_cores(std::size_t n, std::size_t chunk, F work) {
  std::atomic<std::size_t> next{0};
  std::atomic<double> cpu{0.0};
  auto worker = [&] {
    const double t0 = thread_cpu_seconds();
    for (std::size_t a; (a = next.fetch_add(chunk)) < n;) work(a, std::min(n, a + chunk));
    cpu.fetch_add(thread_cpu_seconds() - t0);
  };
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < cores(); i++) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return cpu.load();
}

bool differs(float a, float b) {
  if (std::isinf(a) || std::isinf(b)) return a != b;
  return std::fabs(a - b) > 1e-5f * std::max(a, b);
}

}  // namespace

constexpr std::uint64_t kMinPasses = 3;  // counted passes each method runs at least (race)

void race(std::vector<Result*> methods, double seconds) {
  for (Result* m : methods) m->pass(false);
  auto pending = [&](const Result* m) { return m->wall < seconds || m->passes < kMinPasses; };
  for (bool more = true; more;) {
    more = false;
    for (Result* m : methods) {
      if (pending(m)) m->pass(true), more = more || pending(m);
    }
  }
}

std::function<void(bool)> cpu_pass(Result& r, const RaySet& rays, std::function<void()> setup,
                                   std::function<void(const std::size_t*, std::size_t, std::size_t, float*)> trace) {
  return [&r, &rays, setup, trace](bool counted) {
    r.t.assign(rays.size(), kMiss);
    setup();
    const std::size_t* index = r.subset.empty() ? nullptr : r.subset.data();
    const std::size_t n = r.subset.empty() ? rays.size() : r.subset.size();
    Clock::time_point t0 = Clock::now();
    double cpu = on_all_cores(n, index ? 4 : 256, [&](std::size_t a, std::size_t b) { trace(index, a, b, r.t.data()); });
    if (counted) r.wall += seconds_since(t0), r.cpu += cpu, r.rays += n, r.passes++;
  };
}

void Csv::row(const char* set, int level, std::size_t triangles, const Result& r, const Result& reference) {
  std::size_t checked = 0, hits = 0, differing = 0;
  double sum_t = 0.0;
  auto visit = [&](std::size_t i) {
    checked++;
    if (!std::isinf(r.t[i])) hits++, sum_t += r.t[i];
    if (&r != &reference && differs(r.t[i], reference.t[i])) differing++;
  };
  if (r.measured) {
    if (r.subset.empty()) {
      for (std::size_t i = 0; i < r.t.size(); i++) visit(i);
    } else {
      for (std::size_t i : r.subset) visit(i);
    }
  }
  const unsigned threads = r.method == "bvh_gpu" ? 0u : cores();
  out << set << "," << level << "," << triangles << "," << r.method << ",\"" << r.device << "\","
      << (threads ? std::to_string(threads) : "") << ",";
  if (r.measured) {
    out << r.rays << "," << r.passes << "," << double(r.rays) / r.wall / 1e6 << ","
        << double(r.rays) / r.cpu * cores() / 1e6 << "," << checked << "," << hits << ","
        << (hits ? fixed(sum_t / double(hits), 7) : "") << "," << differing;
  } else {
    out << ",,,,,,,";
  }
  out << ",\"" << r.note << "\"\n";
  std::printf("  %-7s %-8s %9s M rays/s (by CPU time %9s)  hits %zu/%zu, mean t %s, %zu differ from bvh_cpu%s%s\n",
              set, r.method.c_str(), r.measured ? fixed(double(r.rays) / r.wall / 1e6, 4).c_str() : "-",
              r.measured ? fixed(double(r.rays) / r.cpu * cores() / 1e6, 4).c_str() : "-", hits, checked,
              hits ? fixed(sum_t / double(hits), 6).c_str() : "-", differing, r.note.empty() ? "" : "; ",
              r.note.c_str());
}

}  // namespace pt::bench
