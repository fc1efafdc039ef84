#include <tressvk/host/plugin_host.hpp>

#include <algorithm>
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

engine::DeviceOptions with_plugin_requirements(engine::DeviceOptions options) {
  TvkDeviceRequirements req{};
  tressvk_get_device_requirements(&req);
  engine::DeviceRequirements& r = options.requirements;
  r.min_api_version = std::max(r.min_api_version, req.min_api_version);
  r.synchronization2 = r.synchronization2 || req.synchronization2;
  r.dynamic_rendering = r.dynamic_rendering || req.dynamic_rendering;
  for (uint32_t i = 0; i < req.extension_count; ++i)
    if (std::find(r.extensions.begin(), r.extensions.end(), req.extensions[i]) == r.extensions.end())
      r.extensions.emplace_back(req.extensions[i]);
  return options;
}

TvkContextCreateInfo context_info(const engine::Device& device) {
  TvkContextCreateInfo info{};
  info.struct_size = sizeof(TvkContextCreateInfo);
  info.api_version = device.api_version();
  info.instance = device.instance();
  info.physical_device = device.physical_device();
  info.device = device.device();
  info.queue_family_index = device.queue_family();
  info.get_instance_proc_addr = vkGetInstanceProcAddr;
  return info;
}

engine::DeviceOptions tool_device_options(const std::string& app_name, const std::string& device, bool validation,
                                          bool sync_validation) {
  engine::DeviceOptions options;
  options.app_name = app_name;
  options.device = device;
  options.validation = validation;
  options.sync_validation = sync_validation;
  return with_plugin_requirements(options);
}

TvkContext create_context(const engine::Device& device, uint32_t frames_in_flight, bool timestamps) {
  TvkContextCreateInfo info = context_info(device);
  info.frames_in_flight = frames_in_flight;
  info.enable_timestamps = timestamps ? VK_TRUE : VK_FALSE;
  TvkContext context = nullptr;
  check_tvk(tressvk_create_context(&info, &context), nullptr, "tressvk_create_context");
  return context;
}

TvkInstance create_instance(TvkContext context, TvkAsset asset, const TvkSimSettings& settings,
                            const TvkSimParams& params) {
  TvkInstanceCreateInfo ic{};
  ic.struct_size = sizeof(ic);
  ic.asset = asset;
  ic.settings = &settings;
  ic.params = &params;
  TvkInstance instance = nullptr;
  check_tvk(tressvk_create_instance(context, &ic, &instance), context, "tressvk_create_instance");
  return instance;
}

TvkAsset load_asset(const engine::Device& device, TvkContext context, std::span<const std::byte> asset_bytes) {
  TvkAsset asset = nullptr;
  device.run_commands([&](VkCommandBuffer cmd) {
    TvkAssetLoadInfo li{};
    li.struct_size = sizeof(li);
    li.data = asset_bytes.data();
    li.size = asset_bytes.size();
    li.upload_command_buffer = cmd;
    check_tvk(tressvk_load_asset(context, &li, &asset), context, "tressvk_load_asset");
  });
  return asset;
}

void check_tvk(TvkResult result, TvkContext context, const char* what) {
  if (result == TVK_SUCCESS) return;
  throw engine::Error(std::string(what) + " failed: " + tressvk_result_string(result) +
                      (context ? std::string(": ") + tressvk_last_error(context) : std::string()));
}

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
