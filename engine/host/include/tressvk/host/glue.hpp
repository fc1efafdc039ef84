// The host glue: what every program here (demo, bench, viewer, tests, fuzz harness) does to put TressVK on the
// engine's device: merge the plugin's device requirements, make the context, upload an asset, create an instance.
// The engine core itself never includes the plugin; tressvk::host is where they meet.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/tressvk.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace tressvk::host {

// The options with the plugin's device requirements (tressvk_get_device_requirements) merged in: the least API
// version, features and extensions that engine::Device enables at vkCreateDevice, as any host engine must.
engine::DeviceOptions with_plugin_requirements(engine::DeviceOptions options);

// A TvkContextCreateInfo for the engine's device (the caller adds callbacks and options).
TvkContextCreateInfo context_info(const engine::Device& device);

// The DeviceOptions of a headless tool (bench, soak): the named device (empty: automatic), validation and
// synchronization validation as asked, the plugin's requirements merged.
engine::DeviceOptions tool_device_options(const std::string& app_name, const std::string& device, bool validation,
                                          bool sync_validation);

// A context on the engine's device without callbacks; throws engine::Error naming the failure.
TvkContext create_context(const engine::Device& device, uint32_t frames_in_flight, bool timestamps = false);

// An instance of `asset` with these settings and `params` for every strand group; throws engine::Error.
TvkInstance create_instance(TvkContext context, TvkAsset asset, const TvkSimSettings& settings,
                            const TvkSimParams& params);

// Throws engine::Error with the plugin's message when a TressVK call fails.
void check_tvk(TvkResult result, TvkContext context, const char* what);

// Records tressvk_cmd_simulate of `instances` (one TvkSimulateInfo) into `cmd` and returns the plugin's result.
TvkResult record_simulate(TvkContext context, VkCommandBuffer cmd, std::span<const TvkInstance> instances);
inline TvkResult record_simulate(TvkContext context, VkCommandBuffer cmd, TvkInstance instance) {
  return record_simulate(context, cmd, std::span<const TvkInstance>(&instance, 1));
}

// tressvk_load_asset of an in-memory .tvkhair image, its upload recorded into `cmd`; returns the plugin's result.
TvkResult record_load_asset(TvkContext context, VkCommandBuffer cmd, std::span<const std::byte> asset_bytes,
                            TvkAsset* asset);

// Loads a .tvkhair image through the plugin, its upload recorded into a one-time submission on the engine's queue
// (a streaming engine would put it into the first frame that uses the asset). Throws engine::Error on failure.
TvkAsset load_asset(const engine::Device& device, TvkContext context, std::span<const std::byte> asset_bytes);

}  // namespace tressvk::host
