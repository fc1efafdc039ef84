// The demo's side of the plugin integration: the TressVK context made on the engine's device, and one hair
// instance (asset, instance, renderer) with the calls a host makes each frame. The free functions they use, shared
// with the bench and the tests, are in glue.hpp.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/host/glue.hpp>
#include <tressvk/tressvk.h>

#include <cstddef>
#include <span>
#include <vector>

namespace tressvk::host {

// Owns a TvkContext. Construction checks the header/library version and creates the context on the engine's
// device (which merged tressvk_get_device_requirements() into vkCreateDevice); destruction waits for the device
// to be idle first, as tressvk_destroy_context requires.
class PluginContext {
 public:
  PluginContext(engine::Device& device, uint32_t frames_in_flight, bool timestamps = false);
  ~PluginContext();
  PluginContext(const PluginContext&) = delete;
  PluginContext& operator=(const PluginContext&) = delete;

  TvkContext get() const { return context_; }

 private:
  engine::Device& device_;
  TvkContext context_ = nullptr;
};

// One head of hair: the asset (uploaded with a one-time submission), an instance of it, and a renderer for the
// host's shading target (dynamic rendering formats, or a VkRenderPass) and its shadow map. Destroyed in reverse
// order after the device is idle.
class HairHost {
 public:
  HairHost(engine::Device& device, TvkContext context, std::span<const std::byte> asset_bytes,
           const TvkRendererCreateInfo& renderer_info);
  ~HairHost();
  HairHost(const HairHost&) = delete;
  HairHost& operator=(const HairHost&) = delete;

  TvkAsset asset() const { return asset_; }
  TvkInstance instance() const { return instance_; }
  TvkRenderer renderer() const { return renderer_; }
  const TvkAssetInfo& info() const { return info_; }

 private:
  void release();
  engine::Device& device_;
  TvkContext context_;
  TvkAsset asset_ = nullptr;
  TvkInstance instance_ = nullptr;
  TvkRenderer renderer_ = nullptr;
  TvkAssetInfo info_{};
};

}  // namespace tressvk::host
