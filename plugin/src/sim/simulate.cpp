// Recording the simulation: pipelines per pass variant, the per-frame parameter ring, and the barriers between
// passes, derived from the pass table's read/write sets (see hazards.hpp).
#include "core/objects.hpp"
#include "sim/fused.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

using tressvk::Context;
using tressvk::sim::PassId;
using tressvk::sim::PassUse;

namespace tressvk {

TvkResult ensure_sim_layouts(Context& ctx) {
  if (ctx.sim_pipeline_layout) return TVK_SUCCESS;
  // A set layout left by an earlier attempt whose pipeline layout failed is reused, not made (and leaked) again.
  if (!ctx.sim_set_layout) {
  std::array<VkDescriptorSetLayoutBinding, sim::kBindingCount> bindings{};
  for (uint32_t b = 0; b < sim::kBindingCount; ++b) {
    bindings[b].binding = b;
    bindings[b].descriptorType =
        is_dynamic_binding(b) ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[b].descriptorCount = 1;
    bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo sci{};
  sci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  sci.bindingCount = sim::kBindingCount;
  sci.pBindings = bindings.data();
  if (TvkResult r = ctx.check(
          ctx.vk.vkCreateDescriptorSetLayout(ctx.info.device, &sci, ctx.info.allocator, &ctx.sim_set_layout),
          "vkCreateDescriptorSetLayout");
      r != TVK_SUCCESS) {
    ctx.sim_set_layout = VK_NULL_HANDLE;
    return r;
  }
  }
  const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(sim::PushConstants)};
  VkPipelineLayoutCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  pci.setLayoutCount = 1;
  pci.pSetLayouts = &ctx.sim_set_layout;
  pci.pushConstantRangeCount = 1;
  pci.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  const TvkResult r =
      ctx.check(ctx.vk.vkCreatePipelineLayout(ctx.info.device, &pci, ctx.info.allocator, &layout), "vkCreatePipelineLayout");
  if (r == TVK_SUCCESS) ctx.sim_pipeline_layout = layout;
  return r;
}

void destroy_sim_objects(Context& ctx) {
  for (const Context::PipelineEntry& e : ctx.pipelines)
    ctx.vk.vkDestroyPipeline(ctx.info.device, e.pipeline, ctx.info.allocator);
  ctx.pipelines.clear();
  if (ctx.sim_pipeline_layout)
    ctx.vk.vkDestroyPipelineLayout(ctx.info.device, ctx.sim_pipeline_layout, ctx.info.allocator);
  if (ctx.sim_set_layout)
    ctx.vk.vkDestroyDescriptorSetLayout(ctx.info.device, ctx.sim_set_layout, ctx.info.allocator);
  if (ctx.timestamp_pool) ctx.vk.vkDestroyQueryPool(ctx.info.device, ctx.timestamp_pool, ctx.info.allocator);
  ctx.sim_pipeline_layout = VK_NULL_HANDLE;
  ctx.sim_set_layout = VK_NULL_HANDLE;
  ctx.timestamp_pool = VK_NULL_HANDLE;
}

namespace {

// The strands a workgroup of the conservative local shape's subgroup variant on this device (sim/fused.hpp).
uint32_t conservative_slots(const Context& ctx, uint32_t vertices_per_strand) {
  const VkPhysicalDeviceLimits& l = ctx.device_properties.limits;
  return sim::conservative_slots(vertices_per_strand, ctx.subgroup_size,
                                 std::min(l.maxComputeWorkGroupInvocations, l.maxComputeWorkGroupSize[0]),
                                 l.maxComputeSharedMemorySize);
}

bool pipeline_stats_requested() {
  static const bool on = env_flag("TRESSVK_PIPELINE_STATS");
  return on;
}

void report_pipeline_stats(Context& ctx, VkPipeline pipeline, const char* name, uint32_t workgroup) {
  VkPipelineInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR;
  info.pipeline = pipeline;
  uint32_t executables = 0;
  if (ctx.vk.vkGetPipelineExecutablePropertiesKHR(ctx.info.device, &info, &executables, nullptr) != VK_SUCCESS) return;
  for (uint32_t e = 0; e < executables; ++e) {
    VkPipelineExecutableInfoKHR ei{};
    ei.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR;
    ei.pipeline = pipeline;
    ei.executableIndex = e;
    uint32_t count = 0;
    if (ctx.vk.vkGetPipelineExecutableStatisticsKHR(ctx.info.device, &ei, &count, nullptr) != VK_SUCCESS) continue;
    std::vector<VkPipelineExecutableStatisticKHR> st(count);
    for (VkPipelineExecutableStatisticKHR& x : st) x.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR;
    if (ctx.vk.vkGetPipelineExecutableStatisticsKHR(ctx.info.device, &ei, &count, st.data()) != VK_SUCCESS) continue;
    std::string line;
    for (const VkPipelineExecutableStatisticKHR& x : st) {
      line += line.empty() ? "" : ", ";
      line += x.name;
      line += ' ';
      switch (x.format) {
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: line += x.value.b32 ? "yes" : "no"; break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: line += std::to_string(x.value.i64); break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: line += std::to_string(x.value.u64); break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: line += std::to_string(x.value.f64); break;
        default: line += '?';
      }
    }
    ctx.message(TVK_MESSAGE_INFO, "pipeline %s (workgroup %u): %s", name, workgroup, line.c_str());
  }
}

TvkResult get_pipeline(Context& ctx, const PassUse& use, uint32_t n, uint32_t k, VkPipeline& out) {
  const uint64_t key = uint64_t(use.info->id) | uint64_t(n) << 8 | uint64_t(k) << 16 | uint64_t(use.features) << 32 |
                       uint64_t(use.capsule_count) << 48;
  for (const Context::PipelineEntry& e : ctx.pipelines)
    if (e.key == key) {
      out = e.pipeline;
      return TVK_SUCCESS;
    }
  VkShaderModuleCreateInfo mci{};
  mci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  mci.codeSize = use.info->spirv_bytes;
  mci.pCode = use.info->spirv;
  VkShaderModule module = VK_NULL_HANDLE;
  if (TvkResult r = ctx.check(ctx.vk.vkCreateShaderModule(ctx.info.device, &mci, ctx.info.allocator, &module),
                              "vkCreateShaderModule");
      r != TVK_SUCCESS)
    return r;
  const uint32_t wg = sim::is_frame_lanes(use.info)
                         ? sim::frame_lanes_workgroup(use.info, n, ctx.subgroup_size, conservative_slots(ctx, n),
                                                      (use.features & sim::kFeatureConservative) != 0)
                     : sim::is_frame_private(use.info) ? sim::frame_private_workgroup(use)
                                                       : ctx.workgroup_size;
  // Constant 5: the run kernel's RUN (other shaders have no constant 5, which Vulkan allows).
  const std::array<uint32_t, 6> values = {wg, n, k, use.features, use.capsule_count, sim::frame_run_length(use.info)};
  std::array<VkSpecializationMapEntry, 6> entries{};
  for (uint32_t i = 0; i < 6; ++i) entries[i] = {i, i * 4, 4};
  const VkSpecializationInfo spec{6, entries.data(), sizeof(values), values.data()};
  VkComputePipelineCreateInfo cpi{};
  cpi.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  cpi.stage = {};
  cpi.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  cpi.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  cpi.stage.module = module;
  cpi.stage.pName = "main";
  cpi.stage.pSpecializationInfo = &spec;
  cpi.layout = ctx.sim_pipeline_layout;
  // TRESSVK_PIPELINE_STATS=1 with VK_KHR_pipeline_executable_properties enabled by the host (tressvk-bench and the
  // demo enable it under the same variable): each simulation pipeline's compiler statistics (registers, spills, ...)
  // as info messages. A diagnostic: occupancy, set by registers and shared memory, decides these kernels' speed.
  const bool stats = pipeline_stats_requested() && ctx.vk.vkGetPipelineExecutableStatisticsKHR != nullptr &&
                     ctx.vk.vkGetPipelineExecutablePropertiesKHR != nullptr;
  if (stats) cpi.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  VkPipeline pipeline = VK_NULL_HANDLE;
  const VkResult vr = ctx.vk.vkCreateComputePipelines(ctx.info.device, ctx.info.pipeline_cache, 1, &cpi,
                                                      ctx.info.allocator, &pipeline);
  ctx.vk.vkDestroyShaderModule(ctx.info.device, module, ctx.info.allocator);
  if (TvkResult r = ctx.check(vr, "vkCreateComputePipelines"); r != TVK_SUCCESS) return r;
  if (stats) report_pipeline_stats(ctx, pipeline, use.name.c_str(), wg);
  ctx.pipelines.push_back({key, pipeline});
  out = pipeline;
  return TVK_SUCCESS;
}

// The instance buffer behind a writable binding (the only ones that can carry a hazard).
VkBuffer writable_buffer(const TvkInstance_T& inst, uint32_t binding) {
  switch (binding) {
    case sim::kBindingPositions: return inst.positions.buffer;
    case sim::kBindingPrevPositions: return inst.prev.buffer;
    case sim::kBindingPrevPrevPositions: return inst.prevprev.buffer;
    case sim::kBindingTangents: return inst.tangents.buffer;
    case sim::kBindingCounters: return inst.counters.buffer;
    case sim::kBindingAnchors: return inst.anchors.buffer;
    default: return VK_NULL_HANDLE;
  }
}

VkBufferMemoryBarrier2 buffer_barrier(VkBuffer buffer, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                                      VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  VkBufferMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2;
  b.srcStageMask = src_stage;
  b.srcAccessMask = src_access;
  b.dstStageMask = dst_stage;
  b.dstAccessMask = dst_access;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.buffer = buffer;
  b.size = VK_WHOLE_SIZE;
  return b;
}

void record_barriers(Context& ctx, VkCommandBuffer cmd, const std::vector<VkBufferMemoryBarrier2>& barriers) {
  if (barriers.empty()) return;
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.bufferMemoryBarrierCount = static_cast<uint32_t>(barriers.size());
  dep.pBufferMemoryBarriers = barriers.data();
  ctx.vk.vkCmdPipelineBarrier2(cmd, &dep);
}

struct InstanceWork {
  TvkInstance_T* inst = nullptr;
  PlannedFrame plan;
  uint32_t skin_stride = 0;  // vec4 per substep
  std::vector<PassUse> passes;
  std::array<uint32_t, 3> dynamic_offsets{};
  float rest_move = 0.0f;  // the push constant: the sleeping threshold in a still frame, else 0
  uint32_t follow_strands = 0;  // the push constant: rendered strands whose follows this frame writes
  uint32_t counter_index = 0;  // the push constant: this frame slot's word (resets, awake bit)
  bool idle = false;           // every guide asleep and the frame still: nothing to record
};

// What a step of this frame sees besides the strands' own state: the group parameters, the step's parameters (its
// index within the frame aside) and its skinning rows, as the GPU gets them, laid out one after the other. A frame
// is still (layout.glsl, "Sleeping strands") when every step's bytes equal those of the last step the instance ran:
// no input can move a strand then. Compared in place (a bone-skinned groom's rows are kilobytes a step), and the last
// step's bytes kept in `last`, whose storage is reused from frame to frame.
bool still_and_keep(const std::vector<sim::GroupParams>& groups, const model::GpuFrame& gpu, uint32_t steps,
                    std::vector<std::byte>& last) {
  const size_t group_bytes = groups.size() * sizeof(sim::GroupParams);
  const size_t skin_bytes = size_t{gpu.skin_stride} * sizeof(sim::Vec4);
  const size_t total = group_bytes + sizeof(sim::StepParams) + skin_bytes;
  const auto params_of = [&](uint32_t step) {
    sim::StepParams sp = gpu.steps[step];
    sp.flags[1] = 0;
    return sp;
  };
  const auto skin_of = [&](uint32_t step) { return gpu.skin.data() + size_t{step} * gpu.skin_stride; };
  bool still = steps > 0 && last.size() == total &&
               (group_bytes == 0 || std::memcmp(last.data(), groups.data(), group_bytes) == 0);
  for (uint32_t step = 0; still && step < steps; ++step) {
    const sim::StepParams sp = params_of(step);
    still = std::memcmp(last.data() + group_bytes, &sp, sizeof(sp)) == 0 &&
            (skin_bytes == 0 || std::memcmp(last.data() + group_bytes + sizeof(sp), skin_of(step), skin_bytes) == 0);
  }
  if (steps > 0) {
    const sim::StepParams sp = params_of(steps - 1);
    last.resize(total);
    if (group_bytes) std::memcpy(last.data(), groups.data(), group_bytes);
    std::memcpy(last.data() + group_bytes, &sp, sizeof(sp));
    if (skin_bytes) std::memcpy(last.data() + group_bytes + sizeof(sp), skin_of(steps - 1), skin_bytes);
  }
  return still;
}

// The passes a frame of this instance records (sim/fused.hpp): the compliant model's lane kernel, or on the process's
// simulation path (TRESSVK_SIM_PATH) the run kernel, the one-thread kernel (its shared-memory variant only where the
// strand block fits) or one pass per dispatch. crowd: the frame is one of a crowd's (crowd_prefers_one_thread), where
// the default path takes the one-thread kernel instead of the runs.
std::vector<PassUse> passes_for_path(const Context& ctx, const TvkInstance_T& inst, const sim::SceneTerms& terms,
                                     bool crowd) {
  // The conservative local shape keeps its systems in shared memory: the subgroup variant only where a workgroup of
  // at least one subgroup's strands and their systems fit the device (conservative_slots).
  const model::StrandModel strand_model = model::resolve_model(inst.settings.model);
  if (model::is_compliant_family(strand_model)) {
    const uint32_t n = inst.asset->rest.vertices_per_strand;
    const bool conservative = strand_model == model::StrandModel::kConservative;
    const uint32_t refinements = conservative ? sim::conservative_refinements_for(inst.settings.time.step_rate) : 0u;
    return {sim::frame_lanes_pass_use(
        terms,
        sim::lanes_backend_from_environment() == sim::LanesBackend::kAuto &&
            sim::lanes_fit_subgroup(n, ctx.subgroup_size_min, ctx.subgroup_shuffle_compute) &&
            (!conservative || conservative_slots(ctx, n) > 0),
        conservative, refinements)};
  }
  const sim::SimPath path = sim::sim_path_from_environment();
  if (path == sim::SimPath::kPasses) return sim::passes_for(terms);
  // The run kernel (the default up to its measured crossover; strands pinned at their tip take the one-thread
  // kernel, whose Thomas solve is serial).
  const bool crowd_takes_one_thread = crowd && path == sim::SimPath::kAuto && sim::run_length_from_environment() == 0;
  if ((path == sim::SimPath::kAuto || path == sim::SimPath::kRuns) && (terms.features & sim::kFeaturePinnedTips) == 0 &&
      !crowd_takes_one_thread) {
    const uint32_t n = inst.asset->rest.vertices_per_strand;
    uint32_t run = sim::run_length_from_environment();
    if (run == 0) run = sim::run_length_for(inst.asset->rest.guide_count, n, path == sim::SimPath::kAuto);
    if (run != 0 && sim::runs_fit_subgroup(n, run, ctx.subgroup_size_min, ctx.subgroup_shuffle_compute))
      return {sim::frame_runs_pass_use(terms, run)};
  }
  const bool shared = path == sim::SimPath::kFusedShared &&
                      sim::frame_shared_bytes(inst.asset->rest.vertices_per_strand, terms.vsp) <=
                          ctx.device_properties.limits.maxComputeSharedMemorySize;
  return {sim::frame_pass_use(terms, shared, inst.asset->rest.guide_count)};
}

// The follow-the-leader instances of one tressvk_cmd_simulate call and their guide vertices (the crowd rule).
struct Crowd {
  uint32_t instances = 0;
  uint64_t guide_vertices = 0;
};

// Plans the instance's frame and writes its parameters into this frame's ring slice.
TvkResult prepare(Context& ctx, TvkInstance_T& inst, InstanceWork& work, const Crowd& crowd) {
  work.inst = &inst;
  // Planned ahead (tressvk_plan_frame, perhaps on another thread), or here. Unplanned instances convert into one
  // buffer of the context in turn, so that it stays in the cache. (A buffer per instance kept between frames read 30 %
  // slower for 64 skinned Ratboys on one H100 host when every bone was carried, within noise on another.)
  const bool planned = inst.planned;
  work.plan = planned ? inst.plan : plan_frame(inst, ctx.gpu_frame_scratch);
  inst.planned = false;
  const double h = work.plan.h;  // the plan's own step: a step rate set after tressvk_plan_frame applies next frame
  const model::GpuFrame& gpu = planned ? inst.planned_gpu : ctx.gpu_frame_scratch;
  work.skin_stride = gpu.skin_stride;
  if (work.plan.steps > TVK_MAX_STEPS_PER_FRAME)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "a frame planned %u steps (limit %u)", work.plan.steps,
                    TVK_MAX_STEPS_PER_FRAME);
  const uint32_t slice = static_cast<uint32_t>(ctx.frame % ctx.frames_in_flight);
  const VkDeviceSize base = VkDeviceSize{slice} * inst.slice_size;
  auto* ring = static_cast<std::byte*>(inst.ring.mapped);
  std::vector<sim::GroupParams> groups(inst.params.size());
  const model::StrandModel strand_model = model::resolve_model(inst.settings.model);
  const bool compliant = model::is_compliant_family(strand_model);
  double least_damped = 0.0;  // the largest fraction of the velocity a group keeps a step (settled_run below)
  for (size_t g = 0; g < inst.params.size(); ++g) {
    const model::GroupStep step =
        model::to_group_step(model::resolve_params(inst.params[g], strand_model), h,
                             inst.asset->rest.asset_tip_separation, inst.asset->rest.median_length);
    least_damped = std::max(least_damped, step.velocity_keep);
    groups[g] = compliant ? model::to_gpu_compliant(step, h) : model::to_gpu(step);
    std::memcpy(ring + base + inst.groups_offset + g * sizeof(sim::GroupParams), &groups[g], sizeof(sim::GroupParams));
  }
  // Still or not: every step of this frame against the last step run (a frame without steps leaves that as it was).
  // Follow hairs are written for the strands the host draws: more of them than the last frame that ran wrote is a
  // change of input (sleeping guides would leave the newly drawn follows unwritten), fewer is not.
  work.follow_strands = inst.asset->cpu.simulated_strands(inst.draw_strands);
  const bool more_follows = work.follow_strands > inst.follows_written;
  const bool still = still_and_keep(groups, gpu, work.plan.steps, inst.last_step_inputs) && !more_follows;
  if (!gpu.steps.empty())
    std::memcpy(ring + base + inst.steps_offset, gpu.steps.data(), gpu.steps.size() * sizeof(sim::StepParams));
  if (!gpu.skin.empty()) {
    if (inst.skin_offset + gpu.skin.size() * sizeof(sim::Vec4) > inst.slice_size)
      return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "skinning data exceeds the parameter ring");
    std::memcpy(ring + base + inst.skin_offset, gpu.skin.data(), gpu.skin.size() * sizeof(sim::Vec4));
  }
  vmaFlushAllocation(ctx.allocator, inst.ring.allocation, base, inst.slice_size);
  work.dynamic_offsets = {static_cast<uint32_t>(base), static_cast<uint32_t>(base), static_cast<uint32_t>(base)};
  const sim::SceneTerms terms = sim::scene_terms(inst.params, inst.frame, inst.asset->rest.follow_per_guide,
                                                 inst.asset->rest.pinned_tip_strands > 0);
  work.passes = passes_for_path(ctx, inst, terms,
                                sim::crowd_prefers_one_thread(crowd.instances, crowd.guide_vertices, work.plan.steps));
  // A frame without steps runs nothing and changes nothing: it leaves the count (and idleness) as they were.
  if (work.plan.steps == 0) return TVK_SUCCESS;
  inst.follows_written = work.follow_strands;
  // The fused frame kernels sleep; one pass per dispatch never does. Still frames in a row: one in kMeasureEvery
  // measures the strands' motion (layout.glsl), the others pass the threshold negated.
  const bool fused = work.passes.size() == 1 && (work.passes.front().info->id == PassId::kFrame);
  constexpr uint64_t kMeasureEvery = 4;
  inst.still_frames = still ? inst.still_frames + 1 : 0;
  inst.still_steps = still ? inst.still_steps + work.plan.steps : 0;
  // A settled still run: long enough for the damping of every group to have taken any motion the inputs gave the
  // strands below the threshold (an amplitude keeps velocity_keep^(steps / 2) of itself; 5.8 s at the default damping
  // 0.08). What a strand still moves then is the model's own cycle (follow-the-leader's local shape on curls and on a
  // few of Ratboy's strands, up to 4.3e-3 of the strand a step: docs/accuracy.md, "At rest"), not motion, so the
  // threshold becomes kSettledMove of the median strand a step (sleep_below is at most 1e-3; a strand flying faster
  // than that stays awake, whatever its cause). Never without damping.
  constexpr double kSettledMove = 1e-2;
  const bool settled_run = least_damped < 1.0 && inst.settings.sleep_below > 0.0f &&
                           0.5 * static_cast<double>(inst.still_steps) * -std::log(least_damped) >=
                               -std::log(static_cast<double>(inst.settings.sleep_below));
  const double below = settled_run ? kSettledMove : static_cast<double>(inst.settings.sleep_below);
  const float threshold = static_cast<float>(below * inst.asset->rest.median_length);
  work.rest_move = !still || !fused ? 0.0f : inst.still_frames % kMeasureEvery == 1 ? threshold : -threshold;

