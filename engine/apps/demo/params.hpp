// The parameter file: the simulation parameters and settings, the hair material, wind and LOD as a small JSON
// file that tressvk-demo reads (--params) and writes (--save-params), so a look tuned once is kept and shared.
//
//   { "tressvk_params": 1,
//     "simulation": { "damping": 0.08, "global_stiffness": 0.15, ... every TvkSimParams field },
//     "settings":   { "gravity": [0, -9.81, 0], "step_rate": 240, "max_steps_per_frame": 8, "max_steps_sustained": 16,
//                     "sleep_below": 1e-6, "model": "default" },
//     "material":   { "base_color": [r, g, b], "tip_color": [r, g, b], "kd": 0.7, ... every TvkHairMaterial field },
//     "wind":       { "direction": [1, 0, 0], "strength": 0, "gust_amplitude": 0.5, "gust_frequency": 0.5,
//                     "cone_angle": 0.35 },
//     "lod":        { "start_distance": 0, "end_distance": 0, "min_fraction": 0.25, "target_width_px": 0 } }
//
// Every section and field is optional (missing = the documented default, or the host's own choice for the
// material's strand width). Unknown fields, wrong types and values out of range are errors naming the file and
// the field; JSON syntax errors name the line and column.
#pragma once

#include <tressvk/tressvk.h>

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tressvk::demo {

class ParamsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Params {
  TvkSimParams simulation = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  TvkHairMaterial material = TVK_HAIR_MATERIAL_DEFAULT_INIT;
  TvkWind wind = TVK_WIND_DEFAULT_INIT;
  TvkLodSettings lod{0.0f, 0.0f, 0.25f, 0.0f};
  // Which parts the file set (a host keeps its own choice for the others).
  bool has_strand_width = false, has_tip_width_ratio = false, has_wind = false, has_lod = false;
};

// The names of TvkSimModel in the parameter file ("settings": { "model": ... }) and the tools' --model: default,
// follow-the-leader, conservative, compliant.
const std::map<std::string, TvkSimModel>& sim_model_names();
std::string sim_model_name(TvkSimModel model);
// The model an instance with this setting runs (TVK_SIM_MODEL_DEFAULT resolved through TRESSVK_SIM_MODEL), and its
// name.
std::string resolved_sim_model_name(TvkSimModel model);

// Throws ParamsError naming `name` (and the field, or the line and column).
Params parse_params(std::string_view text, std::string_view name);
Params load_params(const std::filesystem::path& path);  // also when the file cannot be read
std::string params_json(const Params& params);           // every field, 2-space indented
void save_params(const std::filesystem::path& path, const Params& params);  // atomically (temp file + rename)

}  // namespace tressvk::demo
