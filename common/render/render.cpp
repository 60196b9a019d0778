// The render loop shared by every stage (see render.h).
#include "common/render/render.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include "common/base/error.h"
#include "common/render/interrupt.h"
#include "common/scene/environment.h"
#include "common/scene/scene.h"

namespace pt {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void print_progress(const RenderSettings& s, const char* label, std::uint64_t done, double elapsed) {
  if (s.time_budget > 0.0 || s.target_error > 0.0) {  // no fixed end: say where it stands
    std::fprintf(stderr, "\r%s: %llu spp, %.1f s elapsed%s   ", label, (unsigned long long)done, elapsed,
                 s.time_budget > 0.0 ? (" of " + std::to_string(int(s.time_budget)) + " s").c_str() : "");
    std::fflush(stderr);
    return;
  }
  double left = elapsed / double(done) * double(s.spp - done);
  std::fprintf(stderr, "\r%s: %3d%% (%llu/%llu spp), %.1f s elapsed, about %.1f s left   ", label,
               int(100.0 * double(done) / double(s.spp)), (unsigned long long)done, (unsigned long long)s.spp,
               elapsed, left);
  std::fflush(stderr);
}

}  // namespace

std::uint64_t pass_end(std::uint64_t sample) {
  if (sample >= kMaxPassSamples) return (sample / kMaxPassSamples + 1) * kMaxPassSamples;
  std::uint64_t end = 1;  // 1, 2, 4, 8, 16
  while (end <= sample) end *= 2;
  return end;
}

bool is_pass_end(std::uint64_t sample) {
  return sample == 0 || (sample >= kMaxPassSamples ? sample % kMaxPassSamples == 0 : (sample & (sample - 1)) == 0);
}

void RenderCounters::add(const PassResult& pass) {
  depth_cap += pass.counters[kCounterDepthCap];
  zero_pdf += pass.counters[kCounterZeroPdf];
  non_finite += pass.counters[kCounterNonFinite];
  first_non_finite_pixel = std::min(first_non_finite_pixel, pass.non_finite_pixel());
}

FrameParams make_frame_params(const Scene& scene, const RenderSettings& s) {
  FrameParams p{};
  p.camera = make_camera(scene, float(s.width) / float(s.height));
  p.sky = s.sky;
  p.width = uint(s.width), p.height = uint(s.height);
  p.triangle_count = uint(scene.triangles.size());
  p.sphere_count = uint(scene.spheres.size());
  p.material_count = uint(scene.materials.size());
  p.point_light_count = uint(scene.point_lights.size());
  p.seed = s.seed, p.roulette = s.roulette, p.depth_cap = s.depth_cap, p.sampler_kind = s.sampler;
  p.light_count = uint(scene.lights.size());
  p.accel = s.accel == kAccelBvh && !scene.triangles.empty() ? kAccelBvh : kAccelNone;
  p.sky_pick = sky_pick_probability(scene, s.sky);
  p.env_cos = 1.0f, p.env_sin = 0.0f;
  if (scene.environment) {  // environment.glsl: its size, and its turn about +Y
    p.env_width = scene.environment->width, p.env_height = scene.environment->height;
    const glm::vec2 turn = environment_turn(*scene.environment);
    p.env_cos = turn.x, p.env_sin = turn.y;
  }
  Bounds b = scene.bounds();
  p.scene_radius = b.empty() ? 1.0f : glm::max(0.5f * glm::length(b.hi - b.lo), 1e-30f);
  return p;
}

RenderResult render(Backend& backend, const Scene& scene, const RenderSettings& s, const RenderHooks& h) {
  RenderResult result = h.resume ? *h.resume : RenderResult{Film(s.width, s.height), 0.0, 0.0, {}, 0, {}, {}, {}};
  result.device_error.clear();
  const double seconds_before = result.seconds;
  FrameParams params = make_frame_params(scene, s);
  std::vector<glm::vec4> pass(std::size_t(s.width) * std::size_t(s.height));
  bool show_progress = h.progress && ::isatty(2);
  bool shown = false;
  Clock::time_point start = Clock::now(), saved = start;
  std::uint64_t done = result.film.spp();
  // Randomised QMC: the error from the two halves of each aligned block (film.h).
  if (s.sampler == kSamplerSobol) result.film.track_halves(s.first_sample);
  // The BVH: the caller's, or built here from the scene; read by the backend's passes.
  std::optional<Bvh> built;
  const Bvh* bvh = params.accel == kAccelBvh ? h.bvh : nullptr;
  if (params.accel == kAccelBvh && !bvh) bvh = &built.emplace(build_bvh(scene.triangles));
  if (bvh) result.bvh = bvh->stats;
  const uint features = s.all_features ? kFeatureAll : scene_feature_mask(scene, s.sky);
  try {
    backend.set_scene(scene, features, bvh);
    // The stage's own step before the render, if it has one (stage6_variance_aware: a small
    // render that sets its MIS weights). A resumed render or a part runs it again and gets
    // the same values, so it renders the same samples.
    if (BeforeRender before = backend.before_render()) {
      StageTuning tuning = before(backend, params, features, pass);
      params.stage_params = tuning.params;
      result.stage_note = tuning.note;
    }
  } catch (const Error& e) {  // a device that cannot hold the scene: nothing rendered yet
    if (e.code() != kExitNoDevice) throw;
    result.device_error = e.what();
    return result;
  }
  for (std::uint64_t index = result.passes; done < s.spp; index++) {
    const std::uint64_t first = s.first_sample + done;  // the schedule's pass that holds it
    const std::uint64_t n = std::min(pass_end(first) - first, s.spp - done);
    params.first_sample = uint(first);
    params.sample_count = uint(n);
    PassResult pass_result;
    try {
      pass_result = backend.run_pass(params, pass);
    } catch (const Error& e) {  // a lost device: keep the samples done so far
      if (e.code() != kExitNoDevice) throw;
      result.device_error = e.what();
      if (h.save && done > 0) h.save(result);
      break;
    }
    if (!pass_result.cut_short.empty()) {  // the backend could not render it whole: never added to the film
      result.device_error = "pass " + std::to_string(index + 1) + " would be a wrong image: " + pass_result.cut_short;
      if (h.save && done > 0) h.save(result);
      break;
    }
    result.kernel_seconds += pass_result.kernel_seconds;
    result.counters.add(pass_result);
    result.film.add_pass(pass, n);
    done += n;
    result.passes = index + 1;
    double elapsed = seconds_since(start);
    result.seconds = seconds_before + elapsed;
    if (show_progress && elapsed > 1.0 && done < s.spp) print_progress(s, h.label, done, elapsed), shown = true;
    // Ctrl-C or SIGTERM: stop here; the samples done so far make a correct image. Or the
    // user's trade of time for accuracy: every pass ends a correct image of its spp.
    bool stop = interrupt_signal() != 0 || (s.time_budget > 0.0 && elapsed >= s.time_budget) ||
                (s.target_error > 0.0 && done >= kMinSamplesForError &&
                 result.film.per_pixel_relative_error() <= s.target_error);
    if (h.save && done < s.spp && (stop || seconds_since(saved) >= h.save_seconds)) {
      h.save(result);
      saved = Clock::now();
    }
    if (stop) break;
  }
  if (shown) std::fprintf(stderr, "\r%*s\r", 79, "");
  result.seconds = seconds_before + seconds_since(start);
  return result;
}

}  // namespace pt
