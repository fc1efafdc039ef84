// The rest data the runtime uploads (tressvk::model::build_gpu_static, which the plugin's asset upload copies byte
// for byte into its static buffers) against the rest data the baker stored in the asset.
//
// What the runtime takes from the asset as it is: the positions and inverse masses, the root frame (frame[0]), the
// groups, bone weights and follow offsets. What it derives, and why it does not read the asset's copy:
// - Rest lengths: the double reference needs them in double; the model computes them with the baker's formula
//   (|p[v+1] - p[v]| in double, of the same float32 positions), so the float32 the GPU gets equals the asset's
//   rest_lengths bit for bit (checked here), while the double stays exact for the reference.
// - Frames along the strand and the rest edges: the model's frames turn onto the edge arriving at v only where
//   that edge is reliable in float32 (ModelRest::frame_turns: not a pinned edge, not much shorter than the edge
//   leaving v), while the asset's frames turn at every edge (parallel transport, asset.hpp). Where every frame up to
//   v turned, the two agree to float rounding (checked here); elsewhere the GPU needs the model's rest edge, which
//   the asset does not hold. The asset's frame[v > 0] and rest_edge_local are read by nothing at runtime.
#include <catch2/catch_test_macros.hpp>

#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/import.hpp>
#include <tressvk/model/model.hpp>
#include <tressvk/reference/near_duplicates.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "helpers.hpp"

using namespace tvk_test;
namespace model = tressvk::model;

namespace {

struct RestAgreement {
  size_t lengths_differing = 0;   // uploaded rest lengths != asset rest_lengths (bitwise)
  size_t roots_differing = 0;     // uploaded root positions or root frames != the asset's (bitwise)
  double worst_root_frame = 0;    // largest component difference of an uploaded root frame from the asset's
  size_t edges_compared = 0;      // rest edges where the model's frame turned at every edge so far
  size_t edges_own = 0;           // rest edges in the model's own frames (a frame carried over an edge)
  double worst_edge_rel = 0;      // largest |uploaded - asset| / rest length over the edges compared
};

RestAgreement compare(const tressvk::asset::HairAsset& a) {
  const model::ModelRest m = model::build_model_rest(a);
  const model::GpuStatic s = model::build_gpu_static(m);
  const uint32_t n = a.vertices_per_strand;
  RestAgreement r;
  for (uint32_t g = 0; g < m.guide_count; ++g) {
    const size_t b = size_t{g} * n;
    const auto& root = s.rest_positions[tressvk::sim::vertex_index(g, 0, n)];
    for (int c = 0; c < 3; ++c) r.roots_differing += root[c] != a.rest_positions[b][c];
    for (int c = 0; c < 4; ++c) {
      r.roots_differing += s.root_frames[g][c] != a.rest_frames[b][c];
      r.worst_root_frame = std::max(r.worst_root_frame, std::abs(double(s.root_frames[g][c]) - a.rest_frames[b][c]));
    }
    bool turned_everywhere = true;
    for (uint32_t v = 0; v < n; ++v) {
      const size_t o = tressvk::sim::vertex_index(g, v, n);
      r.lengths_differing += s.rest_info[o][0] != a.rest_lengths[b + v];
      if (v > 0) turned_everywhere = turned_everywhere && m.frame_turns[b + v];
      if (v + 1 == n) continue;
      if (!turned_everywhere) {
        ++r.edges_own;
        continue;
      }
      ++r.edges_compared;
      double d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(double(s.rest_edge_local[o][c]) - a.rest_edge_local[b + v][c]));
      r.worst_edge_rel = std::max(r.worst_edge_rel, d / m.rest_length[b + v]);
    }
  }
  INFO("lengths differing " << r.lengths_differing << ", roots differing " << r.roots_differing << " (worst frame "
       << r.worst_root_frame << "), edges compared " << r.edges_compared << " (worst " << r.worst_edge_rel
       << " of the rest length), edges in the model's own frames " << r.edges_own);
  // Bit for bit: the same float32 positions and the same double formula, rounded once.
  CHECK(r.lengths_differing == 0);
  // The root frame is the asset's, renormalised in double and rounded again: at most one float32 ulp of a unit
  // component (2^-23; measured 6e-8 on the Ratboy mohawk).
  CHECK(r.worst_root_frame <= 0x1p-23);
  // Frames built by two codes (the baker's minimal rotation, the model's frame_align) from the same positions,
  // each rounded to float32: a few float ulps of the edge (measured 8e-8 on the Ratboy mohawk).
  CHECK(r.worst_edge_rel <= 1e-6);
  CHECK(r.edges_compared > 0);
  return r;
}

}  // namespace

TEST_CASE("model: the uploaded rest data is the asset's where the model defines it alike", "[reference][model]") {
  for (const char* name : {"straight", "curly", "long128"}) {
    INFO(name);
    compare(groom(name, 64, 1));
  }
}

