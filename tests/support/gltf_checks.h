// Helpers of the glTF loader's tests (tests/common/scene/test_gltf_*.cpp): the fixtures of
// tests/data/gltf by name, checks of loaded points, triangles and materials, and the check
// that a malformed file fails with exit code 3 and a one-line message.
#pragma once

#include <catch2/catch.hpp>

#include <functional>
#include <initializer_list>
#include <string>

#include "common/base/error.h"
#include "common/scene/scene_loading.h"

namespace pt::test {

// A fixture of tests/data/gltf (PT_TEST_DATA_DIR: a compile definition of pt_tests). Built by
// append, not by operator+ on a temporary: GCC 12 warned a false -Warray-bounds there, in
// whichever unity batch the function happened to be inlined.
inline std::string fixture(const std::string& name) {
  std::string path = PT_TEST_DATA_DIR;
  path.append("/gltf/").append(name);
  return path;
}

inline pt::Scene load(const std::string& name) { return pt::load_gltf(fixture(name)); }

inline void check_point(glm::vec3 got, glm::vec3 want) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", " << want.y << ", "
               << want.z << ")");
  CHECK(got.x == Approx(want.x).margin(1e-5));
  CHECK(got.y == Approx(want.y).margin(1e-5));
  CHECK(got.z == Approx(want.z).margin(1e-5));
}

inline void check_triangle(const pt::Triangle& t, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  check_point(t.p0, a);
  check_point(t.p1, b);
  check_point(t.p2, c);
}

// The material of the triangle whose first vertex has this x (fixtures place one
// triangle per material along x).
inline const pt::Material& material_at(const pt::Scene& scene, float x) {
  for (const pt::Triangle& t : scene.triangles) {
    if (t.p0.x == x) return scene.materials.at(t.material);
  }
  FAIL("no triangle at x = " << x);
  throw 0;
}

// A reader's refusal: exit code 3 and one line that contains each word.
inline void require_refusal(const std::function<void()>& read, std::initializer_list<const char*> words) {
  int code = 0;
  std::string message;
  try {
    read();
  } catch (const pt::Error& e) {
    code = e.code();
    message = e.what();
  }
  INFO("message: " << message);
  REQUIRE(code == pt::kExitBadScene);
  CHECK(message.find('\n') == std::string::npos);
  for (const char* word : words) CHECK_THAT(message, Catch::Contains(word));
}

// The loader's failure on a fixture: the exit code and one-line message it carries.
inline void require_bad_scene(const std::string& path, std::initializer_list<const char*> words) {
  require_refusal([&] { pt::load_gltf(path); }, words);
}

}  // namespace pt::test
