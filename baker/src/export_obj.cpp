#include "vec_math.hpp"

#include <tressvk/baker/export.hpp>

#include <charconv>

namespace tressvk::baker {
namespace {

void append_number(std::string& out, double v) {
  char buf[32];
  // Shortest form that reads back as the same double: exports are exact and deterministic.
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  (void)ec;
  out.append(buf, end);
}

}  // namespace

std::string export_obj(const asset::HairAsset& a, bool include_follows) {
  std::string out = "# tressvk-bake export: strands as polylines, root first, metres, +Y up\n";
  const uint32_t n = a.vertices_per_strand, g = a.guide_count();
  const uint32_t k = include_follows ? a.follow_per_guide : 0;
  const Vec3 origin{a.origin[0], a.origin[1], a.origin[2]};
  uint64_t next_vertex = 1;
  int last_group = -1;
  // Rendered order: all guides, then follow layer 0 of every guide, and so on (asset.hpp).
  for (uint32_t layer = 0; layer <= k; ++layer) {
    for (uint32_t s = 0; s < g; ++s) {
      if (a.guide_group[s] != last_group) {
        last_group = a.guide_group[s];
        out += "g " + a.groups[a.guide_group[s]].name + "\n";
      }
      Vec3 offset{0, 0, 0};
      if (layer > 0) {
        const auto& q = a.rest_frames[s * n];
        const auto& f = a.follow_offsets[s * a.follow_per_guide + layer - 1];
        offset = rotate(Quat{q[0], q[1], q[2], q[3]}, Vec3{f[0], f[1], f[2]});
      }
      for (uint32_t v = 0; v < n; ++v) {
        const auto& p = a.rest_positions[s * n + v];
        const double spread = 1.0 + double{a.tip_separation} * v / (n - 1.0);
        const Vec3 w = origin + Vec3{p[0], p[1], p[2]} + offset * spread;
        out += "v ";
        append_number(out, w[0]);
        out += ' ';
        append_number(out, w[1]);
        out += ' ';
        append_number(out, w[2]);
        out += '\n';
      }
      out += 'l';
      for (uint32_t v = 0; v < n; ++v) out += ' ' + std::to_string(next_vertex + v);
      out += '\n';
      next_vertex += n;
    }
  }
  return out;
}

}  // namespace tressvk::baker
