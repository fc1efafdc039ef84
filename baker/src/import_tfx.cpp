// TressFX .tfx (v3: 296-byte header, float3; v4: 160-byte header, float4 + optional strand UVs). Layouts:
// shared/notes/tressfx-reference.md §2. Every field read is bounds-checked; messages name the file, the field
// and its byte offset.
#include "binary_cursor.hpp"
#include "vec_math.hpp"

#include <tressvk/baker/import.hpp>

namespace tressvk::baker {

RawGroom import_tfx_bytes(std::span<const std::byte> b, std::string_view name) {
  auto fail = [&](const std::string& what) { throw InputError(std::string(name) + ": " + what); };
  if (b.empty()) fail("empty file");
  if (b.size() < 160) fail("file of " + std::to_string(b.size()) + " bytes is shorter than a .tfx header");
  const float version = load<float>(b, 0);
  const bool v3 = version >= 3.0f && version < 4.0f;
  const bool v4 = version >= 4.0f && version < 6.0f;
  if (!v3 && !v4) fail("header field version (offset 0) is " + std::to_string(version) + ": not a .tfx 3.x or 4.x file");
  const uint32_t strands = load<uint32_t>(b, 4);
  const uint32_t n = load<uint32_t>(b, 8);
  uint64_t pos_offset = 0, uv_offset = 0;
  bool both_ends = false;
  uint64_t stride = 0;
  if (v3) {
    if (b.size() < 296) fail("file of " + std::to_string(b.size()) + " bytes is shorter than the .tfx v3 header (296)");
    both_ends = load<int32_t>(b, 16) != 0;
    pos_offset = load<uint32_t>(b, 144);
    if (pos_offset == 0) pos_offset = 296;
    stride = 12;
  } else {
    pos_offset = load<uint32_t>(b, 12);
    uv_offset = load<uint32_t>(b, 16);  // 0 = no strand UVs (never read header bytes as UVs)
    if (pos_offset == 0) pos_offset = 160;
    stride = 16;
  }
  if (strands == 0) fail("header field numHairStrands (offset 4) is 0: no hair");
  if (n < 2 || n > 4096) fail("header field numVerticesPerStrand (offset 8) is " + std::to_string(n) + ": expected 2..4096");
  const uint64_t vertex_count = uint64_t{strands} * n;
  if (pos_offset > b.size() || vertex_count > (b.size() - pos_offset) / stride)
    fail("positions (" + std::to_string(strands) + " strands x " + std::to_string(n) + " vertices at offset " +
         std::to_string(pos_offset) + ") run past the end of the file (" + std::to_string(b.size()) + " bytes)");
  if (uv_offset != 0 && (uv_offset > b.size() || strands > (b.size() - uv_offset) / 8))
    fail("header field offsetStrandUV (offset 16) = " + std::to_string(uv_offset) + ": strand UVs run past the end of the file");

  RawGroom g;
  g.group_names = {stem_of(name)};
  g.points.reserve(vertex_count);
  std::vector<Vec3> strand(n);
  for (uint32_t s = 0; s < strands; ++s) {
    for (uint32_t v = 0; v < n; ++v) {
      const uint64_t at = pos_offset + (uint64_t{s} * n + v) * stride;
      const float x = load<float>(b, at), y = load<float>(b, at + 4), z = load<float>(b, at + 8);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        fail("strand " + std::to_string(s) + " vertex " + std::to_string(v) + ": non-finite position (byte offset " +
             std::to_string(at) + ")");
      strand[v] = {x, y, z};
    }
    g.add_strand(strand.data(), n, 0, both_ends);
  }
  if (uv_offset) {
    g.strand_uv.resize(strands);
    for (uint32_t s = 0; s < strands; ++s) {
      const float u = load<float>(b, uv_offset + 8ull * s), v = load<float>(b, uv_offset + 8ull * s + 4);
      if (!std::isfinite(u) || !std::isfinite(v)) fail("strand " + std::to_string(s) + ": non-finite strand UV");
      g.strand_uv[s] = {u, v};
    }
  }
  g.input_vertices = vertex_count;
  return g;
}

RawGroom import_tfx(const std::filesystem::path& path) {
  const auto bytes = read_binary_file(path);
  return import_tfx_bytes(bytes, path.string());
}

}  // namespace tressvk::baker
