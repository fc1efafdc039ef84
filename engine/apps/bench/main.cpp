// tressvk-bench: the speed of the GPU simulation next to its error against the double-precision reference, both
// measured in the same run.
//
//   tressvk-bench compare --builtin curly --scene shake --frames 300 --json out.json
//   tressvk-bench compare --asset mohawk.tvkhair --scene run
//   tressvk-bench sweep --builtin curly --guides 2048 --around-default --csv sweep.csv --json sweep.json
//   tressvk-bench hardcases --validation --json hardcases.json
#include "bench.hpp"
#include "common.hpp"
#include "params.hpp"
#include "perf_bench.hpp"
#include "render_bench.hpp"
#include "run_bench.hpp"
#include "soak_bench.hpp"
#include "sweep_bench.hpp"
#include "hardcases_bench.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/check.hpp>
#include <tressvk/host/plugin_host.hpp>
#include <tressvk/reference/scenes.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <clocale>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

using namespace tressvk;

namespace {

nlohmann::json to_json(const bench::CompareResult& r, const bench::CompareOptions& o) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& p : r.pass_times) passes.push_back({{"name", p.name}, {"median_ms", p.median_ms}, {"dispatches", p.dispatches}});
  return {
      {"device", r.device},
      {"groom", r.groom},
      {"scene", r.scene},
      {"frames", r.frames},
      {"guides", r.guides},
      {"follow_per_guide", r.follows},
      {"vertices_per_strand", r.vertices_per_strand},
      {"guide_vertices", r.guide_vertices},
      {"rendered_vertices", r.rendered_vertices},
      {"median_strand_length_m", r.median_strand_length_m},
      {"settings", {{"model", demo::resolved_sim_model_name(o.settings.model)}, {"step_rate_hz", o.settings.time.step_rate}, {"max_steps_per_frame", o.settings.time.max_steps_per_frame},
                    {"max_steps_sustained", o.settings.time.max_steps_sustained},
                    {"frame_dt_s", reference::kSceneFrameDt}, {"local_iterations", o.params.local_iterations},
                    {"length_iterations", o.params.length_iterations}, {"local_stiffness", o.params.local_stiffness},
                    {"global_stiffness", o.params.global_stiffness}, {"vsp_coefficient", o.params.vsp_coefficient}}},
      {"steps_per_frame", r.steps_per_frame},
      {"dispatches_per_frame", r.dispatches_per_frame},
      {"gpu_ms_per_frame", r.gpu_ms_per_frame},
      {"gpu_ms_per_frame_p99", r.gpu_ms_p99},
      {"cpu_reference_ms_per_frame", o.trajectory ? nlohmann::json(r.cpu_reference_ms_per_frame) : nlohmann::json()},
      {"gpu_ms_per_million_vertex_steps",
       r.steps_per_frame > 0 ? r.gpu_ms_per_frame / (r.steps_per_frame * double(r.guide_vertices) * 1e-6) : 0.0},
      {"step_error_max_rel", r.step_error_max_rel},
      {"step_error_rms_rel", r.step_error_rms_rel},
      {"trajectory_error_rms_rel", o.trajectory ? nlohmann::json(r.trajectory_error_rms_rel) : nlohmann::json()},
      {"trajectory_error_max_rel", o.trajectory ? nlohmann::json(r.trajectory_error_max_rel) : nlohmann::json()},
      {"stretch_mean", r.stretch_mean},
      {"stretch_max", r.stretch_max},
      {"nan_strands", r.nan_strands},
      {"exploded_strands", r.exploded_strands},
      {"nonfinite_resets", r.nonfinite_resets},
      {"penetration_depth_rel", r.penetration_depth_rel},
      {"post_contact_speed_mps", r.post_contact_speed_mps},
      {"passes", r.passes},
      {"pass_times", passes},
  };
}

