// `tressvk-bench run`: simulate a groom in a scene on the GPU and write the guides' world positions as JSON, so
// that anyone can check the physics with their own tools (docs/accuracy.md).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

#include <tressvk/tressvk.h>

namespace tressvk::bench {

struct RunCommand {
  CLI::App* app = nullptr;
  std::string asset_path, builtin, scene = "settle", dump_path, device;
  uint32_t frames = 60, dump_every = 1;
  uint32_t guides = 64, vertices = 0;
  TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  bool validation = false;
};

// Registers the subcommand and its options on `app`; `cmd` must outlive parsing.
void add_run_command(CLI::App& app, RunCommand& cmd);
// Runs it (after parsing, when cmd.app was selected). Returns the process exit code: 0, 1 for bad input (the message
// names the option), 2 for a failure while simulating or writing. Nothing is written unless the whole run succeeds.
int execute_run_command(const RunCommand& cmd);

}  // namespace tressvk::bench
