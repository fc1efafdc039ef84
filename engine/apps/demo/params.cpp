#include "params.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/model/planner.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

namespace tressvk::demo {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

struct Reader {
  std::string name;
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw ParamsError(name + ": " + field + ": " + what);
  }
  float number(const json& v, const std::string& field, double lo, double hi) const {
    if (!v.is_number()) fail(field, "expected a number, got " + std::string(v.type_name()));
    const double d = v.get<double>();
    if (!std::isfinite(d) || d < lo || d > hi) {
      std::ostringstream s;
      s << d << " is outside " << lo << ".." << hi;
      fail(field, s.str());
    }
    return static_cast<float>(d);
  }
  uint32_t count(const json& v, const std::string& field, uint32_t lo, uint32_t hi) const {
    if (!v.is_number_integer() && !v.is_number_unsigned()) fail(field, "expected a whole number, got " + v.dump());
    const long long n = v.get<long long>();
    if (n < lo || n > hi) fail(field, std::to_string(n) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
    return static_cast<uint32_t>(n);
  }
  // "model": the value the instance's model runs at (TVK_STEP_RATE_BY_MODEL, TVK_ITERATIONS_BY_MODEL).
  static bool by_model(const json& v) { return v.is_string() && v.get<std::string>() == "model"; }
  void vec3(const json& v, const std::string& field, float* out, double lo, double hi) const {
    if (!v.is_array() || v.size() != 3) fail(field, "expected an array of 3 numbers");
    for (int i = 0; i < 3; ++i) out[i] = number(v[static_cast<size_t>(i)], field + "[" + std::to_string(i) + "]", lo, hi);
  }
  // Calls the handler of each field; unknown fields are errors (a typo would otherwise be silently ignored).
  void section(const json& root, const char* key, const std::map<std::string, std::function<void(const json&, const std::string&)>>& fields) const {
    if (!root.contains(key)) return;
    const json& s = root[key];
    if (!s.is_object()) fail(key, "expected an object");
    for (const auto& [k, v] : s.items()) {
      const auto it = fields.find(k);
      if (it == fields.end()) {
        std::string known;
        for (const auto& f : fields) known += (known.empty() ? "" : ", ") + f.first;
        fail(std::string(key) + "." + k, "unknown field (known: " + known + ")");
      }
      it->second(v, std::string(key) + "." + k);
    }
  }
};

}  // namespace

