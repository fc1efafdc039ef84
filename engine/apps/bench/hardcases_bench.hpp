// `tressvk-bench hardcases`: runs the hard-case suite (hard_cases.hpp) on a device and prints its table: per case
// pass/fail, NaN strands, resets, refused frames, worst stretch, step error, model error and the penetration metric.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <tressvk/tressvk.h>
#include <string>

namespace tressvk::bench {

struct HardCasesCommand {
  CLI::App* app = nullptr;
  std::string json_path, device, only;
  double converged_rate = 3840;   // Hz, the converged reference of the report-only model error
  uint32_t model_error_guides = 4;  // guides compared for the model error
  double step_rate = 0;             // Hz; 0: each case's own (the default 240 Hz)
  uint32_t local_iterations = 0;    // 0: each case's own
  TvkSimModel model = TVK_SIM_MODEL_DEFAULT;  // every case's TvkSimSettings::model
  bool validation = false;
};

void add_hardcases_command(CLI::App& app, HardCasesCommand& cmd);
// Exit code: 0 every case passed; 1 a case failed (or bad input, named); 2 a failure while running; 3 the JSON cannot
// be written; 4 validation messages (with --validation).
int execute_hardcases_command(const HardCasesCommand& cmd);

}  // namespace tressvk::bench
