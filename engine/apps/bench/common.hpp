// What every tressvk-bench subcommand shares: the groom options, the statistics, the JSON output and the exit codes.
#pragma once

#include <tressvk/engine/device.hpp>
#include <tressvk/tressvk.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <exception>
#include <string>
#include <vector>

namespace tressvk::bench {

// The exit codes of every subcommand: 0 success; 1 bad input (CLI11 or the message names the option); 2 a failure
// while running; 3 the JSON cannot be written; 4 validation messages (with --validation).
inline constexpr int kExitFailure = 2;
inline constexpr int kExitCannotWrite = 3;
inline constexpr int kExitValidation = 4;

// The value below which a fraction `p` (0..1) of `v` lies (0 for an empty `v`); median(v) is percentile(v, 0.5).
double percentile(std::vector<double> v, double p);
inline double median(std::vector<double> v) { return percentile(std::move(v), 0.5); }

// The groom of a subcommand: exactly one of --asset FILE (a baked .tvkhair) and --builtin NAME (procedural).
void add_groom_options(CLI::App& subcommand, std::string& asset_path, std::string& builtin);

// The simulation options every simulating subcommand takes: --step-rate, --local-iterations, --length-iterations.
// --model: the strand model (TvkSimSettings::model) by name: default, follow-the-leader, conservative, compliant.
void add_model_option(CLI::App& subcommand, TvkSimModel& model);
void add_simulation_options(CLI::App& subcommand, TvkSimParams& params, TvkSimSettings& settings);

// Replaces what the settings and parameters leave to the model (TVK_STEP_RATE_BY_MODEL, TVK_ITERATIONS_BY_MODEL) by
// the values an instance of a groom of n vertices a strand resolves them to, so that every row and report names the
// rate and iterations that ran.
void resolve_for_model(TvkSimSettings& settings, TvkSimParams& params, uint32_t vertices_per_strand);

// Writes `j` (indented) to `path`; false, with "`tool`: cannot write PATH" on stderr, when that fails.
bool write_json(const nlohmann::json& j, const std::string& path, const char* tool);

// With `validation` on and messages counted on `device`: prints how many under `tool` and returns true.
bool validation_failed(const engine::Device& device, bool validation, const char* tool);

// Prints "`tool`: what" for a failure while running and returns kExitFailure.
int report_failure(const std::exception& e, const char* tool);

}  // namespace tressvk::bench
