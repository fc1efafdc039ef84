#include "hard_cases.hpp"

#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/model/math.hpp>
#include <tressvk/reference/near_duplicates.hpp>
#include <tressvk/reference/scaling.hpp>

#include <cmath>
#include <limits>
#include <numbers>

namespace tressvk::bench {
namespace {

using model::Vec3;

asset::HairAsset builtin(const char* name, uint32_t guides, uint32_t n = 0) {
  baker::BuiltinGroomOptions o;
  o.guide_count = guides;
  o.vertices_per_strand = n;
  return baker::make_builtin_groom(name, o);
}

std::function<TvkSimFrame(uint32_t, const reference::SceneGeometry&)> scene(std::string name) {
  return [name](uint32_t f, const reference::SceneGeometry& g) { return reference::scene_frame(name, f, g); };
}

// Tight curls: helices of radius 4 mm and pitch 8 mm, 6 cm tall (about 0.19 m of hair, 7.5 turns), at 64 vertices
// (8.5 per turn), rooted on the upper half of a 0.1 m head like the built-in grooms.
asset::HairAsset tight_curls(uint32_t guides) {
  baker::RawGroom raw;
  raw.group_names = {"tight"};
  const double pi = std::numbers::pi, radius = 0.004, pitch = 0.008, height = 0.06;
  for (uint32_t i = 0; i < guides; ++i) {
    const double y = 1.0 - (i + 0.5) / guides;
    const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
    const double phi = 2.399963229728653 * i;
    const Vec3 n{r * std::cos(phi), y, r * std::sin(phi)};
    const Vec3 a = std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
    const Vec3 u = model::normalize(model::cross(n, a)), w = model::cross(n, u);
    const Vec3 root = 0.1 * n, centre = root - radius * u;
    std::vector<baker::Vec3> poly;
    const int points = static_cast<int>(height / pitch * 48);
    for (int k = 0; k <= points; ++k) {
      const double t = 2.0 * pi * k / 48.0;
      const Vec3 p = centre + (pitch * t / (2.0 * pi)) * n + radius * (std::cos(t) * u + std::sin(t) * w);
      poly.push_back({p.x, p.y, p.z});
    }
    raw.add_strand(poly.data(), poly.size(), 0);
  }
  raw.input_vertices = raw.points.size();
  baker::BakeOptions o;
  o.vertices_per_strand = 64;
  return baker::bake(raw, o);
}

HardCase scaled_case(double s) {
  HardCase c;
  c.name = s < 1 ? "groom scaled 1/100" : "groom scaled 100x";
  c.setup = std::string("straight 16 x 32 at ") + (s < 1 ? "1/100" : "100x") +
            " (every length, gravity, speed limit and VSP threshold scaled), shake";
  c.unscaled_groom = builtin("straight", 16);
  c.groom = reference::scaled_groom(c.unscaled_groom, s);
  reference::scale_inputs(s, c.params, c.settings);
  c.frame_of = scene("shake");
  c.against = ModelErrorAgainst::kUnscaled;
  c.scale = s;
  c.reference_scene = "shake";
  c.max_model_error = 1e-4;
  c.criteria_reason =
      "model error: the GPU trajectory / scale against the unscaled groom on the double reference; float32 rounding "
      "at the scaled size grows along the trajectory; measured 6.2e-6 to 8.8e-6 (lavapipe, NVIDIA H100), 1e-4 leaves "
      "room for it";
  return c;
}

// A case of a groom in a scene at the default settings, judged by the default criteria.
HardCase basic(std::string name, std::string setup, asset::HairAsset groom,
               std::function<TvkSimFrame(uint32_t, const reference::SceneGeometry&)> frame_of = {},
               uint32_t frames = 60) {
  HardCase c;
  c.name = std::move(name);
  c.setup = std::move(setup);
  c.groom = std::move(groom);
  c.frame_of = std::move(frame_of);
  c.frames = frames;
  return c;
}

}  // namespace

std::vector<HardCase> hard_cases() {
  std::vector<HardCase> out;
  {
    HardCase c = basic("stiff strands",
                       "curly 16 x 32, local stiffness 1, global stiffness 1, 8 local iterations, shake",
                       builtin("curly", 16));
    c.params.local_stiffness = 1.0f;
    c.params.global_stiffness = 1.0f;
    c.params.local_iterations = 8;
    c.frame_of = scene("shake");
    out.push_back(std::move(c));
  }
  // Grooms in a scene at the default settings ("helices": tight_curls, otherwise a built-in groom).
  struct Plain {
    const char* name;
    const char* setup;
    const char* groom;
    uint32_t guides;
    const char* scene;
    uint32_t frames;
  };
  const Plain plain[] = {
      {"128-vertex strands", "long128 8 x 128 (0.5 m), run (capsules for head and shoulders)", "long128", 8, "run", 60},
      {"tight curls", "12 helices of radius 4 mm, pitch 8 mm, 64 vertices (8.5 per turn), shake", "helices", 12,
       "shake", 60},
      {"frame hitch", "curly 16 x 32, hitch (frames alternate 1/60 s and 0.25 s while the head turns and walks)",
       "curly", 16, "hitch", 60},
      {"teleport", "straight 16 x 32, teleport (a 1 m, 90 degree jump flagged as a teleport at frame 60)", "straight",
       16, "teleport", 72},
  };
  for (const Plain& c : plain) {
    asset::HairAsset groom = std::string(c.groom) == "helices" ? tight_curls(c.guides) : builtin(c.groom, c.guides);
    out.push_back(basic(c.name, c.setup, std::move(groom), scene(c.scene), c.frames));
  }
  {
    HardCase c = basic("fast head motion",
                       "curly 16 x 32, the shake script at 3x speed (+-60 degrees at 6 Hz)",
                       builtin("curly", 16));
    // Frame f shows the shake script's pose of frame 3f + 2 (its motion 3x as fast), each frame still 1/60 s long.
    c.frame_of = [](uint32_t f, const reference::SceneGeometry& g) { return reference::scene_frame("shake", 3 * f + 2, g); };
    out.push_back(std::move(c));
  }
  {
    HardCase c = basic("10 km from the origin",
                       "straight 16 x 32, far (shake 10 km along +X)",
                       builtin("straight", 16));
    c.frame_of = scene("far");
    c.against = ModelErrorAgainst::kShake;
    c.reference_scene = "shake";
    c.max_model_error = 1e-4;
    c.criteria_reason = "model error: against shake at the origin on the double reference; the same bound as the 1/100 "
                        "and 100x grooms (float32 rounding grown along the trajectory; measured 2.9e-6 lavapipe, 3.5e-6 NVIDIA H100)";
    out.push_back(std::move(c));
  }
  out.push_back(basic("zero-length and duplicate vertices",
                      "straight 8 x 32 with segments of 0.1-0.2 um (a vertex next to its parent, a tip on its "
                      "parent, a cluster of 4 vertices within 0.4 um; respaced evenly on load), shake",
                      reference::with_near_duplicate_vertices(builtin("straight", 8)),
                      scene("shake")));
  {
    HardCase c = basic("perfectly straight strands",
                       "straight 16 x 32 (every frame's bend direction ill-defined), settle then shake",
                       builtin("straight", 16));
    c.frame_of = [](uint32_t f, const reference::SceneGeometry& g) {
      return reference::scene_frame(f < 20 ? "settle" : "shake", f < 20 ? f : f - 20, g);
    };
    out.push_back(std::move(c));
  }
  {
    HardCase c = basic("roots deep inside a collider",
                       "curly 16 x 32, run with the head capsule's radius 1.25x the scalp's (roots 20 % of the "
                       "radius inside)",
                       builtin("curly", 16));
    c.frame_of = [](uint32_t f, const reference::SceneGeometry& g) {
      TvkSimFrame fr = reference::scene_frame("run", f, g);
      fr.capsules[0].r0 = fr.capsules[0].r1 = static_cast<float>(1.25 * g.head_radius);
      return fr;
    };
    out.push_back(std::move(c));
  }
  {
    HardCase c = basic("extreme wind",
                       "curly 16 x 32, wind of 100 m/s^2 (10 g) gusting +-80 % at 0.5 Hz",
                       builtin("curly", 16));
    c.frame_of = [](uint32_t f, const reference::SceneGeometry& g) {
      TvkSimFrame fr = reference::scene_frame("wind", f, g);
      fr.wind.strength = 100.0f;
      return fr;
    };
    out.push_back(std::move(c));
  }
  {
    HardCase c = basic("NaN/Inf in host transforms",
                       "straight 8 x 32, run; frames 10-18 (even) carry a NaN translation, an Inf rotation, a NaN "
                       "capsule end, an Inf capsule radius and a NaN wind strength",
                       builtin("straight", 8));
    c.frames = 30;
    c.frame_of = [](uint32_t f, const reference::SceneGeometry& g) {
      TvkSimFrame fr = reference::scene_frame("run", f, g);
      const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
      switch (f) {
        case 10: fr.transform.translation[1] = nan; break;
        case 12: fr.transform.rotation[2] = inf; break;
        case 14: fr.capsules[1].p0[0] = static_cast<float>(nan); break;
        case 16: fr.capsules[0].r1 = static_cast<float>(inf); break;
        case 18: fr.wind.strength = static_cast<float>(nan); break;
        default: break;
      }
      return fr;
    };
    c.expected_refusals = 5;
    out.push_back(std::move(c));
  }
  {
    HardCase c = basic("strands pinned at both ends",
                       "curly 8 x 32 with every other strand's tip pinned too (TressFX bothEndsImmovable), shake",
                       builtin("curly", 8));
    const uint32_t n = c.groom.vertices_per_strand;
    for (uint32_t g = 0; g < c.groom.guide_count(); g += 2) c.groom.rest_positions[size_t{g} * n + n - 1][3] = 0.0f;
    c.frame_of = scene("shake");
    out.push_back(std::move(c));
  }
  out.push_back(scaled_case(0.01));
  out.push_back(scaled_case(100.0));
  return out;
}

}  // namespace tressvk::bench
