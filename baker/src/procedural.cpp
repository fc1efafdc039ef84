// Built-in procedural grooms (see procedural.hpp): polylines generated finely, then baked like any import.
#include "vec_math.hpp"

#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/procedural.hpp>

#include <stdexcept>

namespace tressvk::baker {
namespace {

constexpr double kHeadRadius = 0.1;
constexpr double kPi = 3.14159265358979323846;

enum class Kind { kStraight, kCurly, kLong };

// Two unit vectors perpendicular to n and to each other.
void basis(const Vec3& n, Vec3& u, Vec3& w) {
  const Vec3 a = std::abs(n[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
  u = normalized(cross(n, a));
  w = cross(n, u);
}

RawGroom generate(Kind kind, uint32_t guides, uint64_t seed) {
  RawGroom g;
  g.group_names = {kind == Kind::kStraight ? "straight" : kind == Kind::kCurly ? "curly" : "long128"};
  Random rng(seed);
  const double spin = 2.0 * kPi * rng.uniform();
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  std::vector<Vec3> poly;
  for (uint32_t i = 0; i < guides; ++i) {
    // Fibonacci spiral over the upper hemisphere: equal-area bands in y keep the root density even.
    const double y = 1.0 - (i + 0.5) / guides;
    const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
    const double phi = spin + golden * i;
    const Vec3 n{r * std::cos(phi), y, r * std::sin(phi)};
    const Vec3 root = n * kHeadRadius;
    Vec3 u, w;
    basis(n, u, w);
    poly.clear();
    switch (kind) {
      case Kind::kStraight: {
        constexpr double kLength = 0.15;
        for (int k = 0; k <= 64; ++k) poly.push_back(root + n * (kLength * k / 64.0));
        break;
      }
      case Kind::kCurly: {
        constexpr double kRadius = 0.01, kPitch = 0.02, kHeight = 0.15;
        constexpr int kPointsPerTurn = 24;
        const double phase = 2.0 * kPi * rng.uniform();
        const int points = static_cast<int>(kHeight / kPitch * kPointsPerTurn);
        // Axis offset so the helix starts exactly at the root.
        const Vec3 centre = root - (u * std::cos(phase) + w * std::sin(phase)) * kRadius;
        for (int k = 0; k <= points; ++k) {
          const double t = 2.0 * kPi * k / kPointsPerTurn;
          poly.push_back(centre + n * (kPitch * t / (2.0 * kPi)) +
                         (u * std::cos(phase + t) + w * std::sin(phase + t)) * kRadius);
        }
        break;
      }
      case Kind::kLong: {
        constexpr double kLength = 0.5;
        constexpr int kSteps = 512;
        const double ds = kLength / kSteps;
        // Direction turns from the scalp normal towards -Y along the strand, like hair combed down.
        Vec3 p = root;
        poly.push_back(p);
        for (int k = 0; k < kSteps; ++k) {
          const double s = (k + 0.5) / kSteps;
          const double bend = std::min(1.0, 3.0 * s);
          const Vec3 d = normalized(n * (1.0 - bend) + (Vec3{n[0], 0.0, n[2]} * 0.35 + Vec3{0, -1, 0}) * bend);
          p = p + d * ds;
          poly.push_back(p);
        }
        break;
      }
    }
    g.add_strand(poly.data(), poly.size(), 0);
  }
  g.input_vertices = g.points.size();
  return g;
}

}  // namespace

std::vector<std::string> builtin_groom_names() { return {"straight", "curly", "long128"}; }

asset::HairAsset make_builtin_groom(std::string_view name, const BuiltinGroomOptions& options) {
  Kind kind;
  if (name == "straight") kind = Kind::kStraight;
  else if (name == "curly") kind = Kind::kCurly;
  else if (name == "long128") kind = Kind::kLong;
  else throw std::invalid_argument("unknown built-in groom '" + std::string(name) + "' (straight, curly, long128)");
  if (options.guide_count == 0) throw std::invalid_argument("built-in groom: guide_count must be > 0");
  BakeOptions bake_options;
  bake_options.vertices_per_strand =
      options.vertices_per_strand ? options.vertices_per_strand : (kind == Kind::kLong ? 128u : 32u);
  if (bake_options.vertices_per_strand < asset::kMinVerticesPerStrand ||
      bake_options.vertices_per_strand > asset::kMaxVerticesPerStrand)
    throw std::invalid_argument("built-in groom: vertices_per_strand must be 4..128");
  bake_options.follow_per_guide = options.follow_per_guide;
  bake_options.seed = options.seed;
  bake_options.follow_radius = 0.008;  // 8 mm: a little under the root spacing of 1024 guides on the scalp
  return bake(generate(kind, options.guide_count, options.seed), bake_options);
}

}  // namespace tressvk::baker
