#include "core/context.hpp"

#include "core/fault_injection.hpp"
#include "core/objects.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>

namespace tressvk {

namespace {
std::string vformat(const char* format, va_list args) {
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  std::string s(n > 0 ? static_cast<size_t>(n) : 0, '\0');
  if (n > 0) std::vsnprintf(s.data(), s.size() + 1, format, args);
  return s;
}

// `out` = the formatted message, or empty when there is no memory for it (the result code still says what happened).
void set_message(std::string& out, const char* format, va_list args) noexcept {
  try {
    out = vformat(format, args);
  } catch (const std::bad_alloc&) {
    out.clear();
  }
}
}  // namespace

thread_local std::string g_error_without_context;

TvkResult Context::fail(TvkResult result, const char* format, ...) {
  const std::lock_guard<std::recursive_mutex> lock(report_mutex);
  ++error_serial;
  va_list args;
  va_start(args, format);
  set_message(last_error, format, args);
  va_end(args);
  if (info.message_callback) info.message_callback(TVK_MESSAGE_ERROR, last_error.c_str(), info.message_user_data);
  return result;
}

TvkResult fail_without_context(TvkResult result, const char* format, ...) {
  va_list args;
  va_start(args, format);
  set_message(g_error_without_context, format, args);
  va_end(args);
  return result;
}

void Context::message(TvkMessageSeverity severity, const char* format, ...) {
  if (!info.message_callback) return;
  va_list args;
  va_start(args, format);
  const std::string text = vformat(format, args);
  va_end(args);
  const std::lock_guard<std::recursive_mutex> lock(report_mutex);
  info.message_callback(severity, text.c_str(), info.message_user_data);
}

TvkResult Context::check(VkResult vr, const char* what) {
  if (vr == VK_SUCCESS) return TVK_SUCCESS;
  if (vr == VK_ERROR_DEVICE_LOST) {
    device_lost = true;
    return fail(TVK_ERROR_DEVICE_LOST, "%s failed: VK_ERROR_DEVICE_LOST (destroy every TressVK object and the context, "
                "then recreate them on a new device)", what);
  }
  if (vr == VK_ERROR_OUT_OF_HOST_MEMORY || vr == VK_ERROR_OUT_OF_DEVICE_MEMORY || vr == VK_ERROR_OUT_OF_POOL_MEMORY)
    return fail(TVK_ERROR_OUT_OF_MEMORY, "%s failed: %s", what, vk_result_name(vr));
  return fail(TVK_ERROR_VULKAN, "%s failed: %s", what, vk_result_name(vr));
}

TvkResult Context::require_device(const char* call) {
  if (!device_lost) return TVK_SUCCESS;
  return fail(TVK_ERROR_DEVICE_LOST,
              "%s: the device was lost; destroy every TressVK object and the context, then recreate them on a new "
              "device", call);
}

uint32_t Context::time_begin(VkCommandBuffer cmd) {
  if (!timestamp_pool) return UINT32_MAX;
  const uint32_t slice = static_cast<uint32_t>(frame % frames_in_flight);
  TimedSlice& t = timed_slices[slice];
  const auto pair = static_cast<uint32_t>(t.pass_names.size());
  if (t.frame != frame || 2 * (pair + 1) > queries_per_frame) return UINT32_MAX;
  vk.vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, timestamp_pool, slice * queries_per_frame + 2 * pair);
  t.pass_names.emplace_back();  // named by time_end
  t.dispatches.push_back(1);
  return pair;
}

void Context::time_end(VkCommandBuffer cmd, uint32_t pair, const char* name) {
  if (pair == UINT32_MAX) return;
  const uint32_t slice = static_cast<uint32_t>(frame % frames_in_flight);
  vk.vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, timestamp_pool,
                          slice * queries_per_frame + 2 * pair + 1);
  timed_slices[slice].pass_names[pair] = name;
}

const char* vk_result_name(VkResult result) {
  switch (result) {
#define TVK_CASE(x) case x: return #x
    TVK_CASE(VK_SUCCESS);
    TVK_CASE(VK_NOT_READY);
    TVK_CASE(VK_TIMEOUT);
    TVK_CASE(VK_INCOMPLETE);
    TVK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY);
    TVK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY);
    TVK_CASE(VK_ERROR_INITIALIZATION_FAILED);
    TVK_CASE(VK_ERROR_DEVICE_LOST);
    TVK_CASE(VK_ERROR_MEMORY_MAP_FAILED);
    TVK_CASE(VK_ERROR_LAYER_NOT_PRESENT);
    TVK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT);
    TVK_CASE(VK_ERROR_FEATURE_NOT_PRESENT);
    TVK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER);
    TVK_CASE(VK_ERROR_TOO_MANY_OBJECTS);
    TVK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED);
    TVK_CASE(VK_ERROR_FRAGMENTED_POOL);
    TVK_CASE(VK_ERROR_UNKNOWN);
    TVK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY);
    TVK_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE);
    TVK_CASE(VK_ERROR_FRAGMENTATION);
    TVK_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS);
    TVK_CASE(VK_PIPELINE_COMPILE_REQUIRED);
