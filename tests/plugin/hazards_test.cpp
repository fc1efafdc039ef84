// The barrier derivation between simulation passes (plugin/src/core/hazards.hpp), on the real pass table.
#include "core/hazards.hpp"
#include "sim/passes.hpp"

#include <catch2/catch_test_macros.hpp>

using tressvk::HazardTracker;
using namespace tressvk::sim;

namespace {
constexpr uint32_t bit(uint32_t b) { return 1u << b; }
}

TEST_CASE("read-after-write needs a memory barrier on exactly the written buffer", "[plugin][barriers]") {
  HazardTracker t;
  t.pass_recorded(bit(kBindingRestPositions), bit(kBindingPositions));
  const auto need = t.before(bit(kBindingPositions) | bit(kBindingRestInfo), bit(kBindingTangents));
  CHECK(need.memory == bit(kBindingPositions));
  CHECK(need.execution == 0);
}

TEST_CASE("write-after-read needs only an execution dependency", "[plugin][barriers]") {
  HazardTracker t;
  t.pass_recorded(bit(kBindingPrevPositions), bit(kBindingPositions));
  const auto need = t.before(0, bit(kBindingPrevPositions));
  CHECK(need.memory == 0);
  CHECK(need.execution == bit(kBindingPrevPositions));
}

TEST_CASE("a barrier on one buffer leaves another buffer's write pending", "[plugin][barriers]") {
  HazardTracker t;
  t.pass_recorded(0, bit(kBindingPositions) | bit(kBindingTangents));
  auto need = t.before(bit(kBindingPositions), 0);
  REQUIRE(need.memory == bit(kBindingPositions));
  t.barrier_recorded(need);
  t.pass_recorded(bit(kBindingPositions), 0);
  need = t.before(bit(kBindingTangents), 0);
  CHECK(need.memory == bit(kBindingTangents));
}

TEST_CASE("independent passes need no barrier", "[plugin][barriers]") {
  HazardTracker t;
  t.pass_recorded(bit(kBindingRestPositions), bit(kBindingPositions));
  CHECK_FALSE(t.before(bit(kBindingRestInfo), bit(kBindingCounters)).any());
}

TEST_CASE("every consecutive pair of simulation passes is ordered where the table says they touch", "[plugin][barriers]") {
  // Walk the recording order of a full frame (two substeps and the follow pass) and check that each pass that
  // touches a buffer written earlier gets a barrier naming it.
  const auto table = pass_table();
  HazardTracker t;
  uint32_t barriers = 0;
  for (int step = 0; step < 2; ++step) {
    for (const PassInfo& p : table) {
      if (p.frequency != Frequency::kPerSubstep) continue;
      const auto need = t.before(p.reads, p.writes);
      CHECK((need.memory & (p.reads | p.writes)) == need.memory);
      if (need.any()) ++barriers;
      t.barrier_recorded(need);
      CHECK((t.pending_writes & (p.reads | p.writes)) == 0);
      t.pass_recorded(p.reads, p.writes);
    }
  }
  const PassInfo& follow = pass_info(PassId::kFollow);
  const auto need = t.before(follow.reads, follow.writes);
  CHECK((need.memory & bit(kBindingPositions)) != 0);  // follows read the guides the length pass wrote
  CHECK(barriers >= 7);  // every per-substep pass after the first depends on its predecessor
}