  // Idle instances. In a still frame every guide that runs (is not asleep as the frame starts) sets the frame slot's
  // awake bit (layout.glsl, note_awake); the host clears the bit as it records that frame and reads it when it records
  // the slot's next frame, which tressvk_new_frame's promise says the GPU has finished. A clear bit from a still
  // frame of the current still run means that frame ran no guide, and since then no input changed: no later
  // still frame would run one either (sleeping guides are padding), so none is recorded, barriers included, until a
  // frame is not still.
  work.counter_index = slice;
  if (work.rest_move == 0.0f) {  // not still, not a frame kernel, or sleeping off
    inst.idle = false;
    inst.awake_probe[slice] = 0;
    return TVK_SUCCESS;
  }
  if (inst.still_frames == 1) inst.still_run_first = ctx.frame;
  auto* words = static_cast<uint32_t*>(inst.counters.mapped);
  if (!inst.idle && inst.awake_probe[slice] != 0 && inst.awake_probe[slice] - 1 >= inst.still_run_first) {
    vmaInvalidateAllocation(ctx.allocator, inst.counters.allocation, 0, VK_WHOLE_SIZE);
    inst.idle = (words[work.counter_index] & sim::kCounterAwakeBit) == 0;
  }
  work.idle = inst.idle;
  if (!work.idle) {
    words[work.counter_index] &= ~sim::kCounterAwakeBit;
    vmaFlushAllocation(ctx.allocator, inst.counters.allocation, 0, VK_WHOLE_SIZE);
    inst.awake_probe[slice] = ctx.frame + 1;
  }
  return TVK_SUCCESS;
}

}  // namespace

