// tressvk-bench soak: a groom driven through every reference scene with random host behaviour on top --
// teleports, hitches (long frames), pauses (dt 0), parameter and settings changes, wind gusts, instances created
// and destroyed every few frames -- for a given wall-clock time. Every `--check-every` frames each live instance is
// read back: it must have 0 NaN strands and 0 non-finite resets, and a bounded stretch; GPU memory (per live
// instance count) and the process's resident memory must stay flat. With --device-lost-every N the host's submit
// of every Nth frame is taken as having returned VK_ERROR_DEVICE_LOST, and the host recovers as docs/integration.md
// says: tressvk_report_device_lost, every call that uses the device refuses, everything is destroyed, the VkDevice
// and the context are recreated, the asset is loaded again and the instances start over from their rest pose.
// Under --validation the resident-memory growth is reported and not held against the run: the validation layer's
// synchronization tracking (1.3.239, Debian 12) keeps access state for every buffer range it has seen, destroyed
// ones included, so with instance churn the process grows with the layer's state, not ours (lavapipe, 20 s of
// churn: 151 -> 183 MB with synchronization validation, 148.5 -> 148.6 MB with validation but without it, 124 ->
// 125 MB over 60 s without validation). The tests run the soak twice: with validation for the messages, without
// it for resident memory.
// Exit 0 when all held, 1 otherwise.
//
//   tressvk-bench soak --builtin curly --seconds 3600 --json soak.json
//   tressvk-bench soak --asset Ratboy_mohawk.tvkhair --seconds 3600 --instances 4
#include "soak_bench.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/host/hair_readback.hpp>
#include <tressvk/host/plugin_host.hpp>
#include <tressvk/reference/metrics.hpp>
#include <tressvk/model/model.hpp>
#include <tressvk/reference/scenes.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace tressvk::bench {
namespace {

struct SoakOptions {
  std::string asset_path, builtin = "curly", device, json_path;
  baker::BuiltinGroomOptions groom;
  double seconds = 60;
  uint64_t max_frames = 0;      // 0 = until the time is up
  uint32_t max_instances = 3;
  uint32_t check_every = 30;
  uint64_t seed = 1;
  double max_stretch = 0.5;     // relative, over guide segments
  double rss_slack_mb = 32;     // allowed resident-memory growth after the warm-up
  bool validation = false;
  uint64_t device_lost_every = 0;  // frames; 0 = never
};

SoakOptions g_options;

struct SoakInstance {
  TvkInstance handle = nullptr;
  uint32_t frame = 0;           // frames since creation
  std::string scene;
  uint32_t scene_frame = 0;
  double offset[3] = {0, 0, 0};  // added to the scene's translation (teleports move it)
  uint32_t paused = 0;          // frames of dt 0 left
};

struct Totals {
  uint64_t frames = 0, instance_frames = 0, created = 0, destroyed = 0, teleports = 0, hitches = 0, pauses = 0,
           param_changes = 0, settings_changes = 0, checks = 0, nan_strands = 0, exploded = 0, resets = 0,
           device_losses = 0, recoveries = 0;
  double stretch_max = 0;
  double rss_start_mb = 0, rss_end_mb = 0, rss_max_mb = 0;
  double rss_recovery_mb = 0;  // resident memory added across device recreations (reported, not held against the run)
  // Resident memory added while recording a frame that built a simulation pipeline variant never recorded before
  // (the driver compiles it into the process: lavapipe's LLVM keeps code and heap), reported, not held against the
  // run; the memory check covers every other frame.
  double rss_variants_mb = 0;
  std::set<std::string> variants;
  std::map<uint32_t, std::pair<uint64_t, uint64_t>> gpu_bytes_by_instances;  // first and last seen
  std::map<uint32_t, std::pair<uint64_t, uint64_t>> gpu_bytes_reported;      // the last device's with checks
  bool gpu_flat = true;
};

double rss_mb() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  long pages = 0, resident = 0;
  const int n = std::fscanf(f, "%ld %ld", &pages, &resident);
  std::fclose(f);
  return n == 2 ? double(resident) * 4096.0 / (1024.0 * 1024.0) : 0;
}

}  // namespace

