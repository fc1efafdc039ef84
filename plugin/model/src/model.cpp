#include "tressvk/model/model.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

namespace tressvk::model {
namespace {

Vec3 widen(const std::array<float, 4>& v) { return {v[0], v[1], v[2]}; }

sim::Vec4 narrow(Vec3 v, double w) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z), static_cast<float>(w)};
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("reference: asset field " + what);
}

// kRespaceBelowRel: where a free vertex's segment is shorter than that fraction of the strand's mean segment, every
// run of free vertices between two fixed points (a pinned vertex, or the free tip itself) is placed at equal arc
// length along the strand's polyline between them, rounded to float as the GPU holds it. Returns whether it did.
bool respace_short_segments(std::vector<Vec3>& pos, const std::vector<double>& inv_mass, size_t b, uint32_t n) {
  double total = 0;
  for (uint32_t v = 0; v + 1 < n; ++v) total += length(pos[b + v + 1] - pos[b + v]);
  const double floor_len = kRespaceBelowRel * total / (n - 1);
  bool short_free = false;
  for (uint32_t v = 0; v + 1 < n; ++v) {
    const bool free = inv_mass[b + v] > 0.0 || inv_mass[b + v + 1] > 0.0;
    short_free = short_free || (free && length(pos[b + v + 1] - pos[b + v]) < floor_len);
  }
  if (!short_free || !(total > 0.0)) return false;
  uint32_t v = 0;
  while (v < n) {
    if (!(inv_mass[b + v] > 0.0)) {
      ++v;
      continue;
    }
    // Free vertices start .. end; fixed points a (the vertex before, or the free root) and z (the pinned vertex after,
    // or the free tip).
    uint32_t end = v;
    while (end + 1 < n && inv_mass[b + end + 1] > 0.0) ++end;
    const uint32_t a = v > 0 ? v - 1 : v;
    const uint32_t z = end + 1 < n ? end + 1 : end;
    std::vector<double> arc(z - a + 1, 0.0);
    for (uint32_t k = a; k < z; ++k) arc[k - a + 1] = arc[k - a] + length(pos[b + k + 1] - pos[b + k]);
    const double run = arc.back();
    std::vector<Vec3> placed(z - a + 1);
    uint32_t seg = 0;
    for (uint32_t k = a + 1; k < z; ++k) {
      const double s = run * (k - a) / (z - a);
      while (seg + 1 < z - a && arc[seg + 1] < s) ++seg;
      const double len = arc[seg + 1] - arc[seg];
      const double t = len > 0.0 ? (s - arc[seg]) / len : 0.0;
      const Vec3 p = pos[b + a + seg] + t * (pos[b + a + seg + 1] - pos[b + a + seg]);
      placed[k - a] = Vec3{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
    }
    if (run > 0.0) {
      for (uint32_t k = a + 1; k < z; ++k) pos[b + k] = placed[k - a];
    }
    v = end + 1;
  }
  return true;
}

// Renumbers the guides' bones to the ones some guide reads (a nonzero weight), in the asset's order
// (ModelRest::bone_source); a zero weight's index becomes the guide's first weighted bone.
void compact_bones(ModelRest& m) {
  m.bone_source.clear();
  m.bone_count = 0;
  if (m.asset_bone_count == 0) return;
  std::vector<uint32_t> compact(m.asset_bone_count, UINT32_MAX);
  for (size_t g = 0; g < m.bone_index.size(); ++g)
    for (size_t k = 0; k < 4; ++k)
      if (m.bone_weight[g][k] != 0.0) compact[m.bone_index[g][k]] = 0;
  for (uint32_t b = 0; b < m.asset_bone_count; ++b) {
    if (compact[b] == UINT32_MAX) continue;
    compact[b] = static_cast<uint32_t>(m.bone_source.size());
    m.bone_source.push_back(b);
  }
  m.bone_count = static_cast<uint32_t>(m.bone_source.size());
  for (size_t g = 0; g < m.bone_index.size(); ++g) {
    uint32_t first = UINT32_MAX;
    for (size_t k = 0; k < 4; ++k)
      if (m.bone_weight[g][k] != 0.0 && first == UINT32_MAX) first = compact[m.bone_index[g][k]];
    for (size_t k = 0; k < 4; ++k)
      m.bone_index[g][k] = m.bone_weight[g][k] != 0.0 ? compact[m.bone_index[g][k]] : first;
  }
}

}  // namespace

