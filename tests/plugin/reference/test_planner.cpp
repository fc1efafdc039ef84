// The frame planner: fixed steps with an accumulator, the cap, interpolation, teleport/reset, far translation,
// and the GPU conversion.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "helpers.hpp"

using namespace tvk_test;

namespace {

// The planner tests use a 120 Hz step with a cap of 4, independent of the library defaults.
TvkSimSettings settings_120hz() {
  TvkSimSettings s = TVK_SIM_SETTINGS_DEFAULT_INIT;
  s.time.step_rate = 120.0f;
  s.time.max_steps_per_frame = 4;
  return s;
}

TvkSimFrame still_frame(double dt) {
  TvkSimFrame f{};
  f.dt = static_cast<float>(dt);
  f.transform = TVK_INSTANCE_TRANSFORM_DEFAULT_INIT;
  f.wind = TVK_WIND_DEFAULT_INIT;
  return f;
}

// All non-reset step times of a sequence of frames of length dt adding up to `total`.
std::vector<double> step_times(double dt, int frames) {
  // A cap high enough never to bind: invariance under frame splitting holds as long as no step is dropped.
  TvkSimSettings settings = settings_120hz();
  settings.time.max_steps_per_frame = 8;
  FramePlanner planner(settings, {0, 0, 0}, 0);
  std::vector<double> times;
  for (int i = 0; i < frames; ++i) {
    for (const Substep& s : planner.plan(still_frame(dt)).steps) {
      if (!s.reset) times.push_back(s.time);
    }
  }
  return times;
}

}  // namespace

TEST_CASE("planner: same steps for the same total time however the frames are split", "[reference][planner]") {
  const auto a = step_times(1.0 / 60.0, 60);
  const auto b = step_times(1.0 / 120.0, 120);
  const auto c = step_times(1.0 / 30.0, 30);
  const auto d = step_times(1.0 / 144.0, 144);
  REQUIRE(a.size() == 120);
  REQUIRE(b.size() == a.size());
  REQUIRE(c.size() == a.size());
  REQUIRE(d.size() == a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    REQUIRE(a[i] == b[i]);
    REQUIRE(a[i] == c[i]);
    REQUIRE(a[i] == d[i]);
  }
}

TEST_CASE("planner: every step has the fixed length and the first frame resets", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0, 0, 0}, 0);
  FramePlan first = planner.plan(still_frame(1.0 / 60.0));
  REQUIRE(first.steps.size() == 3);  // the zero-time reset step, then two steps of 1/120 s
  CHECK(first.steps[0].reset);
  CHECK_FALSE(first.steps[1].reset);
  for (const Substep& s : first.steps) CHECK(s.h == 1.0 / 120.0);
  FramePlan second = planner.plan(still_frame(1.0 / 60.0));
  REQUIRE(second.steps.size() == 2);
  CHECK_FALSE(second.steps[0].reset);
}

TEST_CASE("planner: a frame never plans more steps than the cap, the reset step included", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0, 0, 0}, 0);
  FramePlan first = planner.plan(still_frame(0.25));
  CHECK(first.steps.size() == 4);  // the reset step and 3 steps
  CHECK(first.steps[0].reset);
}

TEST_CASE("planner: a 0.25 s hitch is capped and the surplus dropped, not owed", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0, 0, 0}, 0);
  planner.plan(still_frame(1.0 / 60.0));
  FramePlan hitch = planner.plan(still_frame(0.25));
  CHECK(hitch.steps.size() == 4);
  CHECK(hitch.dropped_steps == 26);
  FramePlan after = planner.plan(still_frame(1.0 / 60.0));
  CHECK(after.steps.size() == 2);  // nothing carried over from the hitch
}

