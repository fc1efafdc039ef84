// The shared Vulkan test fixture. Every Vulkan test of the project uses it:
//
//   #include <tressvk/test/vulkan.hpp>
//   TEST_CASE("my dispatch", "[vulkan]") {
//     auto& dev = tressvk::test::device();          // created on first use, once per process
//     auto buf = tressvk::test::make_buffer(std::vector<float>{1, 2, 3});
//     tressvk::test::run_commands([&](VkCommandBuffer cmd) { ... });
//     auto out = tressvk::test::read_buffer<float>(buf);
//   }
//
// - One engine::Device per test process, created lazily, with VK_LAYER_KHRONOS_validation AND synchronization
//   validation on. The device name is printed once per process. TRESSVK_DEVICE picks another device.
// - ANY validation message (warning or error) fails the running test case at the point it is reported, with
//   the message text. Messages outside a test case (device teardown) make the test process exit non-zero.
// - Negative tests wrap the wrong code in `auto expect = expect_validation_messages(1, "SYNC-HAZARD");`.
// - If the validation layer is not installed, device() throws a clear error (the test fails; CI installs it).
//
// What synchronization validation (VVL 1.3.239, the bookworm layer) can and cannot see, measured here:
// - It reports hazards between commands of ONE command buffer (e.g. vkCmdFillBuffer then a dispatch writing the
//   same buffer with no barrier: SYNC-HAZARD-WRITE-AFTER-WRITE at record time).
// - It does NOT report hazards between command buffers of different submissions (the same fill and copy split
//   over two submits, with or without a fence wait between them, gave no message), nor a missing
//   compute -> compute barrier. So a test that wants barriers checked across frames must record those frames
//   into one command buffer (one run_commands call).
#pragma once

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/engine/messenger.hpp>
#include <tressvk/host/plugin_host.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace tressvk::test {

// The process-wide test device (validation + synchronization validation on).
engine::Device& device();

// Records, submits and waits (engine::Device::run_commands on the test device).
void run_commands(const std::function<void(VkCommandBuffer)>& record);

// Buffers: device-local by default (host access goes through staging copies), with STORAGE usage unless told.
template <typename T>
engine::Buffer make_buffer(std::span<const T> data,
                           VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           engine::MemoryUsage memory = engine::MemoryUsage::device_local) {
  return engine::create_buffer_with_data(device(), data, usage, memory);
}
template <typename T>
engine::Buffer make_buffer(const std::vector<T>& data,
                           VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           engine::MemoryUsage memory = engine::MemoryUsage::device_local) {
  return make_buffer(std::span<const T>(data), usage, memory);
}
// An uninitialised buffer of `bytes`.
engine::Buffer make_buffer(VkDeviceSize bytes, VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           engine::MemoryUsage memory = engine::MemoryUsage::device_local);

// Reads `count` elements of T (all of the buffer when count is 0), after all earlier GPU work.
template <typename T>
std::vector<T> read_buffer(const engine::Buffer& buffer, size_t count = 0, VkDeviceSize offset = 0) {
  if (count == 0) count = static_cast<size_t>((buffer.size() - offset) / sizeof(T));
  return engine::read_buffer_as<T>(device(), buffer, count, offset);
}

// A TressVK context on the test device, created through the C API the way a host does. Plugin messages are
// printed; creation failure fails the test (REQUIRE) with tressvk_result_string and the plugin's message. The
// deleter waits for the device to be idle before tressvk_destroy_context, as the API requires.
struct PluginContextDeleter {
  void operator()(TvkContext context) const;
};
using PluginContext = std::unique_ptr<TvkContext_T, PluginContextDeleter>;
PluginContext create_plugin_context(uint32_t frames_in_flight = 2);

// Validation messages counted on the test device since it was created.
uint64_t validation_message_count();

// While alive, validation messages are expected instead of failing the test: each one is captured (and must
// contain `id_contains` in its message id or text, when that is not empty). On destruction the guard checks
// that at least `min_count` were captured, so a test that expects a hazard fails if the layer stays silent.
class ExpectedValidationMessages {
 public:
  ExpectedValidationMessages(uint64_t min_count, std::string id_contains);
  ~ExpectedValidationMessages();
  ExpectedValidationMessages(const ExpectedValidationMessages&) = delete;
  ExpectedValidationMessages& operator=(const ExpectedValidationMessages&) = delete;

  uint64_t count() const;
  std::vector<engine::ValidationMessage> messages() const;

 private:
  uint64_t min_count_;
  std::string id_contains_;
};

[[nodiscard]] inline ExpectedValidationMessages expect_validation_messages(uint64_t min_count,
                                                                           std::string id_contains = {}) {
  return ExpectedValidationMessages(min_count, std::move(id_contains));
}

// Real data (env TRESSVK_DATA_DIR, set by ctest). Returns the path of `relative` inside it, or SKIPs the
// running test with a message naming what is missing.
std::filesystem::path data_file(const std::filesystem::path& relative);

// A directory for test artefacts (PNG frames...), created on demand: $TRESSVK_TEST_OUTPUT or ./test-output.
std::filesystem::path output_dir();

}  // namespace tressvk::test