void print_table(const bench::CompareResult& r) {
  std::printf("device      %s\n", r.device.c_str());
  std::printf("groom       %s: %u guides x %u vertices, %u follows/guide (%llu guide vertices), median strand %.3f m\n",
              r.groom.c_str(), r.guides, r.vertices_per_strand, r.follows,
              static_cast<unsigned long long>(r.guide_vertices), r.median_strand_length_m);
  std::printf("scene       %s, %u frames, %.2f steps/frame, %u dispatches/frame\n", r.scene.c_str(), r.frames,
              r.steps_per_frame, r.dispatches_per_frame);
  if (r.cpu_reference_ms_per_frame > 0)
    std::printf("speed       GPU %.4f ms/frame median (p99 %.4f); CPU double reference %.3f ms/frame (same frames)\n",
                r.gpu_ms_per_frame, r.gpu_ms_p99, r.cpu_reference_ms_per_frame);
  else
    std::printf("speed       GPU %.4f ms/frame median (p99 %.4f); CPU reference not run every frame\n",
                r.gpu_ms_per_frame, r.gpu_ms_p99);
  std::printf("            %.3f ms per million guide-vertex steps\n",
              r.steps_per_frame > 0 ? r.gpu_ms_per_frame / (r.steps_per_frame * double(r.guide_vertices) * 1e-6) : 0.0);
  std::printf("error       step max %.3g, step rms %.3g of the median strand length", r.step_error_max_rel,
              r.step_error_rms_rel);
  if (r.cpu_reference_ms_per_frame > 0)
    std::printf("; trajectory rms %.3g (max %.3g)", r.trajectory_error_rms_rel, r.trajectory_error_max_rel);
  std::printf("\n");
  std::printf("health      stretch mean %.3g max %.3g; NaN strands %u, exploded %u, non-finite resets %u\n",
              r.stretch_mean, r.stretch_max, r.nan_strands, r.exploded_strands, r.nonfinite_resets);
  std::printf("contact     deepest free vertex %.3g of the capsule radius inside; fastest after a contact %.3g m/s\n",
              r.penetration_depth_rel, r.post_contact_speed_mps);
  std::printf("%-32s %12s %10s\n", "pass", "median ms", "dispatches");
  for (const auto& p : r.pass_times) std::printf("%-32s %12.4f %10u\n", p.name.c_str(), p.median_ms, p.dispatches);
}

}  // namespace

