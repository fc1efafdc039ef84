// TressVK hair asset: the in-memory form of a baked `.tvkhair` file, shared by the baker (which writes it),
// the plugin (which uploads it) and the CPU reference (which simulates it). No Vulkan, no baker code.
//
// Conventions (docs/asset-format.md is the byte-level specification of the file):
// - Units are metres, +Y is up, right-handed. Positions are stored relative to `origin` (double precision) so
//   that float32 keeps sub-micrometre resolution for a groom anywhere; nothing stores large world coordinates.
// - Every strand has exactly `vertices_per_strand` (N) vertices, root first. Vertex v of guide g is at g*N+v.
// - Guides are stored in a shuffled level-of-detail order: any prefix of the guide list is an even thinning of
//   the groom. Rendered strand r of G*(K+1) is guide (r % G) when r < G, otherwise follow (r / G - 1) of guide
//   (r % G): follow layers come after all guides, so a prefix of the rendered list is an even thinning too.
// - Quaternions are (x, y, z, w), unit length, and map a frame's local coordinates to asset space.
// - Rest frames (parallel transport along the rest strand, as in TressFX 3.x/4.0, computed in double):
//     frame[0]: local +X along the root edge (p1 - p0); local +Y is the component, perpendicular to +X, of the
//               asset axis least aligned with +X (ties broken in the order X, Y, Z); Z = X x Y.
//     frame[v], 1 <= v <= N-1: frame[v-1] followed by the minimal rotation that takes frame[v-1]'s +X onto the
//               direction of edge (v-1 -> v). So frame[v]'s +X is along the edge arriving at v.
//     rest_edge_local[v] = conjugate(frame[v]) * (p[v+1] - p[v]) for v <= N-2, i.e. the edge leaving v in the
//               frame of the edge arriving at v ("each edge in its parent frame"); zero for v = N-1.
//               rest_edge_local[0] = (|p1 - p0|, 0, 0) by construction.
// - Follow hairs: follow f of guide g has `follow_offsets[g*K+f]`, an offset of its root from the guide root,
//   expressed in the guide's root frame (frame[0]). At runtime the offset is turned by the guide's current
//   root frame, so follows rotate with the head; vertex v of the follow is
//   guide[v] + R_root * offset * (1 + tip_separation * v / (N-1)).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tressvk::asset {

inline constexpr uint32_t kMinVerticesPerStrand = 4;
inline constexpr uint32_t kMaxVerticesPerStrand = 128;
inline constexpr uint32_t kMaxBoneInfluences = 4;
// Resource limits every reader enforces (docs/asset-format.md, "Limits"): follow hairs per guide, and vertices
// rendered (guides x (1 + follows) x N), which bounds the GPU memory and the 32-bit indices of the runtime.
inline constexpr uint32_t kMaxFollowPerGuide = 64;
inline constexpr uint64_t kMaxRenderedVertices = uint64_t{1} << 31;

struct BoneInfluences {
  std::array<uint32_t, kMaxBoneInfluences> bone{};  // indices into HairAsset::bone_names
  std::array<float, kMaxBoneInfluences> weight{};   // sorted descending, sum to 1; unused slots have weight 0
};

struct StrandGroup {
  std::string name;  // OBJ `o`/`g` name, or the source file's stem; unique within an asset
};

struct HairAsset {
  uint32_t vertices_per_strand = 0;  // N, 4..128
  uint32_t follow_per_guide = 0;     // K
  float tip_separation = 0.0f;       // baked default for follow spreading toward the tip (dimensionless)
  std::array<double, 3> origin{};    // asset origin in metres; positions below are relative to it

  // Per guide vertex (G*N entries).
  std::vector<std::array<float, 4>> rest_positions;    // xyz relative to origin; w = inverse mass (0 = pinned)
  std::vector<float> rest_lengths;                     // |p[v+1]-p[v]| in metres; 0 for the last vertex
  std::vector<std::array<float, 4>> rest_frames;       // quaternion (x,y,z,w) of frame[v]
  std::vector<std::array<float, 4>> rest_edge_local;   // xyz = edge leaving v in frame[v]; w = 0

  // Per guide (G entries).
  std::vector<uint16_t> guide_group;                  // index into groups
  std::vector<std::array<float, 2>> root_uv;          // optional (empty when the source had none)
  std::vector<BoneInfluences> bone_weights;           // optional (empty when no bones were given)

  // Per follow (G*K entries).
  std::vector<std::array<float, 4>> follow_offsets;   // xyz in the guide's root frame; w = 0

  std::vector<StrandGroup> groups;                    // at least one
  std::vector<std::string> bone_names;                // empty when no bones

  // How the asset was baked (tool options as a small deterministic JSON object), for `tressvk-bake info`.
  // Informational only: nothing at runtime depends on it. Empty when unknown.
  std::string bake_settings;

  uint32_t guide_count() const {
    return vertices_per_strand ? static_cast<uint32_t>(rest_positions.size() / vertices_per_strand) : 0;
  }
  uint32_t total_strands() const { return guide_count() * (1 + follow_per_guide); }
  // The rendered strands (guides, then follow layers) a frame simulates when the host draws `draw_strands` of them
  // (tressvk_set_draw_strands; 0: every one): the guides always, the follow hairs of the drawn prefix.
  uint32_t simulated_strands(uint32_t draw_strands) const {
    return draw_strands == 0 ? total_strands() : std::clamp(draw_strands, guide_count(), total_strands());
  }
};

}  // namespace tressvk::asset
