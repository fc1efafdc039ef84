// Which simulation kernel the default path (TRESSVK_SIM_PATH unset) records for the follow-the-leader model
// (plugin/src/sim/fused.hpp): the run kernel up to 768 k guide vertices (runs of 4 up to 160 k), the one-thread kernel
// above; the crossovers measured on an NVIDIA H100 (fused.cpp).
#include <catch2/catch_test_macros.hpp>

#include "sim/fused.hpp"

using tressvk::sim::crowd_prefers_one_thread;
using tressvk::sim::lanes_fit_subgroup;
using tressvk::sim::run_length_for;
using tressvk::sim::runs_fit_subgroup;

TEST_CASE("the default path takes runs of 4, then of 8, then the one-thread kernel as grooms grow",
          "[plugin][simulation]") {
  CHECK(run_length_for(2221, 32, true) == 4);    // Ratboy: runs of 4 measured fastest
  CHECK(run_length_for(4096, 32, true) == 4);
  CHECK(run_length_for(8192, 32, true) == 8);    // runs of 8 fastest from 8,192 x 32 to 16,384 x 32
  CHECK(run_length_for(16384, 32, true) == 8);
  CHECK(run_length_for(32768, 32, true) == 0);   // 1 M guide vertices: the one-thread kernel
  CHECK(run_length_for(32768, 32, false) == 8);  // TRESSVK_SIM_PATH=runs: never falls back
  CHECK(run_length_for(65536, 8, true) == 8);    // the bounds count guide vertices
}

TEST_CASE("a crowd prefers the one-thread kernel where the measured crossovers put it ahead", "[plugin][simulation]") {
  constexpr uint64_t kRatboy = 2221 * 32;
  // From 4 instances and 400 k guide vertices, at every step rate (H100, us per frame: the one-thread kernel against
  // each instance's own runs).
  CHECK(crowd_prefers_one_thread(6, 6 * kRatboy, 4));          // 240 Hz: 313 against 395
  CHECK(crowd_prefers_one_thread(64, 64 * kRatboy, 4));        // 1,955 against 3,213
  CHECK(crowd_prefers_one_thread(4, 4 * 4096 * 32, 4));        // 318 against 416
  CHECK(crowd_prefers_one_thread(32, 32 * 512 * 32, 4));       // 298 against 415
  CHECK(crowd_prefers_one_thread(6, 6 * kRatboy, 2));          // 120 Hz: 193 against 229
  CHECK(crowd_prefers_one_thread(4, 4 * 4096 * 32, 2));        // 191 against 230
  CHECK(crowd_prefers_one_thread(6, 6 * kRatboy, 1));          // 60 Hz: 132 against 150
  CHECK(crowd_prefers_one_thread(32, 32 * 512 * 32, 1));       // 123 against 139
  CHECK_FALSE(crowd_prefers_one_thread(4, 4 * kRatboy, 4));    // 284 k: the runs, 280 against 288
  CHECK_FALSE(crowd_prefers_one_thread(4, 4 * kRatboy, 2));    // 165 against 171
  CHECK_FALSE(crowd_prefers_one_thread(4, 4 * kRatboy, 1));    // 112 against 118
  CHECK_FALSE(crowd_prefers_one_thread(8, 8 * 512 * 32, 4));   // 131 k: the runs, 134 against 204
  CHECK_FALSE(crowd_prefers_one_thread(2, 2 * 8192 * 32, 4));  // 2 instances: the runs, 329 against 345
  CHECK_FALSE(crowd_prefers_one_thread(1, 600 * 1024, 4));     // one groom: run_length_for decides
  CHECK_FALSE(crowd_prefers_one_thread(64, 64 * kRatboy, 0));  // no steps, nothing to run
}

