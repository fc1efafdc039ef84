// `tressvk-bench perf`: trustworthy GPU time per frame. The GPU is kept busy (several frames in flight, no readback
// between timed frames), each frame is timed by its own GPU timestamps, a plain buffer copy of the frame's byte count
// is timed in the same run (the memory speed the frame is measured against), and the step error against the
// double-precision reference is measured after the timed frames, on frames that are not timed.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

#include <tressvk/tressvk.h>

namespace tressvk::bench {

struct PerfCommand {
  CLI::App* app = nullptr;
  std::string asset_path, builtin, scene = "shake", json_path, device, params_path;
  uint32_t frames = 300, warmup = 60, frames_in_flight = 3, error_frames = 3;
  uint32_t guides = 64, follows = 0, vertices = 0;
  uint32_t draw_strands = 0;  // rendered strands whose follow hairs are simulated (tressvk_set_draw_strands; 0 = all)
  uint32_t instances = 1;  // instances of the groom simulated in one tressvk_cmd_simulate a frame (a crowd)
  // Warm-up (frame_timing.hpp, WarmUp): at least `warmup` frames and `warmup_ms` of GPU work, then until the frame time
  // has settled, at most `warmup_ms_max` (0 and 0: frames only). A GPU that idled while the host built the groom can
  // take a second to climb back to its working clock; frames timed on the climb read up to 2.2x slow.
  double warmup_ms = 500, warmup_ms_max = 5000;
  TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  bool validation = false;
  bool table_row = false;
  bool pass_timings = false;  // the plugin's per-pass timestamps (they add to the frame time)
  bool bones = false;  // drive the asset's bones every frame (reference::rocking_bones), as a skinned character does
  uint32_t plan_threads = 0;  // > 0: set_frame and tressvk_plan_frame on that many threads (time_frames)
};

void add_perf_command(CLI::App& app, PerfCommand& cmd);
// Exit code: 0; 1 bad input (the message names the option); 2 a failure while running; 3 the JSON cannot be
// written; 4 validation messages (with --validation).
int execute_perf_command(const PerfCommand& cmd);

}  // namespace tressvk::bench
