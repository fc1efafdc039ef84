// Which simulation kernel the default path (TRESSVK_SIM_PATH unset) records for the follow-the-leader model
// (plugin/src/sim/fused.hpp): the lane kernel for small grooms whose strands fit the subgroup, the one-thread kernel
// otherwise (the H100 crossover in fused.cpp).
#include <catch2/catch_test_macros.hpp>

#include "sim/fused.hpp"

using tressvk::sim::ftl_lanes_by_default;
using tressvk::sim::lanes_fit_subgroup;

TEST_CASE("the default path takes the lane kernel for small grooms only", "[plugin][simulation]") {
  // Ratboy (2,221 guides x 32) and a 1,024-guide groom measured faster on lanes; 4,096 guides and up slower.
  CHECK(ftl_lanes_by_default(2221, 32, true, false));
  CHECK(ftl_lanes_by_default(1024, 32, true, false));
  CHECK_FALSE(ftl_lanes_by_default(4096, 32, true, false));
  CHECK_FALSE(ftl_lanes_by_default(32768, 32, true, false));
  // The bound counts lanes: shorter strands take fewer lanes each.
  CHECK(ftl_lanes_by_default(4096, 16, true, false));
  CHECK(ftl_lanes_by_default(10240, 8, true, false));
  // Never where the strand does not fit the subgroup or a strand is pinned at its tip (the Thomas solve is serial).
  CHECK_FALSE(ftl_lanes_by_default(64, 32, false, false));
  CHECK_FALSE(ftl_lanes_by_default(64, 32, true, true));
}

TEST_CASE("a strand fits the subgroup when the power of two at or above N does", "[plugin][simulation]") {
  CHECK(lanes_fit_subgroup(32, 32, true));
  CHECK(lanes_fit_subgroup(17, 32, true));
  CHECK_FALSE(lanes_fit_subgroup(33, 32, true));
  CHECK(lanes_fit_subgroup(8, 8, true));  // lavapipe's subgroup
  CHECK_FALSE(lanes_fit_subgroup(32, 8, true));
  CHECK_FALSE(lanes_fit_subgroup(8, 32, false));  // no shuffles in compute shaders
}
