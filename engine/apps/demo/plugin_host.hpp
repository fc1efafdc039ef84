// The demo's side of the plugin integration: the TressVK context made on the engine's device.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/tressvk.h>

namespace tressvk::demo {

// Owns a TvkContext. Construction checks the header/library version and creates the context on the engine's
// device (which merged tressvk_get_device_requirements() into vkCreateDevice); destruction waits for the device
// to be idle first, as tressvk_destroy_context requires.
class PluginContext {
 public:
  PluginContext(engine::Device& device, uint32_t frames_in_flight);
  ~PluginContext();
  PluginContext(const PluginContext&) = delete;
  PluginContext& operator=(const PluginContext&) = delete;

  TvkContext get() const { return context_; }

 private:
  engine::Device& device_;
  TvkContext context_ = nullptr;
};

}  // namespace tressvk::demo
