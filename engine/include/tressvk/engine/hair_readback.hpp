// Reading a TressVK instance's simulation state back to the CPU, the way a host does it: after
// tressvk_cmd_simulate, a COMPUTE_SHADER write -> COPY read barrier (the simulation leaves its writes visible to
// shader reads only), then copies into host-readable buffers. Used by tressvk-bench and the plugin tests.
#pragma once

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/tressvk.h>

#include <array>
#include <stdexcept>
#include <vector>

namespace tressvk::engine {

struct HairState {
  std::vector<std::array<float, 4>> positions;           // every rendered strand: guides, then follow layers
  std::vector<std::array<float, 4>> previous;            // guides
  std::vector<std::array<float, 4>> previous_previous;   // guides
  std::vector<std::array<float, 4>> tangents;            // every rendered strand
};

inline HairState read_hair_state(const Device& device, TvkInstance instance) {
  TvkInstanceBuffers b{};
  if (tressvk_get_instance_buffers(instance, &b) != TVK_SUCCESS)
    throw std::runtime_error("tressvk_get_instance_buffers failed");
  const VkBuffer sources[4] = {b.positions, b.previous_positions, b.previous_previous_positions, b.tangents};
  const VkDeviceSize sizes[4] = {b.positions_size, b.previous_positions_size, b.previous_positions_size,
                                 b.tangents_size};
  std::array<Buffer, 4> copies;
  for (size_t i = 0; i < 4; ++i)
    copies[i] = create_buffer(device, sizes[i], VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::readback);
  device.run_commands([&](VkCommandBuffer cmd) {
    VkMemoryBarrier2 barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
    VkDependencyInfo dep{};
    dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
    for (size_t i = 0; i < 4; ++i) {
      const VkBufferCopy region{0, 0, sizes[i]};
      vkCmdCopyBuffer(cmd, sources[i], copies[i].handle(), 1, &region);
    }
  });
  using Vec4 = std::array<float, 4>;
  HairState s;
  s.positions = read_buffer_as<Vec4>(device, copies[0], sizes[0] / sizeof(Vec4));
  s.previous = read_buffer_as<Vec4>(device, copies[1], sizes[1] / sizeof(Vec4));
  s.previous_previous = read_buffer_as<Vec4>(device, copies[2], sizes[2] / sizeof(Vec4));
  s.tangents = read_buffer_as<Vec4>(device, copies[3], sizes[3] / sizeof(Vec4));
  return s;
}

}  // namespace tressvk::engine
