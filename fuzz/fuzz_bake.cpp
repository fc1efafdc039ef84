// libFuzzer target: the whole bake, input bytes -> RawGroom -> HairAsset -> validate -> write -> read.
// The first four bytes are the options (the CLI's flags), the rest is the file:
//   byte 0: bit 0 format (0 OBJ, 1 .tfx), bit 1 up axis Z, bit 2 no LOD shuffle, bits 3..5 units/scale,
//           bit 6 OBJ roots from the faces, bit 7 skip invalid OBJ strands
//   byte 1: vertices per strand 4 + b % 125        byte 2: follow hairs per guide b % 9
//   byte 3: pinned root vertices b % 8, bits 3..7 the seed
#include "fuzz_common.hpp"

#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/import.hpp>

#include <string_view>

using namespace tressvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 4) return 0;
  const uint8_t flags = data[0];
  baker::BakeOptions o;
  o.up = (flags & 2) ? baker::UpAxis::kZ : baker::UpAxis::kY;
  o.shuffle = (flags & 4) == 0;
  static constexpr double kScales[8] = {1.0, 0.01, 0.001, 0.0254, 1e-6, 1e6, 1e-30, 1e30};
  o.units_to_metres = kScales[(flags >> 3) & 7];
  o.vertices_per_strand = 4u + data[1] % 125u;
  o.follow_per_guide = data[2] % 9u;
  o.pin = data[3] % 8u;
  o.seed = data[3] >> 3;
  const uint8_t* file = data + 4;
  const size_t file_size = size - 4;
  try {
    baker::RawGroom g;
    if (flags & 1) {
      g = baker::import_tfx_bytes(fuzz::as_bytes(file, file_size), "fuzz.tfx");
    } else {
      baker::ObjImportOptions io;
      io.root_from = (flags & 64) ? baker::RootFrom::kFaces : baker::RootFrom::kIndex;
      io.skip_invalid = (flags & 128) != 0;
      g = baker::import_obj_text(std::string_view(reinterpret_cast<const char*>(file), file_size), "fuzz.obj", io);
    }
    baker::BakeReport report;
    const asset::HairAsset a = baker::bake(g, o, &report);
    if (a.vertices_per_strand != o.vertices_per_strand) fuzz::finding("the bake changed N");
    if (a.follow_per_guide != o.follow_per_guide) fuzz::finding("the bake changed the follow count");
    fuzz::check_asset(a, "bake()");
  } catch (const baker::InputError&) {
  }
  return 0;
}
