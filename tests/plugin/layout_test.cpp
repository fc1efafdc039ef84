// The GPU layout's single definitions agree with the public header: the strand block and the vertex index a host
// computes from tressvk.h are the ones the shaders and the plugin use (tressvk/model/gpu_layout.h).
#include <tressvk/model/gpu_layout.hpp>
#include <tressvk/tressvk.h>

#include <catch2/catch_test_macros.hpp>

#include <vector>

static_assert(TVK_BLOCK == TVK_STRAND_BLOCK);
static_assert(tressvk::sim::kStrandBlock == TVK_STRAND_BLOCK);
static_assert(tressvk::sim::kBindingCount == TVK_BINDING_COUNT && TVK_BINDING_ANCHORS + 1 == TVK_BINDING_COUNT);

TEST_CASE("tvk_vertex_index (tressvk.h) is the layout's vertex index", "[plugin][layout]") {
  uint64_t checked = 0;
  for (uint64_t n : {4u, 31u, 32u, 128u})
    for (uint64_t s = 0; s < 3 * TVK_STRAND_BLOCK + 5; ++s)
      for (uint64_t v = 0; v < n; ++v) {
        REQUIRE(tvk_vertex_index(s, v, n) == tressvk::sim::vertex_index(s, v, n));
        ++checked;
      }
  CHECK(checked > 0);
  // Every element of a padded buffer is hit exactly once.
  const uint64_t n = 5, strands = 2 * TVK_STRAND_BLOCK;
  std::vector<int> hits(tressvk::sim::padded_strands(strands) * n, 0);
  for (uint64_t s = 0; s < strands; ++s)
    for (uint64_t v = 0; v < n; ++v) ++hits[tvk_vertex_index(s, v, n)];
  for (int h : hits) CHECK(h == 1);
}
