// The plugin's C interface: context, asset loading and its errors, instance parameters, memory reporting.
#include "sim_harness.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/host/glue.hpp>
#include <tressvk/reference/near_duplicates.hpp>

#include <catch2/catch_test_macros.hpp>

#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

using namespace tressvk;

TEST_CASE("an asset loads from memory and reports its counts", "[plugin]") {
  test::PluginContext ctx = test::create_plugin_context();
  const asset::HairAsset hair = test::small_groom("straight", 40, 2);
  TvkAsset a = test::load_asset(ctx.get(), hair);
  TvkAssetInfo info{};
  REQUIRE(tressvk_get_asset_info(a, &info) == TVK_SUCCESS);
  CHECK(info.guide_count == 40);
  CHECK(info.follow_per_guide == 2);
  CHECK(info.total_strands == 120);
  CHECK(info.vertices_per_strand == hair.vertices_per_strand);
  CHECK(info.median_strand_length > 0.1f);
  CHECK(std::string(tressvk_get_asset_group_name(a, 0)) == hair.groups[0].name);
  TvkMemoryUsage usage{};
  REQUIRE(tressvk_get_memory_usage(ctx.get(), &usage) == TVK_SUCCESS);
  CHECK(usage.device_bytes >= 40ull * hair.vertices_per_strand * 16);
  tressvk_destroy_asset(a);
}

namespace {
std::vector<std::string> g_warnings;
void keep_warnings(TvkMessageSeverity severity, const char* message, void*) {
  if (severity == TVK_MESSAGE_WARNING) g_warnings.emplace_back(message);
}
// A context whose warnings land in g_warnings (cleared).
test::PluginContext context_keeping_warnings() {
  TvkContextCreateInfo info = host::context_info(test::device());
  info.message_callback = keep_warnings;
  TvkContext raw = nullptr;
  REQUIRE(tressvk_create_context(&info, &raw) == TVK_SUCCESS);
  g_warnings.clear();
  return test::PluginContext(raw);
}
}  // namespace

// The conservative model below the step rate it is recommended at for the asset's strands (60 Hz; 240 Hz for more
// than 64 vertices: sim::conservative_least_rate) warns the host once, at creation or when the settings change to it;
// follow-the-leader, and the conservative model at its rates, do not.
TEST_CASE("the conservative model below its recommended step rate warns the host", "[plugin]") {
  test::PluginContext ctx = context_keeping_warnings();
  TvkAsset curly = test::load_asset(ctx.get(), test::small_groom("curly", 4));
  TvkAsset long128 = test::load_asset(ctx.get(), test::small_groom("long128", 4));
  const auto create = [&](TvkAsset asset, TvkSimModel model, float rate) {
    TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
    settings.model = model;
    settings.time.step_rate = rate;
    TvkInstanceCreateInfo ici{};
    ici.struct_size = sizeof(ici);
    ici.asset = asset;
    ici.settings = &settings;
    TvkInstance inst = nullptr;
    REQUIRE(tressvk_create_instance(ctx.get(), &ici, &inst) == TVK_SUCCESS);
    return inst;
  };
  g_warnings.clear();
  TvkInstance ftl = create(curly, TVK_SIM_MODEL_FOLLOW_THE_LEADER, 30.0f);
  TvkInstance at60 = create(curly, TVK_SIM_MODEL_CONSERVATIVE, 60.0f);
  TvkInstance long240 = create(long128, TVK_SIM_MODEL_CONSERVATIVE, 240.0f);
  CHECK(g_warnings.empty());
  TvkInstance at30 = create(curly, TVK_SIM_MODEL_CONSERVATIVE, 30.0f);
  REQUIRE(g_warnings.size() == 1);
  INFO(g_warnings.back());
  CHECK(g_warnings.back().find("tressvk_create_instance: time.step_rate 30 Hz is below 60 Hz") != std::string::npos);
  CHECK(g_warnings.back().find("strands of 32 vertices") != std::string::npos);
  // Set to 120 Hz on 128-vertex strands: warned once, not again for the same settings.
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  settings.model = TVK_SIM_MODEL_CONSERVATIVE;
  settings.time.step_rate = 120.0f;
  REQUIRE(tressvk_set_sim_settings(long240, &settings) == TVK_SUCCESS);
  REQUIRE(g_warnings.size() == 2);
  INFO(g_warnings.back());
  CHECK(g_warnings.back().find("tressvk_set_sim_settings: time.step_rate 120 Hz is below 240 Hz") != std::string::npos);
  REQUIRE(tressvk_set_sim_settings(long240, &settings) == TVK_SUCCESS);
  CHECK(g_warnings.size() == 2);
  for (TvkInstance i : {ftl, at60, long240, at30}) tressvk_destroy_instance(i);
  tressvk_destroy_asset(curly);
  tressvk_destroy_asset(long128);
}

