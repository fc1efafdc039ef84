// Internal state of a TressVK context. Not part of the public interface.
#pragma once

#include <tressvk/tressvk.h>

#include <tressvk/model/planner.hpp>
#include <volk.h>
#include <vk_mem_alloc.h>

#include <atomic>
#include <cstdarg>
#include <exception>
#include <mutex>
#include <new>
#include <string>
#include <vector>

namespace tressvk {

struct Context {
  TvkContextCreateInfo info{};
  VolkDeviceTable vk{};                       // this context's own device-level function table
  PFN_vkGetPhysicalDeviceProperties get_physical_device_properties = nullptr;
  VkPhysicalDeviceProperties device_properties{};
  // The device's subgroup size (0 when unknown) and whether compute shaders may shuffle and vote in subgroups: the
  // lane and run kernels keep a strand in one subgroup where it fits the smallest (sim/fused.hpp).
  uint32_t subgroup_size = 0;
  uint32_t subgroup_size_min = 0;  // the smallest a compute shader may run at (Vulkan 1.3 minSubgroupSize)
  bool subgroup_shuffle_compute = false;
  VmaAllocator allocator = VK_NULL_HANDLE;    // private to TressVK, on the host's device
  uint32_t frames_in_flight = 2;
  std::string last_error;
  // fail() and message() take it: the per-instance calls of distinct instances may run on several threads at once
  // (tressvk.h, "Thread safety"), and their failures report through the context.
  std::recursive_mutex report_mutex;  // recursive: a message callback may call back into TressVK
  // Set by tressvk_report_device_lost or a Vulkan call of ours that returned VK_ERROR_DEVICE_LOST; then every call
  // that would use the device refuses (require_device) and only destruction works.
  bool device_lost = false;
  // Counts fail() calls: guarded() sees whether a failure has a message. Atomic: the per-instance calls may run on
  // several threads at once (tressvk.h, "Thread safety").
  std::atomic<uint64_t> error_serial{0};

  // Frame pacing: tressvk_new_frame() advances `frame`; the host promises that the GPU has finished the frame
  // recorded `frames_in_flight` frames earlier, so resources released then can be destroyed now.
  uint64_t frame = 0;
  struct DeferredBuffer {
    uint64_t release_frame;
    VkBuffer buffer;
    VmaAllocation allocation;
  };
  std::vector<DeferredBuffer> deferred_buffers;
  struct DeferredPool {
    uint64_t release_frame;
    VkDescriptorPool pool;
  };
  std::vector<DeferredPool> deferred_pools;
  void collect_garbage(bool everything);

  // Simulation pipelines: one descriptor set layout and pipeline layout for every pass; pipelines created on
  // first use per (pass, N, K, features, capsule count).
  VkDescriptorSetLayout sim_set_layout = VK_NULL_HANDLE;
  VkPipelineLayout sim_pipeline_layout = VK_NULL_HANDLE;
  struct PipelineEntry {
    uint64_t key;
    VkPipeline pipeline;
  };
  std::vector<PipelineEntry> pipelines;
  uint32_t workgroup_size = 64;

  // Names of the passes recorded by the last simulate (static strings from the pass table, plus variants).
  std::vector<std::string> recorded_passes;
  tressvk::model::GpuFrame gpu_frame_scratch;  // tressvk_cmd_simulate's per-instance upload, made in turn (simulate.cpp)
  uint32_t recorded_dispatches = 0;  // by the last tressvk_cmd_simulate

  // Timestamps: a pool of frames_in_flight slices; each slice remembers which pass each query pair timed.
  VkQueryPool timestamp_pool = VK_NULL_HANDLE;
  double timestamp_period_ns = 1.0;
  uint32_t queries_per_frame = 0;
  struct TimedSlice {
    uint64_t frame = 0;
    std::vector<std::string> pass_names;  // one per query pair
    std::vector<uint32_t> dispatches;     // dispatches in that pair
  };
  std::vector<TimedSlice> timed_slices;
  // Query pairs per frame slice kept for the hair rendering calls (after the simulation's).
  static constexpr uint32_t kRenderQueryPairs = 16;

  // Per-pass timestamps of the rendering calls, in the slice tressvk_cmd_simulate reset for this frame (nothing
  // when timestamps are off or no simulate was recorded this frame). begin returns the pair or UINT32_MAX.
  uint32_t time_begin(VkCommandBuffer cmd);
  void time_end(VkCommandBuffer cmd, uint32_t pair, const char* name);

  // Records an error, forwards it to the host's callback, and returns `result` for `return ctx.fail(...)`.
  TvkResult fail(TvkResult result, const char* format, ...) __attribute__((format(printf, 3, 4)));
  void message(TvkMessageSeverity severity, const char* format, ...) __attribute__((format(printf, 3, 4)));
  // Maps a VkResult to TVK_SUCCESS or a recorded TVK_ERROR_VULKAN naming `what` (TVK_ERROR_OUT_OF_MEMORY for the
  // out-of-memory results; TVK_ERROR_DEVICE_LOST for VK_ERROR_DEVICE_LOST, which also marks the context lost).
  TvkResult check(VkResult vr, const char* what);
  // TVK_SUCCESS, or TVK_ERROR_DEVICE_LOST with a message naming `call` once the device is lost.
  TvkResult require_device(const char* call);
};

const char* vk_result_name(VkResult result);

// The most frames in flight a context accepts (the per-frame rings are sized by it).
inline constexpr uint32_t kMaxFramesInFlight = 16;

// Records the error of a call that has no valid context (tressvk_last_error(NULL) on this thread) and returns
// `result`.
TvkResult fail_without_context(TvkResult result, const char* format, ...) __attribute__((format(printf, 2, 3)));

// The one status path of the C interface: runs an entry point's body, turns any C++ exception into a TvkResult
// with a message, and gives every failure that recorded no message of its own one naming the call. Bodies hold
// what they create in owners (unique_ptr, guards) until they hand it to the host, so an early return or an
// exception leaves nothing behind.
template <class Body>
TvkResult guarded(Context& ctx, const char* call, Body&& body) noexcept {
  const uint64_t serial = ctx.error_serial;
  TvkResult r = TVK_SUCCESS;
  try {
    r = body();
  } catch (const std::bad_alloc&) {
    r = ctx.fail(TVK_ERROR_OUT_OF_MEMORY, "%s: out of host memory", call);
  } catch (const std::exception& e) {
    r = ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: %s", call, e.what());
  } catch (...) {
    r = ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: unexpected exception", call);
  }
  if (r != TVK_SUCCESS && ctx.error_serial == serial) ctx.fail(r, "%s failed (%d)", call, static_cast<int>(r));
  return r;
}

// A diagnostic switch from the environment (TRESSVK_PIPELINE_STATS, TRESSVK_DEBUG_ALLOCATIONS): set, and not "0".
bool env_flag(const char* name);

}  // namespace tressvk

// The opaque handle type of the C interface is the context itself.
struct TvkContext_T : tressvk::Context {};
