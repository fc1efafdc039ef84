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
 * - Functions return TvkResult; no C++ exception ever crosses this interface. Every failure records a message
 *   that names the function and the field or Vulkan call at fault: it goes to the host's message callback and is
 *   available from tressvk_last_error() (of the context, or of the calling thread for calls that have no valid
 *   context, e.g. a failed tressvk_create_context).
 * - A failed create or load call leaves nothing behind: no object, no GPU memory, no change to the objects it was
 *   given (an asset's instance count included), so the host may fix the input and call again.
 * - Units are metres, seconds and radians.
 * - Thread safety: a context and the objects made from it may be used from one thread at a time, with one
 *   exception for a frame's per-instance work: tressvk_set_frame, tressvk_plan_frame, tressvk_set_sim_params,
 *   tressvk_set_sim_settings and tressvk_set_draw_strands calls for distinct instances of a context may run at the same
 *   time, from any threads (a job system's workers: each character's job calls them for its own instance), while no
 *   other call of that context runs. Their failures reach the message callback one at a time (the plugin serialises
 *   them) and tressvk_last_error(context) once they have returned.
 *
 * docs/integration.md walks through a complete integration.
 */
#ifndef TRESSVK_TRESSVK_H
#define TRESSVK_TRESSVK_H

#include <stddef.h>
#include <stdint.h>

/* Only types are used here: this header neither defines VK_NO_PROTOTYPES nor needs it, so a host that includes
 * it before <vulkan/vulkan.h> keeps its vk* prototypes (and a volk host defines VK_NO_PROTOTYPES itself). */
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
#define TVK_VERSION_MINOR 2
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
  TVK_ERROR_VERSION_MISMATCH = -7,  /* header and library disagree (see TVK_CHECK_VERSION) */
  TVK_ERROR_DEVICE_LOST = -8        /* the device was lost (see tressvk_report_device_lost): recreate the context */
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
  VkBool32 enable_timestamps;                 /* record GPU timestamps around every pass (tressvk_get_pass_timings) */
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

/* Device loss. When the host's vkQueueSubmit, vkWaitForFences, vkDeviceWaitIdle or present returns
 * VK_ERROR_DEVICE_LOST, it tells the context so. TressVK also marks the context lost by itself when one of its own
 * Vulkan calls returns VK_ERROR_DEVICE_LOST (e.g. reading timestamps). From then on every call that would use the
 * device (load, create, tressvk_new_frame, every tressvk_cmd_*) returns TVK_ERROR_DEVICE_LOST with a message; the
 * destroy calls still work and never wait for the GPU. To recover, destroy every renderer, instance and asset and
 * the context, recreate the VkDevice, then create a new context and load again (docs/integration.md, "Device
 * loss"). Returns VK_TRUE once the context is lost. */
TVK_API void tressvk_report_device_lost(TvkContext context);
TVK_API VkBool32 tressvk_is_device_lost(TvkContext context);

TVK_API TvkResult tressvk_get_memory_usage(TvkContext context, TvkMemoryUsage* out_usage);
/* The message of the last failed call on this context ("" when none). With context NULL: the message of the last
 * call on this thread that failed without a valid context (tressvk_create_context, or any call given a NULL
 * handle). Valid until the next call. */
TVK_API const char* tressvk_last_error(TvkContext context);


/* ---- Assets ------------------------------------------------------------------------------------------------
 * A baked .tvkhair asset (see tressvk-bake). Its static GPU buffers are shared by every instance made from it.
 * Loading verifies every checksum and records the upload (copies from a staging buffer, then a barrier that makes
 * the data visible to compute and vertex shaders) into `upload_command_buffer`, which the host submits before, or
 * as part of, the first frame that simulates an instance of the asset. The staging memory is freed
 * frames_in_flight frames later (see tressvk_new_frame). */
typedef struct TvkAsset_T* TvkAsset;

typedef struct TvkAssetLoadInfo {
  size_t struct_size;                /* sizeof(TvkAssetLoadInfo) */
  const void* next;
  const char* path;                  /* a .tvkhair file, or NULL to load from `data` */
  const void* data;                  /* the bytes of a .tvkhair file when path is NULL; copied, need not outlive the call */
  size_t size;
  VkCommandBuffer upload_command_buffer; /* recording, outside any render pass */
} TvkAssetLoadInfo;

typedef struct TvkAssetInfo {
  uint32_t guide_count;
  uint32_t follow_per_guide;
  uint32_t total_strands;            /* guides * (1 + follows), the strands rendered */
  uint32_t vertices_per_strand;
  uint32_t group_count;
  uint32_t bone_count;
  double origin[3];                  /* m, asset space origin that positions are relative to */
  float median_strand_length;        /* m, over guides */
} TvkAssetInfo;

TVK_API TvkResult tressvk_load_asset(TvkContext context, const TvkAssetLoadInfo* info, TvkAsset* out_asset);
/* The asset's memory is released once no instance uses it any more and the GPU is done with it. */
TVK_API void tressvk_destroy_asset(TvkAsset asset);
TVK_API TvkResult tressvk_get_asset_info(TvkAsset asset, TvkAssetInfo* out_info);
/* Name of group `group` ("" when out of range). Valid as long as the asset. */
TVK_API const char* tressvk_get_asset_group_name(TvkAsset asset, uint32_t group);

/* ---- Instances ---------------------------------------------------------------------------------------------
 * One simulated head of hair: an asset placed in the world, with its own state and parameters. */
typedef struct TvkInstance_T* TvkInstance;

typedef struct TvkInstanceCreateInfo {
  size_t struct_size;                /* sizeof(TvkInstanceCreateInfo) */
  const void* next;
  TvkAsset asset;
  const TvkSimSettings* settings;    /* NULL = TVK_SIM_SETTINGS_DEFAULT_INIT */
  const TvkSimParams* params;        /* NULL = TVK_SIM_PARAMS_DEFAULT_INIT for every group */
} TvkInstanceCreateInfo;

TVK_API TvkResult tressvk_create_instance(TvkContext context, const TvkInstanceCreateInfo* info,
                                          TvkInstance* out_instance);
/* Freed frames_in_flight frames later, so the host may destroy an instance while a frame using it is in flight. */
TVK_API void tressvk_destroy_instance(TvkInstance instance);
/* Parameters of one strand group, or of every group with group = TVK_ALL_GROUPS. Take effect next frame. */
#define TVK_ALL_GROUPS 0xFFFFFFFFu
TVK_API TvkResult tressvk_set_sim_params(TvkInstance instance, uint32_t group, const TvkSimParams* params);
TVK_API TvkResult tressvk_set_sim_settings(TvkInstance instance, const TvkSimSettings* settings);
/* What the instance runs: its settings and one group's parameters as set, with every value left to the model
 * (TVK_STEP_RATE_BY_MODEL, TVK_ITERATIONS_BY_MODEL) replaced by the model's, and TVK_SIM_MODEL_DEFAULT by the
 * model it stands for. */
TVK_API TvkResult tressvk_get_sim_settings(TvkInstance instance, TvkSimSettings* out_settings);
TVK_API TvkResult tressvk_get_sim_params(TvkInstance instance, uint32_t group, TvkSimParams* out_params);
/* This frame's motion, wind and colliders. Call before tressvk_cmd_simulate; the frame is copied. An instance
 * whose frame was not set since its last simulation keeps its pose and advances no time (dt 0). */
TVK_API TvkResult tressvk_set_frame(TvkInstance instance, const TvkSimFrame* frame);
/* Plans the instance's frame now (the frame of the last tressvk_set_frame, or dt 0 when none was set since the last
 * simulation): its substeps, the skinning of every bone its strands read and its colliders and wind, in double
 * precision and simulation space, converted for the GPU. This is the simulation's CPU work for the instance;
 * tressvk_cmd_simulate then only copies the plan into the frame's parameters. Optional: tressvk_cmd_simulate plans
 * every instance not planned, so calling it changes no result, only where the work runs. Call it after the frame's
 * tressvk_set_frame, from any thread (see "Thread safety" above: the per-instance calls of distinct instances may run
 * concurrently), and simulate the instance before its next tressvk_set_frame (which refuses a planned instance).
 * Planning twice is planning once. A planned frame keeps the step rate, gravity and step limits it was planned with;
 * the other settings and the parameters are read when it is simulated. */
TVK_API TvkResult tressvk_plan_frame(TvkInstance instance);
/* Follow hairs only for the strands the host will draw: `strands` is the most rendered strands (a prefix: guides,
 * then follow layers; tressvk_get_draw_strands gives the count a draw's LOD picks) any draw of the coming frames
 * takes, and the simulation writes follow hairs below it only: a groom drawn thinned by LOD does not pay for the
 * follows it does not show. Guides are always simulated. 0 = every rendered strand (the default). Takes effect at
 * the next tressvk_cmd_simulate; a draw never takes more strands than the last frame that ran steps wrote, so raising
 * the count shows the new follows from that frame on. */
TVK_API TvkResult tressvk_set_draw_strands(TvkInstance instance, uint32_t strands);

/* Builds ahead of time the compute pipelines that simulating `frame` will use (NULL: the frame last given to
 * tressvk_set_frame), so that the first tressvk_cmd_simulate does not build them (36 ms on lavapipe). Pipelines depend
 * on the asset's strand size, the instance's parameters and which terms the frame has (wind, capsules, bones);
 * call it after the parameters are set, e.g. at load time with the first frame. A follow-the-leader instance also
 * gets the kernel it takes in a crowd (4 or more such instances in one tressvk_cmd_simulate with 400 k guide
 * vertices between them). Records nothing; optional. */
TVK_API TvkResult tressvk_prewarm_instance(TvkInstance instance, const TvkSimFrame* frame);

/* The simulated state, for hosts that draw or read it themselves (read only: a guide that sleeps,
 * TvkSimSettings::sleep_below, would not see a host's write). Per-vertex buffers hold strands in blocks of
 * TVK_STRAND_BLOCK, vertex-major within a block (so that GPU threads walking neighbouring strands read neighbouring
 * addresses): vertex v of rendered strand s (guides first, then follow layers) is element
 *   i = tvk_vertex_index(s, v, vertices_per_strand)
 * and lies at anchors[s % guide_count].xyz + positions[i].xyz in simulation space (world axes, origin at `origin`),
 * at origin + that in the world. Positions are kept relative to each guide's anchor (its skinned root) so that
 * float32 rounding is relative to the strand, not to the character. Buffers hold whole blocks. Follow strands at or
 * above a count given to tressvk_set_draw_strands are not written and hold stale values. */
#define TVK_STRAND_BLOCK 32u
static inline uint64_t tvk_vertex_index(uint64_t strand, uint64_t vertex, uint64_t vertices_per_strand) {
  return strand / TVK_STRAND_BLOCK * TVK_STRAND_BLOCK * vertices_per_strand + vertex * TVK_STRAND_BLOCK +
         strand % TVK_STRAND_BLOCK;
}
typedef struct TvkInstanceBuffers {
  VkBuffer positions;                /* vec4 per vertex of every rendered strand (guides, then follow layers): xyz the
                                        offset from the strand's anchor, w = inverse mass */
  VkBuffer tangents;                 /* vec4 per guide vertex, same layout; xyz unit. A follow strand's tangent is its
                                        guide's: vertex v of rendered strand s takes tangents[tvk_vertex_index(
                                        s % guide_count, v, vertices_per_strand)] */
  VkBuffer previous_positions;       /* vec4 per guide vertex, the previous step (offset from the same anchor) */
  VkBuffer previous_previous_positions; /* vec4 per guide vertex, two steps back (for checking against the
                                        reference, tressvk::reference::Simulator::set_state) */
  VkBuffer anchors;                  /* vec4 per guide: xyz its anchor in simulation space; w the guide's count of
                                        quiet still frames, >= TVK_ASLEEP_QUIET_FRAMES while it sleeps */
  VkDeviceSize positions_size;
  VkDeviceSize tangents_size;
  VkDeviceSize previous_positions_size;  /* also the size of previous_previous_positions */
  VkDeviceSize anchors_size;
  uint32_t guide_count;
  uint32_t vertices_per_strand;
  uint32_t follow_per_guide;         /* rendered strands = guide_count * (1 + follow_per_guide) */
  double origin[3];                  /* m, world position of the simulation-space origin after the last frame */
} TvkInstanceBuffers;

TVK_API TvkResult tressvk_get_instance_buffers(TvkInstance instance, TvkInstanceBuffers* out_buffers);

typedef struct TvkInstanceStats {
  uint64_t steps;                    /* simulation steps run so far */
  uint64_t frames;                   /* frames simulated so far */
  uint32_t nonfinite_strand_resets;  /* strands reset after going non-finite; read back from the GPU, current as of
                                        the last frame the host waited for */
  uint32_t steps_last_frame;
} TvkInstanceStats;

TVK_API TvkResult tressvk_get_instance_stats(TvkInstance instance, TvkInstanceStats* out_stats);

/* ---- Frames ------------------------------------------------------------------------------------------------
 * Call once per host frame before recording TressVK work. By calling it the host promises that the GPU has
 * finished the work it recorded frames_in_flight frames ago: per-frame parameter slices are reused and released
 * resources are freed on that promise. */
TVK_API TvkResult tressvk_new_frame(TvkContext context);

typedef struct TvkSimulateInfo {
  size_t struct_size;                /* sizeof(TvkSimulateInfo) */
  const void* next;
  uint32_t instance_count;
  const TvkInstance* instances;      /* each has had tressvk_set_frame called this frame */
} TvkSimulateInfo;

/* Records the whole simulation of the listed instances for this frame into `command_buffer`, which must be
 * recording and outside any render pass (the simulation owns its barriers, which cannot be recorded inside one).
 *
 * Synchronization contract:
 * - on entry, TressVK orders its work after earlier vertex-shader, fragment-shader, compute and transfer accesses
 *   to the instances' buffers (the previous frame's draws and any host copies);
 * - between passes, buffer barriers scoped to exactly the buffers a pass reads and writes;
 * - on exit, positions, tangents and anchors are visible to VERTEX_SHADER and COMPUTE_SHADER storage reads. A host that
 *   copies them (transfer) records its own COMPUTE_SHADER write -> COPY read barrier.
 * State disturbed in the command buffer: the bound compute pipeline, compute descriptor set 0 and compute push
 * constants. Graphics state is untouched. */
TVK_API TvkResult tressvk_cmd_simulate(TvkContext context, VkCommandBuffer command_buffer, const TvkSimulateInfo* info);

/* The passes recorded by the last tressvk_cmd_simulate, in order, deduplicated across substeps and instances
 * (the base pass and the terms compiled in: by default one fused frame pass, e.g.
 * "frame+vsp+local_shape+global+collision"; with TRESSVK_SIM_PATH=passes e.g. "integrate+global", "vsp",
 * "local_shape", "length+wind+collision+clamp", "follow"). Returns how many there are; writes at
 * most `capacity` names (static strings). */
TVK_API uint32_t tressvk_get_recorded_passes(TvkContext context, const char** names, uint32_t capacity);

/* The compute dispatches the last tressvk_cmd_simulate recorded: every pass of every substep of every instance (by
 * default one per instance that ran; 0 when every instance was idle). Needs no timestamps, so a host can check its
 * dispatch budget, or time its frames, without the timestamps that tressvk_get_pass_timings writes into the frame. */
TVK_API uint32_t tressvk_get_recorded_dispatches(TvkContext context);

typedef struct TvkPassTiming {
  const char* name;                  /* pass name, as in tressvk_get_recorded_passes */
  uint32_t dispatches;               /* dispatches of that pass in the frame (substeps x instances) */
  double milliseconds;               /* GPU time summed over those dispatches */
} TvkPassTiming;

/* Per-pass GPU times of the newest frame that tressvk_new_frame's promise says is complete (needs
 * enable_timestamps at context creation and a queue family with timestamp support). The compute hair path's
 * passes of that frame follow the simulation's, named "render.*" (recorded after tressvk_cmd_simulate in the same
 * frame; a frame without a simulate call times none of them). Returns the number of passes;
 * writes at most `capacity`. 0 when no results are available: after the last frame, the host (once the GPU is
 * done) calls tressvk_new_frame frames_in_flight more times to make it readable. */
TVK_API uint32_t tressvk_get_pass_timings(TvkContext context, TvkPassTiming* timings, uint32_t capacity);

#ifdef __cplusplus
}
#endif

/* The rendering half of the interface (hair shadow and shading passes). */
#include "tressvk/render.h"

#endif /* TRESSVK_TRESSVK_H */