TEST_CASE("a strand fits the subgroup when its lanes do", "[plugin][simulation]") {
  CHECK(runs_fit_subgroup(32, 8, 32, true));   // 4 lanes
  CHECK(runs_fit_subgroup(32, 4, 8, true));    // 8 lanes: lavapipe's subgroup
  CHECK_FALSE(runs_fit_subgroup(64, 4, 8, true));
  CHECK(runs_fit_subgroup(128, 4, 32, true));  // 32 lanes
  CHECK_FALSE(runs_fit_subgroup(32, 8, 32, false));  // no shuffles in compute shaders
  CHECK(lanes_fit_subgroup(32, 32, true));  // the compliant model's lane kernel: a lane per vertex
  CHECK_FALSE(lanes_fit_subgroup(33, 32, true));
  CHECK_FALSE(lanes_fit_subgroup(32, 8, true));
}

TEST_CASE("the conservative shape's subgroup variant packs as many strands as the device's limits allow",
          "[plugin][simulation]") {
  using tressvk::sim::conservative_slots;
  // 32 nodes of 148 bytes and 136 bytes of exchange and padding a strand of 32 vertices: 10 in NVIDIA's 48 KB (320
  // invocations).
  CHECK(conservative_slots(32, 32, 1024, 49152) == 10);
  // lavapipe (8-lane subgroups, 32 KB): 24 strands of 8 vertices; 44 of 4.
  CHECK(conservative_slots(8, 8, 1024, 32768) == 24);
  CHECK(conservative_slots(4, 8, 1024, 32768) == 44);
  // At most 384 invocations: 24 strands of 16 vertices with 64 KB.
  CHECK(conservative_slots(16, 32, 1024, 65536) == 24);
  // Whole subgroups: 16-vertex strands on 32-lane subgroups come in pairs (16 fit 42,000 bytes; 17 fit 44,000, 16
  // taken).
  CHECK(conservative_slots(16, 32, 1024, 42000) == 16);
  CHECK(conservative_slots(16, 32, 1024, 44000) == 16);
  // Vulkan's minimum limits (128 invocations, 16 KB): 3 strands of 32 vertices, or none where not one subgroup's fit.
  CHECK(conservative_slots(32, 32, 128, 16384) == 3);
  CHECK(conservative_slots(32, 32, 1024, 3000) == 0);
  CHECK(conservative_slots(8, 32, 1024, 4000) == 0);  // 2 strands fit, a subgroup holds 4
}

TEST_CASE("the one-thread kernel runs in workgroups of 512 from 64 Ki guides", "[plugin][simulation]") {
  using tressvk::sim::frame_dispatch_groups;
  using tressvk::sim::frame_pass_use;
  using tressvk::sim::frame_private_workgroup;
  tressvk::sim::SceneTerms terms;
  terms.vsp = true;
  terms.local_shape = true;
  // H100, 240 Hz, us per frame, workgroups of 32 against 512 (fused.cpp): 1 M guide vertices 612 against 639, so 32;
  // 2 M without VSP 1,175 against 891 (with every pass 902 / 901), 4 M 2,320 against 1,761 (1,775 / 1,786), so 512.
  const auto narrow = frame_pass_use(terms, false, 32768);
  CHECK(frame_private_workgroup(narrow) == 32);
  CHECK(frame_dispatch_groups(narrow, 32768) == 1024);
  CHECK(narrow.name.rfind("frame+", 0) == 0);
  const auto wide = frame_pass_use(terms, false, 65536);
  CHECK(frame_private_workgroup(wide) == 512);
  CHECK(frame_dispatch_groups(wide, 65536) == 128);
  CHECK(frame_dispatch_groups(wide, 65537) == 129);  // the last workgroup's threads past the last guide return
  CHECK(wide.name.rfind("frame(wide)+", 0) == 0);
  CHECK(wide.features != narrow.features);  // their own pipelines in the context's cache
  // A crowd's one-thread kernel (each instance its own dispatch of its own guides) stays narrow.
  CHECK(frame_private_workgroup(frame_pass_use(terms, false, 2221)) == 32);
}
