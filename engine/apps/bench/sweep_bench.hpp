// `tressvk-bench sweep`: speed against model error over the settings a user can change (docs/accuracy.md, "Pareto
// fronts"). For every step rate x local iterations x length iterations x vertices per strand, and every scene: GPU ms
// per frame (timed as `perf` times it), the model error (the trajectory of a few guides against the converged
// reference: the same model on the double reference stepped far finer, matched by rest arc length), the step error,
// stretch and the penetration metric. Writes one row per configuration and scene as CSV and JSON.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include <tressvk/tressvk.h>

namespace tressvk::bench {

struct SweepCommand {
  CLI::App* app = nullptr;
  std::string builtin = "curly", csv_path, json_path, device, params_path;
  std::vector<std::string> scenes{"settle", "shake", "run", "wind"};
  std::vector<double> rates{60, 120, 240, 480};
  std::vector<uint32_t> local_iterations{1, 2, 4, 8};
  std::vector<uint32_t> length_iterations{1, 2, 4};
  std::vector<uint32_t> vertices{16, 32, 64};
  bool around_default = false;  // the default setting and one axis changed at a time
  uint32_t guides = 1024;       // the timed groom
  uint32_t error_guides = 8;    // its first guides (an even thinning), tracked for the model error
  uint32_t frames = 120;        // scene frames whose trajectory is compared
  uint32_t timed_frames = 120, warmup = 30, frames_in_flight = 3;
  double warmup_ms = 1000;      // GPU work before the first timed configuration (its clock ramps up)
  double warmup_ms_each = 250;  // and at least this much before each configuration (after the gap between two)
  double warmup_ms_max = 5000;  // then until the frame time settles (frame_timing.hpp, WarmUp), at most this long
  // The fronts compare what the model's settings cost, so by default no guide sleeps (TvkSimSettings::sleep_below):
  // a settled groom's rows would otherwise time the sleeping kernel, the same for every setting.
  float sleep_below = 0.0f;
  double reference_rate = 3840;
  uint32_t reference_local_iterations = 8, reference_length_iterations = 4, reference_vertices = 128;
  uint32_t threads = 0;         // reference threads (0: one per scene, at most the hardware's)
  TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  bool validation = false;
};

void add_sweep_command(CLI::App& app, SweepCommand& cmd);
// Exit code: 0; 1 bad input (the message names the option); 2 a failure while running; 3 an output cannot be written;
// 4 validation messages (with --validation). Nothing is written unless the whole sweep ran.
int execute_sweep_command(const SweepCommand& cmd);

}  // namespace tressvk::bench