Params parse_params(std::string_view text, std::string_view name) {
  Reader r{std::string(name)};
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    // nlohmann's message carries the line and column ("syntax error while parsing ... at line 3, column 5").
    throw ParamsError(r.name + ": not valid JSON: " + e.what());
  }
  if (!root.is_object()) r.fail("(top level)", "expected an object");
  for (const auto& [k, v] : root.items()) {
    if (k != "tressvk_params" && k != "simulation" && k != "settings" && k != "material" && k != "wind" && k != "lod")
      r.fail(k, "unknown section (known: tressvk_params, simulation, settings, material, wind, lod)");
  }
  if (root.contains("tressvk_params") && r.count(root["tressvk_params"], "tressvk_params", 1, 1000) != 1)
    r.fail("tressvk_params", "this build reads version 1");
  Params p;
  TvkSimParams& s = p.simulation;
  r.section(root, "simulation", {
    {"damping", [&](const json& v, const std::string& f) { s.damping = r.number(v, f, 0, 10); }},
    {"global_stiffness", [&](const json& v, const std::string& f) { s.global_stiffness = r.number(v, f, 0, 1); }},
    {"global_range", [&](const json& v, const std::string& f) { s.global_range = r.number(v, f, 0, 1); }},
    {"local_stiffness", [&](const json& v, const std::string& f) { s.local_stiffness = r.number(v, f, 0, 1); }},
    {"local_iterations", [&](const json& v, const std::string& f) {
       s.local_iterations = Reader::by_model(v) ? TVK_ITERATIONS_BY_MODEL : r.count(v, f, 0, TVK_MAX_ITERATIONS); }},
    {"length_iterations", [&](const json& v, const std::string& f) { s.length_iterations = r.count(v, f, 1, TVK_MAX_ITERATIONS); }},
    {"vsp_coefficient", [&](const json& v, const std::string& f) { s.vsp_coefficient = r.number(v, f, 0, 1); }},
    {"vsp_threshold", [&](const json& v, const std::string& f) { s.vsp_threshold = r.number(v, f, 0, 1e6); }},
    {"max_speed", [&](const json& v, const std::string& f) { s.max_speed = r.number(v, f, 0, 1e6); }},
    {"tip_separation", [&](const json& v, const std::string& f) { s.tip_separation = r.number(v, f, -1, 100); }},
    {"rigid_below", [&](const json& v, const std::string& f) { s.rigid_below = r.number(v, f, -1, 1000); }},
  });
  TvkSimSettings& st = p.settings;
  r.section(root, "settings", {
    {"gravity", [&](const json& v, const std::string& f) { r.vec3(v, f, st.gravity, -1000, 1000); }},
    {"step_rate", [&](const json& v, const std::string& f) {
       st.time.step_rate = Reader::by_model(v) ? TVK_STEP_RATE_BY_MODEL : r.number(v, f, 30, 480); }},
    {"max_steps_per_frame", [&](const json& v, const std::string& f) { st.time.max_steps_per_frame = r.count(v, f, 1, TVK_MAX_STEPS_PER_FRAME); }},
    {"max_steps_sustained", [&](const json& v, const std::string& f) { st.time.max_steps_sustained = r.count(v, f, 0, TVK_MAX_STEPS_PER_FRAME); }},
    {"sleep_below", [&](const json& v, const std::string& f) { st.sleep_below = r.number(v, f, 0, 1e-3); }},
    {"model", [&](const json& v, const std::string& f) {
       const auto& names = sim_model_names();
       const auto it = v.is_string() ? names.find(v.get<std::string>()) : names.end();
       if (it == names.end()) r.fail(f, "expected one of default, follow-the-leader, conservative, compliant, got " + v.dump());
       st.model = it->second;
     }},
  });
  TvkHairMaterial& m = p.material;
  r.section(root, "material", {
    {"base_color", [&](const json& v, const std::string& f) { r.vec3(v, f, m.base_color, 0, 100); }},
    {"tip_color", [&](const json& v, const std::string& f) { r.vec3(v, f, m.tip_color, 0, 100); }},
    {"kd", [&](const json& v, const std::string& f) { m.kd = r.number(v, f, 0, 100); }},
    {"ks1", [&](const json& v, const std::string& f) { m.ks1 = r.number(v, f, 0, 100); }},
    {"ex1", [&](const json& v, const std::string& f) { m.ex1 = r.number(v, f, 0, 10000); }},
    {"ks2", [&](const json& v, const std::string& f) { m.ks2 = r.number(v, f, 0, 100); }},
    {"ex2", [&](const json& v, const std::string& f) { m.ex2 = r.number(v, f, 0, 10000); }},
    {"shift1", [&](const json& v, const std::string& f) { m.shift1 = r.number(v, f, -3.2, 3.2); }},
    {"shift2", [&](const json& v, const std::string& f) { m.shift2 = r.number(v, f, -3.2, 3.2); }},
    {"strand_width", [&](const json& v, const std::string& f) { m.strand_width = r.number(v, f, 1e-6, 0.1); p.has_strand_width = true; }},
    {"tip_width_ratio", [&](const json& v, const std::string& f) { m.tip_width_ratio = r.number(v, f, 0, 1); p.has_tip_width_ratio = true; }},
    {"opacity", [&](const json& v, const std::string& f) { m.opacity = r.number(v, f, 0, 1); }},
    {"fiber_spacing", [&](const json& v, const std::string& f) { m.fiber_spacing = r.number(v, f, 0, 1000); }},
    {"fiber_alpha", [&](const json& v, const std::string& f) { m.fiber_alpha = r.number(v, f, 0, 1); }},
    {"color_variation", [&](const json& v, const std::string& f) { m.color_variation = r.number(v, f, 0, 1); }},
  });
  TvkWind& w = p.wind;
  r.section(root, "wind", {
    {"direction", [&](const json& v, const std::string& f) { r.vec3(v, f, w.direction, -1e3, 1e3); p.has_wind = true; }},
    {"strength", [&](const json& v, const std::string& f) { w.strength = r.number(v, f, 0, 1000); p.has_wind = true; }},
    {"gust_amplitude", [&](const json& v, const std::string& f) { w.gust_amplitude = r.number(v, f, 0, 1); p.has_wind = true; }},
    {"gust_frequency", [&](const json& v, const std::string& f) { w.gust_frequency = r.number(v, f, 0, 100); p.has_wind = true; }},
    {"cone_angle", [&](const json& v, const std::string& f) { w.cone_angle = r.number(v, f, 0, 3.2); p.has_wind = true; }},
  });
  r.section(root, "lod", {
    {"start_distance", [&](const json& v, const std::string& f) { p.lod.start_distance = r.number(v, f, 0, 1e6); p.has_lod = true; }},
    {"end_distance", [&](const json& v, const std::string& f) { p.lod.end_distance = r.number(v, f, 0, 1e6); p.has_lod = true; }},
    {"min_fraction", [&](const json& v, const std::string& f) { p.lod.min_fraction = r.number(v, f, 0.01, 1); p.has_lod = true; }},
    {"target_width_px", [&](const json& v, const std::string& f) { p.lod.target_width_px = r.number(v, f, 0, 64); p.has_lod = true; }},
  });
  if (p.has_lod && p.lod.end_distance > 0 && p.lod.end_distance <= p.lod.start_distance)
    r.fail("lod.end_distance", "must be greater than lod.start_distance");
  return p;
}

