#include "common.hpp"

#include "params.hpp"

#include <tressvk/model/planner.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace tressvk::bench {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())))];
}

void add_groom_options(CLI::App& subcommand, std::string& asset_path, std::string& builtin) {
  auto* source = subcommand.add_option_group("groom");
  source->add_option("--asset", asset_path, "a baked .tvkhair file");
  source->add_option("--builtin", builtin, "a procedural groom: straight, curly or long128");
  source->require_option(1);
}

void add_model_option(CLI::App& subcommand, TvkSimModel& model) {
  subcommand.add_option("--model", model,
                        "the strand model: default (follow-the-leader, or TRESSVK_SIM_MODEL), follow-the-leader, "
                        "conservative, compliant")
      ->transform(CLI::CheckedTransformer(demo::sim_model_names()));
}

void add_simulation_options(CLI::App& subcommand, TvkSimParams& params, TvkSimSettings& settings) {
  subcommand.add_option("--step-rate", settings.time.step_rate,
                        "simulation steps per second, 30..480 (default: the model's: 240; conservative 120 for "
                        "strands of up to 64 vertices)");
  subcommand.add_option("--local-iterations", params.local_iterations,
                        "local shape iterations a step (default: the model's: 2; conservative 1)");
  subcommand.add_option("--length-iterations", params.length_iterations)->capture_default_str();
  add_model_option(subcommand, settings.model);
  subcommand.add_option("--sleep-below", settings.sleep_below,
                        "a still groom's guides sleep below this move per step (fraction of the median strand length; 0 = never)")
      ->capture_default_str();
}

void resolve_for_model(TvkSimSettings& settings, TvkSimParams& params, uint32_t vertices_per_strand) {
  const model::StrandModel m = model::resolve_model(settings.model);
  settings = model::resolve_settings(settings, m, vertices_per_strand);
  params = model::resolve_params(params, m);
}

bool write_json(const nlohmann::json& j, const std::string& path, const char* tool) {
  std::ofstream f(path);
  f << j.dump(2) << "\n";
  if (f) return true;
  std::fprintf(stderr, "%s: cannot write %s\n", tool, path.c_str());
  return false;
}

bool validation_failed(const engine::Device& device, bool validation, const char* tool) {
  if (!validation || device.messages().count() == 0) return false;
  std::fprintf(stderr, "%s: %llu validation messages\n", tool,
               static_cast<unsigned long long>(device.messages().count()));
  return true;
}

int report_failure(const std::exception& e, const char* tool) {
  std::fprintf(stderr, "%s: %s\n", tool, e.what());
  return kExitFailure;
}

}  // namespace tressvk::bench
