// Instances: a placed asset with its own dynamic state, parameters, per-frame parameter ring and descriptor set.
#include "core/objects.hpp"
#include "sim/fused.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <memory>
#include <new>

using tressvk::Context;
using tressvk::GpuBuffer;
using tressvk::Memory;

namespace {

VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

void destroy_instance_now(TvkInstance_T* inst, bool deferred) {
  Context& ctx = *inst->ctx;
  for (GpuBuffer* b : {&inst->positions, &inst->prev, &inst->prevprev, &inst->tangents, &inst->counters,
                       &inst->anchors, &inst->ring})
    deferred ? destroy_buffer_deferred(ctx, *b) : destroy_buffer(ctx, *b);
  // The descriptor pool holds no GPU memory the device could still read after the buffers are gone; a pool
  // destroyed while a command buffer using its set is pending is invalid, so it follows the same deferral by
  // being destroyed with the context's garbage when deferred.
  if (inst->pool) {
    if (deferred)
      ctx.deferred_pools.push_back({ctx.frame, inst->pool});
    else
      ctx.vk.vkDestroyDescriptorPool(ctx.info.device, inst->pool, ctx.info.allocator);
  }
  if (inst->asset && inst->holds_asset) inst->asset->release();
  delete inst;
}

// Tells the host where the conservative model steps slower than it is recommended at for the asset's strands
// (sim::conservative_least_rate): there it may not follow its reference. A warning, not a refusal.
void warn_if_below_recommended_rate(Context& ctx, const TvkInstance_T& inst, const char* call) {
  if (tressvk::model::resolve_model(inst.settings.model) != tressvk::model::StrandModel::kConservative) return;
  const uint32_t n = inst.asset->rest.vertices_per_strand;
  const float least = tressvk::sim::conservative_least_rate(n);
  if (!(inst.settings.time.step_rate < least)) return;
  ctx.message(TVK_MESSAGE_WARNING,
              "%s: time.step_rate %g Hz is below %g Hz, the slowest the conservative model is recommended at for "
              "strands of %u vertices; it may not follow its reference there (docs/accuracy.md, \"Which model, at "
              "which rate\")",
              call, static_cast<double>(inst.settings.time.step_rate), static_cast<double>(least), n);
}

// The settings with a rate left to the model replaced by the model's for strands of n vertices.
TvkSimSettings resolved_settings(const TvkSimSettings& settings, uint32_t n) {
  namespace model = tressvk::model;
  return model::resolve_settings(settings, model::resolve_model(settings.model), n);
}

// Owns an instance under construction: a failure anywhere frees what was made, at once (nothing was recorded).
struct DestroyNow {
  void operator()(TvkInstance_T* inst) const { destroy_instance_now(inst, false); }
};

TvkResult create_instance_resources(Context& ctx, TvkInstance_T& inst) {
  const auto& rest = inst.asset->rest;
  // Whole strand blocks (the blocked vertex layout of gpu_layout.hpp).
  static_assert(tressvk::sim::kStrandBlock == TVK_STRAND_BLOCK);
  const VkDeviceSize guide_vertices = tressvk::sim::padded_strands(rest.guide_count) * rest.vertices_per_strand;
  const VkDeviceSize all_vertices =
      tressvk::sim::padded_strands(uint64_t{rest.guide_count} * (1 + rest.follow_per_guide)) * rest.vertices_per_strand;
  const VkBufferUsageFlags state_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                         VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  // A word per frame slot: strands reset after going non-finite in the slot's frames, and the slot's awake bit
  // (layout.glsl; simulate.cpp, "Idle instances").
  const VkDeviceSize counter_bytes = std::max<VkDeviceSize>(16, 4 * VkDeviceSize{ctx.frames_in_flight});
  TvkResult r = TVK_SUCCESS;
  if ((r = create_buffer(ctx, all_vertices * 16, state_usage, Memory::device, "positions", inst.positions)) ||
      (r = create_buffer(ctx, guide_vertices * 16, state_usage, Memory::device, "previous positions", inst.prev)) ||
      (r = create_buffer(ctx, guide_vertices * 16, state_usage, Memory::device, "positions two steps back",
                         inst.prevprev)) ||
      (r = create_buffer(ctx, guide_vertices * 16, state_usage, Memory::device, "tangents", inst.tangents)) ||
      (r = create_buffer(ctx, VkDeviceSize{rest.guide_count} * 16, state_usage, Memory::device, "strand anchors",
                         inst.anchors)) ||
      (r = create_buffer(ctx, counter_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::host_readback, "counters",
                         inst.counters)))
    return r;
  std::memset(inst.counters.mapped, 0, counter_bytes);
  inst.awake_probe.assign(ctx.frames_in_flight, 0);

  // The ring: per frame in flight, [group params][step params x max steps][skin x max steps x the bones the strands read].
  const VkDeviceSize align = std::max<VkDeviceSize>(ctx.device_properties.limits.minStorageBufferOffsetAlignment, 16);
  const uint32_t groups = static_cast<uint32_t>(inst.params.size());
  const uint32_t bones = std::max<uint32_t>(1, rest.bone_count);
  inst.groups_offset = 0;
  inst.steps_offset = align_up(groups * sizeof(tressvk::sim::GroupParams), align);
  inst.skin_offset = inst.steps_offset + align_up(TVK_MAX_STEPS_PER_FRAME * sizeof(tressvk::sim::StepParams), align);
  inst.slice_size = align_up(inst.skin_offset + VkDeviceSize{TVK_MAX_STEPS_PER_FRAME} * bones *
                                                    tressvk::sim::kSkinVec4PerBone * 16,
                             align);
  if ((r = create_buffer(ctx, inst.slice_size * ctx.frames_in_flight, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         Memory::host_upload, "per-frame simulation parameters", inst.ring)))
    return r;

  // One descriptor set, written once: the per-frame bindings move with dynamic offsets.
  const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, tressvk::sim::kBindingCount - 3},
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 3}};
  VkDescriptorPoolCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pci.maxSets = 1;
  pci.poolSizeCount = 2;
  pci.pPoolSizes = sizes;
  if ((r = ctx.check(ctx.vk.vkCreateDescriptorPool(ctx.info.device, &pci, ctx.info.allocator, &inst.pool),
                     "vkCreateDescriptorPool")))
    return r;
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = inst.pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &ctx.sim_set_layout;
  if ((r = ctx.check(ctx.vk.vkAllocateDescriptorSets(ctx.info.device, &ai, &inst.set), "vkAllocateDescriptorSets")))
    return r;

  std::array<VkDescriptorBufferInfo, tressvk::sim::kBindingCount> infos{};
  const GpuBuffer* dynamic_state[4] = {&inst.positions, &inst.prev, &inst.prevprev, &inst.tangents};
  for (uint32_t b = 0; b < 4; ++b) infos[b] = {dynamic_state[b]->buffer, 0, VK_WHOLE_SIZE};
  for (uint32_t b = 0; b < 8; ++b) infos[4 + b] = {inst.asset->statics[b].buffer, 0, VK_WHOLE_SIZE};
  infos[tressvk::sim::kBindingSkin] = {inst.ring.buffer, inst.skin_offset, inst.slice_size - inst.skin_offset};
  infos[tressvk::sim::kBindingGroups] = {inst.ring.buffer, inst.groups_offset, inst.steps_offset};
  infos[tressvk::sim::kBindingSteps] = {inst.ring.buffer, inst.steps_offset, inst.skin_offset - inst.steps_offset};
  infos[tressvk::sim::kBindingCounters] = {inst.counters.buffer, 0, VK_WHOLE_SIZE};
  infos[tressvk::sim::kBindingAnchors] = {inst.anchors.buffer, 0, VK_WHOLE_SIZE};
  std::array<VkWriteDescriptorSet, tressvk::sim::kBindingCount> writes{};
  for (uint32_t b = 0; b < tressvk::sim::kBindingCount; ++b) {
    writes[b] = {};
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = inst.set;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = tressvk::is_dynamic_binding(b) ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC
                                                              : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[b].pBufferInfo = &infos[b];
  }
  ctx.vk.vkUpdateDescriptorSets(ctx.info.device, tressvk::sim::kBindingCount, writes.data(), 0, nullptr);
  return TVK_SUCCESS;
}