Params load_params(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw ParamsError(path.string() + ": cannot open the parameter file");
  std::stringstream s;
  s << f.rdbuf();
  if (f.bad()) throw ParamsError(path.string() + ": cannot read the parameter file");
  return parse_params(s.str(), path.string());
}

// A float as the shortest decimal that reads back as the same float (0.08, not 0.07999999821186066).
double shortest(float f) {
  char buf[32];
  for (int digits = 6; digits <= 9; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(f));
    if (std::strtof(buf, nullptr) == f) break;
  }
  return std::strtod(buf, nullptr);
}

const std::map<std::string, TvkSimModel>& sim_model_names() {
  static const std::map<std::string, TvkSimModel> names{{"default", TVK_SIM_MODEL_DEFAULT},
                                                         {"follow-the-leader", TVK_SIM_MODEL_FOLLOW_THE_LEADER},
                                                         {"conservative", TVK_SIM_MODEL_CONSERVATIVE},
                                                         {"compliant", TVK_SIM_MODEL_COMPLIANT}};
  return names;
}

std::string sim_model_name(TvkSimModel model) {
  for (const auto& [name, m] : sim_model_names())
    if (m == model) return name;
  return "default";
}

std::string resolved_sim_model_name(TvkSimModel model) { return sim_model_name(model::resolved_sim_model(model)); }

std::string params_json(const Params& p) {
  auto v3 = [](const float* a) { return ordered_json::array({shortest(a[0]), shortest(a[1]), shortest(a[2])}); };
  const TvkSimParams& s = p.simulation;
  const TvkHairMaterial& m = p.material;
  const TvkWind& w = p.wind;
  ordered_json j;
  j["tressvk_params"] = 1;
  j["simulation"] = {{"damping", shortest(s.damping)}, {"global_stiffness", shortest(s.global_stiffness)}, {"global_range", shortest(s.global_range)},
                     {"local_stiffness", shortest(s.local_stiffness)}, {"local_iterations", s.local_iterations == TVK_ITERATIONS_BY_MODEL ? ordered_json("model") : ordered_json(s.local_iterations)},
                     {"length_iterations", s.length_iterations}, {"vsp_coefficient", shortest(s.vsp_coefficient)},
                     {"vsp_threshold", shortest(s.vsp_threshold)}, {"max_speed", shortest(s.max_speed)},
                     {"tip_separation", shortest(s.tip_separation)}, {"rigid_below", shortest(s.rigid_below)}};
  j["settings"] = {{"gravity", v3(p.settings.gravity)}, {"step_rate", p.settings.time.step_rate == TVK_STEP_RATE_BY_MODEL ? ordered_json("model") : ordered_json(shortest(p.settings.time.step_rate))},
                   {"max_steps_per_frame", p.settings.time.max_steps_per_frame},
                   {"max_steps_sustained", p.settings.time.max_steps_sustained},
                   {"sleep_below", shortest(p.settings.sleep_below)}, {"model", sim_model_name(p.settings.model)}};
  j["material"] = {{"base_color", v3(m.base_color)}, {"tip_color", v3(m.tip_color)}, {"kd", shortest(m.kd)}, {"ks1", shortest(m.ks1)},
                   {"ex1", shortest(m.ex1)}, {"ks2", shortest(m.ks2)}, {"ex2", shortest(m.ex2)}, {"shift1", shortest(m.shift1)}, {"shift2", shortest(m.shift2)},
                   {"strand_width", shortest(m.strand_width)}, {"tip_width_ratio", shortest(m.tip_width_ratio)},
                   {"opacity", shortest(m.opacity)}, {"fiber_spacing", shortest(m.fiber_spacing)}, {"fiber_alpha", shortest(m.fiber_alpha)},
                   {"color_variation", shortest(m.color_variation)}};
  j["wind"] = {{"direction", v3(w.direction)}, {"strength", shortest(w.strength)}, {"gust_amplitude", shortest(w.gust_amplitude)},
               {"gust_frequency", shortest(w.gust_frequency)}, {"cone_angle", shortest(w.cone_angle)}};
  j["lod"] = {{"start_distance", shortest(p.lod.start_distance)}, {"end_distance", shortest(p.lod.end_distance)},
              {"min_fraction", shortest(p.lod.min_fraction)}, {"target_width_px", shortest(p.lod.target_width_px)}};
  return j.dump(2) + "\n";
}

void save_params(const std::filesystem::path& path, const Params& params) {
  const std::string text = params_json(params);
  const auto err = asset::write_file(path, std::as_bytes(std::span(text.data(), text.size())));
  if (!err.empty()) throw ParamsError(err);
}

}  // namespace tressvk::demo