ModelRest build_model_rest(const asset::HairAsset& a) {
  const uint32_t n = a.vertices_per_strand;
  require(n >= asset::kMinVerticesPerStrand && n <= asset::kMaxVerticesPerStrand,
          "vertices_per_strand out of range (" + std::to_string(n) + ")");
  require(a.rest_positions.size() % n == 0 && !a.rest_positions.empty(), "rest_positions: size not G*N");
  const uint32_t g_count = a.guide_count();
  const size_t vcount = size_t{g_count} * n;
  require(a.rest_frames.size() == vcount, "rest_frames: size not G*N");
  require(a.guide_group.empty() || a.guide_group.size() == g_count, "guide_group: size not G");
  require(a.follow_offsets.size() == size_t{g_count} * a.follow_per_guide, "follow_offsets: size not G*K");
  require(a.bone_weights.empty() || a.bone_weights.size() == g_count, "bone_weights: size not G");

  ModelRest m;
  m.guide_count = g_count;
  m.vertices_per_strand = n;
  m.follow_per_guide = a.follow_per_guide;
  m.asset_tip_separation = a.tip_separation;
  m.asset_origin = a.origin;
  m.asset_bone_count = a.bone_weights.empty() ? 0u : static_cast<uint32_t>(a.bone_names.size());
  m.group_count = std::max<uint32_t>(1u, static_cast<uint32_t>(a.groups.size()));

  m.rest_pos.resize(vcount);
  m.inv_mass.resize(vcount);
  m.rest_length.assign(vcount, 0.0);
  m.arc_fraction.assign(vcount, 0.0);
  m.frame_turns.assign(vcount, 0);
  m.rest_edge_local.assign(vcount, Vec3{});
  m.root_frame.resize(g_count);
  m.strand_length.assign(g_count, 0.0);
  m.group.assign(g_count, 0);
  m.bone_index.assign(g_count, {0, 0, 0, 0});
  m.bone_weight.assign(g_count, {1, 0, 0, 0});

  for (size_t i = 0; i < vcount; ++i) {
    m.rest_pos[i] = widen(a.rest_positions[i]);
    m.inv_mass[i] = a.rest_positions[i][3];
  }
  for (uint32_t g = 0; g < g_count; ++g) {
    if (respace_short_segments(m.rest_pos, m.inv_mass, size_t{g} * n, n)) ++m.respaced_strands;
  }
  for (uint32_t g = 0; g < g_count; ++g) {
    const size_t b = size_t{g} * n;
    double total = 0;
    for (uint32_t v = 0; v + 1 < n; ++v) {
      m.rest_length[b + v] = length(m.rest_pos[b + v + 1] - m.rest_pos[b + v]);
      m.arc_fraction[b + v] = total;
      total += m.rest_length[b + v];
    }
    m.arc_fraction[b + n - 1] = total;
    for (uint32_t v = 0; v < n; ++v) m.arc_fraction[b + v] = total > 0 ? m.arc_fraction[b + v] / total : 0.0;
    m.strand_length[g] = total;
    if (!a.guide_group.empty()) {
      m.group[g] = a.guide_group[g];
      require(m.group[g] < m.group_count, "guide_group[" + std::to_string(g) + "] names no group");
    }
    if (m.asset_bone_count > 0) {
      const auto& bw = a.bone_weights[g];
      double sum = 0;
      for (uint32_t k = 0; k < 4; ++k) {
        require(bw.weight[k] == 0.0f || bw.bone[k] < m.asset_bone_count,
                "bone_weights[" + std::to_string(g) + "] names bone " + std::to_string(bw.bone[k]));
        m.bone_index[g][k] = bw.weight[k] == 0.0f ? 0u : bw.bone[k];
        m.bone_weight[g][k] = bw.weight[k];
        sum += bw.weight[k];
      }
      require(sum > 0, "bone_weights[" + std::to_string(g) + "] are all zero");
    }
  }
  compact_bones(m);
  // Strands far shorter than the groom's typical strand are carried rigidly by the skinning (every vertex pinned),
  // by each group's TvkSimParams::rigid_below at run time (applied by the GPU and the reference, not here, so that
  // instances of one asset can choose): counted here for the default rule.
  m.median_length = median_strand_length(m);
  for (uint32_t g = 0; g < g_count; ++g) {
    if (rigid_by_rule(m.strand_length[g], default_rigid_below(m.median_length))) m.rigid_strands++;
  }
  for (uint32_t g = 0; g < g_count; ++g) {
    const size_t b = size_t{g} * n;
    bool any_free = false;
    for (uint32_t v = 0; v < n; ++v) any_free = any_free || m.inv_mass[b + v] > 0.0;
    if (any_free && m.inv_mass[b + n - 1] == 0.0) ++m.pinned_tip_strands;
  }
  for (uint32_t g = 0; g < g_count; ++g) {
    const size_t b = size_t{g} * n;
    const double mean_seg = m.strand_length[g] / (n - 1);
    const auto& f = a.rest_frames[b];
    Quat frame = normalize(Quat{f[0], f[1], f[2], f[3]});
    m.root_frame[g] = frame;
    for (uint32_t v = 1; v < n; ++v) {
      const double e_in = m.rest_length[b + v - 1];
      const double e_out = m.rest_length[b + v];
      // An edge between two pinned vertices moves with the skinning, which already turns the frame exactly;
      // re-aligning to it would only add its float rounding, amplified by the lever arm.
      const bool pinned_edge = m.inv_mass[b + v - 1] == 0.0 && m.inv_mass[b + v] == 0.0;
      const bool turns = !pinned_edge && e_in >= kFrameEdgeRatio * e_out && e_in >= kFrameEdgeMinRel * mean_seg && e_in > 0;
      m.frame_turns[b + v] = turns ? 1 : 0;
      if (turns) frame = frame_align(frame, m.rest_pos[b + v] - m.rest_pos[b + v - 1], e_in);
      if (v + 1 < n) m.rest_edge_local[b + v] = quat_rotate(conjugate(frame), m.rest_pos[b + v + 1] - m.rest_pos[b + v]);
    }
    m.rest_edge_local[b] = quat_rotate(conjugate(m.root_frame[g]), m.rest_pos[b + 1] - m.rest_pos[b]);
  }
  m.follow_offset.resize(a.follow_offsets.size());
  for (size_t i = 0; i < a.follow_offsets.size(); ++i) m.follow_offset[i] = widen(a.follow_offsets[i]);
  m.follow_length.assign(m.follow_offset.size(), 0.0);
  for (uint32_t g = 0; g < g_count; ++g) {
    const size_t b = size_t{g} * n;
    for (uint32_t f = 0; f < m.follow_per_guide; ++f) {
      const Vec3 off = quat_rotate(m.root_frame[g], m.follow_offset[size_t{g} * m.follow_per_guide + f]);
      double total = 0;
      for (uint32_t v = 0; v + 1 < n; ++v) {
        const double s0 = 1.0 + m.asset_tip_separation * v / (n - 1);
        const double s1 = 1.0 + m.asset_tip_separation * (v + 1) / (n - 1);
        total += length((m.rest_pos[b + v + 1] + s1 * off) - (m.rest_pos[b + v] + s0 * off));
      }
      m.follow_length[size_t{g} * m.follow_per_guide + f] = total;
    }
  }
  return m;
}