TvkResult check_params(Context& ctx, const TvkSimParams& p, const char* what) {
  // The model's conversion validates every field and names the one at fault (the ranges are every model's).
  try {
    namespace model = tressvk::model;
    (void)model::to_group_step(model::resolve_params(p, model::StrandModel::kFollowTheLeader), 1.0 / 120.0, 0.0, 1.0);
  } catch (const std::exception& e) {
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: %s", what, e.what());
  }
  return TVK_SUCCESS;
}

}  // namespace

extern "C" {

TvkResult tressvk_create_instance(TvkContext context, const TvkInstanceCreateInfo* info, TvkInstance* out) {
  constexpr const char* kCall = "tressvk_create_instance";
  if (out) *out = nullptr;
  if (!context) return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "%s: context is NULL", kCall);
  Context& ctx = *context;
  return tressvk::guarded(ctx, kCall, [&]() -> TvkResult {
    if (const TvkResult lost = ctx.require_device(kCall); lost != TVK_SUCCESS) return lost;
    if (!out) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: out_instance is NULL", kCall);
    if (!info) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: info is NULL", kCall);
    if (info->struct_size != sizeof(TvkInstanceCreateInfo))
      return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: struct_size is %zu, expected %zu", kCall, info->struct_size,
                      sizeof(TvkInstanceCreateInfo));
    if (!info->asset) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: asset is NULL", kCall);
    if (info->asset->ctx != &ctx)
      return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: the asset belongs to another context", kCall);
    const TvkSimSettings settings = info->settings ? *info->settings : TvkSimSettings TVK_SIM_SETTINGS_DEFAULT_INIT;
    const TvkSimParams params = info->params ? *info->params : TvkSimParams TVK_SIM_PARAMS_DEFAULT_INIT;
    if (TvkResult r = check_params(ctx, params, "tressvk_create_instance: params"); r != TVK_SUCCESS) return r;
    if (TvkResult r = tressvk::ensure_sim_layouts(ctx); r != TVK_SUCCESS) return r;

    std::unique_ptr<TvkInstance_T, DestroyNow> inst(new TvkInstance_T());
    inst->ctx = &ctx;
    inst->asset = info->asset;
    // The instance keeps its settings resolved (a rate left to the model is the model's); its parameters as the host
    // gave them, resolved as each frame converts them, so that a change of model changes what they resolve to.
    inst->settings = resolved_settings(settings, info->asset->rest.vertices_per_strand);
    inst->params.assign(std::max<size_t>(1, info->asset->cpu.groups.size()), params);
    // The planner checks the settings and names the field at fault (e.g. time.step_rate); it throws.
    inst->planner = std::make_unique<tressvk::model::FramePlanner>(inst->settings, info->asset->cpu.origin,
                                                                        info->asset->rest.asset_bone_count);
    inst->planner->set_bone_source(info->asset->rest.bone_source);
    if (TvkResult r = create_instance_resources(ctx, *inst); r != TVK_SUCCESS) return r;
    warn_if_below_recommended_rate(ctx, *inst, kCall);
    // Handed to the host: only now does the instance count as a user of the asset.
    ++info->asset->users;
    inst->holds_asset = true;
    *out = inst.release();
    return TVK_SUCCESS;
  });
}

