// The allocator of the large arrays (common/base/huge_pages.h; issue 50): storage of 2 MiB or
// more starts on a 2 MiB boundary (where a huge page can back it), smaller storage is plain,
// and a HugeVector keeps its values through growth, copies and moves like any std::vector.
// Whether Linux then backs it with huge pages is its choice: docs/acceleration.md, round eight.
// Not part of the article: the machinery of the stage programs.
#include <catch2/catch.hpp>

#include <cstdint>
#include <utility>

#include "common/base/huge_pages.h"

TEST_CASE("huge pages: 2 MiB or more starts on a 2 MiB boundary, less is plain", "[memory]") {
  pt::HugeVector<float> big(pt::kHugePage / sizeof(float));
  CHECK(reinterpret_cast<std::uintptr_t>(big.data()) % pt::kHugePage == 0u);
  pt::HugeVector<float> small(1000);
  CHECK(reinterpret_cast<std::uintptr_t>(small.data()) % alignof(float) == 0u);
  struct alignas(64) Line {
    float v[16];
  };
  pt::HugeVector<Line> lines(3);  // an over-aligned type below 2 MiB keeps its alignment
  CHECK(reinterpret_cast<std::uintptr_t>(lines.data()) % 64u == 0u);
}

TEST_CASE("huge pages: a HugeVector keeps its values through growth, copies and moves", "[memory]") {
  pt::HugeVector<std::uint32_t> v;
  const std::uint32_t n = 3u * std::uint32_t(pt::kHugePage / sizeof(std::uint32_t)) + 7u;
  for (std::uint32_t i = 0; i < n; i++) v.push_back(i * 2654435761u);  // grows from plain storage to huge
  pt::HugeVector<std::uint32_t> copy = v;
  pt::HugeVector<std::uint32_t> moved = std::move(copy);
  REQUIRE(moved.size() == n);
  bool same = true;
  for (std::uint32_t i = 0; i < n; i++) same = same && moved[i] == i * 2654435761u && v[i] == moved[i];
  CHECK(same);
  CHECK(reinterpret_cast<std::uintptr_t>(moved.data()) % pt::kHugePage == 0u);
  moved.resize(10);
  moved.shrink_to_fit();  // back to plain storage, freed by the matching call
  CHECK(moved[9] == 9u * 2654435761u);
}
