#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/generators/catch_generators.hpp>

#include <cstdint>
#include <numeric>
#include <vector>

using namespace tressvk;

TEST_CASE("buffers round-trip data in every memory usage", "[vulkan][engine]") {
  // device_local goes through staging copies (the path real GPUs take); upload/readback are mapped.
  const auto usage = GENERATE(engine::MemoryUsage::device_local, engine::MemoryUsage::upload,
                              engine::MemoryUsage::readback);
  std::vector<uint32_t> data(1024);
  std::iota(data.begin(), data.end(), 7u);
  engine::Buffer buffer = test::make_buffer(data, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, usage);
  REQUIRE(buffer.size() == data.size() * sizeof(uint32_t));
  CHECK((buffer.mapped() != nullptr) == (usage != engine::MemoryUsage::device_local));
  CHECK(test::read_buffer<uint32_t>(buffer) == data);

  // Partial write and read at an offset.
  const std::vector<uint32_t> patch{1, 2, 3};
  engine::write_buffer(test::device(), buffer, std::as_bytes(std::span<const uint32_t>(patch)), 16);
  const auto window = test::read_buffer<uint32_t>(buffer, 5, 12);
  CHECK(window == std::vector<uint32_t>{data[3], 1, 2, 3, data[7]});
}

TEST_CASE("buffer access outside the buffer is refused with a clear error", "[vulkan][engine]") {
  engine::Buffer buffer = test::make_buffer(64);
  std::vector<std::byte> big(65);
  CHECK_THROWS_AS(engine::write_buffer(test::device(), buffer, big), engine::Error);
  CHECK_THROWS_AS(engine::read_buffer(test::device(), buffer, std::span<std::byte>(big).first(8), 60),
                  engine::Error);
  CHECK_THROWS_AS(test::make_buffer(0), engine::Error);
}