void tressvk_destroy_instance(TvkInstance instance) {
  if (instance) destroy_instance_now(instance, true);
}

TvkResult tressvk_set_sim_params(TvkInstance instance, uint32_t group, const TvkSimParams* params) {
  if (!instance)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_set_sim_params: instance is NULL");
  Context& ctx = *instance->ctx;
  if (!params) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_set_sim_params: params is NULL");
  if (group != TVK_ALL_GROUPS && group >= instance->params.size())
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_set_sim_params: group %u out of range (asset has %zu)",
                    group, instance->params.size());
  if (TvkResult r = check_params(ctx, *params, "tressvk_set_sim_params"); r != TVK_SUCCESS) return r;
  if (group == TVK_ALL_GROUPS)
    std::fill(instance->params.begin(), instance->params.end(), *params);
  else
    instance->params[group] = *params;
  return TVK_SUCCESS;
}

TvkResult tressvk_set_sim_settings(TvkInstance instance, const TvkSimSettings* settings) {
  if (!instance)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_set_sim_settings: instance is NULL");
  Context& ctx = *instance->ctx;
  return tressvk::guarded(ctx, "tressvk_set_sim_settings", [&]() -> TvkResult {
    if (!settings) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_set_sim_settings: settings is NULL");
    const TvkSimSettings resolved = resolved_settings(*settings, instance->asset->rest.vertices_per_strand);
    instance->planner->set_settings(resolved);  // throws naming the field; the settings stay as they were
    const bool changed = resolved.model != instance->settings.model ||
                         resolved.time.step_rate != instance->settings.time.step_rate;
    instance->settings = resolved;
    if (changed) warn_if_below_recommended_rate(ctx, *instance, "tressvk_set_sim_settings");
    return TVK_SUCCESS;
  });
}

