/* TressVK: real-time strand hair for Vulkan engines.
 *
 * The C interface of the `tressvk` plugin library. The host engine owns the instance, the device and every
 * queue; it hands them to tressvk_create_context() and then records TressVK's work into its own command buffers.
 * TressVK never submits work in steady state and never touches the host's global Vulkan function pointers: it
 * loads its own device function table from the `get_instance_proc_addr` the host gives it.
 *
 * Conventions
 * - Every create-info struct starts with `struct_size` (set it to sizeof the struct) and `next` (NULL or an
 *   extension chain). Zero-initialise structs before filling them: zero means "default" for every field.
 * - Functions return TvkResult; no C++ exception ever crosses this interface. Messages go to the host's
 *   message callback, and the last error of a context is available from tressvk_last_error().
 * - Units are metres, seconds and radians.
 * - Thread safety: a context and the objects made from it may be used from one thread at a time.
 *
 * docs/integration.md walks through a complete integration.
 */
#ifndef TRESSVK_TRESSVK_H
#define TRESSVK_TRESSVK_H

#include <stddef.h>
#include <stdint.h>

#ifndef VK_NO_PROTOTYPES
#define VK_NO_PROTOTYPES
#endif
#include <vulkan/vulkan.h>

#include "tressvk/sim_types.h"

#if defined(_WIN32)
#if defined(TRESSVK_BUILDING_LIBRARY)
#define TVK_API __declspec(dllexport)
#else
#define TVK_API __declspec(dllimport)
#endif
#else
#define TVK_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define TVK_VERSION_MAJOR 0
#define TVK_VERSION_MINOR 1
#define TVK_VERSION_PATCH 0
#define TVK_VERSION_NUM (TVK_VERSION_MAJOR * 10000 + TVK_VERSION_MINOR * 100 + TVK_VERSION_PATCH)

typedef enum TvkResult {
  TVK_SUCCESS = 0,
  TVK_ERROR_INVALID_ARGUMENT = -1,  /* a null pointer, a wrong struct_size, a value out of range */
  TVK_ERROR_VULKAN = -2,            /* a Vulkan call failed; the message names it and its VkResult */
  TVK_ERROR_OUT_OF_MEMORY = -3,     /* host or device memory */
  TVK_ERROR_INVALID_ASSET = -4,     /* a .tvkhair file or buffer that is corrupt, truncated or too new */
  TVK_ERROR_IO = -5,                /* a file that cannot be read */
  TVK_ERROR_MISSING_FEATURE = -6,   /* the device lacks a feature or extension TressVK needs */
  TVK_ERROR_VERSION_MISMATCH = -7   /* header and library disagree (see TVK_CHECK_VERSION) */
} TvkResult;

typedef enum TvkMessageSeverity {
  TVK_MESSAGE_INFO = 0,
  TVK_MESSAGE_WARNING = 1,
  TVK_MESSAGE_ERROR = 2
} TvkMessageSeverity;

typedef void (*PFN_tvkMessageCallback)(TvkMessageSeverity severity, const char* message, void* user_data);

typedef struct TvkContext_T* TvkContext;

/* What the device must provide, to be merged into the host's VkDeviceCreateInfo before vkCreateDevice.
 * TressVK needs Vulkan 1.3 with synchronization2 and dynamicRendering; it needs no device extension. */
typedef struct TvkDeviceRequirements {
  uint32_t min_api_version;                   /* VK_API_VERSION_1_3 */
  uint32_t extension_count;                   /* device extensions TressVK needs (currently 0) */
  const char* const* extensions;
  VkBool32 synchronization2;                  /* VkPhysicalDeviceVulkan13Features::synchronization2 */
  VkBool32 dynamic_rendering;                 /* VkPhysicalDeviceVulkan13Features::dynamicRendering */
} TvkDeviceRequirements;

typedef struct TvkContextCreateInfo {
  size_t struct_size;                         /* sizeof(TvkContextCreateInfo) */
  const void* next;                           /* NULL */
  uint32_t api_version;                       /* the host's VkApplicationInfo::apiVersion (>= 1.3) */
  VkInstance instance;
  VkPhysicalDevice physical_device;
  VkDevice device;                            /* created with the features of tressvk_get_device_requirements */
  uint32_t queue_family_index;                /* the family whose command buffers TressVK records into */
  PFN_vkGetInstanceProcAddr get_instance_proc_addr;
  uint32_t frames_in_flight;                  /* 0 means 2; per-frame data is ringed this many times */
  VkPipelineCache pipeline_cache;             /* optional */
  const VkAllocationCallbacks* allocator;     /* optional, used for Vulkan objects */
  PFN_tvkMessageCallback message_callback;    /* optional */
  void* message_user_data;
} TvkContextCreateInfo;

typedef struct TvkMemoryUsage {
  uint64_t device_bytes;                      /* GPU memory TressVK allocated (buffers and images) */
  uint32_t allocation_count;
} TvkMemoryUsage;

/* Version of the library actually linked (TVK_VERSION_NUM of the build). */
TVK_API uint32_t tressvk_version(void);
/* Returns TVK_ERROR_VERSION_MISMATCH when the header used by the caller does not match the library. */
TVK_API TvkResult tressvk_check_version(uint32_t header_version_num, size_t context_create_info_size);
#define TVK_CHECK_VERSION() tressvk_check_version(TVK_VERSION_NUM, sizeof(TvkContextCreateInfo))

TVK_API const char* tressvk_result_string(TvkResult result);

TVK_API void tressvk_get_device_requirements(TvkDeviceRequirements* out_requirements);

TVK_API TvkResult tressvk_create_context(const TvkContextCreateInfo* info, TvkContext* out_context);
/* The host must make sure the GPU no longer uses anything of the context (e.g. vkDeviceWaitIdle) first. */
TVK_API void tressvk_destroy_context(TvkContext context);

TVK_API TvkResult tressvk_get_memory_usage(TvkContext context, TvkMemoryUsage* out_usage);
/* The message of the last failed call on this context ("" when none). Valid until the next call. */
TVK_API const char* tressvk_last_error(TvkContext context);

#ifdef __cplusplus
}
#endif

#endif /* TRESSVK_TRESSVK_H */
