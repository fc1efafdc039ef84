#include <tressvk/engine/timestamps.hpp>

namespace tressvk::engine {

double timestamp_delta_ms(uint64_t begin, uint64_t end, double period_ns, uint32_t valid_bits) {
  const uint64_t mask = valid_bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << valid_bits) - 1;
  const uint64_t ticks = (end - begin) & mask;  // unsigned wrap-around handles a counter that rolled over
  return static_cast<double>(ticks) * period_ns * 1e-6;
}

TimestampQueries::TimestampQueries(const Device& device, uint32_t count)
    : device_of_pool_(device.device()), count_(count), period_ns_(device.timestamp_period_ns()), valid_bits_(device.timestamp_valid_bits()) {
  if (!device.timestamps_supported() || count == 0) return;
  VkQueryPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = count;
  VkQueryPool pool = VK_NULL_HANDLE;
  vk_check(vkCreateQueryPool(device.device(), &info, nullptr, &pool), "vkCreateQueryPool");
  pool_ = DeviceHandle<VkQueryPool>(device.device(), pool, vkDestroyQueryPool);
}

void TimestampQueries::cmd_reset(VkCommandBuffer cmd) const {
  if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, count_);
}

void TimestampQueries::cmd_write(VkCommandBuffer cmd, uint32_t slot, VkPipelineStageFlags2 stage) const {
  if (pool_ && slot < count_) vkCmdWriteTimestamp2(cmd, stage, pool_, slot);
}

std::vector<uint64_t> TimestampQueries::fetch() const {
  if (!pool_) return {};
  std::vector<uint64_t> values(count_);
  vk_check(vkGetQueryPoolResults(device_of_pool_, pool_, 0, count_, values.size() * sizeof(uint64_t), values.data(),
                                 sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
           "vkGetQueryPoolResults");
  return values;
}

std::optional<double> TimestampQueries::elapsed_ms(uint32_t begin_slot, uint32_t end_slot) const {
  if (!pool_ || begin_slot >= count_ || end_slot >= count_) return std::nullopt;
  const auto values = fetch();
  return timestamp_delta_ms(values[begin_slot], values[end_slot], period_ns_, valid_bits_);
}

}  // namespace tressvk::engine