TvkResult tressvk_get_sim_settings(TvkInstance instance, TvkSimSettings* out_settings) {
  if (!instance)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_sim_settings: instance is NULL");
  if (!out_settings)
    return instance->ctx->fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_sim_settings: out_settings is NULL");
  *out_settings = instance->settings;
  out_settings->model = tressvk::model::resolved_sim_model(instance->settings.model);
  return TVK_SUCCESS;
}

TvkResult tressvk_get_sim_params(TvkInstance instance, uint32_t group, TvkSimParams* out_params) {
  if (!instance)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_sim_params: instance is NULL");
  Context& ctx = *instance->ctx;
  if (!out_params) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_sim_params: out_params is NULL");
  if (group >= instance->params.size())
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_sim_params: group %u out of range (asset has %zu)", group,
                    instance->params.size());
  namespace model = tressvk::model;
  *out_params = model::resolve_params(instance->params[group], model::resolve_model(instance->settings.model));
  return TVK_SUCCESS;
}

TvkResult tressvk_set_draw_strands(TvkInstance instance, uint32_t strands) {
  if (!instance)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_set_draw_strands: instance is NULL");
  const uint32_t rendered = instance->asset->cpu.total_strands();
  if (strands > rendered)
    return instance->ctx->fail(TVK_ERROR_INVALID_ARGUMENT,
                               "tressvk_set_draw_strands: strands %u exceeds the instance's %u rendered strands",
                               strands, rendered);
  instance->draw_strands = strands;
  return TVK_SUCCESS;
}

TvkResult tressvk_set_frame(TvkInstance instance, const TvkSimFrame* frame) {
  if (!instance || !frame) return TVK_ERROR_INVALID_ARGUMENT;
  Context& ctx = *instance->ctx;
  if (instance->planned)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT,
                    "tressvk_set_frame: the instance's frame is planned (tressvk_plan_frame) and not yet simulated: "
                    "set a frame once, before planning it");
  // Every host number is checked here, so a NaN or infinity never reaches the GPU (where it would reset every strand
  // every step and freeze the groom) and the host learns which field was wrong.
  try {
    tressvk::model::validate_frame(*frame, instance->asset->rest.asset_bone_count);
  } catch (const std::exception& e) {
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_set_frame: %s", e.what());
  }
  instance->frame = *frame;
  if (frame->bones) {
    instance->bones.assign(frame->bones, frame->bones + frame->bone_count);
    instance->frame.bones = instance->bones.data();
  } else {
    instance->bones.clear();
  }
  instance->frame_set = true;
  return TVK_SUCCESS;
}

