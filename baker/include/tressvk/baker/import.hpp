// Importers: OBJ polylines, TressFX .tfx (v3 and v4) and .tfxbone (4.x and 5.x layouts) into a RawGroom.
// All throw InputError (message names the file and line or field) or IoError; none of them crashes on garbage.
#pragma once

#include <tressvk/baker/raw_groom.hpp>

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace tressvk::baker {

enum class RootFrom {
  kIndex,  // the end with the lower OBJ vertex index; for a multi-index `l` record, its first index
  kFaces,  // the end nearer the faces of the same OBJ file (the scalp)
};

struct ObjImportOptions {
  RootFrom root_from = RootFrom::kIndex;
  bool skip_invalid = false;  // drop branching or looping strands (counted) instead of refusing the file
};

// A triangle mesh used to decide which end of a strand is the root (the end nearer its surface).
struct ScalpMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
};

// `name` is used in messages and as the default group name (OBJ strands outside any `o`/`g`).
RawGroom import_obj_text(std::string_view text, std::string_view name, const ObjImportOptions& options = {},
                         ScalpMesh* faces_out = nullptr);
RawGroom import_obj(const std::filesystem::path& path, const ObjImportOptions& options = {});
// Reads the faces of an OBJ file (its polylines are ignored). InputError when it has no faces.
ScalpMesh load_scalp(const std::filesystem::path& path);
// Reverses every strand whose last vertex is nearer the scalp surface than its first (a uniform grid over the
// triangles keeps this near O(strands) for real scalps).
void orient_to_scalp(RawGroom& groom, const ScalpMesh& scalp);
// Distance from p to the scalp surface, through the grid and by brute force (the latter for tests).
double distance_to_scalp(const Vec3& p, const ScalpMesh& scalp);
double distance_to_scalp_brute_force(const Vec3& p, const ScalpMesh& scalp);

RawGroom import_tfx_bytes(std::span<const std::byte> bytes, std::string_view name);
RawGroom import_tfx(const std::filesystem::path& path);

// Attaches .tfxbone weights (strand i of the file -> strand i of the groom, which must come from one .tfx):
// keeps the 4 largest influences of each strand, renormalised, and counts what was dropped.
void apply_tfxbone_bytes(RawGroom& groom, std::span<const std::byte> bytes, std::string_view name);
void apply_tfxbone(RawGroom& groom, const std::filesystem::path& path);

// Picks the importer from the extension (.obj, .tfx), falling back to the content.
RawGroom import_file(const std::filesystem::path& path, const ObjImportOptions& options = {});

// Whole file into memory; IoError naming the file on failure.
std::vector<std::byte> read_binary_file(const std::filesystem::path& path);

}  // namespace tressvk::baker
