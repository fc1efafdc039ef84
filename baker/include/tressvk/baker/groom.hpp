// The groom generator: hair grown from a scalp mesh's faces with the controls groomers use, deterministic from a
// seed (the same scalp, preset, options and seed give the same asset, byte for byte).
//
// Conventions: the scalp is in metres, +Y up, the face looking down +Z (the sample head's space; OBJ exported
// from Blender with "Y up, -Z forward" is in it). Roots are placed on the scalp's faces area-weighted (stratified
// over the area, so coverage is even); every guide is grown as a fine polyline and then baked like any import
// (resampling, rest frames, follow hairs, level-of-detail order).
//
// Growth, per guide, in order:
//   1. length: `length` x (1 + `length_variation` x uniform(-1, 1)) x the length map at the root (the red channel
//      of the scalp OBJ's vertex colours, `v x y z r g b`, as Blender writes them; 1 where there are none);
//   2. comb: the root leaves the scalp along its surface, away from the parting (a line over the top of the head
//      from the forehead to the crown at x = `parting` x the scalp's half width) and back from the face;
//   3. gravity: the direction turns towards -Y as the strand leaves its root (`gravity`: how soon straight hair
//      falls), lying on the head's shape over the top (an axis-aligned ellipsoid fitted to the scalp, a little
//      outside it, one layer per strand) and kept out of it below; strands never hang in front of the face (+Z,
//      from the brows to the chin): they are moved to its sides;
//   4. clumping: strands are gathered into clumps of about `clump_size` guides; a strand moves towards its
//      clump's centre strand, none at the root and `clump` (0..1) of the way at the tip;
//   5. curl: a helix of radius `curl_radius` (m) and `curl_frequency` (turns per metre of strand) around the
//      combed path, one phase per clump (ringlets), easing in over the first centimetres;
//   6. frizz: smooth random displacement growing to `frizz` (m) at the tip.
// Taper (the tip's width over the root's) is not geometry in a .tvkhair asset: it is recorded in the asset's
// bake settings as "taper" for hosts to use as TvkHairMaterial::tip_width_ratio (tressvk-demo does).
#pragma once

#include <tressvk/asset.hpp>
#include <tressvk/baker/raw_groom.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tressvk::baker {

// A scalp for the generator: triangles, and optionally a length-map value per vertex.
struct GroomScalp {
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<double> length_map;  // empty, or one per vertex (OBJ vertex colour red channel, 0..1)
};

// Reads an OBJ scalp: `v x y z [r g b]` and `f` records (polygons fanned into triangles; `v/vt/vn` forms and
// negative indices accepted), everything else ignored. InputError naming the file and line for a malformed
// record, and "has no faces" when there are none; IoError when the file cannot be read.
GroomScalp load_groom_scalp(const std::filesystem::path& path);
GroomScalp parse_groom_scalp(std::string_view text, std::string_view name);
// The scalp as OBJ text (vertex colours written when there is a length map), %.9g: for the sample head.
std::string groom_scalp_obj(const GroomScalp& scalp);

struct GroomParams {
  uint32_t guides = 1500;          // guide strands
  uint32_t follow = 6;             // follow hairs per guide (made by the bake)
  uint32_t vertices = 32;          // vertices per strand after resampling
  uint64_t seed = 1;
  double length = 0.3;             // m
  double length_variation = 0.15;  // 0..1, +- fraction
  bool parting_on = true;
  double parting = 0.3;            // -1..1: the parting's x over the scalp's half width (+x = the head's left)
  double gravity = 1.0;            // 0..10: 0 = strands keep their combed direction, 1 = straight hair falls
  double lift = 0.35;              // 0..1: how much roots stand up from the scalp before the comb lays them down
  double clump = 0.35;             // 0..1
  double clump_size = 10.0;        // guides per clump, >= 1
  double curl_radius = 0.0;        // m
  double curl_frequency = 0.0;     // turns per metre
  double frizz = 0.0;              // m at the tip
  double taper = 0.25;             // tip width / root width, 0..1 (recorded, see above)
};

// The named presets: "straight" (shoulder-length straight with a side parting) and "curly" (shoulder-length
// ringlets). InputError for an unknown name (the message lists the names).
GroomParams groom_preset(std::string_view name);
std::vector<std::string> groom_preset_names();

struct GroomReport {
  uint32_t scalp_triangles = 0;
  double scalp_area = 0.0;          // m^2
  std::array<double, 3> head_center{};  // the sphere fitted to the scalp
  double head_radius = 0.0;
  double mean_length = 0.0;         // m, of the grown polylines
};

// Grows the guides as polylines (root first, metres). InputError for out-of-range parameters or an unusable
// scalp (no triangles with area, a vertex index out of range).
RawGroom grow_groom(const GroomScalp& scalp, const GroomParams& params, GroomReport* report = nullptr);
// grow_groom + bake, with the parameters recorded in the asset's bake settings.
asset::HairAsset make_groom(const GroomScalp& scalp, const GroomParams& params, std::string_view preset_name,
                            GroomReport* report = nullptr);

}  // namespace tressvk::baker