// A host that runs steadily slower than step_rate / max_steps_per_frame is not hitching: capping each of its frames
// ran the simulation in slow motion (20 fps at 120 Hz steps with a cap of 4: 4 of 6 steps, 67 % speed).
TEST_CASE("planner: a sustained low host rate runs every step; a hitch among short frames is still capped",
          "[reference][planner]") {
  auto simulated = [](const TvkSimSettings& settings, const std::vector<double>& dts) {
    FramePlanner planner(settings, {0, 0, 0}, 0);
    std::vector<uint32_t> steps;
    for (double dt : dts) {
      uint32_t n = 0;
      for (const Substep& s : planner.plan(still_frame(dt)).steps) n += s.reset ? 0u : 1u;
      steps.push_back(n);
    }
    return steps;
  };
  TvkSimSettings settings = settings_120hz();  // cap 4, max_steps_sustained 16 (the default)
  const std::vector<double> at_20fps(12, 1.0 / 20.0);
  const auto got = simulated(settings, at_20fps);
  // The first frames cannot tell a low rate from a hitch (half the 8-frame window must be seen): capped.
  CHECK(got[0] == 3);  // the reset step counts toward the cap
  CHECK(got[1] == 4);
  CHECK(got[2] == 4);
  for (size_t f = 3; f < got.size(); ++f) {
    INFO("frame " << f);
    CHECK(got[f] == 6);
  }
  // 0 keeps the old rule: every frame capped, slow motion.
  settings.time.max_steps_sustained = 0;
  for (uint32_t n : simulated(settings, at_20fps)) CHECK(n <= 4);
  // A 0.25 s hitch among 60 fps frames (2 steps each) is still a hitch.
  settings.time.max_steps_sustained = 16;
  std::vector<double> hitch(10, 1.0 / 60.0);
  hitch[6] = 0.25;
  const auto h = simulated(settings, hitch);
  CHECK(h[6] == 4);
  CHECK(h[7] == 2);
  // Three hitches in the last eight frames are still hitches; a rate that stays low for most of them is not.
  std::vector<double> mixed(12, 1.0 / 60.0);
  mixed[5] = mixed[7] = mixed[9] = 0.25;
  const auto m = simulated(settings, mixed);
  CHECK(m[9] == 4);
  // The cap while sustained is max_steps_sustained: 10 fps needs 12 steps a frame.
  settings.time.max_steps_sustained = 8;
  const auto slow = simulated(settings, std::vector<double>(8, 0.1));
  CHECK(slow.back() == 8);
}

TEST_CASE("planner: motion is interpolated across the steps of a frame", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0, 0, 0}, 0);
  planner.plan(still_frame(1.0 / 60.0));
  TvkSimFrame f = still_frame(1.0 / 30.0);  // 4 steps
  f.transform.translation[0] = 0.4;
  FramePlan plan = planner.plan(f);
  REQUIRE(plan.steps.size() == 4);
  for (const Substep& s : plan.steps) {
    CHECK(s.move_state);
    // The origin moves on a 1/1024 m grid (exact in float32); the remainder is in the skinning transform.
    CHECK(s.origin_shift.x == Catch::Approx(0.1).margin(1.0 / 1024));
    CHECK(std::ldexp(s.origin_shift.x, 10) == std::round(std::ldexp(s.origin_shift.x, 10)));
  }
  CHECK(plan.sim_origin[0] + plan.steps.back().skin[0].rows[0][3] == Catch::Approx(0.4).margin(1e-15));
}

TEST_CASE("planner: a frame shorter than a step carries its motion to the next step", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0, 0, 0}, 0);
  planner.plan(still_frame(1.0 / 120.0));
  TvkSimFrame f = still_frame(1.0 / 240.0);
  f.transform.translation[1] = 0.2;
  CHECK(planner.plan(f).steps.empty());
  f.transform.translation[1] = 0.3;
  FramePlan plan = planner.plan(f);
  REQUIRE(plan.steps.size() == 1);
  CHECK(plan.steps[0].origin_shift.y == Catch::Approx(0.3).margin(1.0 / 1024));
  CHECK(plan.sim_origin[1] + plan.steps[0].skin[0].rows[1][3] == Catch::Approx(0.3).margin(1e-15));
}

