// tressvk-demo's command line.
#pragma once

#include <cstdint>
#include <string>

namespace tressvk::demo {

struct Options {
  uint32_t frames = 1;
  std::string out_dir = "out/demo";
  uint32_t width = 960;
  uint32_t height = 540;
  std::string device;  // index or name substring; empty: TRESSVK_DEVICE or automatic
  bool validation = false;
  bool list_devices = false;
};

// Parses argv. Returns an exit code to stop with (0 after --help), or -1 to go on.
int parse_options(int argc, char** argv, Options& options);

}  // namespace tressvk::demo