PlannedFrame plan_frame(TvkInstance_T& inst, model::GpuFrame& gpu) {
  const model::FramePlan plan = inst.planner->plan_validated(inst.frame);  // checked at tressvk_set_frame
  model::to_gpu_into(plan, gpu);
  return {static_cast<uint32_t>(plan.steps.size()),
          plan.steps.empty() ? inst.planner->step_length() : plan.steps.front().h, plan.sim_origin};
}

TvkResult prewarm_sim_pipelines(Context& ctx, const TvkInstance_T& inst, const TvkSimFrame& frame) {
  if (TvkResult r = ensure_sim_layouts(ctx); r != TVK_SUCCESS) return r;
  const auto& rest = inst.asset->rest;
  const sim::SceneTerms terms =
      sim::scene_terms(inst.params, frame, rest.follow_per_guide, rest.pinned_tip_strands > 0);
  // The instance's own kernel, and the one it takes in a crowd (the same pipeline where they agree).
  for (const bool crowd : {false, true}) {
    for (const PassUse& use : passes_for_path(ctx, inst, terms, crowd)) {
      VkPipeline pipeline = VK_NULL_HANDLE;
      if (TvkResult r = get_pipeline(ctx, use, rest.vertices_per_strand, rest.follow_per_guide, pipeline);
          r != TVK_SUCCESS)
        return r;
    }
  }
  return TVK_SUCCESS;
}
}  // namespace tressvk