TEST_CASE("planner: a teleport is a rotation of the state about the origin and no shift", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0.0, 1.5, 0.0}, 0);
  planner.plan(still_frame(1.0 / 60.0));
  TvkSimFrame f = still_frame(1.0 / 60.0);
  f.teleport = 1;
  f.transform.translation[0] = 1.0;
  const double s = std::sqrt(0.5);
  f.transform.rotation[1] = s;
  f.transform.rotation[3] = s;
  FramePlan plan = planner.plan(f);
  REQUIRE(plan.steps.size() == 2);
  CHECK(plan.steps[0].move_state);
  CHECK(length(plan.steps[0].origin_shift) < 1e-15);
  CHECK(plan.steps[0].teleport.y == Catch::Approx(s).margin(1e-15));
  CHECK_FALSE(plan.steps[1].move_state);
}

TEST_CASE("planner: 10 km away plans the same simulation-space steps", "[reference][planner]") {
  FramePlanner near(settings_120hz(), {0.01, 1.6, -0.02}, 0);
  FramePlanner far(settings_120hz(), {0.01, 1.6, -0.02}, 0);
  for (int i = 0; i < 30; ++i) {
    TvkSimFrame f = still_frame(1.0 / 60.0);
    const double angle = 0.3 * std::sin(0.2 * i);
    f.transform.rotation[1] = std::sin(0.5 * angle);
    f.transform.rotation[3] = std::cos(0.5 * angle);
    f.transform.translation[2] = 0.01 * i;
    TvkSimFrame g = f;
    g.transform.translation[0] += 10000.0;
    FramePlan a = near.plan(f), b = far.plan(g);
    REQUIRE(a.steps.size() == b.steps.size());
    for (size_t k = 0; k < a.steps.size(); ++k) {
      CHECK(a.steps[k].origin_shift.x == b.steps[k].origin_shift.x);
      CHECK(a.steps[k].origin_shift.z == b.steps[k].origin_shift.z);
      CHECK(a.steps[k].skin[0].rows == b.steps[k].skin[0].rows);
    }
  }
}

TEST_CASE("planner: to_gpu keeps the layout the shaders read", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0, 0, 0}, 0);
  TvkSimFrame f = still_frame(1.0 / 60.0);
  f.capsule_count = 1;
  f.capsules[0] = TvkCapsule{{0, 0, 0}, 0.1f, {0, 1, 0}, 0.05f};
  FramePlan plan = planner.plan(f);
  GpuFrame gpu = to_gpu(plan);
  REQUIRE(gpu.steps.size() == plan.steps.size());
  CHECK(gpu.skin_stride == tressvk::sim::kSkinVec4PerBone);
  CHECK(gpu.skin.size() == plan.steps.size() * tressvk::sim::kSkinVec4PerBone);
  CHECK(gpu.steps[0].flags[0] == tressvk::sim::kStepReset);
  CHECK(gpu.steps[1].flags[1] == 1u);
  CHECK(gpu.steps[1].gravity[1] == Catch::Approx(-9.81 / (120.0 * 120.0)).epsilon(1e-6));
  CHECK(gpu.steps[1].capsule[1][3] == 0.05f);
  GroupStep g = to_group_step(resolve_params(default_params(), StrandModel::kFollowTheLeader), 1.0 / 120.0, 0.0, 1.0);
  CHECK(g.local_iterations == 2u);
  CHECK(g.velocity_keep == Catch::Approx(std::exp(-0.08 * 0.5)));
  CHECK(g.max_step == Catch::Approx(50.0 / 120.0));
  CHECK(g.vsp_threshold == Catch::Approx(100.0 / (120.0 * 120.0)));
  CHECK(g.local_stiffness == Catch::Approx(0.45));
}

