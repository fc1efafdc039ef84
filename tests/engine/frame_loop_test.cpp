#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/engine/sync.hpp>
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/generators/catch_generators.hpp>

#include <cstring>
#include <vector>

using namespace tressvk;

TEST_CASE("the frame loop reports every frame once, in order, with its own slot's results", "[vulkan][engine]") {
  const uint32_t in_flight = GENERATE(1u, 2u, 3u);
  constexpr uint32_t kFrames = 7;
  constexpr uint32_t kWords = 64;
  engine::Device& dev = test::device();
  // One host-visible buffer per slot; frame n fills its slot's buffer with n.
  std::vector<engine::Buffer> per_slot;
  for (uint32_t i = 0; i < in_flight; ++i)
    per_slot.push_back(test::make_buffer(kWords * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                         engine::MemoryUsage::readback));
  std::vector<uint64_t> completed;
  bool contents_ok = true;
  {
    engine::FrameLoop loop(dev, in_flight, 2, [&](const engine::FrameLoop::Frame& frame) {
      completed.push_back(frame.number);
      const engine::Buffer& buffer = per_slot[frame.slot];
      vmaInvalidateAllocation(buffer.allocator(), buffer.allocation(), 0, VK_WHOLE_SIZE);
      std::vector<uint32_t> words(kWords);
      std::memcpy(words.data(), buffer.mapped(), kWords * sizeof(uint32_t));
      for (uint32_t w : words) contents_ok = contents_ok && w == frame.number;
      if (dev.timestamps_supported()) contents_ok = contents_ok && frame.timestamps->elapsed_ms(0, 1).has_value();
    });
    REQUIRE(loop.frames_in_flight() == in_flight);
    for (uint32_t f = 0; f < kFrames; ++f) {
      const engine::FrameLoop::Frame& frame = loop.begin();
      CHECK(frame.number == f);
      CHECK(frame.slot == f % in_flight);
      frame.timestamps->cmd_write(frame.cmd, 0, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
      // The previous user of this slot's buffer was the host (already waited for); order after it anyway
      // against earlier transfers, as a real frame would.
      engine::cmd_buffer_barrier(frame.cmd, per_slot[frame.slot].handle(), engine::state::kHostRead,
                                 engine::state::kTransferDst);
      vkCmdFillBuffer(frame.cmd, per_slot[frame.slot].handle(), 0, VK_WHOLE_SIZE, f);
      engine::cmd_buffer_barrier(frame.cmd, per_slot[frame.slot].handle(), engine::state::kTransferDst,
                                 engine::state::kHostRead);
      frame.timestamps->cmd_write(frame.cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      loop.end();
    }
    loop.finish();
  }
  CHECK(completed == std::vector<uint64_t>{0, 1, 2, 3, 4, 5, 6});
  CHECK(contents_ok);
}

TEST_CASE("the frame loop refuses begin/end out of order", "[vulkan][engine]") {
  engine::FrameLoop loop(test::device(), 2, 0, nullptr);
  CHECK_THROWS_AS(loop.end(), engine::Error);
  loop.begin();
  CHECK_THROWS_AS(loop.begin(), engine::Error);
  CHECK_THROWS_AS(loop.finish(), engine::Error);
  loop.end();
  loop.finish();
}
