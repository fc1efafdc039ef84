// CPU-side helpers of the engine: no Vulkan device needed.
#include <tressvk/engine/device_select.hpp>
#include <tressvk/engine/image.hpp>
#include <tressvk/engine/messenger.hpp>
#include <tressvk/engine/pipeline.hpp>
#include <tressvk/engine/timestamps.hpp>

#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>

#include <vector>

using namespace tressvk::engine;

namespace {
const std::vector<DeviceCandidate> kDevices = {
    {"llvmpipe (LLVM 15.0.6, 256 bits)", VK_PHYSICAL_DEVICE_TYPE_CPU, VK_API_VERSION_1_3},
    {"Intel(R) UHD Graphics 620", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, VK_API_VERSION_1_3},
    {"NVIDIA H100 80GB HBM3", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_API_VERSION_1_3},
    {"Old GPU", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_API_VERSION_1_1},
};
}  // namespace

TEST_CASE("automatic device choice prefers discrete, then integrated, virtual, CPU", "[engine]") {
  CHECK(choose_device(kDevices, "", VK_API_VERSION_1_3).index == 2u);
  const std::vector<DeviceCandidate> no_discrete(kDevices.begin(), kDevices.begin() + 2);
  CHECK(choose_device(no_discrete, "", VK_API_VERSION_1_3).index == 1u);
  const std::vector<DeviceCandidate> cpu_only(kDevices.begin(), kDevices.begin() + 1);
  CHECK(choose_device(cpu_only, "", VK_API_VERSION_1_3).index == 0u);
  CHECK(device_type_rank(VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU) < device_type_rank(VK_PHYSICAL_DEVICE_TYPE_CPU));
}

TEST_CASE("automatic device choice skips devices below the required Vulkan version", "[engine]") {
  const std::vector<DeviceCandidate> devices = {kDevices[3], kDevices[0]};
  CHECK(choose_device(devices, "", VK_API_VERSION_1_3).index == 1u);
  const std::vector<DeviceCandidate> only_old = {kDevices[3]};
  const DeviceChoice none = choose_device(only_old, "", VK_API_VERSION_1_3);
  CHECK_FALSE(none.index);
  CHECK(none.error.find("Old GPU") != std::string::npos);
}

TEST_CASE("devices can be chosen by index or by case-insensitive name substring", "[engine]") {
  CHECK(choose_device(kDevices, "0", VK_API_VERSION_1_3).index == 0u);
  CHECK(choose_device(kDevices, "LLVMpipe", VK_API_VERSION_1_3).index == 0u);
  CHECK(choose_device(kDevices, "h100", VK_API_VERSION_1_3).index == 2u);

  const DeviceChoice out_of_range = choose_device(kDevices, "7", VK_API_VERSION_1_3);
  CHECK_FALSE(out_of_range.index);
  CHECK(out_of_range.error.find("out of range") != std::string::npos);
  const DeviceChoice unknown = choose_device(kDevices, "radeon", VK_API_VERSION_1_3);
  CHECK_FALSE(unknown.index);
  CHECK(unknown.error.find("radeon") != std::string::npos);
  // An explicitly chosen device that is too old is an error naming it, not a silent fallback.
  const DeviceChoice old = choose_device(kDevices, "3", VK_API_VERSION_1_3);
  CHECK_FALSE(old.index);
  CHECK(old.error.find("Old GPU") != std::string::npos);
  CHECK_FALSE(choose_device({}, "", VK_API_VERSION_1_3).index);
}

TEST_CASE("timestamp deltas honour the period and wrap at the valid bits", "[engine]") {
  CHECK(timestamp_delta_ms(1000, 3'001'000, 1.0, 64) == Catch::Approx(3.0));
  CHECK(timestamp_delta_ms(0, 1000, 83.333, 64) == Catch::Approx(0.083333));
  // A 36-bit counter that wrapped: from 2^36 - 10 to 5 is 15 ticks.
  const uint64_t top = (uint64_t{1} << 36) - 10;
  CHECK(timestamp_delta_ms(top, 5, 1e6, 36) == Catch::Approx(15.0));
}

TEST_CASE("warnings and errors count as validation messages, except the loader's own", "[engine]") {
  constexpr auto kValidation = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  constexpr auto kGeneral = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
  CHECK(counts_as_validation(VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT, kValidation, "VUID-x"));
  CHECK(counts_as_validation(VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT, kValidation, nullptr));
  CHECK(counts_as_validation(VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT,
                             VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT, "UNASSIGNED-perf"));
  // A GENERAL warning from the layer (settings, for example) counts; the loader's does not.
  CHECK(counts_as_validation(VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT, kGeneral, "UNASSIGNED-settings"));
  CHECK_FALSE(counts_as_validation(VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT, kGeneral, "Loader Message"));
  CHECK_FALSE(counts_as_validation(VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT, kValidation, "VUID-x"));
}

TEST_CASE("the message log counts, keeps and hands messages to its hook", "[engine]") {
  MessageLog log;
  log.set_print(false);
  std::vector<std::string> seen;
  log.set_hook([&](const ValidationMessage& m) {
    seen.push_back(m.id_name);
    return true;
  });
  VkDebugUtilsMessengerCallbackDataEXT data{};
  data.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CALLBACK_DATA_EXT;
  data.pMessageIdName = "SYNC-HAZARD-WRITE-AFTER-WRITE";
  data.pMessage = "vkCmdDispatch: hazard";
  log.receive(VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT, VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT, &data);
  data.pMessageIdName = "Loader Message";
  log.receive(VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT, VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT, &data);
  data.pMessageIdName = "UNASSIGNED-BestPractices";
  log.receive(VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT, VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
              &data);
  CHECK(log.count() == 2);
  CHECK(log.error_count() == 1);
  REQUIRE(log.messages().size() == 2);
  CHECK(seen == std::vector<std::string>{"SYNC-HAZARD-WRITE-AFTER-WRITE", "UNASSIGNED-BestPractices"});
  const std::string text = format_message(log.messages()[0]);
  CHECK(text == "[validation error] SYNC-HAZARD-WRITE-AFTER-WRITE: vkCmdDispatch: hazard");
}

TEST_CASE("format and dispatch-size helpers", "[engine]") {
  CHECK(is_depth_format(VK_FORMAT_D32_SFLOAT));
  CHECK_FALSE(is_depth_format(VK_FORMAT_R8G8B8A8_SRGB));
  CHECK(format_texel_size(VK_FORMAT_R8G8B8A8_UNORM) == 4);
  CHECK(format_texel_size(VK_FORMAT_R32G32B32A32_SFLOAT) == 16);
  CHECK(format_texel_size(VK_FORMAT_BC1_RGB_UNORM_BLOCK) == 0);
  CHECK(group_count(1000, 64) == 16);
  CHECK(group_count(1024, 64) == 16);
  CHECK(group_count(0, 64) == 0);
}
