#include "run_bench.hpp"

#include "common.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/host/hair_readback.hpp>
#include <tressvk/host/plugin_host.hpp>
#include <tressvk/reference/scenes.hpp>
#include <tressvk/reference/simulator.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace tressvk::bench {
namespace {

// Shortest text that reads back as the same double.
void put_number(std::string& out, double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  out += buf;
}

}  // namespace

void add_run_command(CLI::App& app, RunCommand& cmd) {
  CLI::App* run = app.add_subcommand(
      "run", "simulate a groom in a scene on the GPU and dump the guides' world positions (metres) as JSON");
  cmd.app = run;
  add_groom_options(*run, cmd.asset_path, cmd.builtin);
  run->add_option("--scene", cmd.scene, "settle (head still, gravity on), shake, run, teleport, wind, hitch or far")
      ->capture_default_str();
  run->add_option("--frames", cmd.frames, "frames of 1/60 s")->capture_default_str();
  add_simulation_options(*run, cmd.params, cmd.settings);
  run->add_option("--guides", cmd.guides, "guides of a built-in groom")->capture_default_str();
  run->add_option("--vertices", cmd.vertices, "vertices per strand of a built-in groom (0 = its default)");
  run->add_option("--dump", cmd.dump_path, "the JSON file to write")->required();
  run->add_option("--dump-every", cmd.dump_every, "write every Kth frame (the last frame always)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  run->add_option("--device", cmd.device, "device index or name substring (default: discrete GPU first)");
  run->add_flag("--validation", cmd.validation,
                "enable the Vulkan validation layer with synchronization validation; any message fails the run");
}

int execute_run_command(const RunCommand& cmd) {
  const auto names = reference::scene_names();
  if (std::find(names.begin(), names.end(), cmd.scene) == names.end()) {
    std::fprintf(stderr, "tressvk-bench run: --scene: unknown scene '%s'\n", cmd.scene.c_str());
    return 1;
  }
  if (cmd.frames == 0) {
    std::fprintf(stderr, "tressvk-bench run: --frames must be at least 1\n");
    return 1;
  }
  asset::HairAsset groom;
  TvkSimSettings settings = cmd.settings;
  TvkSimParams params = cmd.params;
  try {
    if (!cmd.asset_path.empty()) {
      asset::ReadResult read = asset::read_file(cmd.asset_path);
      if (!read.ok()) {
        std::fprintf(stderr, "tressvk-bench run: --asset %s: %s\n", cmd.asset_path.c_str(), read.error.c_str());
        return 1;
      }
      groom = std::move(read.asset);
    } else {
      baker::BuiltinGroomOptions o;
      o.guide_count = cmd.guides;
      o.vertices_per_strand = cmd.vertices;
      groom = baker::make_builtin_groom(cmd.builtin, o);
    }
    // Parameters checked the way the plugin checks them (the message names the field), with the model's rate and
    // iterations where they are left to it (what the dump names).
    resolve_for_model(settings, params, groom.vertices_per_strand);
    reference::to_group_step(params, 1.0 / 240.0, groom.tip_separation, 1.0);
    reference::FramePlanner(settings, groom.origin, 0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tressvk-bench run: %s\n", e.what());
    return 1;
  }

  std::string json;
  try {
    engine::Device dev(host::tool_device_options("tressvk-bench", cmd.device, cmd.validation, cmd.validation));
    TvkContext ctx = host::create_context(dev, 1);
    const std::vector<std::byte> bytes = asset::write(groom);
    TvkAsset asset = host::load_asset(dev, ctx, bytes);
    TvkInstance inst = host::create_instance(ctx, asset, settings, params);
    for (uint32_t g = 0; g < std::max<size_t>(1, groom.groups.size()); ++g)
      host::check_tvk(tressvk_set_sim_params(inst, g, &params), ctx, "tressvk_set_sim_params");

    reference::Simulator probe(groom, std::span<const TvkSimParams>(&params, 1), settings);
    const reference::SceneGeometry geometry = reference::scene_geometry(probe.rest());
    const size_t guide_vertices = groom.rest_positions.size();
    const uint32_t n = groom.vertices_per_strand;
    json = "{\"groom\": \"" + (cmd.asset_path.empty() ? cmd.builtin : std::filesystem::path(cmd.asset_path).filename().string()) +
           "\", \"scene\": \"" + cmd.scene + "\", \"step_rate_hz\": ";
    put_number(json, settings.time.step_rate);
    json += ", \"local_iterations\": " + std::to_string(params.local_iterations) +
            ", \"length_iterations\": " + std::to_string(params.length_iterations) +
            ", \"vertices_per_strand\": " + std::to_string(n) + ", \"units\": \"m\", \"frames\": [";
    bool first_frame = true;
    double time = 0;
    for (uint32_t f = 0; f < cmd.frames; ++f) {
      const TvkSimFrame frame = reference::scene_frame(cmd.scene, f, geometry);
      time += static_cast<double>(frame.dt);
      host::check_tvk(tressvk_set_frame(inst, &frame), ctx, "tressvk_set_frame");
      host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
      dev.run_commands([&](VkCommandBuffer c) {
        host::check_tvk(host::record_simulate(ctx, c, inst), ctx, "tressvk_cmd_simulate");
      });
      if (f % cmd.dump_every != 0 && f + 1 != cmd.frames) continue;
      const host::HairState state = host::read_hair_state(dev, inst);
      TvkInstanceBuffers buffers{};
      host::check_tvk(tressvk_get_instance_buffers(inst, &buffers), ctx, "tressvk_get_instance_buffers");
      json += first_frame ? "\n" : ",\n";
      first_frame = false;
      json += "{\"frame\": " + std::to_string(f) + ", \"time_s\": ";
      put_number(json, time);
      json += ", \"strands\": [";
      for (size_t i = 0; i < guide_vertices; ++i) {
        const size_t v = i % n;
        json += v == 0 ? (i == 0 ? "[" : ", [") : ", ";
        json += "[";
        for (int k = 0; k < 3; ++k) {
          if (k) json += ", ";
          put_number(json, buffers.origin[k] + state.positions[i][static_cast<size_t>(k)]);
        }
        json += "]";
        if (v + 1 == n) json += "]";
      }
      json += "]}";
    }
    json += "\n]}\n";
    dev.wait_idle();
    tressvk_destroy_instance(inst);
    tressvk_destroy_asset(asset);
    tressvk_destroy_context(ctx);
    if (cmd.validation) {
      const uint64_t messages = dev.messages().count();
      std::printf("validation: %llu message(s)\n", static_cast<unsigned long long>(messages));
      if (messages > 0) {
        std::fprintf(stderr, "tressvk-bench run: validation messages: nothing written\n");
        return 2;
      }
    }
  } catch (const std::exception& e) {
    return report_failure(e, "tressvk-bench run");
  }
  // Written only once the whole run succeeded: no partial output.
  const std::string tmp = cmd.dump_path + ".partial";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << json;
    if (!out) {
      std::fprintf(stderr, "tressvk-bench run: --dump %s: cannot write\n", cmd.dump_path.c_str());
      std::filesystem::remove(tmp);
      return 2;
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, cmd.dump_path, ec);
  if (ec) {
    std::fprintf(stderr, "tressvk-bench run: --dump %s: %s\n", cmd.dump_path.c_str(), ec.message().c_str());
    std::filesystem::remove(tmp);
    return 2;
  }
  std::printf("tressvk-bench run: %u frames of %s in '%s' -> %s\n", cmd.frames,
              cmd.asset_path.empty() ? cmd.builtin.c_str() : cmd.asset_path.c_str(), cmd.scene.c_str(),
              cmd.dump_path.c_str());
  return 0;
}

}  // namespace tressvk::bench