TEST_CASE("model: the uploaded rest data is the asset's on the baked Ratboy mohawk", "[reference][model][data]") {
  const char* dir = std::getenv("TRESSVK_DATA_DIR");
  const std::filesystem::path tfx =
      std::filesystem::path(dir ? dir : "") / "tressfx" / "ratboy" / "Ratboy_mohawk.tfx";
  if (!dir || !std::filesystem::exists(tfx)) SKIP("no shared data (TRESSVK_DATA_DIR): " << tfx.string());
  const tressvk::asset::HairAsset a = tressvk::baker::bake(tressvk::baker::import_tfx(tfx), {});
  const RestAgreement r = compare(a);
  // Pinned roots and the mohawk's short kinked segments carry frames over some edges.
  CHECK(r.edges_own > 0);
  CHECK(model::build_model_rest(a).respaced_strands == 0);  // baked strands are evenly spaced
}

// Hard case 8's groom (0.1-0.2 um segments in guides 0-2): those strands' free vertices are respaced evenly along them
// on load (model::kRespaceBelowRel); pinned vertices, free tips and every other strand keep the asset's float values.
TEST_CASE("model: strands with sub-micrometre segments are respaced evenly on load", "[reference][model]") {
  const tressvk::asset::HairAsset a = tressvk::reference::with_near_duplicate_vertices(groom("straight", 8));
  const model::ModelRest m = model::build_model_rest(a);
  const uint32_t n = a.vertices_per_strand;
  CHECK(m.respaced_strands == 3);
  for (uint32_t g = 0; g < m.guide_count; ++g) {
    INFO("guide " << g);
    const size_t b = size_t{g} * n;
    const double mean = m.strand_length[g] / (n - 1);
    double shortest = mean, longest = 0;
    size_t moved = 0;
    for (uint32_t v = 0; v < n; ++v) {
      const auto& p = a.rest_positions[b + v];
      const bool same = m.rest_pos[b + v].x == p[0] && m.rest_pos[b + v].y == p[1] && m.rest_pos[b + v].z == p[2];
      moved += !same;
      if (m.inv_mass[b + v] == 0.0 || v + 1 == n) CHECK(same);  // pinned vertices and the tip stay
      if (v + 1 < n && m.inv_mass[b + v + 1] > 0.0) {
        shortest = std::min(shortest, m.rest_length[b + v]);
        longest = std::max(longest, m.rest_length[b + v]);
      }
    }
    if (g < 3) {
      CHECK(moved > 0);
      // Evenly spaced along a straight strand (float rounding of the placed vertices: ~1e-7 of a segment).
      CHECK(shortest >= (1.0 - 1e-5) * longest);
    } else {
      CHECK(moved == 0);
    }
  }
}

// The bones the strands read, compacted (ModelRest::bone_source): the planner works out and the GPU holds only those,
// the guides' indices name them, and a zero weight's index is the guide's first weighted bone (the skinning blend's
// quaternion hemisphere is its first entry's, which must be a bone the guide reads).
TEST_CASE("model: the bones no strand reads are left out of the runtime's bone list", "[reference][model]") {
  tressvk::asset::HairAsset a = groom("straight", 4);
  a.bone_names = {"root", "spine", "neck", "head", "jaw", "ear"};
  a.bone_weights.assign(4, {});
  a.bone_weights[0].bone = {3, 0, 0, 0};
  a.bone_weights[0].weight = {1.0f, 0.0f, 0.0f, 0.0f};
  a.bone_weights[1].bone = {5, 3, 0, 0};
  a.bone_weights[1].weight = {0.75f, 0.25f, 0.0f, 0.0f};
  a.bone_weights[2].bone = {0, 2, 0, 0};
  a.bone_weights[2].weight = {0.0f, 1.0f, 0.0f, 0.0f};  // a zero weight first
  a.bone_weights[3].bone = {3, 3, 3, 3};
  a.bone_weights[3].weight = {0.5f, 0.5f, 0.0f, 0.0f};
  const model::ModelRest m = model::build_model_rest(a);
  CHECK(m.asset_bone_count == 6);
  CHECK(m.bone_count == 3);
  CHECK(m.bone_source == std::vector<uint32_t>{2, 3, 5});
  using Index = std::array<uint32_t, 4>;
  CHECK(m.bone_index[0] == Index{1, 1, 1, 1});
  CHECK(m.bone_index[1] == Index{2, 1, 2, 2});
  CHECK(m.bone_index[2] == Index{0, 0, 0, 0});
  CHECK(m.bone_index[3] == Index{1, 1, 1, 1});
  CHECK(m.bone_weight[1][0] == 0.75);
  const model::GpuStatic s = model::build_gpu_static(m);
  REQUIRE(s.bone_indices.size() == 4);
  for (uint32_t g = 0; g < 4; ++g)
    for (uint32_t k = 0; k < 4; ++k) CHECK(s.bone_indices[g][k] == m.bone_index[g][k]);

  a.bone_weights.clear();  // no bones: rigid only
  const model::ModelRest rigid = model::build_model_rest(a);
  CHECK(rigid.bone_count == 0);
  CHECK(rigid.asset_bone_count == 0);
  CHECK(rigid.bone_source.empty());
}
