#include <tressvk/host/plugin_host.hpp>

#include <cstdio>
#include <string>

namespace tressvk::host {

namespace {
void on_plugin_message(TvkMessageSeverity severity, const char* message, void* /*user_data*/) {
  const char* level = severity == TVK_MESSAGE_ERROR ? "error" : severity == TVK_MESSAGE_WARNING ? "warning" : "info";
  // Information goes to stdout with the demo's own progress lines; problems go to stderr.
  std::fprintf(severity == TVK_MESSAGE_INFO ? stdout : stderr, "tressvk %s: %s\n", level, message);
}
}  // namespace

PluginContext::PluginContext(engine::Device& device, uint32_t frames_in_flight, bool timestamps) : device_(device) {
  if (TVK_CHECK_VERSION() != TVK_SUCCESS)
    throw engine::Error("libtressvk " + std::to_string(tressvk_version()) + " does not match the header " +
                        std::to_string(TVK_VERSION_NUM));
  TvkContextCreateInfo info = context_info(device);
  info.frames_in_flight = frames_in_flight;
  info.message_callback = on_plugin_message;
  info.enable_timestamps = timestamps ? VK_TRUE : VK_FALSE;
  const TvkResult r = tressvk_create_context(&info, &context_);
  if (r != TVK_SUCCESS)
    throw engine::Error(std::string("tressvk_create_context failed: ") + tressvk_result_string(r));
}

PluginContext::~PluginContext() {
  if (!context_) return;
  vkDeviceWaitIdle(device_.device());  // a destructor must not throw; a lost device is reported elsewhere
  tressvk_destroy_context(context_);
}

HairHost::HairHost(engine::Device& device, TvkContext context, std::span<const std::byte> asset_bytes,
                   const TvkRendererCreateInfo& renderer_info)
    : device_(device), context_(context) {
  try {
    asset_ = load_asset(device, context, asset_bytes);
    check_tvk(tressvk_get_asset_info(asset_, &info_), context, "tressvk_get_asset_info");
    TvkInstanceCreateInfo ic{};
    ic.struct_size = sizeof(ic);
    ic.asset = asset_;
    check_tvk(tressvk_create_instance(context, &ic, &instance_), context, "tressvk_create_instance");
    check_tvk(tressvk_create_renderer(context, &renderer_info, &renderer_), context, "tressvk_create_renderer");
  } catch (...) {
    release();
    throw;
  }
}

HairHost::~HairHost() { release(); }

void HairHost::release() {
  vkDeviceWaitIdle(device_.device());  // the GPU may still use them (destruction needs an idle device)
  if (renderer_) tressvk_destroy_renderer(renderer_);
  if (instance_) tressvk_destroy_instance(instance_);
  if (asset_) tressvk_destroy_asset(asset_);
  renderer_ = nullptr;
  instance_ = nullptr;
  asset_ = nullptr;
}

}  // namespace tressvk::host