// A skinned character's planner works out only the bones its strands read (FramePlanner::set_bone_source, from
// ModelRest::bone_source): each of them keeps, bit for bit, what a planner of every bone gives it, through
// interpolated steps, a teleport, a hitch and a frame without bones, on the planner and in the GPU data. The frames
// convert into one reused GpuFrame (to_gpu_into), as the plugin's do: reused storage must not change a bit either.
TEST_CASE("planner: a planner of the bones read gives each of them what a planner of every bone does",
          "[reference][planner]") {
  constexpr uint32_t kBones = 7;
  const std::vector<uint32_t> source = {1, 4, 6};  // bone 0 unread: the first compact bone is not the asset's first
  FramePlanner all(settings_120hz(), {0.01, 1.6, -0.02}, kBones);
  FramePlanner some(settings_120hz(), {0.01, 1.6, -0.02}, kBones);
  some.set_bone_source(source);
  CHECK(all.skin_bones() == kBones);
  CHECK(some.skin_bones() == source.size());
  CHECK_THROWS(some.set_bone_source({1, 7}));  // no bone 7
  CHECK_THROWS(some.set_bone_source({4, 1}));  // not increasing
  CHECK(some.skin_bones() == source.size());   // a refused source leaves the planner as it was
  std::vector<TvkBoneMatrix> bones(kBones, TvkBoneMatrix TVK_BONE_MATRIX_IDENTITY_INIT);
  uint32_t compared = 0;
  GpuFrame gb;  // reused frame after frame
  for (int i = 0; i < 40; ++i) {
    TvkSimFrame f = still_frame(i == 25 ? 0.25 : 1.0 / 50.0);  // 50 Hz: steps between frames; frame 25 a hitch
    f.transform.rotation[1] = std::sin(0.1 * std::sin(0.3 * i));
    f.transform.rotation[3] = std::cos(0.1 * std::sin(0.3 * i));
    f.transform.translation[2] = 0.02 * i;
    f.teleport = i == 12 ? 1 : 0;
    for (uint32_t b = 0; b < kBones; ++b) {
      const double a = 0.2 * std::sin(0.4 * i + 0.9 * b);
      const double c = std::cos(a), sn = std::sin(a);
      bones[b] = TvkBoneMatrix TVK_BONE_MATRIX_IDENTITY_INIT;
      bones[b].rows[0][0] = static_cast<float>(c);
      bones[b].rows[0][2] = static_cast<float>(sn);
      bones[b].rows[2][0] = static_cast<float>(-sn);
      bones[b].rows[2][2] = static_cast<float>(c);
      bones[b].rows[1][3] = static_cast<float>(0.01 * b * std::sin(0.2 * i));
    }
    const bool skinned = i != 30;  // frame 30 runs the rigid transform alone
    if (skinned) {
      f.bones = bones.data();
      f.bone_count = kBones;
    }
    const FramePlan a = all.plan(f);
    const FramePlan b = some.plan(f);
    REQUIRE(a.steps.size() == b.steps.size());
    const GpuFrame ga = to_gpu(a);
    to_gpu_into(b, gb);
    for (size_t k = 0; k < a.steps.size(); ++k) {
      CHECK(a.steps[k].skinned == skinned);
      CHECK(b.steps[k].skinned == skinned);
      REQUIRE(a.steps[k].skin.size() == (skinned ? kBones : 1u));
      REQUIRE(b.steps[k].skin.size() == (skinned ? source.size() : 1u));
      for (size_t t = 0; t < b.steps[k].skin.size(); ++t) {
        const size_t from = skinned ? source[t] : 0;
        const SkinTransform& x = a.steps[k].skin[from];
        const SkinTransform& y = b.steps[k].skin[t];
        CHECK(x.rows == y.rows);
        // The rigid frame's map change is measured from the previous step's first skin entry (bone 0 against bone 1
        // here): a switch between bones and the rigid transform has no per-bone history to compare with.
        if (skinned) CHECK(x.move_rows == y.move_rows);
        CHECK((x.rotation.x == y.rotation.x && x.rotation.w == y.rotation.w));
        CHECK((x.delta.x == y.delta.x && x.delta.y == y.delta.y && x.delta.w == y.delta.w));
        CHECK((x.delta_before.y == y.delta_before.y && x.delta_before.w == y.delta_before.w));
        const size_t at_a = (k * a.steps[k].skin.size() + from) * tressvk::sim::kSkinVec4PerBone;
        const size_t at_b = (k * b.steps[k].skin.size() + t) * tressvk::sim::kSkinVec4PerBone;
        for (uint32_t v = 0; v < tressvk::sim::kSkinVec4PerBone; ++v) {
          if (skinned || (v < 6)) CHECK(ga.skin[at_a + v] == gb.skin[at_b + v]);  // 6..8: the map change
        }
        ++compared;
      }
    }
    CHECK(gb.skin.size() == b.steps.size() * (skinned ? source.size() : 1u) * tressvk::sim::kSkinVec4PerBone);
    CHECK(gb.skin_stride == (skinned ? source.size() : 1u) * tressvk::sim::kSkinVec4PerBone);
    CHECK(ga.steps.size() == gb.steps.size());
    for (size_t k = 0; k < ga.steps.size() && k < gb.steps.size(); ++k)
      CHECK(std::memcmp(&ga.steps[k], &gb.steps[k], sizeof(ga.steps[k])) == 0);
  }
  CHECK(compared > 200);  // 39 skinned frames of 2-3 steps, 3 bones a step
}

