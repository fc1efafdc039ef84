// The parameter file (engine/apps/demo/params.hpp): a saved file reads back to the same values, every field is
// read, and a broken file is a clear error naming the file and the field (or the line and column).
#include "params.hpp"

#include <catch2/catch_test_macros.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

using tressvk::demo::Params;
using tressvk::demo::ParamsError;
using tressvk::demo::parse_params;

namespace {

std::string error_of(const std::string& text) {
  try {
    parse_params(text, "p.json");
  } catch (const ParamsError& e) {
    return e.what();
  }
  return "no error";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("params: defaults, every section read, and a saved file reads back the same", "[engine][params]") {
  const Params empty = parse_params("{}", "empty.json");
  const TvkSimParams defaults = TVK_SIM_PARAMS_DEFAULT_INIT;
  CHECK(std::memcmp(&empty.simulation, &defaults, sizeof defaults) == 0);
  CHECK_FALSE(empty.has_wind);
  CHECK_FALSE(empty.has_strand_width);

  const Params p = parse_params(R"({"tressvk_params": 1,
    "simulation": {"damping": 0.2, "local_iterations": 4, "vsp_coefficient": 0.5},
    "settings": {"gravity": [0, -5, 0], "step_rate": 120, "max_steps_per_frame": 4, "max_steps_sustained": 6,
                 "model": "conservative"},
    "material": {"base_color": [0.2, 0.1, 0.05], "strand_width": 0.0004, "tip_width_ratio": 0.1},
    "wind": {"direction": [0, 0, -1], "strength": 3},
    "lod": {"start_distance": 2, "end_distance": 6, "min_fraction": 0.3}})", "p.json");
  CHECK(p.simulation.damping == 0.2f);
  CHECK(p.simulation.local_iterations == 4);
  CHECK(p.simulation.vsp_coefficient == 0.5f);
  CHECK(p.simulation.global_stiffness == defaults.global_stiffness);
  CHECK(p.settings.gravity[1] == -5.0f);
  CHECK(p.settings.time.step_rate == 120.0f);
  CHECK(p.settings.time.max_steps_per_frame == 4);
  CHECK(p.settings.time.max_steps_sustained == 6);
  CHECK(p.settings.model == TVK_SIM_MODEL_CONSERVATIVE);
  CHECK(empty.settings.model == TVK_SIM_MODEL_DEFAULT);
  CHECK(p.material.base_color[2] == 0.05f);
  CHECK(p.has_strand_width);
  CHECK(p.material.strand_width == 0.0004f);
  CHECK(p.has_wind);
  CHECK(p.wind.strength == 3.0f);
  CHECK(p.has_lod);
  CHECK(p.lod.end_distance == 6.0f);

  // Saved and read back: the same floats (written as their shortest decimal).
  const Params back = parse_params(tressvk::demo::params_json(p), "back.json");
  CHECK(std::memcmp(&back.simulation, &p.simulation, sizeof p.simulation) == 0);
  CHECK(std::memcmp(&back.settings, &p.settings, sizeof p.settings) == 0);
  CHECK(std::memcmp(&back.material, &p.material, sizeof p.material) == 0);
  CHECK(std::memcmp(&back.wind, &p.wind, sizeof p.wind) == 0);
  CHECK(std::memcmp(&back.lod, &p.lod, sizeof p.lod) == 0);
  CHECK(contains(tressvk::demo::params_json(p), "\"damping\": 0.2,"));
}

// "model" leaves the step rate or the local iterations to the instance's model (TVK_STEP_RATE_BY_MODEL,
// TVK_ITERATIONS_BY_MODEL, the defaults), and a saved file says so in words, not as 0 or 4294967295.
TEST_CASE("params: the step rate and local iterations may be left to the model", "[engine][params]") {
  const Params empty = parse_params("{}", "empty.json");
  CHECK(empty.settings.time.step_rate == TVK_STEP_RATE_BY_MODEL);
  CHECK(empty.simulation.local_iterations == TVK_ITERATIONS_BY_MODEL);
  const std::string saved = tressvk::demo::params_json(empty);
  CHECK(contains(saved, "\"step_rate\": \"model\""));
  CHECK(contains(saved, "\"local_iterations\": \"model\""));
  const Params back = parse_params(saved, "back.json");
  CHECK(back.settings.time.step_rate == TVK_STEP_RATE_BY_MODEL);
  CHECK(back.simulation.local_iterations == TVK_ITERATIONS_BY_MODEL);
  const Params p = parse_params(R"({"simulation": {"local_iterations": "model"}, "settings": {"step_rate": "model"}})",
                                "p.json");
  CHECK(p.settings.time.step_rate == TVK_STEP_RATE_BY_MODEL);
  CHECK(p.simulation.local_iterations == TVK_ITERATIONS_BY_MODEL);
  CHECK(contains(error_of(R"({"settings": {"step_rate": "fast"}})"), "settings.step_rate: expected a number"));
  CHECK(contains(error_of(R"({"settings": {"step_rate": 0}})"), "settings.step_rate: 0 is outside 30..480"));
}

TEST_CASE("params: a broken file names the file and the field, or the line and column", "[engine][params]") {
  CHECK(contains(error_of("{\"simulation\": {\n  \"damping\": 0.1,,\n}}"), "p.json: not valid JSON"));
  CHECK(contains(error_of("{\"simulation\": {\n  \"damping\": 0.1,,\n}}"), "line 2"));
  CHECK(contains(error_of(R"({"simulation": {"dampin": 0.1}})"), "p.json: simulation.dampin: unknown field"));
  CHECK(contains(error_of(R"({"simulaton": {}})"), "p.json: simulaton: unknown section"));
  CHECK(contains(error_of(R"({"material": {"kd": "high"}})"), "p.json: material.kd: expected a number, got string"));
  CHECK(contains(error_of(R"({"simulation": {"global_stiffness": 2}})"), "simulation.global_stiffness: 2 is outside 0..1"));
  CHECK(contains(error_of(R"({"simulation": {"local_iterations": 1.5}})"), "simulation.local_iterations: expected a whole number"));
  CHECK(contains(error_of(R"({"settings": {"gravity": [0, 1]}})"), "settings.gravity: expected an array of 3 numbers"));
  CHECK(contains(error_of(R"({"settings": {"model": "ftl"}})"),
                 "settings.model: expected one of default, follow-the-leader, conservative, compliant, got \"ftl\""));
  CHECK(contains(error_of(R"({"lod": {"start_distance": 5, "end_distance": 2}})"), "lod.end_distance: must be greater"));
  CHECK(contains(error_of(R"({"tressvk_params": 2})"), "tressvk_params: this build reads version 1"));
  CHECK(contains(error_of("[1, 2]"), "expected an object"));
  CHECK(contains(error_of(""), "not valid JSON"));
  const auto missing = std::filesystem::temp_directory_path() / ("tressvk-no-such-params-" + std::to_string(::getpid()) + ".json");
  try {
    tressvk::demo::load_params(missing);
    FAIL("no error for a missing file");
  } catch (const ParamsError& e) {
    CHECK(contains(e.what(), missing.string() + ": cannot open the parameter file"));
  }
}
