// pt_bench's acceleration section: Embree 3, the reference CPU ray tracer the BVH of issue
// 17 is measured against (accel.h). One triangle mesh that shares the scene's own triangle
// array as its vertex buffer (p0, p1, p2 of each Triangle lie 16 bytes apart), a
// high-quality build (RTC_BUILD_QUALITY_HIGH), and rtcIntersect1 one ray at a time. Built
// only when CMake found Embree (PT_HAVE_EMBREE); otherwise the section says so and leaves
// Embree's column empty.
#include <chrono>
#include <cstdio>

#include "bench/accel.h"
#include "common/base/error.h"

#ifdef PT_HAVE_EMBREE
#include <algorithm>
#include <atomic>
#include <string>

#include <embree3/rtcore.h>
#endif

namespace pt::bench {

#ifdef PT_HAVE_EMBREE

namespace {

// Bytes Embree holds on a device: its memory monitor callback adds every allocation and
// subtracts every release.
bool count_bytes(void* user, ssize_t bytes, bool) {
  static_cast<std::atomic<long long>*>(user)->fetch_add(bytes);
  return true;
}

void device_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "embree: error %d: %s\n", int(code), message ? message : "");
}

}  // namespace

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::atomic<long long> bytes{0};
};

bool EmbreeScene::available() {
  return true;
}

std::string EmbreeScene::missing_reason() {
  return "";
}

std::string EmbreeScene::version() {
  return "Embree " + std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
         std::to_string(RTC_VERSION_PATCH);
}

EmbreeScene::EmbreeScene(std::span<const Triangle> triangles, unsigned build_threads) : impl_(new Impl) {
  std::string config = "threads=" + std::to_string(build_threads);
  impl_->device = rtcNewDevice(config.c_str());
  if (!impl_->device) throw Error(kExitOutput, "embree: rtcNewDevice failed");
  rtcSetDeviceErrorFunction(impl_->device, device_error, nullptr);
  rtcSetDeviceMemoryMonitorFunction(impl_->device, count_bytes, &impl_->bytes);
  using Clock = std::chrono::steady_clock;
  Clock::time_point start = Clock::now();
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry mesh = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(mesh, RTC_BUILD_QUALITY_HIGH);
  const std::size_t n = triangles.size();
  // Vertex 3 i + k is vertex k of triangle i: 16 bytes apart, the Triangle's own layout
  // (a 4-byte field follows every vec3, so Embree's 16-byte loads stay inside the array).
  rtcSetSharedGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, triangles.data(), 0, 16, 3 * n);
  auto* index = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (std::size_t i = 0; i < 3 * n; i++) index[i] = unsigned(i);
  rtcCommitGeometry(mesh);
  rtcAttachGeometry(impl_->scene, mesh);
  rtcReleaseGeometry(mesh);
  const long long before = impl_->bytes.load();
  Clock::time_point commit = Clock::now();
  rtcCommitScene(impl_->scene);
  Clock::time_point end = Clock::now();
  build_seconds_ = std::chrono::duration<double>(end - start).count();
  commit_seconds_ = std::chrono::duration<double>(end - commit).count();
  bytes_ = std::size_t(std::max(0LL, impl_->bytes.load() - before));
  if (rtcGetDeviceError(impl_->device) != RTC_ERROR_NONE) throw Error(kExitOutput, "embree: the build failed");
}

EmbreeScene::~EmbreeScene() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

void EmbreeScene::trace(const RaySet& rays, std::size_t first, std::size_t n, float* t_out) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  auto set_ray = [&](std::size_t i, RTCRay& ray) {
    const glm::vec3 o = rays.origins[i], d = rays.dirs[i];
    ray.org_x = o.x, ray.org_y = o.y, ray.org_z = o.z, ray.tnear = 0.0f;
    ray.dir_x = d.x, ray.dir_y = d.y, ray.dir_z = d.z, ray.time = 0.0f;
    ray.tfar = rays.bound(i), ray.mask = ~0u, ray.id = 0u, ray.flags = 0u;
  };
  if (rays.any_hit) {
    for (std::size_t i = first; i < first + n; i++) {
      RTCRay ray;
      set_ray(i, ray);
      rtcOccluded1(impl_->scene, &context, &ray);
      t_out[i] = ray.tfar < 0.0f ? rays.bound(i) : kMiss;  // -inf: blocked
    }
    return;
  }
  for (std::size_t i = first; i < first + n; i++) {
    RTCRayHit rh;
    set_ray(i, rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &rh);
    t_out[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? kMiss : rh.ray.tfar;
  }
}

#else  // no Embree: the section leaves its column empty

struct EmbreeScene::Impl {};

bool EmbreeScene::available() {
  return false;
}

std::string EmbreeScene::missing_reason() {
  return "Embree 3 was not found when pt_bench was built (Debian: libembree-dev)";
}

std::string EmbreeScene::version() {
  return "";
}

EmbreeScene::EmbreeScene(std::span<const Triangle>, unsigned) {
  throw Error(kExitOutput, missing_reason());
}

EmbreeScene::~EmbreeScene() = default;

void EmbreeScene::trace(const RaySet&, std::size_t, std::size_t, float*) const {}

#endif

}  // namespace pt::bench
