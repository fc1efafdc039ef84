#include "perf_bench.hpp"

#include "common.hpp"
#include "frame_timing.hpp"

#include "params.hpp"
#include "tressvk_bench_spirv.h"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/descriptors.hpp>
#include <tressvk/engine/pipeline.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/engine/sync.hpp>
#include <tressvk/host/hair_readback.hpp>
#include <tressvk/host/glue.hpp>
#include <tressvk/engine/timestamps.hpp>
#include <tressvk/reference/metrics.hpp>
#include <tressvk/reference/scenes.hpp>
#include <tressvk/reference/simulator.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace tressvk::bench {
namespace {

// The bytes a frame must move at the least: the state (positions and the previous positions) read once and written
// once, prevprev written when VSP runs, tangents written once, the static rest data each pass reads (rest positions
// and rest info; the local frame's rest edges with local shape) read once, and each follow hair's positions written
// once (a follow's tangent is its guide's). What the frame kernel re-reads from caches within the frame is not counted.
uint64_t frame_bytes(uint64_t guide_vertices, uint64_t follow_vertices, bool vsp, bool local_shape) {
  const uint64_t per_guide_vertex = 16 * (2 + 2 + (vsp ? 1 : 0) + 1 + 2 + (local_shape ? 1 : 0));
  return guide_vertices * per_guide_vertex + follow_vertices * 16;
}

struct CopyTiming {
  double ms = 0;           // the copy kernel
  double gb_per_s = 0;
  double transfer_ms = 0;  // vkCmdCopyBuffer of the same bytes
  double transfer_gb_per_s = 0;
};

// The frame's bytes moved by a plain copy, `bytes` / 2 read and `bytes` / 2 written between two device-local
// buffers, two ways, each timed with GPU timestamps as the median of `repeats` back to back in one command buffer:
// a copy kernel (shaders/copy.comp, on the shader cores like the simulation: the bandwidth reference) and
// vkCmdCopyBuffer, which a driver may run on a copy engine with a lower ceiling (an NVIDIA H100 moved about a third of
// the kernel's bytes per second through it: docs/simulation.md, "Measured").
CopyTiming time_copy(const engine::Device& dev, uint64_t bytes, uint32_t repeats) {
  const VkDeviceSize half = std::max<VkDeviceSize>(256, (bytes / 2 + 255) / 256 * 256);
  const VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  engine::Buffer src = engine::create_buffer(dev, half, usage, engine::MemoryUsage::device_local);
  engine::Buffer dst = engine::create_buffer(dev, half, usage, engine::MemoryUsage::device_local);
  engine::TimestampQueries ts(dev, 4 * repeats);
  if (!ts.supported()) return {};
  const auto set_layout =
      engine::create_set_layout(dev, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                                      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}});
  const engine::DescriptorPool pool(dev, 1);
  const VkDescriptorSet set = pool.allocate(set_layout.get());
  engine::write_buffer_descriptor(dev, set, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, src.handle());
  engine::write_buffer_descriptor(dev, set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, dst.handle());
  engine::ComputePipelineDesc desc;
  desc.spirv = k_spv_copy_comp;
  desc.layout.set_layouts = {set_layout.get()};
  desc.layout.push_constant_size = sizeof(uint32_t);
  desc.debug_name = "tressvk-bench copy";
  const engine::Pipeline copy = engine::create_compute_pipeline(dev, desc);
  const uint32_t elements = static_cast<uint32_t>(std::min<VkDeviceSize>(half / 16, UINT32_MAX));
  const uint32_t groups = std::min<uint32_t>(engine::group_count(elements, 256), 65535);
  // Each copy waits for the one before (write-after-write on dst), whichever way it copies.
  const engine::ResourceState written{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                      VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  const engine::ResourceState next{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                   VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
                                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  dev.run_commands([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, src.handle(), 0, VK_WHOLE_SIZE, 0x3f800000u);
    ts.cmd_reset(cmd);
    copy.cmd_bind(cmd);
    copy.cmd_bind_set(cmd, 0, set);
    copy.cmd_push(cmd, elements);
    for (uint32_t i = 0; i < repeats; ++i) {
      engine::cmd_memory_barrier(cmd, written, next);
      ts.cmd_write(cmd, 4 * i, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
      vkCmdDispatch(cmd, groups, 1, 1);
      ts.cmd_write(cmd, 4 * i + 1, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    }
    for (uint32_t i = 0; i < repeats; ++i) {
      engine::cmd_memory_barrier(cmd, written, next);
      ts.cmd_write(cmd, 4 * i + 2, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
      const VkBufferCopy region{0, 0, half};
      vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
      ts.cmd_write(cmd, 4 * i + 3, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    }
  });
  const auto median_ms = [&](uint32_t first_slot) {
    std::vector<double> ms;
    for (uint32_t i = repeats / 5; i < repeats; ++i)  // the first fifth warms the clocks and caches up
      if (auto t = ts.elapsed_ms(4 * i + first_slot, 4 * i + first_slot + 1)) ms.push_back(*t);
    return ms.empty() ? 0.0 : percentile(ms, 0.5);
  };
  const auto gb_per_s = [&](double ms) { return ms > 0 ? double(2 * half) / (ms * 1e-3) * 1e-9 : 0.0; };
  CopyTiming out;
  out.ms = median_ms(0);
  out.gb_per_s = gb_per_s(out.ms);
  out.transfer_ms = median_ms(2);
  out.transfer_gb_per_s = gb_per_s(out.transfer_ms);
  return out;
}

}  // namespace

void add_perf_command(CLI::App& app, PerfCommand& cmd) {
  CLI::App* perf = app.add_subcommand(
      "perf", "GPU time per frame with frames in flight, against a plain copy of the frame's bytes, and the step error");
  cmd.app = perf;
  add_groom_options(*perf, cmd.asset_path, cmd.builtin);
  perf->add_option("--scene", cmd.scene, "settle, shake, run, teleport, wind, hitch or far")->capture_default_str();
  perf->add_option("--frames", cmd.frames, "timed frames")->capture_default_str()->check(CLI::PositiveNumber);
  perf->add_option("--warmup", cmd.warmup, "frames run before timing (at least)")->capture_default_str();
  perf->add_option("--warmup-ms", cmd.warmup_ms, "milliseconds of GPU work before timing (at least)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  perf->add_option("--warmup-ms-max", cmd.warmup_ms_max,
                   "then warm up until the frame time has settled, at most this many milliseconds (0 with "
                   "--warmup-ms 0: --warmup frames only)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  perf->add_flag("--pass-timings", cmd.pass_timings,
                 "enable the plugin's per-pass timestamps (JSON sim_pass_ms_per_frame); they add to the frame's time");
  perf->add_option("--in-flight", cmd.frames_in_flight, "frames in flight")->capture_default_str()->check(CLI::Range(1, 8));
  perf->add_option("--error-frames", cmd.error_frames, "frames after the timed ones whose step error is measured")
      ->capture_default_str();
  perf->add_option("--guides", cmd.guides, "guides of a built-in groom")->capture_default_str();
  perf->add_option("--follows", cmd.follows, "follow hairs per guide of a built-in groom")->capture_default_str();
  perf->add_option("--vertices", cmd.vertices, "vertices per strand of a built-in groom (0 = its default)");
  perf->add_option("--instances", cmd.instances,
                   "instances of the groom, all simulated in one tressvk_cmd_simulate a frame (a crowd); the step error "
                   "is the first one's")
      ->capture_default_str()
      ->check(CLI::Range(1, 4096));
  perf->add_option("--plan-threads", cmd.plan_threads,
                   "plan the instances' frames ahead of tressvk_cmd_simulate with tressvk_plan_frame, their set_frame and "
                   "plan_frame calls split over this many threads (the bench's own among them), as a job system would; "
                   "0 = tressvk_cmd_simulate plans them")
      ->capture_default_str()
      ->check(CLI::Range(0, 256));
  perf->add_option("--draw-strands", cmd.draw_strands,
                   "rendered strands (guides, then follow layers) whose follow hairs are simulated, as a host drawing "
                   "that many by LOD sets (tressvk_set_draw_strands); 0 = all. The step error covers those strands")
      ->capture_default_str();
  add_simulation_options(*perf, cmd.params, cmd.settings);
  perf->add_option("--params", cmd.params_path, "JSON parameter file (as compare --params)")->check(CLI::ExistingFile);
  perf->add_option("--json", cmd.json_path, "write the results as JSON");
  perf->add_option("--device", cmd.device, "device index or name substring (default: discrete GPU first)");
  perf->add_flag("--bones", cmd.bones,
                 "drive the asset's bones every frame (each turning about the head centre out of phase; the asset "
                 "needs bone weights): the host's CPU time then covers a skinned character's per-bone work");
  perf->add_flag("--table-row", cmd.table_row, "print one Markdown table row instead of the report");
  perf->add_flag("--validation", cmd.validation, "enable the Vulkan validation layer; any message fails the run");
}

int execute_perf_command(const PerfCommand& given) {
  PerfCommand cmd = given;
  const auto names = reference::scene_names();
  if (std::find(names.begin(), names.end(), cmd.scene) == names.end()) {
    std::fprintf(stderr, "tressvk-bench perf: --scene: unknown scene '%s'\n", cmd.scene.c_str());
    return 1;
  }
  if (!cmd.params_path.empty()) {
    try {
      const demo::Params file = demo::load_params(cmd.params_path);
      cmd.params = file.simulation;
      cmd.settings = file.settings;
      if (cmd.app->count("--step-rate")) cmd.settings.time.step_rate = given.settings.time.step_rate;
      if (cmd.app->count("--model")) cmd.settings.model = given.settings.model;
      if (cmd.app->count("--local-iterations")) cmd.params.local_iterations = given.params.local_iterations;
      if (cmd.app->count("--length-iterations")) cmd.params.length_iterations = given.params.length_iterations;
    } catch (const demo::ParamsError& e) {
      std::fprintf(stderr, "tressvk-bench perf: %s\n", e.what());
      return 1;
    }
  }
  asset::HairAsset groom;
  std::string groom_name;
  if (!cmd.asset_path.empty()) {
    asset::ReadResult read = asset::read_file(cmd.asset_path);
    if (!read.ok()) {
      std::fprintf(stderr, "tressvk-bench perf: --asset %s: %s\n", cmd.asset_path.c_str(), read.error.c_str());
      return 1;
    }
    groom = std::move(read.asset);
    groom_name = std::filesystem::path(cmd.asset_path).filename().string();
  } else {
    try {
      baker::BuiltinGroomOptions o;
      o.guide_count = cmd.guides;
      o.follow_per_guide = cmd.follows;
      o.vertices_per_strand = cmd.vertices;
      groom = baker::make_builtin_groom(cmd.builtin, o);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "tressvk-bench perf: --builtin %s: %s\n", cmd.builtin.c_str(), e.what());
      return 1;
    }
    groom_name = cmd.builtin;
  }
  if (cmd.bones && (groom.bone_names.empty() || groom.bone_weights.empty())) {
    std::fprintf(stderr, "tressvk-bench perf: --bones: the groom %s has no bone weights (bake it with --bones FILE.tfxbone)\n",
                 groom_name.c_str());
    return 1;
  }

  resolve_for_model(cmd.settings, cmd.params, groom.vertices_per_strand);
  nlohmann::json out;
  try {
    engine::Device dev(host::tool_device_options("tressvk-bench", cmd.device, cmd.validation, cmd.validation));
    // The plugin's parameter ring turns with the frame loop's slots. Its own timestamps (--pass-timings) add two
    // waits for idle inside the frame that a host without them does not pay (3 us a frame on an NVIDIA H100).
    TvkContext ctx = host::create_context(dev, cmd.frames_in_flight, cmd.pass_timings);
    const std::vector<std::byte> bytes = asset::write(groom);
    TvkAsset asset = host::load_asset(dev, ctx, bytes);
    TvkInstanceCreateInfo ic{};
    ic.struct_size = sizeof(ic);
    ic.asset = asset;
    ic.settings = &cmd.settings;
    ic.params = &cmd.params;
    std::vector<TvkInstance> crowd(cmd.instances, nullptr);
    for (TvkInstance& i : crowd) {
      host::check_tvk(tressvk_create_instance(ctx, &ic, &i), ctx, "tressvk_create_instance");
      host::check_tvk(tressvk_set_draw_strands(i, cmd.draw_strands), ctx, "tressvk_set_draw_strands");
    }
    TvkInstance inst = crowd.front();
    // The strands the step error covers: the written ones.
    const size_t written_vertices = size_t{groom.simulated_strands(cmd.draw_strands)} * groom.vertices_per_strand;

    const std::vector<TvkSimParams> params(std::max<size_t>(1, groom.groups.size()), cmd.params);
    reference::Simulator ref(groom, params, cmd.settings);  // planner in step; loaded from the GPU for the error
    const reference::SceneGeometry geometry = reference::scene_geometry(ref.rest());
    const double median_length = ref.median_strand_length();

    // The GPU idled while the host built the groom and the reference: its clock may be climbing back for a second,
    // and frames timed on the climb read slow (docs/simulation.md, "Slow rows: the GPU's clock after a gap"). So
    // the warm-up lasts until the frame time has settled, as the sweep's does.
    WarmUp warm;
    warm.frames = cmd.warmup;
    warm.min_ms = cmd.warmup_ms;
    warm.max_ms = std::max(cmd.warmup_ms, cmd.warmup_ms_max);
    // With --bones each frame's matrices live here until the next frame's are made (set_frame copies them).
    std::vector<TvkBoneMatrix> bones;
    const uint32_t bone_count = static_cast<uint32_t>(groom.bone_names.size());
    const auto frame_of = [&](uint32_t f) {
      TvkSimFrame frame = reference::scene_frame(cmd.scene, f, geometry);
      if (cmd.bones) {
        bones = reference::rocking_bones(bone_count, groom.origin, f, geometry);
        frame.bones = bones.data();
        frame.bone_count = bone_count;
      }
      return frame;
    };
    const FrameTimes times = time_frames(dev, ctx, crowd, ref.planner(), frame_of, warm, cmd.frames,
                                         cmd.frames_in_flight, cmd.plan_threads);
    const uint32_t total = times.warmup_frames + cmd.frames;
    const std::vector<double>& frame_ms = times.frame_ms;
    const std::vector<double>& sim_ms = times.sim_ms;
    const uint32_t dispatches = times.dispatches;
    const double wall_ms = times.wall_ms;
    const double steps_per_frame = times.steps_per_frame;
    // The passes of the last timed frame (the whole crowd's, whose kernel may not be one instance's own).
    const uint32_t np = tressvk_get_recorded_passes(ctx, nullptr, 0);
    std::vector<const char*> recorded(np);
    tressvk_get_recorded_passes(ctx, recorded.data(), np);
    const std::vector<std::string> pass_names(recorded.begin(), recorded.end());  // the next simulate reuses the names

    // The copy right after the timed frames, while the GPU is still at its working clock (timed after the step-error
    // frames, where the GPU idles while the CPU reference runs, it reads up to 2x slow).
    bool vsp = false, local_shape = false;
    for (const TvkSimParams& p : params) {
      vsp |= p.vsp_coefficient > 0;
      local_shape |= p.local_stiffness > 0 && p.local_iterations > 0;
    }
    const uint64_t guide_vertices = uint64_t{groom.guide_count()} * groom.vertices_per_strand;
    const uint64_t follow_vertices = guide_vertices * groom.follow_per_guide;
    const uint64_t frame_byte_count = cmd.instances * frame_bytes(guide_vertices, follow_vertices, vsp, local_shape);
    const CopyTiming copy = time_copy(dev, frame_byte_count, 50);

    // Guides asleep after the timed frames (a still groom at rest, docs/simulation.md "Sleeping").
    uint32_t guides_asleep = 0;
    for (const auto& a : host::read_hair_state(dev, inst).anchors)
      guides_asleep += a[3] >= float(TVK_ASLEEP_QUIET_FRAMES) ? 1u : 0u;

    // Step error, outside the timed frames: load the reference with the GPU state, advance both one frame (the whole
    // crowd in one call, so that the first instance runs the timed frames' kernel).
    double step_error = 0;
    uint32_t error_frames = 0;
    for (uint32_t e = 0; e < cmd.error_frames; ++e) {
      const uint32_t f = total + e;
      const host::HairState before = host::read_hair_state(dev, inst);
      ref.set_state(before.positions, before.previous, before.previous_previous);
      const TvkSimFrame frame = frame_of(f);
      ref.advance(frame);
      for (TvkInstance i : crowd) host::check_tvk(tressvk_set_frame(i, &frame), ctx, "tressvk_set_frame");
      host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
      dev.run_commands([&](VkCommandBuffer c) {
        host::check_tvk(host::record_simulate(ctx, c, std::span<const TvkInstance>(crowd)), ctx, "tressvk_cmd_simulate");
      });
      const host::HairState after = host::read_hair_state(dev, inst);
      const std::vector<std::array<double, 3>> held = host::held_where_skipped(before, after, ref.positions());
      const auto err = reference::position_error(
          std::span<const std::array<double, 3>>(after.positions).first(written_vertices),
          std::span<const std::array<double, 3>>(held).first(written_vertices), median_length);
      step_error = std::max(step_error, err.max_rel);
      ++error_frames;
    }

    const char* path_env = std::getenv("TRESSVK_SIM_PATH");
    // The kernel that ran: the frame pass's name up to its terms ("frame(runs4)", "frame"), or "passes".
    // (No pass: the instance was idle, every guide asleep: docs/simulation.md, "Idle instances".)
    std::string kernel = np > 1 ? std::string("passes") : np == 1 ? std::string(pass_names[0]) : std::string("idle");
    kernel = kernel.substr(0, kernel.find('+'));

    const double gpu_ms = percentile(frame_ms, 0.5);

    out = {
        {"device", dev.description()},
        {"groom", groom_name},
        {"scene", cmd.scene},
        {"sim_path", path_env && *path_env ? path_env : "default"},
        {"kernel", kernel},
        {"guides", groom.guide_count()},
        {"vertices_per_strand", groom.vertices_per_strand},
        {"follow_per_guide", groom.follow_per_guide},
        {"guide_vertices", guide_vertices},
        {"instances", cmd.instances},
        {"plan_threads", cmd.plan_threads},
        {"bones", cmd.bones ? groom.bone_names.size() : 0},
        {"step_rate_hz", cmd.settings.time.step_rate},
        {"sleep_below", cmd.settings.sleep_below},
        {"guides_asleep", guides_asleep},
        {"steps_per_frame", steps_per_frame},
        {"frames", cmd.frames},
        {"warmup", cmd.warmup},
        {"warmup_frames", times.warmup_frames},
        {"warmup_ms", times.warmup_ms},
        {"warmup_settled", times.warmup_settled},
        {"clock_probe_ms", times.clock_probe_ms},
        {"clock_probe_fastest_ms", times.clock_probe_fastest_ms},
        {"frames_in_flight", cmd.frames_in_flight},
        {"passes", pass_names},
        {"dispatches_per_frame", dispatches},
        {"gpu_ms_per_frame", gpu_ms},
        {"gpu_ms_per_frame_p99", percentile(frame_ms, 0.99)},
        {"gpu_ms_per_frame_min", percentile(frame_ms, 0.0)},
        {"sim_pass_ms_per_frame", sim_ms.empty() ? 0.0 : percentile(sim_ms, 0.5)},
        {"wall_ms_per_frame", wall_ms / cmd.frames},
        {"host_ms_per_frame", times.host_ms.empty() ? 0.0 : percentile(times.host_ms, 0.5)},
        {"host_ms_per_frame_p99", times.host_ms.empty() ? 0.0 : percentile(times.host_ms, 0.99)},
        {"host_simulate_ms_per_frame", times.record_ms.empty() ? 0.0 : percentile(times.record_ms, 0.5)},
        {"bytes_per_frame", frame_byte_count},
        {"achieved_gb_per_s", gpu_ms > 0 ? double(frame_byte_count) / (gpu_ms * 1e-3) * 1e-9 : 0.0},
        {"copy_ms", copy.ms},
        {"copy_gb_per_s", copy.gb_per_s},
        {"transfer_copy_ms", copy.transfer_ms},
        {"transfer_copy_gb_per_s", copy.transfer_gb_per_s},
        {"pass_timings", cmd.pass_timings},
        {"step_error_max_rel", step_error},
        {"draw_strands", cmd.draw_strands},
        {"step_error_frames", error_frames},
    };

    dev.wait_idle();
    for (TvkInstance i : crowd) tressvk_destroy_instance(i);
    tressvk_destroy_asset(asset);
    tressvk_destroy_context(ctx);
    if (validation_failed(dev, cmd.validation, "tressvk-bench perf")) return kExitValidation;
  } catch (const std::exception& e) {
    return report_failure(e, "tressvk-bench perf");
  }

  if (!out["warmup_settled"].get<bool>())
    std::fprintf(stderr, "tressvk-bench perf: the frame time (or the GPU clock) had not settled after %.0f ms of warm-up; timed anyway\n",
                 out["warmup_ms"].get<double>());
  if (cmd.table_row) {
    // | groom | guide vertices | step rate | path (kernel) | us/frame | p99 | GB/s (copy) | dispatches | step error |
    // (the median cell says "unsettled" when the warm-up ran out before the frame time settled)
    const std::string groom_cell = out["groom"].get<std::string>() +
                                   (cmd.instances > 1 ? " x " + std::to_string(cmd.instances) + " instances" : "");
    std::printf("| %s | %llu | %.0f Hz | %s (%s) | %.1f%s | %.1f | %.0f (%.0f) | %u | %.2g |\n", groom_cell.c_str(),
                static_cast<unsigned long long>(out["guide_vertices"].get<uint64_t>()),
                out["step_rate_hz"].get<double>(), out["sim_path"].get<std::string>().c_str(),
                out["kernel"].get<std::string>().c_str(), 1e3 * out["gpu_ms_per_frame"].get<double>(),
                out["warmup_settled"].get<bool>() ? "" : " (unsettled)", 1e3 * out["gpu_ms_per_frame_p99"].get<double>(),
                out["achieved_gb_per_s"].get<double>(), out["copy_gb_per_s"].get<double>(),
                out["dispatches_per_frame"].get<uint32_t>(), out["step_error_max_rel"].get<double>());
  } else {
    std::printf("%s\n", out.dump(2).c_str());
  }
  if (!cmd.json_path.empty() && !write_json(out, cmd.json_path, "tressvk-bench perf")) return kExitCannotWrite;
  return 0;
}

}  // namespace tressvk::bench
