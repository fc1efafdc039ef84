#include "double_pipeline.hpp"

#include <tressvk/engine/sync.hpp>
#include <tressvk/engine/timestamps.hpp>
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <vector>

using namespace tressvk;

TEST_CASE("a compute dispatch doubles a buffer", "[vulkan][engine]") {
  // 1000 is not a multiple of the workgroup size, so the bounds check in the shader is exercised too; the
  // element just past the end must be left alone.
  constexpr uint32_t kCount = 1000;
  std::vector<float> input(kCount + 1);
  for (uint32_t i = 0; i < input.size(); ++i) input[i] = 0.5f * static_cast<float>(i) - 100.0f;

  test::DoublePipeline doubler;
  engine::Buffer buffer = test::make_buffer(input);
  const VkDescriptorSet set = doubler.set_for(buffer);
  test::run_commands([&](VkCommandBuffer cmd) { doubler.cmd_dispatch(cmd, set, kCount); });

  const std::vector<float> output = test::read_buffer<float>(buffer);
  REQUIRE(output.size() == input.size());
  // Doubling a float is exact (no rounding), so exact equality is the right check.
  for (uint32_t i = 0; i < kCount; ++i) {
    INFO("element " << i);
    REQUIRE(output[i] == 2.0f * input[i]);
  }
  CHECK(output[kCount] == input[kCount]);
}

TEST_CASE("dependent dispatches with a barrier between them double twice", "[vulkan][engine]") {
  constexpr uint32_t kCount = 256;
  std::vector<float> input(kCount, 3.0f);
  test::DoublePipeline doubler;
  engine::Buffer buffer = test::make_buffer(input);
  const VkDescriptorSet set = doubler.set_for(buffer);
  test::run_commands([&](VkCommandBuffer cmd) {
    doubler.cmd_dispatch(cmd, set, kCount);
    engine::cmd_buffer_barrier(cmd, buffer.handle(), engine::state::kComputeReadWrite,
                               engine::state::kComputeReadWrite);
    doubler.cmd_dispatch(cmd, set, kCount);
  });
  for (float v : test::read_buffer<float>(buffer)) REQUIRE(v == 12.0f);
}

TEST_CASE("timestamps around a dispatch give a finite, non-negative duration", "[vulkan][engine]") {
  engine::Device& dev = test::device();
  if (!dev.timestamps_supported()) SKIP("the queue of '" << dev.name() << "' has no timestamps");
  test::DoublePipeline doubler;
  engine::Buffer buffer = test::make_buffer(std::vector<float>(4096, 1.0f));
  const VkDescriptorSet set = doubler.set_for(buffer);
  engine::TimestampQueries queries(dev, 2);
  REQUIRE(queries.supported());
  test::run_commands([&](VkCommandBuffer cmd) {
    queries.cmd_reset(cmd);
    queries.cmd_write(cmd, 0, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
    doubler.cmd_dispatch(cmd, set, 4096);
    queries.cmd_write(cmd, 1, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  });
  const auto ms = queries.elapsed_ms(0, 1);
  REQUIRE(ms.has_value());
  CHECK(std::isfinite(*ms));
  CHECK(*ms >= 0.0);
}
