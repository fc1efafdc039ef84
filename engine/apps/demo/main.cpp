// tressvk-demo: the host engine's main job. It brings up the device the way an engine integrating TressVK must
// (plugin requirements merged before vkCreateDevice), builds the scene (a head with a groom, or the given asset
// and mesh), simulates and renders the hair through the plugin's C API inside the engine's own shadow and main
// passes, and writes the frames as PNG files with per-frame GPU times.
#include "demo_app.hpp"
#include "demo_options.hpp"
#include "head.hpp"
#include "params.hpp"
#include "video.hpp"

#include <tressvk/engine/device.hpp>
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

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
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
  auto device_owner = std::make_unique<engine::Device>(host::with_plugin_requirements(device_options));
  engine::Device& device = *device_owner;
  const auto messages = device.message_log();
  std::printf("device: %s%s\n", device.description().c_str(),
              options.validation ? " [validation + synchronization validation]" : "");

  {
    demo::DemoApp app(device, options);
    const TvkAssetInfo& info = app.asset_info();
    std::printf("hair: %s: %u strands (%u guides x %u), %u vertices each, median length %.3f m, strand width "
                "%.2f mm\n",
                app.scene().asset_name.c_str(), info.total_strands, info.guide_count, 1 + info.follow_per_guide,
                info.vertices_per_strand, static_cast<double>(info.median_strand_length),
                1000.0 * static_cast<double>(app.scene().strand_width));
    std::printf("scene: %s head mesh (%zu triangles), %zu capsule collider(s), animate %s, wind %.2f m/s^2, shadows "
                "%s\n",
                options.mesh.empty() ? (options.asset.empty() ? "procedural" : "no") : options.mesh.c_str(),
                app.scene().head.vertices.size() / 3, app.scene().capsules.size(),
                demo::animation_name(options.animate), static_cast<double>(options.wind),
                options.shadows ? "on" : "off");
    // What the instance runs, with what the parameters leave to the model resolved (tressvk_get_sim_settings).
    TvkSimSettings ran{};
    TvkSimParams ran_params{};
    if (tressvk_get_sim_settings(app.instance(), &ran) == TVK_SUCCESS &&
        tressvk_get_sim_params(app.instance(), 0, &ran_params) == TVK_SUCCESS)
      std::printf("simulation: %s model, %g Hz steps, %u local iteration(s)\n", demo::sim_model_name(ran.model).c_str(),
                  static_cast<double>(ran.time.step_rate), ran_params.local_iterations);
    if (!options.save_params.empty()) {
      demo::save_params(options.save_params, app.params());
      std::printf("parameters: %s\n", std::filesystem::absolute(options.save_params).c_str());
    }
    TvkMemoryUsage usage{};
    if (tressvk_get_memory_usage(app.plugin(), &usage) == TVK_SUCCESS)
      std::printf("TressVK GPU memory: %u allocation(s), %.2f MB\n", usage.allocation_count,
                  static_cast<double>(usage.device_bytes) / 1e6);

    const std::filesystem::path out_dir = std::filesystem::absolute(options.out_dir);
    std::vector<double> sim_ms, shadow_ms, shading_ms;
    std::unique_ptr<demo::VideoWriter> video;
    if (!options.video.empty())
      video = std::make_unique<demo::VideoWriter>(options.video, options.width, options.height,
                                                  options.frame_time > 0 ? 1.0 / options.frame_time : 60.0);
    app.run(options.frames, [&](demo::FrameReport& frame) {
      if (video)
        video->write(frame.pixels);
      else
        engine::write_png(out_dir / frame_name(frame.index), frame.pixels);
      if (!options.poster.empty() && frame.index == options.poster_frame) engine::write_png(options.poster, frame.pixels);
      if (frame.simulation_ms && frame.shadow_ms && frame.shading_ms) {
        std::printf("frame %u: GPU simulation %.3f ms, shadow %.3f ms, shading %.3f ms (%u strands drawn)\n",
                    frame.index, *frame.simulation_ms, *frame.shadow_ms, *frame.shading_ms, frame.strands_drawn);
        sim_ms.push_back(*frame.simulation_ms);
        shadow_ms.push_back(*frame.shadow_ms);
        shading_ms.push_back(*frame.shading_ms);
      } else {
        std::printf("frame %u: GPU time unavailable (no timestamps on this queue)\n", frame.index);
      }
    });
    if (sim_ms.size() > 1)
      // The first frame pays for shader compilation (lavapipe JITs on first use), so the median says more.
      std::printf("GPU time per frame (median of %zu): simulation %.3f ms, shadow %.3f ms, shading %.3f ms\n",
                  sim_ms.size(), median(sim_ms), median(shadow_ms), median(shading_ms));
    device.wait_idle();
    if (video) {
      video->finish();
      std::printf("video: %s\n", std::filesystem::absolute(options.video).c_str());
    } else {
      std::printf("wrote %u frame(s) of %ux%u to %s\n", options.frames, options.width, options.height,
                  out_dir.c_str());
    }
    if (!options.poster.empty())
      std::printf("poster: %s\n", std::filesystem::absolute(options.poster).c_str());
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
    if (!options.export_head.empty()) {
      tressvk::demo::export_sample_head(tressvk::demo::make_sample_head(), options.export_head);
      std::printf("wrote %s/head.obj and %s/scalp.obj\n", options.export_head.c_str(), options.export_head.c_str());
      return 0;
    }
    // Before any rendering: a broken parameter file and a missing encoder are known at once.
    if (!options.params_file.empty()) (void)tressvk::demo::load_params(options.params_file);
    if (!options.video.empty() && tressvk::demo::find_ffmpeg().empty())
      throw tressvk::demo::FfmpegMissing("--video needs ffmpeg, which is not on PATH: install it (Debian: apt-get "
                                         "install ffmpeg, or ./scripts/setup-deps.sh), or write PNG frames without "
                                         "--video");
    return run(options);
  } catch (const tressvk::demo::FfmpegMissing& e) {
    std::fprintf(stderr, "tressvk-demo: error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tressvk-demo: error: %s\n", e.what());
    return 1;
  }
}