CLI::App* add_soak_subcommand(CLI::App& app) {
  SoakOptions& o = g_options;
  CLI::App* soak = app.add_subcommand("soak", "random host motion, events and instance churn for a given time");
  soak->add_option("--asset", o.asset_path, "a baked .tvkhair file (default: a built-in groom)");
  soak->add_option("--builtin", o.builtin, "a procedural groom: straight, curly or long128")->capture_default_str();
  soak->add_option("--guides", o.groom.guide_count, "guides of a built-in groom")->capture_default_str();
  soak->add_option("--follows", o.groom.follow_per_guide, "follow hairs per guide of a built-in groom")->capture_default_str();
  soak->add_option("--seconds", o.seconds, "wall-clock duration")->capture_default_str();
  soak->add_option("--frames", o.max_frames, "stop after this many frames (0: only the time limit)");
  soak->add_option("--instances", o.max_instances, "most instances alive at once")->capture_default_str();
  soak->add_option("--check-every", o.check_every, "read the state back every N frames")->capture_default_str();
  soak->add_option("--seed", o.seed)->capture_default_str();
  soak->add_option("--max-stretch", o.max_stretch, "largest relative segment stretch allowed")->capture_default_str();
  soak->add_option("--rss-slack-mb", o.rss_slack_mb, "resident memory growth allowed after the first 10 %")->capture_default_str();
  soak->add_option("--device", o.device, "device index or name substring");
  soak->add_option("--json", o.json_path, "write the figures as JSON");
  soak->add_option("--device-lost-every", o.device_lost_every,
                   "take every Nth frame's submit as VK_ERROR_DEVICE_LOST and recover (0: never)")->capture_default_str();
  soak->add_flag("--validation", o.validation, "enable the Vulkan validation layer (any message fails the run)");
  return soak;
}

