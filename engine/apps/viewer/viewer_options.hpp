// tressvk-viewer's command line.
#pragma once

#include <cstdint>
#include <string>

namespace tressvk::viewer {

struct ViewerOptions {
  std::string file;        // .tvkhair, .tfx or OBJ hair curves; empty: the bundled head with its groom
  uint32_t frames = 0;     // quit after this many frames (0: run until the window closes)
  std::string screenshot;  // PNG: the last frame, written on exit
  std::string mesh;        // OBJ head or character mesh (the demo's --mesh)
  float mesh_scale = 1.0f; // OBJ units to metres (the demo's --mesh-scale)
  std::string params_file; // JSON parameter file (the demo's --params)
  uint32_t width = 960;
  uint32_t height = 540;
  std::string device;
  bool validation = false;
  bool step_error = false;  // with --frames: measure the step error of the middle frame and print it
};

// Exit codes, also in --help.
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;      // anything else (device, window, validation messages)
inline constexpr int kExitBadInput = 2;   // the hair file or parameter file is missing or broken

// Parses argv. Returns an exit code to stop with (0 after --help), or -1 to go on.
int parse_viewer_options(int argc, char** argv, ViewerOptions& options);

}  // namespace tressvk::viewer
