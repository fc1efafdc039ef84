#include "plugin_host.hpp"

#include <cstdio>
#include <string>

namespace tressvk::demo {

namespace {
void on_plugin_message(TvkMessageSeverity severity, const char* message, void* /*user_data*/) {
  const char* level = severity == TVK_MESSAGE_ERROR ? "error" : severity == TVK_MESSAGE_WARNING ? "warning" : "info";
  // Information goes to stdout with the demo's own progress lines; problems go to stderr.
  std::fprintf(severity == TVK_MESSAGE_INFO ? stdout : stderr, "tressvk %s: %s\n", level, message);
}
}  // namespace

PluginContext::PluginContext(engine::Device& device, uint32_t frames_in_flight) : device_(device) {
  if (TVK_CHECK_VERSION() != TVK_SUCCESS)
    throw engine::Error("libtressvk " + std::to_string(tressvk_version()) + " does not match the header " +
                        std::to_string(TVK_VERSION_NUM));
  TvkContextCreateInfo info = device.plugin_context_info();
  info.frames_in_flight = frames_in_flight;
  info.message_callback = on_plugin_message;
  const TvkResult r = tressvk_create_context(&info, &context_);
  if (r != TVK_SUCCESS)
    throw engine::Error(std::string("tressvk_create_context failed: ") + tressvk_result_string(r));
}

PluginContext::~PluginContext() {
  if (!context_) return;
  vkDeviceWaitIdle(device_.device());  // a destructor must not throw; a lost device is reported elsewhere
  tressvk_destroy_context(context_);
}

}  // namespace tressvk::demo