int run_soak() {
  const SoakOptions& o = g_options;
  const engine::DeviceOptions device_options =
      host::tool_device_options("tressvk-bench-soak", o.device, o.validation, o.validation);
  auto device = std::make_unique<engine::Device>(device_options);
  asset::HairAsset groom;
  std::string groom_name;
  if (!o.asset_path.empty()) {
    asset::ReadResult read = asset::read_file(o.asset_path);
    if (!read.ok()) throw std::runtime_error(read.error);
    groom = std::move(read.asset);
    groom_name = o.asset_path;
  } else {
    groom = baker::make_builtin_groom(o.builtin, o.groom);
    groom_name = o.builtin;
  }
  const reference::ModelRest rest = reference::build_model_rest(groom);
  const reference::SceneGeometry geometry = reference::scene_geometry(rest);
  const std::vector<std::string> scenes = reference::scene_names();

  // One frame in flight: every frame is submitted and waited for, so the state can be read back any time.
  const std::vector<std::byte> bytes = asset::write(groom);
  TvkContext ctx = host::create_context(*device, 1);
  TvkAsset asset = host::load_asset(*device, ctx, bytes);

  std::mt19937_64 rng(o.seed);
  const auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const auto chance = [&](double p) { return uniform(0, 1) < p; };
  std::vector<SoakInstance> live;
  Totals t;
  bool ok = true;
  std::string failure;
  const auto fail = [&](const std::string& what) {
    if (ok) failure = what;
    ok = false;
  };
  uint32_t next_churn = 5;

  const auto create_instance = [&] {
    SoakInstance s;
    TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
    TvkInstanceCreateInfo ic{};
    ic.struct_size = sizeof(ic);
    ic.asset = asset;
    ic.settings = &settings;
    host::check_tvk(tressvk_create_instance(ctx, &ic, &s.handle), ctx, "tressvk_create_instance");
    s.scene = scenes[rng() % scenes.size()];
    live.push_back(s);
    ++t.created;
  };
  const auto destroy_instance = [&](size_t i) {
    tressvk_destroy_instance(live[i].handle);
    live.erase(live.begin() + static_cast<std::ptrdiff_t>(i));
    ++t.destroyed;
  };

  // The host's submit returned VK_ERROR_DEVICE_LOST: report it, check that the context refuses device work,
  // destroy everything (nothing waits for the GPU), recreate the device and the context, and start the live
  // instances over from their rest pose (a lost device's memory is gone).
  double rss_before_loss = 0;
  bool rebaseline_rss = false;
  const auto lose_and_recover = [&] {
    ++t.device_losses;
    if (!rebaseline_rss) rss_before_loss = rss_mb();
    tressvk_report_device_lost(ctx);
    if (tressvk_new_frame(ctx) != TVK_ERROR_DEVICE_LOST || !tressvk_is_device_lost(ctx))
      fail("the context did not refuse device work after tressvk_report_device_lost");
    const size_t alive = live.size();
    while (!live.empty()) destroy_instance(live.size() - 1);
    tressvk_destroy_asset(asset);
    tressvk_new_frame(ctx);  // a lost context frees what was deferred at once
    TvkMemoryUsage usage{};
    host::check_tvk(tressvk_get_memory_usage(ctx, &usage), ctx, "tressvk_get_memory_usage");
    if (usage.allocation_count != 0) fail("GPU allocations left after a device loss teardown");
    tressvk_destroy_context(ctx);
    if (o.validation && device->messages().count() > 0) fail("validation messages before the device was recreated");
    device.reset();
    device = std::make_unique<engine::Device>(device_options);
    ctx = host::create_context(*device, 1);
    asset = host::load_asset(*device, ctx, bytes);
    for (size_t i = 0; i < alive; ++i) create_instance();
    // A new device: memory is compared from here on. The last device with checks is kept for the report (a run
    // whose time runs out during a recovery has none on the new one).
    if (!t.gpu_bytes_by_instances.empty()) t.gpu_bytes_reported = t.gpu_bytes_by_instances;
    t.gpu_bytes_by_instances.clear();
    // What a new device adds to the process until its first check (the driver's per-device state and the
    // pipelines compiled again) is reported on its own; the flat-memory check covers the frames between.
    rebaseline_rss = true;
    ++t.recoveries;
  };

  create_instance();
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  bool warm = false;
  while (elapsed() < o.seconds && (o.max_frames == 0 || t.frames < o.max_frames)) {
    // Instance churn: every few frames one is created or destroyed (always at least one alive).
    if (--next_churn == 0) {
      next_churn = 3 + static_cast<uint32_t>(rng() % 20);
      if (live.size() < o.max_instances && (live.size() <= 1 || chance(0.5)))
        create_instance();
      else if (live.size() > 1)
        destroy_instance(rng() % live.size());
    }
    std::vector<TvkInstance> handles;
    for (SoakInstance& s : live) {
      if (s.scene_frame >= 240) {  // through every scene in turn
        s.scene = scenes[rng() % scenes.size()];
        s.scene_frame = 0;
      }
      TvkSimFrame frame = reference::scene_frame(s.scene, s.scene_frame++, geometry);
      if (chance(0.01)) {  // a teleport up to 100 m away: the hair moves rigidly with it
        for (double& x : s.offset) x += uniform(-100, 100);
        frame.teleport = 1;
        ++t.teleports;
      }
      for (int k = 0; k < 3; ++k) frame.transform.translation[k] += s.offset[k];
      if (s.paused) {
        frame.dt = 0;
        --s.paused;
      } else if (chance(0.01)) {
        s.paused = 5 + static_cast<uint32_t>(rng() % 30);
        ++t.pauses;
      } else if (chance(0.01)) {
        frame.dt = static_cast<float>(uniform(0.1, 0.5));  // a hitch: the planner caps the steps
        ++t.hitches;
      }
      if (chance(0.005)) {
        TvkSimParams p = TVK_SIM_PARAMS_DEFAULT_INIT;
        p.global_stiffness = static_cast<float>(uniform(0.0, 0.3));
        p.local_stiffness = static_cast<float>(uniform(0.05, 1.0));
        p.damping = static_cast<float>(uniform(0.0, 0.3));
        p.local_iterations = 1 + static_cast<uint32_t>(rng() % 4);
        p.length_iterations = 1 + static_cast<uint32_t>(rng() % 3);
        host::check_tvk(tressvk_set_sim_params(s.handle, TVK_ALL_GROUPS, &p), ctx, "tressvk_set_sim_params");
        ++t.param_changes;
      }
      if (chance(0.002)) {
        TvkSimSettings st = TVK_SIM_SETTINGS_DEFAULT_INIT;
        const float rates[4] = {60.0f, 120.0f, 240.0f, 480.0f};
        st.time.step_rate = rates[rng() % 4];
        st.gravity[1] = static_cast<float>(uniform(-20.0, 0.0));
        host::check_tvk(tressvk_set_sim_settings(s.handle, &st), ctx, "tressvk_set_sim_settings");
        ++t.settings_changes;
      }
      if (chance(0.02)) frame.wind.direction[0] = static_cast<float>(uniform(-1, 1));
      host::check_tvk(tressvk_set_frame(s.handle, &frame), ctx, "tressvk_set_frame");
      handles.push_back(s.handle);
      ++s.frame;
    }
    host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
    const double rss_before_record = rss_mb();
    device->run_commands([&](VkCommandBuffer cmd) {
      host::check_tvk(host::record_simulate(ctx, cmd, handles), ctx, "tressvk_cmd_simulate");
    });
    {
      const char* names[16] = {};
      const uint32_t count = std::min<uint32_t>(tressvk_get_recorded_passes(ctx, names, 16), 16);
      bool built = false;
      for (uint32_t k = 0; k < count; ++k) built = t.variants.insert(names[k]).second || built;
      if (built && warm) {
        const double added = rss_mb() - rss_before_record;
        t.rss_variants_mb += added;
        t.rss_start_mb += added;
      }
    }
    ++t.frames;
    t.instance_frames += handles.size();
    if (o.device_lost_every && t.frames % o.device_lost_every == 0) {
      lose_and_recover();
      continue;
    }

    if (t.frames % o.check_every == 0) {
      ++t.checks;
      for (const SoakInstance& s : live) {
        const host::HairState state = host::read_hair_state(*device, s.handle);
        const auto h = reference::health(std::span<const std::array<double, 3>>(state.positions), rest);
        const auto st = reference::stretch(std::span<const std::array<double, 3>>(state.positions), rest);
        TvkInstanceStats stats{};
        host::check_tvk(tressvk_get_instance_stats(s.handle, &stats), ctx, "tressvk_get_instance_stats");
        t.nan_strands = std::max<uint64_t>(t.nan_strands, h.nan_strands);
        t.exploded = std::max<uint64_t>(t.exploded, h.exploded_strands);
        t.resets = std::max<uint64_t>(t.resets, stats.nonfinite_strand_resets);
        t.stretch_max = std::max(t.stretch_max, st.max);
        if (h.nan_strands) fail("NaN strands at frame " + std::to_string(t.frames));
        if (stats.nonfinite_strand_resets) fail("non-finite resets at frame " + std::to_string(t.frames));
        if (!(st.max <= o.max_stretch)) fail("stretch " + std::to_string(st.max) + " at frame " + std::to_string(t.frames));
      }
      // GPU memory with n live instances (after retiring released buffers) must not grow over the run.
      host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
      host::check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
      TvkMemoryUsage usage{};
      host::check_tvk(tressvk_get_memory_usage(ctx, &usage), ctx, "tressvk_get_memory_usage");
      auto [it, first] = t.gpu_bytes_by_instances.try_emplace(static_cast<uint32_t>(live.size()), usage.device_bytes,
                                                               usage.device_bytes);
      it->second.second = usage.device_bytes;
      if (!first && usage.device_bytes > it->second.first) {
        t.gpu_flat = false;
        fail("GPU memory grew with " + std::to_string(live.size()) + " instances: " +
             std::to_string(it->second.first) + " -> " + std::to_string(usage.device_bytes) + " bytes");
      }
      const double rss = rss_mb();
      if (rebaseline_rss) {
        rebaseline_rss = false;
        t.rss_recovery_mb += rss - rss_before_loss;
        t.rss_start_mb += rss - rss_before_loss;
      }
      if (!warm && elapsed() >= 0.1 * o.seconds) {
        warm = true;
        t.rss_start_mb = rss;
      }
      t.rss_max_mb = std::max(t.rss_max_mb, rss);
      t.rss_end_mb = rss;
      if (warm && !o.validation && rss > t.rss_start_mb + o.rss_slack_mb)
        fail("resident memory grew from " + std::to_string(t.rss_start_mb) + " to " + std::to_string(rss) + " MB");
    }
    if (o.validation && device->messages().count() > 0) fail("validation messages");
    if (!ok) break;
  }
  device->wait_idle();
  while (!live.empty()) destroy_instance(live.size() - 1);
  tressvk_destroy_asset(asset);
  for (int i = 0; i < 3; ++i) tressvk_new_frame(ctx);
  TvkMemoryUsage end_usage{};
  tressvk_get_memory_usage(ctx, &end_usage);
  if (end_usage.allocation_count != 0) fail("GPU allocations left after destroying everything");
  tressvk_destroy_context(ctx);

  const double secs = elapsed();
  std::printf("soak        %s on %s, %.0f s, seed %llu\n", groom_name.c_str(), device->name(), secs,
              static_cast<unsigned long long>(o.seed));
  std::printf("frames      %llu (%llu instance-frames), %llu instances created, %llu destroyed\n",
              static_cast<unsigned long long>(t.frames), static_cast<unsigned long long>(t.instance_frames),
              static_cast<unsigned long long>(t.created), static_cast<unsigned long long>(t.destroyed));
  std::printf("events      %llu teleports, %llu hitches, %llu pauses, %llu parameter and %llu settings changes\n",
              static_cast<unsigned long long>(t.teleports), static_cast<unsigned long long>(t.hitches),
              static_cast<unsigned long long>(t.pauses), static_cast<unsigned long long>(t.param_changes),
              static_cast<unsigned long long>(t.settings_changes));
  if (o.device_lost_every)
    std::printf("device loss %llu simulated, %llu recovered (context and device recreated, asset reloaded); "
                "resident memory %+.1f MB across them (to the first check on each new device)\n",
                static_cast<unsigned long long>(t.device_losses), static_cast<unsigned long long>(t.recoveries),
                t.rss_recovery_mb);
  std::printf("health      %llu checks: NaN strands max %llu, non-finite resets max %llu, exploded max %llu, "
              "stretch max %.3g (limit %.3g)\n",
              static_cast<unsigned long long>(t.checks), static_cast<unsigned long long>(t.nan_strands),
              static_cast<unsigned long long>(t.resets), static_cast<unsigned long long>(t.exploded), t.stretch_max,
              o.max_stretch);
  std::printf("memory      GPU %s over the run (bytes by live instances:", t.gpu_flat ? "flat" : "GREW");
  if (!t.gpu_bytes_by_instances.empty()) t.gpu_bytes_reported = t.gpu_bytes_by_instances;
  for (const auto& [n, v] : t.gpu_bytes_reported)
    std::printf(" %u: %llu->%llu", n, static_cast<unsigned long long>(v.first), static_cast<unsigned long long>(v.second));
  std::printf("); resident %.1f MB after warm-up, %.1f MB at the end, %.1f MB max; %+.1f MB while building %zu "
              "pipeline variants after the warm-up (not held against the run)%s\n",
              t.rss_start_mb, t.rss_end_mb, t.rss_max_mb, t.rss_variants_mb, t.variants.size(),
              o.validation ? "; not checked under --validation (the layer's synchronization tracking grows with every "
                             "buffer created: run without --validation for the resident-memory check)"
                           : "");
  if (o.validation)
    std::printf("validation  %llu message(s)\n", static_cast<unsigned long long>(device->messages().count()));
  std::printf("result      %s%s\n", ok ? "PASS" : "FAIL: ", failure.c_str());
  if (!o.json_path.empty()) {
    nlohmann::json j = {{"groom", groom_name}, {"device", device->name()}, {"seconds", secs}, {"seed", o.seed},
                        {"frames", t.frames}, {"instance_frames", t.instance_frames}, {"created", t.created},
                        {"destroyed", t.destroyed}, {"teleports", t.teleports}, {"hitches", t.hitches},
                        {"pauses", t.pauses}, {"param_changes", t.param_changes},
                        {"settings_changes", t.settings_changes}, {"checks", t.checks},
                        {"nan_strands_max", t.nan_strands}, {"nonfinite_resets_max", t.resets},
                        {"exploded_strands_max", t.exploded}, {"stretch_max", t.stretch_max},
                        {"gpu_memory_flat", t.gpu_flat}, {"rss_after_warmup_mb", t.rss_start_mb},
                        {"rss_end_mb", t.rss_end_mb}, {"rss_max_mb", t.rss_max_mb}, {"device_losses", t.device_losses}, {"recoveries", t.recoveries},
                        {"rss_across_recoveries_mb", t.rss_recovery_mb},
                        {"rss_while_building_variants_mb", t.rss_variants_mb}, {"pipeline_variants", t.variants.size()}, {"pass", ok}, {"failure", failure}};
    std::ofstream f(o.json_path);
    f << j.dump(2) << "\n";
  }
  return ok ? 0 : 1;
}

}  // namespace tressvk::bench
