// The hard-case suite (docs/accuracy.md, "Hard cases"): one named, counted table of the situations a strand
// simulator gets wrong first, each a small groom, settings and a scripted host, with its pass/fail criteria. Run by
// `tressvk-bench hardcases` on any device (lavapipe in ./scripts/test.sh, the GPU in scripts/gpu-sweep.sh).
#pragma once

#include <tressvk/asset.hpp>
#include <tressvk/reference/scenes.hpp>
#include <tressvk/tressvk.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tressvk::bench {

// What a case's model error is measured against (only where it means something; else it is reported, not judged).
enum class ModelErrorAgainst {
  kConverged,  // the same model on the double reference stepped far finer (report only: docs/accuracy.md)
  kUnscaled,   // the groom at scale 1 on the double reference, the GPU trajectory divided by the scale
  kShake,      // the `shake` scene at the origin on the double reference (the far case)
};

struct HardCase {
  std::string name;
  std::string setup;  // one line: groom, settings, host script
  asset::HairAsset groom;
  TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  uint32_t frames = 60;
  std::function<TvkSimFrame(uint32_t, const reference::SceneGeometry&)> frame_of;
  // The double reference's scene for kUnscaled / kShake (and its groom, params and settings for kUnscaled).
  ModelErrorAgainst against = ModelErrorAgainst::kConverged;
  asset::HairAsset unscaled_groom;
  TvkSimParams unscaled_params = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkSimSettings unscaled_settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  double scale = 1;
  std::string reference_scene;

  // Criteria. NaN strands must be 0 in every case; exploded strands too unless allowed.
  double max_stretch = 0.05;          // worst relative segment stretch over every frame
  double max_step_error = 1e-5;       // one frame, / median strand length
  double max_model_error = NAN;       // max over the trajectory, / median strand length; NaN: report only
  uint32_t expected_refusals = 0;     // frames tressvk_set_frame must refuse
  std::string criteria_reason;        // why a bound differs from the defaults
};

// The cases, small enough for lavapipe in CI time.
std::vector<HardCase> hard_cases();

}  // namespace tressvk::bench
