// tressvk-demo: the host engine's main job. v0 brings up the device the way an engine integrating TressVK
// must (plugin requirements merged before vkCreateDevice), creates and destroys a TressVK context through the C
// API, renders offscreen frames and writes them as PNG files.
#include "demo_options.hpp"
#include "demo_renderer.hpp"
#include "plugin_host.hpp"

#include <tressvk/engine/device.hpp>
#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/engine/png.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

int list_devices() {
  const auto devices = tressvk::engine::list_devices();
  if (devices.empty()) std::printf("no Vulkan devices\n");
  for (const auto& d : devices)
    std::printf("%u: %s (%s, Vulkan %s%s%s)\n", d.index, d.name.c_str(), tressvk::engine::device_type_name(d.type),
                tressvk::engine::api_version_string(d.api_version).c_str(), d.driver.empty() ? "" : ", ",
                d.driver.c_str());
  return 0;
}

std::string frame_name(uint32_t index) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%04u.png", index);
  return name;
}

int run(const tressvk::demo::Options& options) {
  using namespace tressvk;
  TvkDeviceRequirements req{};
  tressvk_get_device_requirements(&req);
  std::printf("tressvk-demo: TressVK %u, device requirements: Vulkan %s, synchronization2=%u, dynamicRendering=%u, "
              "%u extension(s)\n",
              tressvk_version(), engine::api_version_string(req.min_api_version).c_str(), req.synchronization2,
              req.dynamic_rendering, req.extension_count);

  engine::DeviceOptions device_options;
  device_options.app_name = "tressvk-demo";
  device_options.device = options.device;
  device_options.validation = options.validation;
  device_options.sync_validation = options.validation;
  auto device_owner = std::make_unique<engine::Device>(device_options);
  engine::Device& device = *device_owner;
  const auto messages = device.message_log();
  std::printf("device: %s%s\n", device.description().c_str(),
              options.validation ? " [validation + synchronization validation]" : "");

  {
    // Two frames in flight, for the plugin context and the frame loop: the GPU renders frame n+1 while the CPU
    // writes the PNG of frame n.
    constexpr uint32_t kFramesInFlight = 2;
    demo::PluginContext plugin(device, kFramesInFlight);
    TvkMemoryUsage usage{};
    if (tressvk_get_memory_usage(plugin.get(), &usage) == TVK_SUCCESS)
      std::printf("TressVK context created (%u allocation(s), %llu bytes)\n", usage.allocation_count,
                  static_cast<unsigned long long>(usage.device_bytes));

    demo::DemoRenderer renderer(device, options.width, options.height, kFramesInFlight);
    const std::filesystem::path out_dir = std::filesystem::absolute(options.out_dir);
    std::vector<double> gpu_ms;
    engine::FrameLoop loop(device, kFramesInFlight, demo::DemoRenderer::kTimestampCount,
                           [&](const engine::FrameLoop::Frame& done) {
                             demo::FrameResult frame = renderer.result(done);
                             const auto index = static_cast<uint32_t>(done.number);
                             engine::write_png(out_dir / frame_name(index), frame.pixels);
                             if (frame.gpu_ms) {
                               std::printf("frame %u: GPU %.3f ms\n", index, *frame.gpu_ms);
                               gpu_ms.push_back(*frame.gpu_ms);
                             } else {
                               std::printf("frame %u: GPU time unavailable (no timestamps on this queue)\n", index);
                             }
                           });
    for (uint32_t f = 0; f < options.frames; ++f) {
      renderer.record(loop.begin());
      loop.end();
    }
    loop.finish();
    if (gpu_ms.size() > 1) {
      // The first frame pays for shader compilation (lavapipe JITs on first use), so the median says more.
      std::sort(gpu_ms.begin(), gpu_ms.end());
      std::printf("GPU time per frame: median %.3f ms, min %.3f ms, max %.3f ms over %zu frames\n",
                  gpu_ms[gpu_ms.size() / 2], gpu_ms.front(), gpu_ms.back(), gpu_ms.size());
    }
    device.wait_idle();
    std::printf("wrote %u frame(s) of %ux%u to %s\n", options.frames, options.width, options.height,
                out_dir.c_str());
  }
  device_owner.reset();  // destruction is validated too (leaked objects are reported here)
  if (options.validation) {
    const uint64_t n = messages->count();
    std::printf("validation: %llu message(s)\n", static_cast<unsigned long long>(n));
    if (n != 0) return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  tressvk::demo::Options options;
  if (const int code = tressvk::demo::parse_options(argc, argv, options); code >= 0) return code;
  try {
    if (options.list_devices) return list_devices();
    return run(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tressvk-demo: error: %s\n", e.what());
    return 1;
  }
}
