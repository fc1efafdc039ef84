#include <tressvk/host/glue.hpp>

#include <algorithm>
#include <cstdio>
#include <string>

namespace tressvk::host {

namespace {
// The tools keep their output for results: the plugin's messages go to stderr only when TRESSVK_PIPELINE_STATS asks
// for its pipelines' statistics or TRESSVK_DEBUG_ALLOCATIONS for its buffers' places (which it sends as info messages).
void on_tool_message(TvkMessageSeverity severity, const char* message, void* /*user_data*/) {
  const char* level = severity == TVK_MESSAGE_ERROR ? "error" : severity == TVK_MESSAGE_WARNING ? "warning" : "info";
  std::fprintf(stderr, "tressvk %s: %s\n", level, message);
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
  // The plugin's info messages (pipeline statistics, TRESSVK_DEBUG_ALLOCATIONS) only where asked for: the tools'
  // output stays their tables.
  if (engine::pipeline_stats_requested() || engine::env_flag("TRESSVK_DEBUG_ALLOCATIONS"))
    info.message_callback = on_tool_message;
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

TvkResult record_simulate(TvkContext context, VkCommandBuffer cmd, std::span<const TvkInstance> instances) {
  TvkSimulateInfo si{};
  si.struct_size = sizeof(si);
  si.instance_count = static_cast<uint32_t>(instances.size());
  si.instances = instances.data();
  return tressvk_cmd_simulate(context, cmd, &si);
}

TvkResult record_load_asset(TvkContext context, VkCommandBuffer cmd, std::span<const std::byte> asset_bytes,
                            TvkAsset* asset) {
  TvkAssetLoadInfo li{};
  li.struct_size = sizeof(li);
  li.data = asset_bytes.data();
  li.size = asset_bytes.size();
  li.upload_command_buffer = cmd;
  return tressvk_load_asset(context, &li, asset);
}

TvkAsset load_asset(const engine::Device& device, TvkContext context, std::span<const std::byte> asset_bytes) {
  TvkAsset asset = nullptr;
  device.run_commands([&](VkCommandBuffer cmd) {
    check_tvk(record_load_asset(context, cmd, asset_bytes, &asset), context, "tressvk_load_asset");
  });
  return asset;
}

void check_tvk(TvkResult result, TvkContext context, const char* what) {
  if (result == TVK_SUCCESS) return;
  throw engine::Error(std::string(what) + " failed: " + tressvk_result_string(result) +
                      (context ? std::string(": ") + tressvk_last_error(context) : std::string()));
}

}  // namespace tressvk::host