#undef TVK_CASE
    default: return "VkResult error";
  }
}


// Everything tressvk_create_context does once the arguments are checked; on failure the caller destroys the
// half-made context (tressvk_destroy_context copes with any prefix of this).
TvkResult init_context(Context& ctx) {
  const TvkContextCreateInfo& info = ctx.info;
  // Our own copy of volk lives inside this shared library (hidden visibility), so these calls fill TressVK's
  // private globals and table, never the host's.
  volkInitializeCustom(info.get_instance_proc_addr);
  volkLoadInstanceOnly(info.instance);
  volkLoadDeviceTable(&ctx.vk, info.device);
  fault::install(info.next, ctx.vk);
  ctx.get_physical_device_properties = vkGetPhysicalDeviceProperties;
  ctx.get_physical_device_properties(info.physical_device, &ctx.device_properties);
  if (ctx.device_properties.apiVersion < VK_API_VERSION_1_3)
    return ctx.fail(TVK_ERROR_MISSING_FEATURE, "tressvk_create_context: device '%s' supports Vulkan %u.%u; TressVK needs 1.3",
                    ctx.device_properties.deviceName, VK_API_VERSION_MAJOR(ctx.device_properties.apiVersion),
                    VK_API_VERSION_MINOR(ctx.device_properties.apiVersion));
  if (vkGetPhysicalDeviceProperties2) {
    // Vulkan 1.3 is checked above, so both property structs are there.
    VkPhysicalDeviceVulkan13Properties v13{};
    v13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES;
    VkPhysicalDeviceVulkan11Properties v11{};
    v11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES;
    v11.pNext = &v13;
    VkPhysicalDeviceProperties2 p2{};
    p2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    p2.pNext = &v11;
    vkGetPhysicalDeviceProperties2(info.physical_device, &p2);
    constexpr VkSubgroupFeatureFlags kNeeded =
        VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_SHUFFLE_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT;
    ctx.subgroup_size = v11.subgroupSize;
    // A device may run a compute shader at any subgroup size from min to max (Intel: 8 to 32) unless the pipeline
    // asks for one: a strand kept in one subgroup must fit the smallest.
    ctx.subgroup_size_min = std::min(v13.minSubgroupSize, v11.subgroupSize);
    ctx.subgroup_shuffle_compute = (v11.subgroupSupportedStages & VK_SHADER_STAGE_COMPUTE_BIT) != 0 &&
                                   (v11.subgroupSupportedOperations & kNeeded) == kNeeded;
  }

  // VMA calls Vulkan through this context's table (so fault-injection builds see its calls too).
  VmaVulkanFunctions functions{};
  functions.vkGetInstanceProcAddr = info.get_instance_proc_addr;
  functions.vkGetDeviceProcAddr = vkGetDeviceProcAddr;
  functions.vkAllocateMemory = ctx.vk.vkAllocateMemory;
  functions.vkFreeMemory = ctx.vk.vkFreeMemory;
  functions.vkMapMemory = ctx.vk.vkMapMemory;
  functions.vkUnmapMemory = ctx.vk.vkUnmapMemory;
  functions.vkFlushMappedMemoryRanges = ctx.vk.vkFlushMappedMemoryRanges;
  functions.vkInvalidateMappedMemoryRanges = ctx.vk.vkInvalidateMappedMemoryRanges;
  functions.vkBindBufferMemory = ctx.vk.vkBindBufferMemory;
  functions.vkBindImageMemory = ctx.vk.vkBindImageMemory;
  functions.vkGetBufferMemoryRequirements = ctx.vk.vkGetBufferMemoryRequirements;
  functions.vkGetImageMemoryRequirements = ctx.vk.vkGetImageMemoryRequirements;
  functions.vkCreateBuffer = ctx.vk.vkCreateBuffer;
  functions.vkDestroyBuffer = ctx.vk.vkDestroyBuffer;
  functions.vkCreateImage = ctx.vk.vkCreateImage;
  functions.vkDestroyImage = ctx.vk.vkDestroyImage;
  functions.vkCmdCopyBuffer = ctx.vk.vkCmdCopyBuffer;
  functions.vkGetBufferMemoryRequirements2KHR = ctx.vk.vkGetBufferMemoryRequirements2;
  functions.vkGetImageMemoryRequirements2KHR = ctx.vk.vkGetImageMemoryRequirements2;
  functions.vkBindBufferMemory2KHR = ctx.vk.vkBindBufferMemory2;
  functions.vkBindImageMemory2KHR = ctx.vk.vkBindImageMemory2;
  functions.vkGetDeviceBufferMemoryRequirements = ctx.vk.vkGetDeviceBufferMemoryRequirements;
  functions.vkGetDeviceImageMemoryRequirements = ctx.vk.vkGetDeviceImageMemoryRequirements;
  VmaAllocatorCreateInfo aci{};
  aci.physicalDevice = info.physical_device;
  aci.device = info.device;
  aci.instance = info.instance;
  aci.vulkanApiVersion = VK_API_VERSION_1_3;
  aci.pAllocationCallbacks = info.allocator;
  aci.pVulkanFunctions = &functions;
  if (const TvkResult r = ctx.check(vmaCreateAllocator(&aci, &ctx.allocator), "vmaCreateAllocator"); r != TVK_SUCCESS) {
    ctx.allocator = VK_NULL_HANDLE;
    return r;
  }
  if (info.enable_timestamps) {
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(info.physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(info.physical_device, &family_count, families.data());
    if (info.queue_family_index < family_count && families[info.queue_family_index].timestampValidBits > 0 &&
        ctx.device_properties.limits.timestampPeriod > 0.0f) {
      // Two queries per pass slot: up to 4 passes per substep plus the follow pass, then the rendering passes.
      ctx.queries_per_frame = 2 * (4 * TVK_MAX_STEPS_PER_FRAME + 1 + Context::kRenderQueryPairs);
      VkQueryPoolCreateInfo qci{};
      qci.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
      qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
      qci.queryCount = ctx.queries_per_frame * ctx.frames_in_flight;
      VkQueryPool pool = VK_NULL_HANDLE;
      if (const TvkResult r =
              ctx.check(ctx.vk.vkCreateQueryPool(info.device, &qci, info.allocator, &pool), "vkCreateQueryPool");
          r != TVK_SUCCESS)
        return r;
      ctx.timestamp_pool = pool;
      ctx.timestamp_period_ns = ctx.device_properties.limits.timestampPeriod;
      ctx.timed_slices.resize(ctx.frames_in_flight);
    } else {
      ctx.message(TVK_MESSAGE_WARNING, "timestamps requested but queue family %u does not support them",
                  info.queue_family_index);
    }
  }
  ctx.message(TVK_MESSAGE_INFO, "TressVK %d.%d.%d context on '%s'", TVK_VERSION_MAJOR, TVK_VERSION_MINOR,
              TVK_VERSION_PATCH, ctx.device_properties.deviceName);
  return TVK_SUCCESS;
}

bool env_flag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && v[0] != '\0' && v[0] != '0';
}

}  // namespace tressvk

