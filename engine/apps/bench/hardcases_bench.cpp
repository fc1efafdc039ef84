#include "hardcases_bench.hpp"

#include "common.hpp"
#include "gpu_track.hpp"
#include "hard_cases.hpp"

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

namespace tressvk::bench {
namespace {

const char* against_name(ModelErrorAgainst a) {
  switch (a) {
    case ModelErrorAgainst::kConverged: return "converged";
    case ModelErrorAgainst::kUnscaled: return "unscaled groom (double reference)";
    case ModelErrorAgainst::kShake: return "shake at the origin (double reference)";
  }
  return "";
}

// The double reference's trajectory a case's model error is measured against, for its first `guides` guides.
reference::Trajectory model_reference(const HardCase& c, uint32_t guides, double converged_rate,
                                      const reference::SceneGeometry& geometry, double& median,
                                      std::vector<reference::Vec3>& origins) {
  reference::TrajectoryOptions o;
  o.frames = c.frames;
  if (c.against == ModelErrorAgainst::kConverged) {
    TvkSimParams p = c.params;
    p.local_iterations = std::max(p.local_iterations, 8u);
    p.length_iterations = std::max(p.length_iterations, 4u);
    o.step_rate = converged_rate;
    // The converged run follows the case's own host script: planned from its frames, one by one.
    const asset::HairAsset prefix = reference::guide_prefix(c.groom, guides);
    TvkSimSettings s = c.settings;
    s.time.step_rate = static_cast<float>(converged_rate);
    s.time.max_steps_per_frame = reference::kConvergedLimits.max_steps_per_frame;
    reference::Simulator sim(prefix, std::span<const TvkSimParams>(&p, 1), s, reference::kConvergedLimits);
    reference::Trajectory out;
    const auto count = static_cast<std::ptrdiff_t>(sim.rest().rest_pos.size());
    for (uint32_t f = 0; f < c.frames; ++f) {
      TvkSimFrame fr = c.frame_of(f, geometry);
      try {
        model::validate_frame(fr, 0);
      } catch (const std::exception&) {
        fr = c.frame_of(f == 0 ? 0 : f - 1, geometry);  // what the plugin keeps: no time advances
        fr.dt = 0;
      }
      sim.advance(fr);
      out.emplace_back(sim.positions().begin(), sim.positions().begin() + count);
    }
    median = sim.median_strand_length();
    return out;
  }
  const bool unscaled = c.against == ModelErrorAgainst::kUnscaled;
  const asset::HairAsset prefix = reference::guide_prefix(unscaled ? c.unscaled_groom : c.groom, guides);
  o.step_rate = c.settings.time.step_rate;
  o.model = c.settings.model;
  o.scene = c.reference_scene;
  const reference::SceneGeometry ref_geometry =
      unscaled ? reference::scene_geometry(model::build_model_rest(c.unscaled_groom)) : geometry;
  o.geometry = &ref_geometry;
  const TvkSimParams p = unscaled ? c.unscaled_params : c.params;
  o.sim_origins = &origins;
  return reference::reference_trajectory(prefix, std::span<const TvkSimParams>(&p, 1), o, &median);
}

}  // namespace

void add_hardcases_command(CLI::App& app, HardCasesCommand& cmd) {
  CLI::App* h = app.add_subcommand("hardcases", "run the hard-case suite on the GPU and print its pass/fail table");
  cmd.app = h;
  h->add_option("--only", cmd.only, "run only the cases whose name contains this text");
  h->add_option("--converged-rate", cmd.converged_rate, "step rate of the converged reference, Hz")
      ->capture_default_str()
      ->check(CLI::Range(30.0, reference::kConvergedLimits.max_step_rate));
  h->add_option("--model-error-guides", cmd.model_error_guides, "guides compared for the model error")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  h->add_option("--step-rate", cmd.step_rate, "run every case at this step rate, Hz (default: each case's own)")
      ->check(CLI::Range(30.0, 480.0));  // TvkTimeSettings::step_rate's range
  h->add_option("--local-iterations", cmd.local_iterations,
                "run every case with this many local-shape iterations (default: each case's own)")
      ->check(CLI::Range(1u, static_cast<uint32_t>(TVK_MAX_ITERATIONS)));
  add_model_option(*h, cmd.model);
  h->add_option("--json", cmd.json_path, "write the table as JSON");
  h->add_option("--device", cmd.device, "device index or name substring (default: discrete GPU first)");
  h->add_flag("--validation", cmd.validation,
              "enable the Vulkan validation layer with synchronization validation; any message fails the run");
}

int execute_hardcases_command(const HardCasesCommand& cmd) {
  const char* me = "tressvk-bench hardcases";
  std::vector<HardCase> cases;
  try {
    cases = hard_cases();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: building the cases: %s\n", me, e.what());
    return 2;
  }
  if (!cmd.only.empty()) {
    std::erase_if(cases, [&](const HardCase& c) { return c.name.find(cmd.only) == std::string::npos; });
    if (cases.empty()) {
      std::fprintf(stderr, "%s: --only: no case name contains '%s'\n", me, cmd.only.c_str());
      return 1;
    }
  }
  for (HardCase& c : cases) {  // a setting other than each case's own, for every case (the table says which)
    if (cmd.step_rate > 0) c.settings.time.step_rate = static_cast<float>(cmd.step_rate);
    if (cmd.local_iterations > 0) c.params.local_iterations = c.unscaled_params.local_iterations = cmd.local_iterations;
    c.settings.model = cmd.model;
    // What the case leaves to the model becomes the model's for its strands (the table names what ran).
    c.unscaled_params = model::resolve_params(c.unscaled_params, model::resolve_model(c.settings.model));
    resolve_for_model(c.settings, c.params, c.groom.vertices_per_strand);
  }
  nlohmann::json rows = nlohmann::json::array();
  uint32_t passed = 0;
  std::string device_name;
  try {
    engine::Device dev(host::tool_device_options("tressvk-bench", cmd.device, cmd.validation, cmd.validation));
    device_name = dev.description();
    TvkContext ctx = host::create_context(dev, 1);
    std::printf("| # | case | pass | NaN strands | resets | refused frames | worst stretch | step error | model error "
                "(against) | deepest in capsule / r | post-contact speed m/s |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    uint32_t index = 0;
    for (const HardCase& c : cases) {
      ++index;
      const auto t0 = std::chrono::steady_clock::now();
      const reference::SceneGeometry geometry = reference::scene_geometry(model::build_model_rest(c.groom));
      const uint32_t guides = std::min(cmd.model_error_guides, c.groom.guide_count());
      TrackOptions to;
      to.frames = c.frames;
      to.frame_of = [&](uint32_t f) { return c.frame_of(f, geometry); };
      to.keep_guides = guides;
      const TrackResult r = track(dev, ctx, c.groom, std::span<const TvkSimParams>(&c.params, 1), c.settings, to);
      double ref_median = 0;
      std::vector<reference::Vec3> ref_origins;
      reference::Trajectory ref = model_reference(c, guides, cmd.converged_rate, geometry, ref_median, ref_origins);
      reference::Trajectory gpu = r.trajectory;
      if (c.against == ModelErrorAgainst::kUnscaled) {
        // In the world (the simulation origin is not the instance's position, so it does not scale with the groom):
        // the scaled groom's positions / scale against the unscaled groom's.
        for (size_t f = 0; f < gpu.size() && f < ref.size(); ++f) {
          for (auto& p : gpu[f]) p = (p + r.origins[f]) * (1.0 / c.scale);
          for (auto& p : ref[f]) p = p + ref_origins[f];
        }
      }
      const reference::ErrorStats model_error = reference::trajectory_error(gpu, ref, ref_median);

      std::vector<std::string> failures;
      if (r.nan_strands) failures.push_back("NaN strands");
      if (r.exploded_strands) failures.push_back("exploded strands");
      if (r.nonfinite_resets) failures.push_back("non-finite resets");
      if (r.refused_frames != c.expected_refusals) failures.push_back("refused frames");
      if (!(r.stretch_max <= c.max_stretch)) failures.push_back("stretch");
      if (!(r.step_error_max_rel <= c.max_step_error)) failures.push_back("step error");
      if (std::isfinite(c.max_model_error) && !(model_error.max_rel <= c.max_model_error))
        failures.push_back("model error");
      const bool pass = failures.empty();
      passed += pass;
      std::string why;
      for (const std::string& f : failures) why += (why.empty() ? "" : ", ") + f;
      char model_text[96];
      std::snprintf(model_text, sizeof model_text, "%.2g (%s%s)", model_error.max_rel, against_name(c.against),
                    std::isfinite(c.max_model_error) ? "" : ", reported");
      std::printf("| %u | %s | %s | %u | %u | %u of %u | %.3g (<= %.3g) | %.2g | %s | %.3g | %.3g |\n", index,
                  c.name.c_str(), pass ? "pass" : ("FAIL: " + why).c_str(), r.nan_strands, r.nonfinite_resets,
                  r.refused_frames, c.expected_refusals, r.stretch_max, c.max_stretch, r.step_error_max_rel, model_text,
                  r.penetration.depth_rel, r.penetration.post_contact_speed);
      std::fflush(stdout);
      rows.push_back({
          {"index", index},
          {"name", c.name},
          {"setup", c.setup},
          {"pass", pass},
          {"failures", failures},
          {"frames", c.frames},
          {"guides", c.groom.guide_count()},
          {"vertices_per_strand", c.groom.vertices_per_strand},
          {"nan_strands", r.nan_strands},
          {"exploded_strands", r.exploded_strands},
          {"nonfinite_resets", r.nonfinite_resets},
          {"refused_frames", r.refused_frames},
          {"expected_refusals", c.expected_refusals},
          {"first_refusal", r.first_refusal},
          {"stretch_max", r.stretch_max},
          {"stretch_bound", c.max_stretch},
          {"step_error_max", r.step_error_max_rel},
          {"step_error_bound", c.max_step_error},
          {"model_error_max", model_error.max_rel},
          {"model_error_rms", model_error.rms_rel},
          {"model_error_against", against_name(c.against)},
          {"model_error_bound", std::isfinite(c.max_model_error) ? nlohmann::json(c.max_model_error) : nlohmann::json()},
          {"penetration_depth_rel", r.penetration.depth_rel},
          {"post_contact_speed_mps", r.penetration.post_contact_speed},
          {"criteria_reason", c.criteria_reason},
          {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()},
      });
    }
    tressvk_destroy_context(ctx);
    if (cmd.validation) {
      const uint64_t messages = dev.messages().count();
      std::printf("validation: %llu message(s)\n", static_cast<unsigned long long>(messages));
      if (messages > 0) {
        std::fprintf(stderr, "%s: validation messages: nothing written\n", me);
        return 4;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", me, e.what());
    return 2;
  }
  std::string setting;
  if (cmd.step_rate > 0) setting += " at " + std::to_string(static_cast<int>(cmd.step_rate)) + " Hz";
  if (cmd.local_iterations > 0)
    setting += " with " + std::to_string(cmd.local_iterations) + (cmd.local_iterations == 1 ? " local iteration" : " local iterations");
  std::printf("%u of %zu hard cases pass%s on %s\n", passed, cases.size(), setting.c_str(), device_name.c_str());
  if (!cmd.json_path.empty()) {
    nlohmann::json doc = {{"device", device_name}, {"cases", cases.size()}, {"passed", passed},
                          {"converged_rate_hz", cmd.converged_rate}, {"rows", rows}};
    if (cmd.step_rate > 0) doc["step_rate_hz"] = cmd.step_rate;
    if (cmd.local_iterations > 0) doc["local_iterations"] = cmd.local_iterations;
    const std::string tmp = cmd.json_path + ".partial";
    bool ok;
    {
      std::ofstream f(tmp);
      f << doc.dump(2) << "\n";
      ok = static_cast<bool>(f);
    }
    std::error_code ec;
    if (ok) std::filesystem::rename(tmp, cmd.json_path, ec);
    if (!ok || ec) {
      std::filesystem::remove(tmp);
      std::fprintf(stderr, "%s: --json %s: cannot write\n", me, cmd.json_path.c_str());
      return 3;
    }
  }
  return passed == cases.size() ? 0 : 1;
}

}  // namespace tressvk::bench
