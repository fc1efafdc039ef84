#include "sweep_bench.hpp"

#include "common.hpp"
#include "frame_timing.hpp"
#include "gpu_track.hpp"
#include "params.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/host/glue.hpp>
#include <tressvk/model/model.hpp>
#include <tressvk/model/planner.hpp>
#include <tressvk/reference/converged.hpp>
#include <tressvk/reference/metrics.hpp>
#include <tressvk/reference/scenes.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <thread>
#include <tuple>

namespace tressvk::bench {
namespace {

struct Config {
  double rate;
  uint32_t local, length, n;
  bool operator<(const Config& o) const {
    return std::tie(n, rate, local, length) < std::tie(o.n, o.rate, o.local, o.length);
  }
  bool operator==(const Config& o) const { return !(*this < o) && !(o < *this); }
};

// The full grid, or the default and each axis changed alone.
std::vector<Config> configurations(const SweepCommand& c, const Config& def) {
  std::vector<Config> out;
  if (!c.around_default) {
    for (uint32_t n : c.vertices)
      for (double r : c.rates)
        for (uint32_t li : c.local_iterations)
          for (uint32_t le : c.length_iterations) out.push_back({r, li, le, n});
  } else {
    out.push_back(def);
    for (double r : c.rates) out.push_back({r, def.local, def.length, def.n});
    for (uint32_t li : c.local_iterations) out.push_back({def.rate, li, def.length, def.n});
    for (uint32_t le : c.length_iterations) out.push_back({def.rate, def.local, le, def.n});
    for (uint32_t n : c.vertices) out.push_back({def.rate, def.local, def.length, n});
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".partial";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f) {
      std::filesystem::remove(tmp);
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) std::filesystem::remove(tmp);
  return !ec;
}

std::string csv_of(const nlohmann::json& rows) {
  static const char* kColumns[] = {
      "groom", "scene", "step_rate_hz", "local_iterations", "length_iterations", "vertices_per_strand", "guides",
      "error_guides", "is_default", "gpu_ms_per_frame", "gpu_ms_per_frame_p99", "steps_per_frame",
      "dispatches_per_frame", "model_error_rms", "model_error_max", "step_error_max", "stretch_max", "stretch_mean",
      "penetration_depth_rel", "post_contact_speed_mps", "nan_strands", "exploded_strands", "nonfinite_resets",
      "warmup_ms", "clock_probe_ms", "clock_probe_fastest_ms"};
  std::string out;
  for (const char* c : kColumns) out += std::string(out.empty() ? "" : ",") + c;
  out += "\n";
  for (const auto& row : rows) {
    bool first = true;
    for (const char* c : kColumns) {
      if (!first) out += ",";
      first = false;
      const auto& v = row.at(c);
      out += v.is_string() ? v.get<std::string>() : v.dump();
    }
    out += "\n";
  }
  return out;
}

}  // namespace

void add_sweep_command(CLI::App& app, SweepCommand& cmd) {
  CLI::App* s = app.add_subcommand(
      "sweep", "GPU ms per frame against model error over step rate x iterations x vertices per strand, per scene");
  cmd.app = s;
  s->add_option("--builtin", cmd.builtin, "the procedural groom, generated at each vertex count: straight or curly")
      ->capture_default_str();
  s->add_option("--scenes", cmd.scenes, "scenes (comma-separated)")->delimiter(',')->capture_default_str();
  s->add_option("--rates", cmd.rates, "step rates, Hz")->delimiter(',')->capture_default_str();
  s->add_option("--local-iterations", cmd.local_iterations)->delimiter(',')->capture_default_str();
  s->add_option("--length-iterations", cmd.length_iterations)->delimiter(',')->capture_default_str();
  s->add_option("--vertices", cmd.vertices, "vertices per strand")->delimiter(',')->capture_default_str();
  s->add_flag("--around-default", cmd.around_default,
              "only the default setting and each axis changed alone (instead of the full grid)");
  s->add_option("--guides", cmd.guides, "guides of the timed groom")->capture_default_str()->check(CLI::PositiveNumber);
  s->add_option("--error-guides", cmd.error_guides, "its first guides (an even thinning) tracked for the model error")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  s->add_option("--frames", cmd.frames, "scene frames (1/60 s) whose trajectory is compared")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  s->add_option("--timed-frames", cmd.timed_frames, "timed frames per configuration")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  s->add_option("--warmup", cmd.warmup, "frames run before timing each configuration")->capture_default_str();
  s->add_option("--warmup-ms", cmd.warmup_ms, "milliseconds of GPU work before the first timed configuration")
      ->capture_default_str();
  s->add_option("--warmup-ms-each", cmd.warmup_ms_each,
                "milliseconds of GPU work before each configuration's timed frames (at least)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  s->add_option("--warmup-ms-max", cmd.warmup_ms_max,
                "milliseconds of warm-up after which a configuration is timed although its frame time has not settled")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  s->add_option("--sleep-below", cmd.sleep_below,
                 "guides of a still groom sleep below this move per step (fraction of the median strand length); 0, "
                 "the default here, times the model itself")
      ->capture_default_str()->check(CLI::Range(0.0, 1e-3));
  s->add_option("--in-flight", cmd.frames_in_flight, "frames in flight while timing")->capture_default_str()->check(CLI::Range(1, 8));
  s->add_option("--reference-rate", cmd.reference_rate, "step rate of the converged reference, Hz")
      ->capture_default_str()
      ->check(CLI::Range(30.0, reference::kConvergedLimits.max_step_rate));
  s->add_option("--reference-local-iterations", cmd.reference_local_iterations)->capture_default_str();
  s->add_option("--reference-length-iterations", cmd.reference_length_iterations)->capture_default_str()->check(CLI::PositiveNumber);
  s->add_option("--reference-vertices", cmd.reference_vertices, "vertices per strand of the converged reference")
      ->capture_default_str()
      ->check(CLI::Range(asset::kMinVerticesPerStrand, asset::kMaxVerticesPerStrand));
  s->add_option("--threads", cmd.threads, "threads for the converged references (0: one per scene)")->capture_default_str();
  s->add_option("--params", cmd.params_path, "JSON parameter file (as compare --params); the swept axes override it")
      ->check(CLI::ExistingFile);
  add_model_option(*s, cmd.settings.model);
  s->add_option("--csv", cmd.csv_path, "write the rows as CSV");
  s->add_option("--json", cmd.json_path, "write the rows as JSON");
  s->add_option("--device", cmd.device, "device index or name substring (default: discrete GPU first)");
  s->add_flag("--validation", cmd.validation, "enable the Vulkan validation layer; any message fails the run");
}

int execute_sweep_command(const SweepCommand& given) {
  SweepCommand cmd = given;
  const char* me = "tressvk-bench sweep";
  const auto names = reference::scene_names();
  for (const std::string& s : cmd.scenes)
    if (std::find(names.begin(), names.end(), s) == names.end()) {
      std::fprintf(stderr, "%s: --scenes: unknown scene '%s'\n", me, s.c_str());
      return 1;
    }
  for (double r : cmd.rates)
    if (!(r >= 30 && r <= 480)) {
      std::fprintf(stderr, "%s: --rates: %g Hz is outside 30..480\n", me, r);
      return 1;
    }
  for (uint32_t n : cmd.vertices)
    if (n < asset::kMinVerticesPerStrand || n > asset::kMaxVerticesPerStrand) {
      std::fprintf(stderr, "%s: --vertices: %u is outside %u..%u\n", me, n, asset::kMinVerticesPerStrand,
                   asset::kMaxVerticesPerStrand);
      return 1;
    }
  if (cmd.scenes.empty() || cmd.rates.empty() || cmd.local_iterations.empty() || cmd.length_iterations.empty() ||
      cmd.vertices.empty()) {
    std::fprintf(stderr, "%s: every axis needs at least one value\n", me);
    return 1;
  }
  if (!cmd.params_path.empty()) {
    try {
      const demo::Params file = demo::load_params(cmd.params_path);
      cmd.params = file.simulation;
      const TvkSimModel given_model = cmd.settings.model;
      cmd.settings = file.settings;
      if (cmd.app->count("--model")) cmd.settings.model = given_model;  // the command line over the file
    } catch (const demo::ParamsError& e) {
      std::fprintf(stderr, "%s: %s\n", me, e.what());
      return 1;
    }
  }
  const auto make = [&](uint32_t n) {
    baker::BuiltinGroomOptions o;
    o.guide_count = cmd.guides;
    o.vertices_per_strand = n;
    return baker::make_builtin_groom(cmd.builtin, o);
  };
  // The default setting: the product's step rate and iterations for the sweep's model, the groom's own vertex count.
  TvkSimParams product = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkSimSettings product_settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  product_settings.model = cmd.settings.model;
  asset::HairAsset ref_groom;
  Config def{};
  try {
    const uint32_t n = make(0).vertices_per_strand;
    resolve_for_model(product_settings, product, n);
    def = {product_settings.time.step_rate, product.local_iterations, product.length_iterations, n};
    ref_groom = reference::guide_prefix(make(cmd.reference_vertices), std::min(cmd.error_guides, cmd.guides));
    const TvkSimParams checked = model::resolve_params(cmd.params, model::resolve_model(cmd.settings.model));
    reference::to_group_step(checked, 1.0 / 240.0, ref_groom.tip_separation, 1.0);  // checked as the plugin checks
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: --builtin %s: %s\n", me, cmd.builtin.c_str(), e.what());
    return 1;
  }
  const std::vector<Config> configs = configurations(cmd, def);
  const uint32_t error_guides = ref_groom.guide_count();

  // The scene geometry of the whole groom (every vertex count has the same roots), so the tracked prefix moves
  // exactly as it does inside the timed groom.
  const reference::SceneGeometry geometry = reference::scene_geometry(model::build_model_rest(make(def.n)));

  // The converged references, one per scene, in parallel: the same model on the double reference at the reference
  // rate, iterations and vertex count.
  TvkSimParams ref_params = cmd.params;
  ref_params.local_iterations = cmd.reference_local_iterations;
  ref_params.length_iterations = cmd.reference_length_iterations;
  const model::ModelRest ref_rest = model::build_model_rest(ref_groom);
  const double median = model::median_strand_length(ref_rest);
  std::map<std::string, reference::Trajectory> converged;
  const auto t_ref0 = std::chrono::steady_clock::now();
  try {
    const uint32_t hw = std::max(1u, std::thread::hardware_concurrency());
    const uint32_t threads = cmd.threads ? cmd.threads : hw;
    for (size_t first = 0; first < cmd.scenes.size(); first += threads) {
      std::vector<std::future<reference::Trajectory>> jobs;
      for (size_t i = first; i < cmd.scenes.size() && i < first + threads; ++i) {
        jobs.push_back(std::async(std::launch::async, [&, i] {
          reference::TrajectoryOptions o;
          o.step_rate = cmd.reference_rate;
          o.model = cmd.settings.model;
          o.scene = cmd.scenes[i];
          o.frames = cmd.frames;
          o.geometry = &geometry;
          return reference::reference_trajectory(ref_groom, std::span<const TvkSimParams>(&ref_params, 1), o);
        }));
      }
      for (size_t i = first; i < cmd.scenes.size() && i < first + threads; ++i) converged[cmd.scenes[i]] = jobs[i - first].get();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: the converged reference: %s\n", me, e.what());
    return 2;
  }
  const double ref_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_ref0).count();
  std::fprintf(stderr, "%s: converged references (%zu scenes, %u guides x %u vertices, %g Hz) in %.1f s\n", me,
               cmd.scenes.size(), error_guides, cmd.reference_vertices, cmd.reference_rate, ref_seconds);

  nlohmann::json rows = nlohmann::json::array();
  std::string device_name;
  try {
    engine::Device dev(host::tool_device_options("tressvk-bench", cmd.device, cmd.validation, cmd.validation));
    device_name = dev.description();
    // No plugin timestamps: they add to the frame's time (perf's --pass-timings); the dispatch count needs none.
    TvkContext ctx = host::create_context(dev, cmd.frames_in_flight, /*timestamps=*/false);
    // The timed grooms, one per vertex count, loaded once.
    std::map<uint32_t, asset::HairAsset> grooms;
    std::map<uint32_t, TvkAsset> timed_assets;
    for (const Config& c : configs)
      if (!grooms.count(c.n)) {
        grooms[c.n] = make(c.n);
        timed_assets[c.n] = host::load_asset(dev, ctx, asset::write(grooms[c.n]));
      }
    const auto with_config = [&](const Config& c, TvkSimParams& p, TvkSimSettings& s) {
      p = cmd.params;
      p.local_iterations = c.local;
      p.length_iterations = c.length;
      s = cmd.settings;
      s.time.step_rate = static_cast<float>(c.rate);
      s.sleep_below = cmd.sleep_below;
    };
    // 1. Accuracy: the tracked guides frame by frame, read back after each frame.
    for (const Config& c : configs) {
      const asset::HairAsset tracked = reference::guide_prefix(grooms[c.n], error_guides);
      const model::ModelRest tracked_rest = model::build_model_rest(tracked);
      TvkSimParams p;
      TvkSimSettings s;
      with_config(c, p, s);
      const std::vector<TvkSimParams> params(std::max<size_t>(1, tracked.groups.size()), p);
      for (const std::string& scene : cmd.scenes) {
        TrackOptions to;
        to.frames = cmd.frames;
        to.frame_of = [&](uint32_t f) { return reference::scene_frame(scene, f, geometry); };
        to.keep_guides = error_guides;
        const TrackResult tr = track(dev, ctx, tracked, params, s, to);
        reference::Trajectory matched;
        for (const auto& frame : converged[scene])
          matched.push_back(reference::at_arc_fractions(frame, ref_rest, tracked_rest));
        const reference::ErrorStats model_error = reference::trajectory_error(tr.trajectory, matched, median);
        rows.push_back({
            {"groom", cmd.builtin},
            {"scene", scene},
            {"step_rate_hz", c.rate},
            {"local_iterations", c.local},
            {"length_iterations", c.length},
            {"vertices_per_strand", c.n},
            {"guides", grooms[c.n].guide_count()},
            {"error_guides", error_guides},
            {"is_default", c == def ? 1 : 0},
            {"sleep_below", cmd.sleep_below},
            {"model_error_rms", model_error.rms_rel},
            {"model_error_max", model_error.max_rel},
            {"step_error_max", tr.step_error_max_rel},
            {"stretch_max", tr.stretch_max},
            {"stretch_mean", tr.stretch_mean},
            {"penetration_depth_rel", tr.penetration.depth_rel},
            {"post_contact_speed_mps", tr.penetration.post_contact_speed},
            {"nan_strands", tr.nan_strands},
            {"exploded_strands", tr.exploded_strands},
            {"nonfinite_resets", tr.nonfinite_resets},
        });
      }
    }
    // 2. Speed: every configuration back to back, the whole groom, frames in flight, no readback between timed
    // frames, each after a warm-up in the same frame loop that lasts until its frame time has settled (WarmUp): at
    // least --warmup-ms before the first (timed right after the CPU-bound accuracy runs, it read up to 5x slow) and
    // --warmup-ms-each before the others, at most --warmup-ms-max. Between two configurations the GPU idles while the
    // host builds the next instance, and its clock then took up to a second to climb back (NVIDIA H100: 585 to 1980
    // MHz over 0.8 s, logged with nvidia-smi); a fixed 250 ms warm-up in chunks of 10 frames, each chunk its own
    // frame loop, still left rows 2.2x slow (follow-the-leader at 60 Hz, 1 M guide vertices, 0.2 ms frames).
    size_t row = 0;
    bool warmed = false;
    for (const Config& c : configs) {
      TvkSimParams p;
      TvkSimSettings s;
      with_config(c, p, s);
      for (const std::string& scene : cmd.scenes) {
        TvkInstance inst = host::create_instance(ctx, timed_assets[c.n], s, p);
        reference::FramePlanner planner(s, grooms[c.n].origin, 0);
        const auto frame_of = [&](uint32_t f) { return reference::scene_frame(scene, f, geometry); };
        WarmUp warm;
        warm.frames = cmd.warmup;
        warm.min_ms = warmed ? cmd.warmup_ms_each : std::max(cmd.warmup_ms, cmd.warmup_ms_each);
        warm.max_ms = std::max(warm.min_ms, cmd.warmup_ms_max);
        warmed = true;
        const FrameTimes t = time_frames(dev, ctx, std::span<const TvkInstance>(&inst, 1), planner, frame_of, warm,
                                         cmd.timed_frames, cmd.frames_in_flight);
        dev.wait_idle();
        tressvk_destroy_instance(inst);
        nlohmann::json& r = rows[row++];
        r["gpu_ms_per_frame"] = percentile(t.frame_ms, 0.5);
        r["gpu_ms_per_frame_p99"] = percentile(t.frame_ms, 0.99);
        r["steps_per_frame"] = t.steps_per_frame;
        r["dispatches_per_frame"] = t.dispatches;
        r["warmup_ms"] = t.warmup_ms;
        r["warmup_settled"] = t.warmup_settled;
        r["clock_probe_ms"] = t.clock_probe_ms;
        r["clock_probe_fastest_ms"] = t.clock_probe_fastest_ms;
        std::printf("%-7s %3.0f Hz  local %u  length %u  N %3u%s  %.4f ms  model rms %.3g max %.3g  step %.2g  stretch %.2g%s\n",
                    scene.c_str(), c.rate, c.local, c.length, c.n, c == def ? "*" : " ", r["gpu_ms_per_frame"].get<double>(),
                    r["model_error_rms"].get<double>(), r["model_error_max"].get<double>(),
                    r["step_error_max"].get<double>(), r["stretch_max"].get<double>(),
                    t.warmup_settled ? "" : "  (frame time or GPU clock still changing after --warmup-ms-max)");
        std::fflush(stdout);
      }
    }
    dev.wait_idle();
    for (auto& [n, a] : timed_assets) tressvk_destroy_asset(a);
    tressvk_destroy_context(ctx);
    if (cmd.validation) std::printf("validation: %llu message(s)\n", static_cast<unsigned long long>(dev.messages().count()));
    if (cmd.validation && dev.messages().count() > 0) {
      std::fprintf(stderr, "%s: %llu validation messages: nothing written\n", me,
                   static_cast<unsigned long long>(dev.messages().count()));
      return 4;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", me, e.what());
    return 2;
  }

  const nlohmann::json doc = {
      {"device", device_name},
      {"groom", cmd.builtin},
      {"guides", cmd.guides},
      {"error_guides", error_guides},
      {"frames", cmd.frames},
      {"timed_frames", cmd.timed_frames},
      {"frames_in_flight", cmd.frames_in_flight},
      {"warmup_ms", cmd.warmup_ms},
      {"warmup_ms_each", cmd.warmup_ms_each},
      {"warmup_ms_max", cmd.warmup_ms_max},
      {"median_strand_length_m", median},
      {"default", {{"step_rate_hz", def.rate}, {"local_iterations", def.local}, {"length_iterations", def.length},
                   {"vertices_per_strand", def.n}}},
      {"reference", {{"step_rate_hz", cmd.reference_rate}, {"local_iterations", cmd.reference_local_iterations},
                     {"length_iterations", cmd.reference_length_iterations},
                     {"vertices_per_strand", cmd.reference_vertices}, {"seconds", ref_seconds}}},
      {"rows", rows},
  };
  if (!cmd.json_path.empty() && !write_atomically(cmd.json_path, doc.dump(2) + "\n")) {
    std::fprintf(stderr, "%s: --json %s: cannot write\n", me, cmd.json_path.c_str());
    return 3;
  }
  if (!cmd.csv_path.empty() && !write_atomically(cmd.csv_path, csv_of(rows))) {
    std::fprintf(stderr, "%s: --csv %s: cannot write\n", me, cmd.csv_path.c_str());
    return 3;
  }
  return 0;
}

}  // namespace tressvk::bench
