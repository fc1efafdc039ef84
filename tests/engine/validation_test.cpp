// Proves that the shared fixture's validation is live: a deliberately missing barrier must be reported by
// synchronization validation, and an unexpected report must fail the running test.
//
// The hazard is transfer -> compute (vkCmdFillBuffer, then a dispatch writing the same buffer with no barrier):
// VVL 1.3.239 does not flag a missing compute -> compute barrier, and lavapipe executes serially, so the
// results would be right anyway; only the layer can catch it.
#include "double_pipeline.hpp"

#include <tressvk/engine/sync.hpp>
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>

using namespace tressvk;

namespace {

void fill_then_dispatch(bool with_barrier) {
  constexpr uint32_t kCount = 256;
  test::DoublePipeline doubler;
  engine::Buffer buffer = test::make_buffer(kCount * sizeof(float));
  const VkDescriptorSet set = doubler.set_for(buffer);
  test::run_commands([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 0);
    if (with_barrier)
      engine::cmd_buffer_barrier(cmd, buffer.handle(), engine::state::kTransferDst, engine::state::kComputeReadWrite);
    doubler.cmd_dispatch(cmd, set, kCount);
  });
}

}  // namespace

TEST_CASE("the correct transfer -> compute barrier gives no validation message", "[vulkan][engine]") {
  const uint64_t before = test::validation_message_count();
  fill_then_dispatch(true);
  CHECK(test::validation_message_count() == before);
}

TEST_CASE("synchronization validation reports a missing transfer -> compute barrier", "[vulkan][engine]") {
  auto expect = test::expect_validation_messages(1, "SYNC-HAZARD");
  fill_then_dispatch(false);
  CHECK(expect.count() >= 1);
}

// [!shouldfail]: Catch2 reports this test as passed only if it fails, which is what the fixture must make an
// unexpected validation message do.
TEST_CASE("an unexpected validation message fails the running test", "[vulkan][engine][!shouldfail]") {
  fill_then_dispatch(false);
}