TEST_CASE("planner: bad input is rejected with the field named", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0, 0, 0}, 0);
  TvkSimFrame f = still_frame(-1.0);
  CHECK_THROWS_WITH(planner.plan(f), Catch::Matchers::ContainsSubstring("dt"));
  f = still_frame(1.0 / 60.0);
  f.transform.rotation[3] = 0.0;
  CHECK_THROWS_WITH(planner.plan(f), Catch::Matchers::ContainsSubstring("transform.rotation"));
  TvkSimParams p = resolve_params(default_params(), StrandModel::kFollowTheLeader);
  p.length_iterations = 0;
  CHECK_THROWS_WITH(to_group_step(p, 1.0 / 120.0, 0.0, 1.0), Catch::Matchers::ContainsSubstring("length_iterations"));
  // A count left to the model is resolved before it is converted: unresolved, it is refused, not run as 2^32 - 1.
  CHECK_THROWS_WITH(to_group_step(default_params(), 1.0 / 120.0, 0.0, 1.0),
                    Catch::Matchers::ContainsSubstring("local_iterations"));
}

// The settings a host leaves to the model (TVK_STEP_RATE_BY_MODEL, TVK_ITERATIONS_BY_MODEL, both the defaults) are
// each model's own: follow-the-leader keeps 240 Hz and 2 iterations, the settings its look is tuned at, and the
// conservative model gets the 1 iteration at 120 Hz it is recommended at, 240 Hz for strands of more than 64
// vertices (docs/accuracy.md, "Which model, at which rate"). A value the host sets is never changed.
TEST_CASE("planner: what the settings leave to the model resolves to the model's rate and iterations",
          "[reference][planner]") {
  const TvkSimSettings defaults = TVK_SIM_SETTINGS_DEFAULT_INIT;
  const TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
  CHECK(defaults.time.step_rate == TVK_STEP_RATE_BY_MODEL);
  CHECK(params.local_iterations == TVK_ITERATIONS_BY_MODEL);
  struct Row {
    StrandModel model;
    uint32_t n;
    float rate;
    uint32_t iterations;
  };
  const Row rows[] = {{StrandModel::kFollowTheLeader, 32, 240.0f, 2u}, {StrandModel::kFollowTheLeader, 128, 240.0f, 2u},
                      {StrandModel::kCompliant, 32, 240.0f, 2u},       {StrandModel::kConservative, 16, 120.0f, 1u},
                      {StrandModel::kConservative, 64, 120.0f, 1u},    {StrandModel::kConservative, 65, 240.0f, 1u},
                      {StrandModel::kConservative, 128, 240.0f, 1u}};
  for (const Row& r : rows) {
    CAPTURE(static_cast<int>(r.model), r.n);
    CHECK(resolve_settings(defaults, r.model, r.n).time.step_rate == r.rate);
    CHECK(resolve_params(params, r.model).local_iterations == r.iterations);
    TvkSimSettings set = defaults;
    set.time.step_rate = 60.0f;
    TvkSimParams set_params = params;
    set_params.local_iterations = 3;
    CHECK(resolve_settings(set, r.model, r.n).time.step_rate == 60.0f);
    CHECK(resolve_params(set_params, r.model).local_iterations == 3u);
    set_params.local_iterations = 0;  // no local shape stays no local shape
    CHECK(resolve_params(set_params, r.model).local_iterations == 0u);
    // Everything else passes through unchanged.
    CHECK(resolve_settings(defaults, r.model, r.n).time.max_steps_per_frame == defaults.time.max_steps_per_frame);
    CHECK(resolve_params(params, r.model).length_iterations == params.length_iterations);
  }
  // The planner is handed resolved settings: a rate still left to the model is refused by name.
  CHECK_THROWS_WITH(FramePlanner(defaults, {0, 0, 0}, 0), Catch::Matchers::ContainsSubstring("time.step_rate"));
}