GpuStatic build_gpu_static(const ModelRest& m) {
  GpuStatic s;
  const uint32_t n = m.vertices_per_strand;
  // The blocked vertex layout (gpu_layout.hpp); padding strands stay zero (pinned, never read).
  const size_t vcount = sim::padded_strands(m.guide_count) * n;
  s.rest_positions.assign(vcount, sim::Vec4{});
  s.rest_info.assign(vcount, sim::Vec4{});
  s.rest_edge_local.assign(vcount, sim::Vec4{});
  for (uint32_t g = 0; g < m.guide_count; ++g) {
    const size_t root = size_t{g} * n;
    for (uint32_t v = 0; v < n; ++v) {
      const size_t i = root + v;
      const size_t o = sim::vertex_index(g, v, n);
      // The root as it is; the other vertices as offsets from it, formed in double (see layout.glsl).
      s.rest_positions[o] = narrow(v == 0 ? m.rest_pos[i] : m.rest_pos[i] - m.rest_pos[root], m.inv_mass[i]);
      s.rest_info[o] = {static_cast<float>(m.rest_length[i]), static_cast<float>(m.arc_fraction[i]),
                        m.frame_turns[i] ? 1.0f : 0.0f, 0.0f};
      s.rest_edge_local[o] = narrow(m.rest_edge_local[i], 0.0);
    }
  }
  for (uint32_t g = 0; g < m.guide_count; ++g) {
    const Quat& q = m.root_frame[g];
    s.root_frames.push_back({static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z),
                             static_cast<float>(q.w)});
    s.guide_info.push_back({m.group[g], 0u,
                            std::bit_cast<uint32_t>(static_cast<float>(m.strand_length[g])), 0u});
    if (m.bone_count > 0) {
      s.bone_indices.push_back(m.bone_index[g]);
      s.bone_weights.push_back({static_cast<float>(m.bone_weight[g][0]), static_cast<float>(m.bone_weight[g][1]),
                                static_cast<float>(m.bone_weight[g][2]), static_cast<float>(m.bone_weight[g][3])});
    }
  }
  for (const Vec3& o : m.follow_offset) s.follow_offsets.push_back(narrow(o, 0.0));
  if (s.follow_offsets.empty()) s.follow_offsets.push_back({0, 0, 0, 0});
  if (s.bone_indices.empty()) s.bone_indices.push_back({0, 0, 0, 0});
  if (s.bone_weights.empty()) s.bone_weights.push_back({1, 0, 0, 0});
  return s;
}

double median_strand_length(const ModelRest& m) {
  if (m.strand_length.empty()) return 0.0;
  std::vector<double> l = m.strand_length;
  auto mid = l.begin() + static_cast<std::ptrdiff_t>(l.size() / 2);
  std::nth_element(l.begin(), mid, l.end());
  return *mid;
}

}  // namespace tressvk::model