extern "C" {

TvkResult tressvk_new_frame(TvkContext context) {
  if (!context) return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_new_frame: context is NULL");
  ++context->frame;
  // After a device loss nothing runs on the GPU any more: release everything deferred at once.
  context->collect_garbage(context->device_lost);
  return context->require_device("tressvk_new_frame");
}

// The body of tressvk_cmd_simulate (run through tressvk::guarded: exceptions and unnamed failures get messages).
static TvkResult record_simulation(tressvk::Context& ctx, VkCommandBuffer cmd, const TvkSimulateInfo* info) {
  using namespace tressvk;
  if (const TvkResult lost = ctx.require_device("tressvk_cmd_simulate"); lost != TVK_SUCCESS) return lost;
  if (!cmd) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_cmd_simulate: command_buffer is VK_NULL_HANDLE");
  if (!info) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_cmd_simulate: info is NULL");
  if (info->struct_size != sizeof(TvkSimulateInfo))
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_cmd_simulate: struct_size is %zu, expected %zu",
                    info->struct_size, sizeof(TvkSimulateInfo));
  if (info->instance_count && !info->instances)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_cmd_simulate: instances is NULL with instance_count %u",
                    info->instance_count);

  std::vector<InstanceWork> work(info->instance_count);
  Crowd crowd;
  for (uint32_t i = 0; i < info->instance_count; ++i) {
    const TvkInstance_T* inst = info->instances[i];
    if (!inst || inst->ctx != &ctx)
      return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_cmd_simulate: instance %u is NULL or of another context", i);
    if (model::resolve_model(inst->settings.model) != model::StrandModel::kFollowTheLeader) continue;
    ++crowd.instances;
    crowd.guide_vertices += uint64_t{inst->asset->rest.guide_count} * inst->asset->rest.vertices_per_strand;
  }
  try {
    for (uint32_t i = 0; i < info->instance_count; ++i) {
      if (TvkResult r = prepare(ctx, *info->instances[i], work[i], crowd); r != TVK_SUCCESS) return r;
    }
  } catch (const std::exception& e) {
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_cmd_simulate: %s", e.what());
  }

  // Timestamps for this frame's slice of the pool.
  Context::TimedSlice* timed = nullptr;
  uint32_t first_query = 0;
  if (ctx.timestamp_pool) {
    const uint32_t slice = static_cast<uint32_t>(ctx.frame % ctx.frames_in_flight);
    timed = &ctx.timed_slices[slice];
    timed->frame = ctx.frame;
    timed->pass_names.clear();
    timed->dispatches.clear();
    first_query = slice * ctx.queries_per_frame;
    ctx.vk.vkCmdResetQueryPool(cmd, ctx.timestamp_pool, first_query, ctx.queries_per_frame);
  }

  // Entry: order this frame's writes after the previous frame's accesses (draws, copies, the last simulate).
  std::vector<VkBufferMemoryBarrier2> barriers;
  const VkPipelineStageFlags2 earlier_users = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                              VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                              VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT;
  // An idle instance records nothing, barriers included: it neither reads nor writes its buffers this frame, and what
  // it wrote last is already visible through the barriers recorded after that.
  for (InstanceWork& w : work) {
    if (w.idle) continue;
    for (uint32_t b : {sim::kBindingPositions, sim::kBindingPrevPositions, sim::kBindingPrevPrevPositions,
                       sim::kBindingTangents, sim::kBindingCounters, sim::kBindingAnchors})
      barriers.push_back(buffer_barrier(writable_buffer(*w.inst, b), earlier_users, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT));
    w.inst->hazards = HazardTracker{};
  }
  record_barriers(ctx, cmd, barriers);

  ctx.recorded_passes.clear();
  ctx.recorded_dispatches = 0;
  const auto note_pass = [&ctx](const std::string& name) {
    if (std::find(ctx.recorded_passes.begin(), ctx.recorded_passes.end(), name) == ctx.recorded_passes.end())
      ctx.recorded_passes.push_back(name);
  };

  // One "slot" = one pass of one substep across every instance that runs it; barriers go between slots.
  const auto record_slot = [&](PassId id, uint32_t step, bool per_frame) -> TvkResult {
    std::vector<std::pair<InstanceWork*, const PassUse*>> users;
    for (InstanceWork& w : work) {
      if (per_frame ? w.plan.steps == 0 : step >= w.plan.steps) continue;
      if (w.idle) continue;  // every guide asleep in a still frame: nothing to run
      for (const PassUse& u : w.passes)
        if (u.info->id == id) users.emplace_back(&w, &u);
    }
    if (users.empty()) return TVK_SUCCESS;
    barriers.clear();
    std::vector<HazardTracker::Need> named(work.size());
    bool any = false;
    for (auto& [w, u] : users) {
      const HazardTracker::Need need = w->inst->hazards.before(u->info->reads, u->info->writes);
      any |= need.any();
      for (uint32_t b = 0; b < sim::kBindingCount; ++b) {
        if (need.memory & (1u << b))
          barriers.push_back(buffer_barrier(writable_buffer(*w->inst, b), VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT));
        else if (need.execution & (1u << b))
          barriers.push_back(buffer_barrier(writable_buffer(*w->inst, b), VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0,
                                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0));
      }
      HazardTracker::Need& n = named[static_cast<size_t>(w - work.data())];
      n.memory |= need.memory;
      n.execution |= need.execution;
    }
    if (any) {
      record_barriers(ctx, cmd, barriers);
      for (size_t i = 0; i < work.size(); ++i) work[i].inst->hazards.barrier_recorded(named[i]);
    }
    const uint32_t pair = timed ? static_cast<uint32_t>(timed->pass_names.size()) : 0;
    const bool time_it = timed && 2 * (pair + 1) <= ctx.queries_per_frame;
    if (time_it)
      ctx.vk.vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, ctx.timestamp_pool, first_query + 2 * pair);
    VkPipeline bound = VK_NULL_HANDLE;
    for (auto& [w, u] : users) {
      TvkInstance_T& inst = *w->inst;
      const auto& rest = inst.asset->rest;
      VkPipeline pipeline = VK_NULL_HANDLE;
      if (TvkResult r = get_pipeline(ctx, *u, rest.vertices_per_strand, rest.follow_per_guide, pipeline);
          r != TVK_SUCCESS)
        return r;
      if (pipeline != bound) ctx.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
      bound = pipeline;
      ctx.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx.sim_pipeline_layout, 0, 1, &inst.set, 3,
                                     w->dynamic_offsets.data());
      const bool fused = u->info->id == PassId::kFrame;  // all substeps from step 0 in one dispatch
      const uint32_t s = fused ? 0 : per_frame ? w->plan.steps - 1 : step;
      const sim::PushConstants pc{rest.guide_count, s, s * w->skin_stride, 0, w->counter_index, w->plan.steps,
                                  w->skin_stride, w->rest_move, w->follow_strands};
      ctx.vk.vkCmdPushConstants(cmd, ctx.sim_pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
      const uint32_t groups = sim::is_frame_lanes(u->info)
                                  ? sim::frame_lanes_groups(u->info, rest.guide_count, rest.vertices_per_strand,
                                                            ctx.subgroup_size,
                                                            conservative_slots(ctx, rest.vertices_per_strand),
                                                            (u->features & sim::kFeatureConservative) != 0)
                              : fused                       ? sim::frame_dispatch_groups(*u, rest.guide_count)
                                    : sim::dispatch_groups(u->info->granularity, rest.guide_count,
                                                           rest.vertices_per_strand, rest.follow_per_guide,
                                                           ctx.workgroup_size);
      if (groups) {
        ctx.vk.vkCmdDispatch(cmd, groups, 1, 1);
        ++ctx.recorded_dispatches;
      }
      inst.hazards.pass_recorded(u->info->reads, u->info->writes);
      note_pass(u->name);
    }
    if (time_it) {
      ctx.vk.vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, ctx.timestamp_pool,
                                  first_query + 2 * pair + 1);
      timed->pass_names.push_back(users.front().second->name);
      timed->dispatches.push_back(static_cast<uint32_t>(users.size()));
    }
    return TVK_SUCCESS;
  };

  uint32_t max_steps = 0;
  for (const InstanceWork& w : work) max_steps = std::max(max_steps, w.plan.steps);
  for (uint32_t s = 0; s < max_steps; ++s)
    for (const sim::PassInfo& p : sim::pass_table())
      if (p.frequency == sim::Frequency::kPerSubstep)
        if (TvkResult r = record_slot(p.id, s, false); r != TVK_SUCCESS) return r;
  for (const sim::PassInfo& p : sim::pass_table())
    if (p.frequency == sim::Frequency::kPerFrame)
      if (TvkResult r = record_slot(p.id, 0, true); r != TVK_SUCCESS) return r;
  if (TvkResult r = record_slot(PassId::kFrame, 0, true); r != TVK_SUCCESS) return r;

  // Exit: positions, tangents and anchors visible to the host's vertex shaders (and compute); counters to the host.
  barriers.clear();
  for (InstanceWork& w : work) {
    if (!w.idle) {  // an idle instance wrote nothing (see the entry barriers)
      for (uint32_t b : {sim::kBindingPositions, sim::kBindingTangents, sim::kBindingAnchors})
        barriers.push_back(buffer_barrier(writable_buffer(*w.inst, b), VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                          VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT));
      barriers.push_back(buffer_barrier(w.inst->counters.buffer, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                                        VK_ACCESS_2_HOST_READ_BIT));
    }
    TvkInstance_T& inst = *w.inst;
    inst.steps += w.plan.steps;
    inst.steps_last_frame = w.plan.steps;
    ++inst.frames;
    inst.sim_origin = w.plan.sim_origin;
    inst.frame.teleport = 0;
    inst.frame.reset = 0;
    inst.frame.dt = 0.0f;
  }
  record_barriers(ctx, cmd, barriers);
  return TVK_SUCCESS;
}