TEST_CASE("planner: every non-finite host number is refused naming its field", "[reference][planner]") {
  FramePlanner planner(settings_120hz(), {0, 0, 0}, 0);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const float finf = std::numeric_limits<float>::infinity(), fnan = std::numeric_limits<float>::quiet_NaN();
  struct Case {
    const char* field;
    std::function<void(TvkSimFrame&)> spoil;
  };
  const std::vector<Case> cases = {
      {"transform.translation[1]", [&](TvkSimFrame& f) { f.transform.translation[1] = nan; }},
      {"transform.translation[2]", [&](TvkSimFrame& f) { f.transform.translation[2] = inf; }},
      {"transform.rotation[0]", [&](TvkSimFrame& f) { f.transform.rotation[0] = nan; }},
      {"transform.rotation", [&](TvkSimFrame& f) { f.transform.rotation[3] = 0.0; }},  // zeroed quaternion
      {"capsules[1].p0", [&](TvkSimFrame& f) { f.capsule_count = 2; f.capsules[1].p0[0] = fnan; }},
      {"capsules[0].p1", [&](TvkSimFrame& f) { f.capsule_count = 1; f.capsules[0].p1[2] = finf; }},
      {"capsules[0] has a radius", [&](TvkSimFrame& f) { f.capsule_count = 1; f.capsules[0].r1 = finf; }},
      {"capsules[0] has a radius", [&](TvkSimFrame& f) { f.capsule_count = 1; f.capsules[0].r0 = fnan; }},
      {"wind.direction", [&](TvkSimFrame& f) { f.wind.direction[1] = fnan; }},
      {"wind.strength", [&](TvkSimFrame& f) { f.wind.strength = finf; }},
      {"wind.gust_amplitude", [&](TvkSimFrame& f) { f.wind.gust_amplitude = fnan; }},
      {"wind.gust_frequency", [&](TvkSimFrame& f) { f.wind.gust_frequency = finf; }},
      {"wind.cone_angle", [&](TvkSimFrame& f) { f.wind.cone_angle = fnan; }},
      {"dt", [&](TvkSimFrame& f) { f.dt = finf; }},
  };
  for (const Case& c : cases) {
    TvkSimFrame f = TVK_SIM_FRAME_DEFAULT_INIT;
    f.dt = 1.0f / 60.0f;
    c.spoil(f);
    INFO(c.field);
    CHECK_THROWS_WITH(validate_frame(f, 0), Catch::Matchers::ContainsSubstring(c.field));
    CHECK_THROWS_WITH(planner.plan(f), Catch::Matchers::ContainsSubstring(c.field));
  }
  // Bones: a NaN in a matrix names the bone.
  std::vector<TvkBoneMatrix> bones(3, TvkBoneMatrix TVK_BONE_MATRIX_IDENTITY_INIT);
  bones[2].rows[1][3] = fnan;
  TvkSimFrame f = TVK_SIM_FRAME_DEFAULT_INIT;
  f.bones = bones.data();
  f.bone_count = 3;
  CHECK_THROWS_WITH(validate_frame(f, 3), Catch::Matchers::ContainsSubstring("bones[2]"));
  // The default frame itself is valid, and so is a frame with finite values everywhere.
  TvkSimFrame ok = TVK_SIM_FRAME_DEFAULT_INIT;
  CHECK_NOTHROW(validate_frame(ok, 0));
  CHECK(ok.dt == 0.0f);
  CHECK(ok.transform.rotation[3] == 1.0);
  CHECK(ok.capsule_count == 0u);
}