using tressvk::Context;

extern "C" {

uint32_t tressvk_version(void) { return TVK_VERSION_NUM; }

TvkResult tressvk_check_version(uint32_t header_version_num, size_t context_create_info_size) {
  if (header_version_num / 100 != TVK_VERSION_NUM / 100) return TVK_ERROR_VERSION_MISMATCH;
  if (context_create_info_size != sizeof(TvkContextCreateInfo)) return TVK_ERROR_VERSION_MISMATCH;
  return TVK_SUCCESS;
}

const char* tressvk_result_string(TvkResult result) {
  switch (result) {
    case TVK_SUCCESS: return "success";
    case TVK_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case TVK_ERROR_VULKAN: return "Vulkan error";
    case TVK_ERROR_OUT_OF_MEMORY: return "out of memory";
    case TVK_ERROR_INVALID_ASSET: return "invalid asset";
    case TVK_ERROR_IO: return "I/O error";
    case TVK_ERROR_MISSING_FEATURE: return "missing device feature";
    case TVK_ERROR_VERSION_MISMATCH: return "version mismatch";
    case TVK_ERROR_DEVICE_LOST: return "device lost";
  }
  return "unknown result";
}

void tressvk_get_device_requirements(TvkDeviceRequirements* out) {
  if (!out) return;
  *out = TvkDeviceRequirements{};
  out->min_api_version = VK_API_VERSION_1_3;
  out->extension_count = 0;
  out->extensions = nullptr;
  out->synchronization2 = VK_TRUE;
  out->dynamic_rendering = VK_TRUE;
}

TvkResult tressvk_create_context(const TvkContextCreateInfo* info, TvkContext* out_context) {
  using tressvk::fail_without_context;
  constexpr const char* kCall = "tressvk_create_context";
  if (!out_context) return fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "%s: out_context is NULL", kCall);
  *out_context = nullptr;
  if (!info) return fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "%s: info is NULL", kCall);
  // The message callback is usable from here on, so failures reach the host's log too.
  const auto refuse = [info](TvkResult r, const std::string& what) {
    fail_without_context(r, "%s: %s", kCall, what.c_str());
    if (info->message_callback) info->message_callback(TVK_MESSAGE_ERROR, tressvk_last_error(nullptr), info->message_user_data);
    return r;
  };
  if (info->struct_size != sizeof(TvkContextCreateInfo))
    return refuse(TVK_ERROR_INVALID_ARGUMENT, "struct_size is " + std::to_string(info->struct_size) + ", expected " +
                                                  std::to_string(sizeof(TvkContextCreateInfo)) +
                                                  " (sizeof(TvkContextCreateInfo) of this version)");
  if (!info->instance) return refuse(TVK_ERROR_INVALID_ARGUMENT, "instance is VK_NULL_HANDLE");
  if (!info->physical_device) return refuse(TVK_ERROR_INVALID_ARGUMENT, "physical_device is VK_NULL_HANDLE");
  if (!info->device) return refuse(TVK_ERROR_INVALID_ARGUMENT, "device is VK_NULL_HANDLE");
  if (!info->get_instance_proc_addr) return refuse(TVK_ERROR_INVALID_ARGUMENT, "get_instance_proc_addr is NULL");
  if (info->frames_in_flight > tressvk::kMaxFramesInFlight)
    return refuse(TVK_ERROR_INVALID_ARGUMENT, "frames_in_flight " + std::to_string(info->frames_in_flight) +
                                                  " exceeds " + std::to_string(tressvk::kMaxFramesInFlight));
  if (info->api_version < VK_API_VERSION_1_3)
    return refuse(TVK_ERROR_MISSING_FEATURE, "api_version: TressVK needs a Vulkan 1.3 instance and device");

  // Owned until handed to the host: every early return below destroys what was made so far.
  std::unique_ptr<TvkContext_T, void (*)(TvkContext_T*)> ctx(new (std::nothrow) TvkContext_T(),
                                                             [](TvkContext_T* c) { tressvk_destroy_context(c); });
  if (!ctx) return refuse(TVK_ERROR_OUT_OF_MEMORY, "out of host memory");
  ctx->info = *info;
  ctx->frames_in_flight = info->frames_in_flight ? info->frames_in_flight : 2;
  const TvkResult r = tressvk::guarded(*ctx, kCall, [&]() -> TvkResult {
    return tressvk::init_context(*ctx);
  });
  if (r != TVK_SUCCESS) {
    fail_without_context(r, "%s", ctx->last_error.c_str());
    return r;
  }
  *out_context = ctx.release();
  return TVK_SUCCESS;
}