// What the settings leave to the model (the defaults: TVK_STEP_RATE_BY_MODEL, TVK_ITERATIONS_BY_MODEL) an instance
// resolves to its model's rate and iterations for its strands, and reports through tressvk_get_sim_settings and
// tressvk_get_sim_params; a change of model resolves them again, and a value the host set stays as set.
TEST_CASE("an instance runs its model's rate and iterations where the settings leave them to it", "[plugin]") {
  test::PluginContext ctx = context_keeping_warnings();
  TvkAsset curly = test::load_asset(ctx.get(), test::small_groom("curly", 4));
  TvkAsset long128 = test::load_asset(ctx.get(), test::small_groom("long128", 4));
  const auto create = [&](TvkAsset asset, const TvkSimSettings* settings) {
    TvkInstanceCreateInfo ici{};
    ici.struct_size = sizeof(ici);
    ici.asset = asset;
    ici.settings = settings;
    TvkInstance inst = nullptr;
    REQUIRE(tressvk_create_instance(ctx.get(), &ici, &inst) == TVK_SUCCESS);
    return inst;
  };
  const auto rate_of = [](TvkInstance i) {
    TvkSimSettings s{};
    REQUIRE(tressvk_get_sim_settings(i, &s) == TVK_SUCCESS);
    return s.time.step_rate;
  };
  const auto iterations_of = [](TvkInstance i) {
    TvkSimParams p{};
    REQUIRE(tressvk_get_sim_params(i, 0, &p) == TVK_SUCCESS);
    return p.local_iterations;
  };
  TvkSimSettings ftl = TVK_SIM_SETTINGS_DEFAULT_INIT;
  ftl.model = TVK_SIM_MODEL_FOLLOW_THE_LEADER;
  TvkSimSettings conservative = TVK_SIM_SETTINGS_DEFAULT_INIT;
  conservative.model = TVK_SIM_MODEL_CONSERVATIVE;
  TvkInstance a = create(curly, &ftl);
  TvkInstance b = create(curly, &conservative);
  TvkInstance c = create(long128, &conservative);
  CHECK(rate_of(a) == 240.0f);
  CHECK(iterations_of(a) == 2u);
  CHECK(rate_of(b) == 120.0f);
  CHECK(iterations_of(b) == 1u);
  CHECK(rate_of(c) == 240.0f);  // more than 64 vertices a strand
  CHECK(iterations_of(c) == 1u);
  CHECK(g_warnings.empty());  // the model's own rates are never below its recommended ones
  // The model changes: what was left to it follows; the reported model is the one that runs.
  REQUIRE(tressvk_set_sim_settings(a, &conservative) == TVK_SUCCESS);
  CHECK(rate_of(a) == 120.0f);
  CHECK(iterations_of(a) == 1u);
  TvkSimSettings reported{};
  REQUIRE(tressvk_get_sim_settings(a, &reported) == TVK_SUCCESS);
  CHECK(reported.model == TVK_SIM_MODEL_CONSERVATIVE);
  // Values the host sets stay as set, whatever the model.
  TvkSimSettings at60 = conservative;
  at60.time.step_rate = 60.0f;
  REQUIRE(tressvk_set_sim_settings(b, &at60) == TVK_SUCCESS);
  CHECK(rate_of(b) == 60.0f);
  TvkSimParams three = TVK_SIM_PARAMS_DEFAULT_INIT;
  three.local_iterations = 3;
  REQUIRE(tressvk_set_sim_params(b, TVK_ALL_GROUPS, &three) == TVK_SUCCESS);
  CHECK(iterations_of(b) == 3u);
  // Bad calls name themselves.
  CHECK(tressvk_get_sim_params(a, 7, &three) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(tressvk_get_sim_settings(a, nullptr) == TVK_ERROR_INVALID_ARGUMENT);
  for (TvkInstance i : {a, b, c}) tressvk_destroy_instance(i);
  tressvk_destroy_asset(curly);
  tressvk_destroy_asset(long128);
}

// Strands with sub-micrometre segments (hard case 8's groom) are respaced on load (model::kRespaceBelowRel), and the
// host is told; a baked-like groom loads without that warning.
TEST_CASE("an asset with sub-micrometre segments loads with a warning that its strands were respaced", "[plugin]") {
  test::PluginContext ctx = context_keeping_warnings();
  TvkAsset plain = test::load_asset(ctx.get(), test::small_groom("straight", 8));
  CHECK(g_warnings.empty());
  TvkAsset dup =
      test::load_asset(ctx.get(), tressvk::reference::with_near_duplicate_vertices(test::small_groom("straight", 8)));
  REQUIRE(g_warnings.size() == 1);
  INFO(g_warnings[0]);
  CHECK(g_warnings[0].find("3 strands") != std::string::npos);
  CHECK(g_warnings[0].find("respaced") != std::string::npos);
  tressvk_destroy_asset(plain);
  tressvk_destroy_asset(dup);
}

TEST_CASE("a corrupt asset is refused with a message naming the problem", "[plugin]") {
  test::PluginContext ctx = test::create_plugin_context();
  std::vector<std::byte> bytes = asset::write(test::small_groom("straight", 8));
  bytes[bytes.size() / 2] ^= std::byte{0x40};
  TvkAsset a = nullptr;
  TvkResult r = TVK_SUCCESS;
  test::run_commands([&](VkCommandBuffer cmd) { r = host::record_load_asset(ctx.get(), cmd, bytes, &a); });
  CHECK(r == TVK_ERROR_INVALID_ASSET);
  CHECK(a == nullptr);
  const std::string message = tressvk_last_error(ctx.get());
  INFO(message);
  CHECK(message.find("<memory>") != std::string::npos);
  CHECK(message.size() > 12);
}

TEST_CASE("a missing asset file is an I/O error naming the file", "[plugin]") {
  test::PluginContext ctx = test::create_plugin_context();
  TvkAsset a = nullptr;
  TvkResult r = TVK_SUCCESS;
  test::run_commands([&](VkCommandBuffer cmd) {
    TvkAssetLoadInfo info{};
    info.struct_size = sizeof(info);
    info.path = "/nonexistent/hair.tvkhair";
    info.upload_command_buffer = cmd;
    r = tressvk_load_asset(ctx.get(), &info, &a);
  });
  CHECK(r == TVK_ERROR_IO);
  CHECK(std::string(tressvk_last_error(ctx.get())).find("/nonexistent/hair.tvkhair") != std::string::npos);
}

TEST_CASE("bad arguments return codes, never crash", "[plugin]") {
  test::PluginContext ctx = test::create_plugin_context();
  TvkAsset a = nullptr;
  CHECK(tressvk_load_asset(ctx.get(), nullptr, &a) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(tressvk_load_asset(nullptr, nullptr, &a) == TVK_ERROR_INVALID_ARGUMENT);
  TvkInstance inst = nullptr;
  TvkInstanceCreateInfo ici{};
  ici.struct_size = sizeof(ici);
  CHECK(tressvk_create_instance(ctx.get(), &ici, &inst) == TVK_ERROR_INVALID_ARGUMENT);
  TvkSimulateInfo si{};
  si.struct_size = sizeof(si) + 1;
  CHECK(tressvk_cmd_simulate(ctx.get(), VK_NULL_HANDLE, &si) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(tressvk_set_frame(nullptr, nullptr) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(tressvk_plan_frame(nullptr) == TVK_ERROR_INVALID_ARGUMENT);
  CHECK(std::string(tressvk_last_error(nullptr)).find("tressvk_plan_frame") != std::string::npos);
  CHECK(tressvk_check_version(TVK_VERSION_NUM, sizeof(TvkContextCreateInfo)) == TVK_SUCCESS);
  CHECK(tressvk_check_version(TVK_VERSION_NUM + 100, sizeof(TvkContextCreateInfo)) == TVK_ERROR_VERSION_MISMATCH);
}

TEST_CASE("out-of-range parameters are refused naming the field", "[plugin]") {
  test::PluginContext ctx = test::create_plugin_context();
  TvkAsset a = test::load_asset(ctx.get(), test::small_groom("straight", 8));
  {
    test::GpuInstance inst(ctx.get(), a, {}, TvkSimSettings TVK_SIM_SETTINGS_DEFAULT_INIT);
    TvkSimParams p = TVK_SIM_PARAMS_DEFAULT_INIT;
    p.local_stiffness = 2.0f;
    CHECK(tressvk_set_sim_params(inst.handle(), 0, &p) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(tressvk_last_error(ctx.get())).find("local_stiffness") != std::string::npos);
    p = TVK_SIM_PARAMS_DEFAULT_INIT;
    p.rigid_below = std::numeric_limits<float>::quiet_NaN();
    CHECK(tressvk_set_sim_params(inst.handle(), 0, &p) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(tressvk_last_error(ctx.get())).find("rigid_below") != std::string::npos);
    p = TVK_SIM_PARAMS_DEFAULT_INIT;
    CHECK(tressvk_set_sim_params(inst.handle(), 7, &p) == TVK_ERROR_INVALID_ARGUMENT);
  }
  tressvk_destroy_asset(a);
}

TEST_CASE("tressvk_set_frame refuses non-finite host input naming the field", "[plugin]") {
  test::PluginContext ctx = test::create_plugin_context();
  TvkAsset a = test::load_asset(ctx.get(), test::small_groom("straight", 8));
  {
    test::GpuInstance inst(ctx.get(), a, {}, TvkSimSettings TVK_SIM_SETTINGS_DEFAULT_INIT);
    TvkSimFrame f = TVK_SIM_FRAME_DEFAULT_INIT;
    f.dt = 1.0f / 60.0f;
    CHECK(tressvk_set_frame(inst.handle(), &f) == TVK_SUCCESS);
    f.transform.translation[0] = std::numeric_limits<double>::quiet_NaN();
    CHECK(tressvk_set_frame(inst.handle(), &f) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(tressvk_last_error(ctx.get())).find("transform.translation[0]") != std::string::npos);
    f = TVK_SIM_FRAME_DEFAULT_INIT;
    f.capsule_count = 1;
    f.capsules[0].r0 = std::numeric_limits<float>::infinity();
    CHECK(tressvk_set_frame(inst.handle(), &f) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(tressvk_last_error(ctx.get())).find("capsules[0]") != std::string::npos);
    f = TVK_SIM_FRAME_DEFAULT_INIT;
    f.wind.strength = std::numeric_limits<float>::quiet_NaN();
    CHECK(tressvk_set_frame(inst.handle(), &f) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(tressvk_last_error(ctx.get())).find("wind.strength") != std::string::npos);
    f = TVK_SIM_FRAME_DEFAULT_INIT;
    for (double& r : f.transform.rotation) r = 0.0;
    CHECK(tressvk_set_frame(inst.handle(), &f) == TVK_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(tressvk_last_error(ctx.get())).find("transform.rotation") != std::string::npos);
    // A refused frame leaves the instance simulating: a good frame still runs.
    f = TVK_SIM_FRAME_DEFAULT_INIT;
    f.dt = 1.0f / 60.0f;
    inst.run_frame(f);
    CHECK(inst.stats().nonfinite_strand_resets == 0u);
    CHECK(inst.stats().frames == 1u);
  }
  tressvk_destroy_asset(a);
}
