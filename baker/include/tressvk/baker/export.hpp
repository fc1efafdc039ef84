// A baked asset back to OBJ polylines: one `l` record per strand, root first, absolute positions in metres,
// `g` records for strand groups. For looking at an asset in Blender and for round-trip tests.
#pragma once

#include <tressvk/asset.hpp>

#include <string>

namespace tressvk::baker {

// With `include_follows`, follow hairs are written too, at their rest pose (root frame = rest frame 0).
std::string export_obj(const asset::HairAsset& asset, bool include_follows);

}  // namespace tressvk::baker
