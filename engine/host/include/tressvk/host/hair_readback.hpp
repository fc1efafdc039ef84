// Reading a TressVK instance's simulation state back to the CPU, the way a host does it: after
// tressvk_cmd_simulate, a COMPUTE_SHADER write -> COPY read barrier (the simulation leaves its writes visible to
// shader reads only), then copies into host-readable buffers. Used by tressvk-bench and the plugin tests.
#pragma once

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/engine/sync.hpp>
#include <tressvk/tressvk.h>

#include <algorithm>
#include <array>
#include <span>
#include <stdexcept>
#include <vector>

namespace tressvk::host {

// Positions in simulation space (world axes, origin at TvkInstanceBuffers::origin): each strand's anchor plus the
// vertex's offset from it, summed in double, so nothing is rounded beyond what the GPU holds. Strand by strand (vertex
// v of strand s at s * N + v), unlike the GPU's blocked layout (tressvk.h, TvkInstanceBuffers).
struct HairState {
  std::vector<std::array<double, 3>> positions;          // every rendered strand: guides, then follow layers
  std::vector<std::array<double, 3>> previous;           // guides
  std::vector<std::array<double, 3>> previous_previous;  // guides
  std::vector<std::array<float, 4>> tangents;            // every rendered strand
  std::vector<std::array<float, 4>> anchors;             // per guide (xyz), as the GPU holds them
};

inline HairState read_hair_state(const engine::Device& device, TvkInstance instance) {
  TvkInstanceBuffers b{};
  if (tressvk_get_instance_buffers(instance, &b) != TVK_SUCCESS)
    throw std::runtime_error("tressvk_get_instance_buffers failed");
  constexpr size_t kCount = 5;
  const VkBuffer sources[kCount] = {b.positions, b.previous_positions, b.previous_previous_positions, b.tangents,
                                    b.anchors};
  const VkDeviceSize sizes[kCount] = {b.positions_size, b.previous_positions_size, b.previous_positions_size,
                                      b.tangents_size, b.anchors_size};
  std::array<engine::Buffer, kCount> copies;
  for (size_t i = 0; i < kCount; ++i)
    copies[i] = engine::create_buffer(device, sizes[i], VK_BUFFER_USAGE_TRANSFER_DST_BIT, engine::MemoryUsage::readback);
  device.run_commands([&](VkCommandBuffer cmd) {
    engine::cmd_memory_barrier(cmd, {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT},
                               engine::state::kTransferSrc);
    for (size_t i = 0; i < kCount; ++i) {
      const VkBufferCopy region{0, 0, sizes[i]};
      vkCmdCopyBuffer(cmd, sources[i], copies[i].handle(), 1, &region);
    }
  });
  using Vec4 = std::array<float, 4>;
  HairState s;
  s.anchors = engine::read_buffer_as<Vec4>(device, copies[4], sizes[4] / sizeof(Vec4));
  const size_t n = b.vertices_per_strand, guides = b.guide_count;
  // Element of vertex v of strand s in the GPU's blocked layout (tressvk.h, TvkInstanceBuffers).
  const auto element = [n](size_t strand, size_t v) { return static_cast<size_t>(tvk_vertex_index(strand, v, n)); };
  const auto absolute = [&](const std::vector<Vec4>& blocked, size_t strands) {
    std::vector<std::array<double, 3>> out(strands * n);
    for (size_t strand = 0; strand < strands; ++strand) {
      const Vec4& a = s.anchors[strand % guides];
      for (size_t v = 0; v < n; ++v) {
        const Vec4& o = blocked[element(strand, v)];
        for (size_t c = 0; c < 3; ++c) out[strand * n + v][c] = static_cast<double>(a[c]) + static_cast<double>(o[c]);
      }
    }
    return out;
  };
  const size_t all = guides * (1 + b.follow_per_guide);
  s.positions = absolute(engine::read_buffer_as<Vec4>(device, copies[0], sizes[0] / sizeof(Vec4)), all);
  s.previous = absolute(engine::read_buffer_as<Vec4>(device, copies[1], sizes[1] / sizeof(Vec4)), guides);
  s.previous_previous = absolute(engine::read_buffer_as<Vec4>(device, copies[2], sizes[2] / sizeof(Vec4)), guides);
  const std::vector<Vec4> tangents = engine::read_buffer_as<Vec4>(device, copies[3], sizes[3] / sizeof(Vec4));
  s.tangents.resize(all * n);
  for (size_t strand = 0; strand < all; ++strand)
    for (size_t v = 0; v < n; ++v)
      s.tangents[strand * n + v] = tangents[element(strand % guides, v)];  // a follow's tangent is its guide's
  return s;
}

// A reference's positions after a frame (strand by strand, as HairState), with the guides the GPU skipped in that frame
// held where the GPU holds them. A guide that sleeps (TvkSimSettings::sleep_below) is not simulated: it was asleep as
// the frame began (its anchor's w at TVK_ASLEEP_QUIET_FRAMES or more) and no vertex of it or of its follow hairs moved.
// The step error compares what both sides simulated, so the reference holds those guides too; everywhere else it is
// the reference's own.
// (P: any point with x, y, z members or three indexed coordinates, such as the reference's Vec3.)
template <class P>
std::vector<std::array<double, 3>> held_where_skipped(const HairState& before, const HairState& after,
                                                    std::span<const P> reference) {
  std::vector<std::array<double, 3>> out;
  out.reserve(reference.size());
  for (const P& p : reference) {
    if constexpr (requires { p.x; }) out.push_back({p.x, p.y, p.z});
    else out.push_back({p[0], p[1], p[2]});
  }
  const size_t guides = before.anchors.size();
  if (guides == 0 || before.previous.size() % guides != 0) return out;
  const size_t n = before.previous.size() / guides;
  const size_t strands = std::min({before.positions.size(), after.positions.size(), out.size()}) / n;
  for (size_t g = 0; g < guides; ++g) {
    if (!(before.anchors[g][3] >= static_cast<float>(TVK_ASLEEP_QUIET_FRAMES))) continue;
    bool still = true;
    for (size_t s = g; s < strands && still; s += guides)
      for (size_t i = s * n; i < (s + 1) * n && still; ++i) still = before.positions[i] == after.positions[i];
    if (!still) continue;
    for (size_t s = g; s < strands; s += guides)
      for (size_t i = s * n; i < (s + 1) * n; ++i) out[i] = after.positions[i];
  }
  return out;
}

}  // namespace tressvk::host