TvkResult tressvk_cmd_simulate(TvkContext context, VkCommandBuffer cmd, const TvkSimulateInfo* info) {
  if (!context)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_cmd_simulate: context is NULL");
  return tressvk::guarded(*context, "tressvk_cmd_simulate", [&] { return record_simulation(*context, cmd, info); });
}

uint32_t tressvk_get_recorded_dispatches(TvkContext context) { return context ? context->recorded_dispatches : 0; }

uint32_t tressvk_get_recorded_passes(TvkContext context, const char** names, uint32_t capacity) {
  if (!context) return 0;
  const auto count = static_cast<uint32_t>(context->recorded_passes.size());
  for (uint32_t i = 0; i < count && i < capacity && names; ++i) names[i] = context->recorded_passes[i].c_str();
  return count;
}

uint32_t tressvk_get_pass_timings(TvkContext context, TvkPassTiming* timings, uint32_t capacity) {
  if (!context || !context->timestamp_pool || context->frame < context->frames_in_flight) return 0;
  Context& ctx = *context;
  const uint64_t done = ctx.frame - ctx.frames_in_flight;
  const uint32_t slice = static_cast<uint32_t>(done % ctx.frames_in_flight);
  const Context::TimedSlice& t = ctx.timed_slices[slice];
  if (t.frame != done || t.pass_names.empty()) return 0;
  if (ctx.device_lost) return 0;
  std::vector<uint64_t> stamps(2 * t.pass_names.size());
  const VkResult vr = ctx.vk.vkGetQueryPoolResults(ctx.info.device, ctx.timestamp_pool, slice * ctx.queries_per_frame,
                                                   static_cast<uint32_t>(stamps.size()), stamps.size() * sizeof(uint64_t),
                                                   stamps.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
  if (vr == VK_ERROR_DEVICE_LOST) ctx.check(vr, "tressvk_get_pass_timings: vkGetQueryPoolResults");  // marks it lost
  if (vr != VK_SUCCESS) return 0;
  // Sum the slots of each pass name (one slot per substep), in the order names first appear.
  std::vector<TvkPassTiming> out;
  for (size_t i = 0; i < t.pass_names.size(); ++i) {
    const double ms = double(stamps[2 * i + 1] - stamps[2 * i]) * ctx.timestamp_period_ns * 1e-6;
    auto it = std::find_if(out.begin(), out.end(), [&](const TvkPassTiming& p) { return t.pass_names[i] == p.name; });
    if (it == out.end()) {
      // Names live in recorded_passes (stable until the next simulate) or in the slice itself.
      out.push_back({t.pass_names[i].c_str(), 0, 0.0});
      it = out.end() - 1;
    }
    it->dispatches += t.dispatches[i];
    it->milliseconds += ms;
  }
  for (size_t i = 0; i < out.size() && i < capacity && timings; ++i) timings[i] = out[i];
  return static_cast<uint32_t>(out.size());
}

}  // extern "C"
