#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/sync.hpp>

#include <string>
#include <utility>

namespace tressvk::engine {

Buffer::Buffer(VmaAllocator allocator, const VkBufferCreateInfo& info, MemoryUsage usage)
    : allocator_(allocator), size_(info.size), usage_(usage) {
  VmaAllocationCreateInfo aci{};
  switch (usage) {
    case MemoryUsage::device_local:
      aci.usage = VMA_MEMORY_USAGE_AUTO_PREFER_DEVICE;
      break;
    case MemoryUsage::upload:
      aci.usage = VMA_MEMORY_USAGE_AUTO;
      aci.flags = VMA_ALLOCATION_CREATE_HOST_ACCESS_SEQUENTIAL_WRITE_BIT | VMA_ALLOCATION_CREATE_MAPPED_BIT;
      break;
    case MemoryUsage::readback:
      aci.usage = VMA_MEMORY_USAGE_AUTO;
      aci.flags = VMA_ALLOCATION_CREATE_HOST_ACCESS_RANDOM_BIT | VMA_ALLOCATION_CREATE_MAPPED_BIT;
      break;
  }
  VmaAllocationInfo ai{};
  vk_check(vmaCreateBuffer(allocator, &info, &aci, &buffer_, &allocation_, &ai), "vmaCreateBuffer");
  mapped_ = ai.pMappedData;
}

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    reset();
    allocator_ = other.allocator_;
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    allocation_ = std::exchange(other.allocation_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    usage_ = other.usage_;
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

void Buffer::reset() {
  if (buffer_) vmaDestroyBuffer(allocator_, buffer_, allocation_);
  buffer_ = VK_NULL_HANDLE;
  allocation_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  size_ = 0;
}

Buffer create_buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory) {
  if (size == 0) throw Error("create_buffer: size 0 (Vulkan buffers cannot be empty)");
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = size;
  info.usage = usage;
  // Device-local buffers are reached from the host only through copies, so they can always be copied.
  if (memory == MemoryUsage::device_local)
    info.usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  return Buffer(device.allocator(), info, memory);
}

namespace {
void check_range(const Buffer& buffer, VkDeviceSize offset, size_t bytes, const char* what) {
  if (offset > buffer.size() || bytes > buffer.size() - offset)
    throw Error(std::string(what) + ": " + std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                " exceed the buffer's " + std::to_string(buffer.size()) + " bytes");
}
}  // namespace

void write_buffer(const Device& device, const Buffer& buffer, std::span<const std::byte> data, VkDeviceSize offset) {
  check_range(buffer, offset, data.size(), "write_buffer");
  if (data.empty()) return;
  if (buffer.mapped()) {
    // vkQueueSubmit makes host writes visible to the device, so later submissions need no barrier.
    std::memcpy(static_cast<std::byte*>(buffer.mapped()) + offset, data.data(), data.size());
    vk_check(vmaFlushAllocation(buffer.allocator(), buffer.allocation(), offset, data.size()), "vmaFlushAllocation");
    return;
  }
  Buffer staging = create_buffer(device, data.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload);
  write_buffer(device, staging, data);
  device.run_commands([&](VkCommandBuffer cmd) {
    // Earlier submissions may still read or write the destination: order the copy after all of them.
    cmd_memory_barrier(cmd, state::kAllCommands, state::kTransferDst);
    const VkBufferCopy region{0, offset, data.size()};
    vkCmdCopyBuffer(cmd, staging.handle(), buffer.handle(), 1, &region);
    cmd_memory_barrier(cmd, state::kTransferDst, state::kAllCommands);
  });
}

void read_buffer(const Device& device, const Buffer& buffer, std::span<std::byte> out, VkDeviceSize offset) {
  check_range(buffer, offset, out.size(), "read_buffer");
  if (out.empty()) return;
  if (buffer.mapped()) {
    device.run_commands(
        [&](VkCommandBuffer cmd) { cmd_memory_barrier(cmd, state::kAllCommands, state::kHostRead); });
    vk_check(vmaInvalidateAllocation(buffer.allocator(), buffer.allocation(), offset, out.size()),
             "vmaInvalidateAllocation");
    std::memcpy(out.data(), static_cast<const std::byte*>(buffer.mapped()) + offset, out.size());
    return;
  }
  Buffer staging = create_buffer(device, out.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::readback);
  device.run_commands([&](VkCommandBuffer cmd) {
    cmd_memory_barrier(cmd, state::kAllCommands, state::kTransferSrc);
    const VkBufferCopy region{offset, 0, out.size()};
    vkCmdCopyBuffer(cmd, buffer.handle(), staging.handle(), 1, &region);
    cmd_memory_barrier(cmd, state::kTransferDst, state::kHostRead);
    // Later submissions may overwrite the source: order them after this copy's read.
    cmd_memory_barrier(cmd, state::kTransferSrc, state::kAllCommands);
  });
  vk_check(vmaInvalidateAllocation(staging.allocator(), staging.allocation(), 0, out.size()), "vmaInvalidateAllocation");
  std::memcpy(out.data(), staging.mapped(), out.size());
}

}  // namespace tressvk::engine
