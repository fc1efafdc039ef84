// The integration the demo performs, on the validated test device: requirements merged at device creation,
// then a TressVK context created and destroyed through the C API without a validation message.
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>

using namespace tressvk;

TEST_CASE("a TressVK context is created and destroyed on the engine's device", "[vulkan][engine]") {
  TvkDeviceRequirements req{};
  tressvk_get_device_requirements(&req);
  engine::Device& dev = test::device();
  CHECK(dev.api_version() >= req.min_api_version);

  test::PluginContext context = test::create_plugin_context();
  TvkMemoryUsage usage{};
  CHECK(tressvk_get_memory_usage(context.get(), &usage) == TVK_SUCCESS);
  CHECK(std::string(tressvk_last_error(context.get())).empty());
  context.reset();
  CHECK(test::validation_message_count() == 0);
}

TEST_CASE("the plugin refuses a create-info without a device", "[vulkan][engine]") {
  TvkContextCreateInfo info = host::context_info(test::device());
  info.device = VK_NULL_HANDLE;
  TvkContext context = nullptr;
  CHECK(tressvk_create_context(&info, &context) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(context == nullptr);
}