void tressvk_destroy_context(TvkContext context) {
  TvkContext_T* ctx = context;
  if (!ctx) return;
  tressvk::destroy_sim_objects(*ctx);
  ctx->collect_garbage(true);
  if (ctx->allocator) {
    // Assets or instances the host did not destroy still hold VMA allocations, and VMA asserts on them; report
    // them instead (their handles become invalid with the context).
    VmaTotalStatistics stats{};
    vmaCalculateStatistics(ctx->allocator, &stats);
    if (stats.total.statistics.allocationCount != 0)
      ctx->message(TVK_MESSAGE_ERROR,
                   "tressvk_destroy_context: %u GPU allocation(s) of assets or instances not destroyed first (leaked)",
                   stats.total.statistics.allocationCount);
    else
      vmaDestroyAllocator(ctx->allocator);
  }
  delete ctx;
}

void tressvk_report_device_lost(TvkContext context) {
  TvkContext_T* ctx = context;
  if (!ctx || ctx->device_lost) return;
  ctx->device_lost = true;
  ctx->message(TVK_MESSAGE_ERROR, "the host reported VK_ERROR_DEVICE_LOST: every call that uses the device now "
               "returns TVK_ERROR_DEVICE_LOST; destroy every TressVK object and the context to recover");
}

VkBool32 tressvk_is_device_lost(TvkContext context) {
  const TvkContext_T* ctx = context;
  return ctx && ctx->device_lost ? VK_TRUE : VK_FALSE;
}

TvkResult tressvk_get_memory_usage(TvkContext context, TvkMemoryUsage* out_usage) {
  TvkContext_T* ctx = context;
  if (!ctx) return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_memory_usage: context is NULL");
  if (!out_usage) return ctx->fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_memory_usage: out_usage is NULL");
  VmaTotalStatistics stats{};
  vmaCalculateStatistics(ctx->allocator, &stats);
  out_usage->device_bytes = stats.total.statistics.allocationBytes;
  out_usage->allocation_count = stats.total.statistics.allocationCount;
  return TVK_SUCCESS;
}

const char* tressvk_last_error(TvkContext context) {
  TvkContext_T* ctx = context;
  return ctx ? ctx->last_error.c_str() : tressvk::g_error_without_context.c_str();
}

}  // extern "C"