int main(int argc, char** argv) {
  std::setlocale(LC_ALL, "C");
  CLI::App app{"tressvk-bench: GPU simulation speed against its error versus the double-precision reference"};
  app.require_subcommand(1);
  CLI::App* compare = app.add_subcommand("compare", "simulate a groom in a scene on the GPU and with the reference");
  std::string asset_path, builtin, json_path, device;
  bench::CompareOptions o;
  baker::BuiltinGroomOptions groom_options;
  bench::add_groom_options(*compare, asset_path, builtin);
  compare->add_option("--scene", o.scene, "settle, shake, run, teleport, wind, hitch or far")->required();
  compare->add_option("--frames", o.frames, "timed frames")->capture_default_str();
  compare->add_option("--warmup", o.warmup, "frames run before timing")->capture_default_str();
  compare->add_option("--step-error-every", o.step_error_every, "measure the step error every Nth frame")->capture_default_str();
  bool no_trajectory = false;
  compare->add_flag("--no-trajectory", no_trajectory, "skip the free-running reference (for large grooms)");
  compare->add_option("--guides", groom_options.guide_count, "guides of a built-in groom")->capture_default_str();
  compare->add_option("--follows", groom_options.follow_per_guide, "follow hairs per guide of a built-in groom")->capture_default_str();
  compare->add_option("--vertices", groom_options.vertices_per_strand, "vertices per strand of a built-in groom (0 = its default)");
  bench::add_simulation_options(*compare, o.params, o.settings);
  std::string params_path;
  compare->add_option("--params", params_path,
                      "JSON parameter file (tressvk-demo --save-params, the viewer's Save): its simulation parameters "
                      "and settings; --step-rate and the iteration options given here override it")
      ->check(CLI::ExistingFile);
  compare->add_option("--json", json_path, "write the results as JSON");
  compare->add_option("--device", device, "device index or name substring (default: discrete GPU first)");
  bool table_row = false;
  compare->add_flag("--table-row", table_row, "print one Markdown table row instead of the report");
  bool validation = false;
  compare->add_flag("--validation", validation, "enable the Vulkan validation layer");
  bench::RenderBenchOptions render_options;
  CLI::App* render = bench::add_render_subcommand(app, render_options);
  bench::RunCommand run_command;
  bench::add_run_command(app, run_command);
  CLI::App* soak = bench::add_soak_subcommand(app);
  bench::PerfCommand perf_command;
  bench::add_perf_command(app, perf_command);
  bench::SweepCommand sweep_command;
  bench::add_sweep_command(app, sweep_command);
  bench::HardCasesCommand hardcases_command;
  bench::add_hardcases_command(app, hardcases_command);
  CLI11_PARSE(app, argc, argv);
  if (perf_command.app->parsed()) return bench::execute_perf_command(perf_command);
  if (sweep_command.app->parsed()) return bench::execute_sweep_command(sweep_command);
  if (hardcases_command.app->parsed()) return bench::execute_hardcases_command(hardcases_command);
  if (render->parsed()) return bench::run_render_bench(render_options);
  if (run_command.app->parsed()) return bench::execute_run_command(run_command);
  if (soak->parsed()) {
    try {
      return bench::run_soak();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "tressvk-bench soak: %s\n", e.what());
      return 2;
    }
  }

  o.trajectory = !no_trajectory;
  if (!params_path.empty()) {
    try {
      const demo::Params file = demo::load_params(params_path);
      const bench::CompareOptions given = o;
      o.params = file.simulation;
      o.settings = file.settings;
      if (compare->count("--step-rate")) o.settings.time.step_rate = given.settings.time.step_rate;
      if (compare->count("--model")) o.settings.model = given.settings.model;
      if (compare->count("--local-iterations")) o.params.local_iterations = given.params.local_iterations;
      if (compare->count("--length-iterations")) o.params.length_iterations = given.params.length_iterations;
    } catch (const demo::ParamsError& e) {
      std::fprintf(stderr, "tressvk-bench: %s\n", e.what());
      return 1;
    }
  }
  try {
    const auto names = reference::scene_names();
    if (std::find(names.begin(), names.end(), o.scene) == names.end()) {
      std::fprintf(stderr, "tressvk-bench: unknown scene '%s'\n", o.scene.c_str());
      return 1;
    }
    engine::Device dev(host::tool_device_options("tressvk-bench", device, validation, false));
    asset::HairAsset groom;
    std::string groom_name;
    if (!asset_path.empty()) {
      asset::ReadResult read = asset::read_file(asset_path);
      if (!read.ok()) {
        std::fprintf(stderr, "tressvk-bench: %s\n", read.error.c_str());
        return 2;
      }
      groom = std::move(read.asset);
      groom_name = std::filesystem::path(asset_path).filename().string();
    } else {
      groom = baker::make_builtin_groom(builtin, groom_options);
      groom_name = builtin;
    }
    bench::resolve_for_model(o.settings, o.params, groom.vertices_per_strand);
    const bench::CompareResult r = bench::run_compare(dev, groom, groom_name, o);
    if (table_row) {
      // | groom | guides x N (+K follows) | scene | steps/frame | GPU ms/frame | step error max | trajectory rms |
      // stretch max | NaN/exploded |
      char traj[32] = "-";
      if (o.trajectory) std::snprintf(traj, sizeof traj, "%.2g", r.trajectory_error_rms_rel);
      std::printf("| %s | %u x %u (+%u) | %s | %.2f | %.3f | %.2g | %s | %.2g | %u/%u |\n", r.groom.c_str(), r.guides,
                  r.vertices_per_strand, r.follows, r.scene.c_str(), r.steps_per_frame, r.gpu_ms_per_frame,
                  r.step_error_max_rel, traj, r.stretch_max, r.nan_strands, r.exploded_strands);
    } else {
      print_table(r);
    }
    if (!json_path.empty() && !bench::write_json(to_json(r, o), json_path, "tressvk-bench"))
      return bench::kExitCannotWrite;
    if (bench::validation_failed(dev, validation, "tressvk-bench")) return bench::kExitValidation;
  } catch (const std::exception& e) {
    return bench::report_failure(e, "tressvk-bench");
  }
  return 0;
}