TvkResult tressvk_plan_frame(TvkInstance instance) {
  if (!instance) return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_plan_frame: instance is NULL");
  if (instance->planned) return TVK_SUCCESS;
  // Touches this instance only (and the context's reporting, which locks): safe beside other instances' calls.
  try {
    instance->plan = tressvk::plan_frame(*instance, instance->planned_gpu);
  } catch (const std::bad_alloc&) {
    return instance->ctx->fail(TVK_ERROR_OUT_OF_MEMORY, "tressvk_plan_frame: out of host memory");
  } catch (const std::exception& e) {
    return instance->ctx->fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_plan_frame: %s", e.what());
  }
  instance->planned = true;
  return TVK_SUCCESS;
}

TvkResult tressvk_prewarm_instance(TvkInstance instance, const TvkSimFrame* frame) {
  if (!instance)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_prewarm_instance: instance is NULL");
  Context& ctx = *instance->ctx;
  return tressvk::guarded(ctx, "tressvk_prewarm_instance", [&]() -> TvkResult {
    if (frame) {
      try {
        tressvk::model::validate_frame(*frame, instance->asset->rest.asset_bone_count);
      } catch (const std::exception& e) {
        return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_prewarm_instance: %s", e.what());
      }
    }
    return tressvk::prewarm_sim_pipelines(ctx, *instance, frame ? *frame : instance->frame);
  });
}

TvkResult tressvk_get_instance_buffers(TvkInstance instance, TvkInstanceBuffers* out) {
  if (!instance)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_instance_buffers: instance is NULL");
  if (!out) return instance->ctx->fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_instance_buffers: out_buffers is NULL");
  *out = TvkInstanceBuffers{};
  out->positions = instance->positions.buffer;
  out->tangents = instance->tangents.buffer;
  out->previous_positions = instance->prev.buffer;
  out->previous_previous_positions = instance->prevprev.buffer;
  out->positions_size = instance->positions.size;
  out->tangents_size = instance->tangents.size;
  out->previous_positions_size = instance->prev.size;
  out->anchors = instance->anchors.buffer;
  out->anchors_size = instance->anchors.size;
  out->guide_count = instance->asset->rest.guide_count;
  out->vertices_per_strand = instance->asset->rest.vertices_per_strand;
  out->follow_per_guide = instance->asset->rest.follow_per_guide;
  for (size_t i = 0; i < 3; ++i) out->origin[i] = instance->sim_origin[i];
  return TVK_SUCCESS;
}

TvkResult tressvk_get_instance_stats(TvkInstance instance, TvkInstanceStats* out) {
  if (!instance)
    return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_instance_stats: instance is NULL");
  if (!out) return instance->ctx->fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_instance_stats: out_stats is NULL");
  *out = TvkInstanceStats{};
  out->steps = instance->steps;
  out->frames = instance->frames;
  out->steps_last_frame = instance->steps_last_frame;
  vmaInvalidateAllocation(instance->ctx->allocator, instance->counters.allocation, 0, VK_WHOLE_SIZE);
  // Each frame slot counts the resets of its own frames (simulate.cpp): the total is their sum.
  const auto* words = static_cast<const uint32_t*>(instance->counters.mapped);
  for (uint32_t slot = 0; slot < instance->ctx->frames_in_flight; ++slot)
    out->nonfinite_strand_resets += words[slot] & ~tressvk::sim::kCounterAwakeBit;
  return TVK_SUCCESS;
}

}  // extern "C"
