// The recording calls: per draw, a constant block in this frame's ring slice (matrices made relative to the
// instance's simulation origin in double), a descriptor set from this frame's pool, and the draws. No barrier,
// no pass begin/end: both calls run inside the host's passes.
#include "core/objects.hpp"
#include "render/render.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tressvk::render {

namespace {

// out = m * translate(origin), i.e. a world-space matrix applied to origin-relative points, in double.
void relative_matrix(const double (&m)[16], const std::array<double, 3>& origin, float (&out)[16]) {
  double r[16];
  std::memcpy(r, m, sizeof(r));
  for (int row = 0; row < 4; ++row)
    r[12 + row] = m[12 + row] + m[0 + row] * origin[0] + m[4 + row] * origin[1] + m[8 + row] * origin[2];
  for (int i = 0; i < 16; ++i) out[i] = static_cast<float>(r[i]);
}

void normalized(const float (&v)[3], float (&out)[4]) {
  const double len = std::sqrt(double{v[0]} * v[0] + double{v[1]} * v[1] + double{v[2]} * v[2]);
  for (int i = 0; i < 3; ++i) out[i] = len > 0 ? static_cast<float>(v[i] / len) : 0.0f;
}

void fill_material(const TvkHairMaterial& m, GpuMaterial& g) {
  g = GpuMaterial{{m.base_color[0], m.base_color[1], m.base_color[2], m.kd},
                  {m.tip_color[0], m.tip_color[1], m.tip_color[2], m.ks1},
                  {m.ex1, m.ks2, m.ex2, m.shift1},
                  {m.shift2, m.strand_width, std::clamp(m.tip_width_ratio, 0.0f, 1.0f),
                   std::clamp(m.opacity, 0.0f, 1.0f)},
                  {m.fiber_spacing, std::clamp(m.fiber_alpha, 0.0f, 1.0f), std::clamp(m.color_variation, 0.0f, 1.0f),
                   0.0f}};
}

bool finite_view(const TvkView& v) {
  for (double x : v.view_projection)
    if (!std::isfinite(x)) return false;
  return v.width > 0 && v.height > 0;
}

// Fraction of the strands to draw for an eye at `distance` metres.
double lod_fraction(const TvkLodSettings& lod, double distance) {
  if (!(lod.end_distance > lod.start_distance) || !(lod.min_fraction > 0.0f) || lod.min_fraction >= 1.0f) return 1.0;
  const double t = std::clamp((distance - lod.start_distance) / (lod.end_distance - lod.start_distance), 0.0, 1.0);
  return 1.0 + t * (double{lod.min_fraction} - 1.0);
}

// Coverage-driven LOD: the fraction that makes the drawn strands about target_width_px wide where the instance's
// origin projects (the same pixels-per-metre as vertex.comp's width: the view-projection's x scale over clip w),
// clamped to [min_fraction, 1]. All strands when the origin is behind the eye (no scale to speak of).
double lod_coverage_fraction(const TvkLodSettings& lod, const TvkView& view, const std::array<double, 3>& origin,
                             float root_width) {
  const double* m = view.view_projection;
  const double w = m[3] * origin[0] + m[7] * origin[1] + m[11] * origin[2] + m[15];
  if (!(w > 1e-9) || !(root_width > 0.0f)) return 1.0;
  const double px_per_metre = std::sqrt(m[0] * m[0] + m[4] * m[4] + m[8] * m[8]) * 0.5 * view.width / w;
  const double width_px = double{root_width} * px_per_metre;
  const double floor = std::clamp(double{lod.min_fraction}, 0.0, 1.0);
  return std::clamp(width_px / double{lod.target_width_px}, floor, 1.0);
}

}  // namespace

uint32_t lod_strands(const TvkDrawInfo* info, const TvkView& lod_view) {
  const TvkAsset_T& asset = *info->instance->asset;
  const auto& origin = info->instance->sim_origin;
  const uint32_t total = asset.cpu.total_strands();
  double fraction = 1.0;
  if (info->lod.target_width_px > 0.0f) {
    float widest = 0.0f;
    const TvkHairMaterial default_material = TVK_HAIR_MATERIAL_DEFAULT_INIT;
    const uint32_t used =
        std::max<uint32_t>({1u, static_cast<uint32_t>(asset.cpu.groups.size()), info->material_count});
    for (uint32_t g = 0; g < std::min<uint32_t>(used, TVK_MAX_MATERIALS); ++g)
      widest = std::max(widest, (!info->materials || info->material_count == 0)
                                    ? default_material.strand_width
                                    : info->materials[std::min(g, info->material_count - 1)].strand_width);
    fraction = lod_coverage_fraction(info->lod, lod_view, origin, widest);
  } else {
    const double dx = lod_view.eye[0] - origin[0], dy = lod_view.eye[1] - origin[1], dz = lod_view.eye[2] - origin[2];
    fraction = lod_fraction(info->lod, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  if (!std::isfinite(fraction)) fraction = 1.0;  // a view the draw itself refuses
  return std::clamp(static_cast<uint32_t>(std::ceil(fraction * total)), 1u, total);
}

TvkResult begin_call(TvkRenderer_T& r, const char* fn) {
  Context& ctx = *r.ctx;
  if (const TvkResult lost = ctx.require_device(fn); lost != TVK_SUCCESS) return lost;
  // A new frame: this slot's previous user finished frames_in_flight frames ago (tressvk_new_frame's promise).
  if (r.current_frame != ctx.frame) {
    r.current_frame = ctx.frame;
    r.slot = static_cast<uint32_t>(ctx.frame % ctx.frames_in_flight);
    r.draws_in_frame = 0;
    if (TvkResult res = ctx.check(ctx.vk.vkResetDescriptorPool(ctx.info.device, r.pools[r.slot], 0),
                                  "vkResetDescriptorPool (hair)");
        res != TVK_SUCCESS)
      return res;
    if (!r.compute_pools.empty())
      if (TvkResult res = ctx.check(ctx.vk.vkResetDescriptorPool(ctx.info.device, r.compute_pools[r.slot], 0),
                                    "vkResetDescriptorPool (hair compute)");
          res != TVK_SUCCESS)
        return res;
  }
  if (r.draws_in_frame >= r.max_draws)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT,
                    "%s: more than max_draws_per_frame (%u) draws since the last tressvk_new_frame", fn, r.max_draws);
  return TVK_SUCCESS;
}

TvkResult fill_constants(TvkRenderer_T& r, const TvkDrawInfo* info, bool shadow_pass, bool shadowed, const char* fn,
                         DrawConstants& dc, uint32_t& drawn) {
  Context& ctx = *r.ctx;
  const TvkInstance_T& inst = *info->instance;
  const TvkAsset_T& asset = *inst.asset;
  const auto& origin = inst.sim_origin;
  const TvkView& view = *info->view;
  dc = DrawConstants{};
  relative_matrix(view.view_projection, origin, dc.view_proj);
  for (int i = 0; i < 3; ++i) dc.eye[i] = static_cast<float>(view.eye[i] - origin[i]);
  dc.eye[3] = view.orthographic ? 1.0f : 0.0f;
  normalized(view.direction, dc.view_dir);
  dc.viewport[0] = static_cast<float>(view.width);
  dc.viewport[1] = static_cast<float>(view.height);

  const uint32_t n = asset.cpu.vertices_per_strand;
  const uint32_t guides = asset.cpu.guide_count();
  const uint32_t total = asset.cpu.total_strands();
  drawn = lod_strands(info, (shadow_pass && info->lod_view) ? *info->lod_view : view);
  // No more than the simulation's last frame wrote follow hairs for (tressvk_set_draw_strands).
  if (inst.follows_written > 0) drawn = std::min(drawn, inst.follows_written);
  dc.counts[0] = n;
  dc.counts[1] = guides;
  dc.counts[2] = drawn;
  dc.counts[3] = shadow_pass ? 0u : info->light_count;
  // Fewer strands, each wider by total/drawn: the hair keeps the coverage (and the shadow) it had.
  dc.lod[0] = static_cast<float>(static_cast<double>(total) / drawn);
  dc.lod[1] = shadow_pass ? 0.0f : 1.0f;   // shading: one pixel of margin for the coverage ramp
  dc.lod[2] = shadow_pass ? 0.75f : 0.0f;  // shadow: every strand at least 1.5 texels wide
  for (int i = 0; i < 3; ++i) dc.ambient[i] = info->ambient[i];

  const uint32_t groups = static_cast<uint32_t>(std::max<size_t>(1, asset.cpu.groups.size()));
  const TvkHairMaterial defaults = TVK_HAIR_MATERIAL_DEFAULT_INIT;
  for (uint32_t g = 0; g < TVK_MAX_MATERIALS; ++g) {
    const TvkHairMaterial& m = (!info->materials || info->material_count == 0)
                                   ? defaults
                                   : info->materials[std::min(g, info->material_count - 1)];
    if (!(m.strand_width > 0.0f) || !std::isfinite(m.strand_width))
      return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: material %u: strand_width must be > 0 m", fn,
                      std::min(g, info->material_count ? info->material_count - 1 : 0u));
    fill_material(m, dc.materials[g]);
    if (g + 1 >= groups && g + 1 >= info->material_count) {
      for (uint32_t rest = g + 1; rest < TVK_MAX_MATERIALS; ++rest) dc.materials[rest] = dc.materials[g];
      break;
    }
  }
  for (uint32_t i = 0; i < dc.counts[3]; ++i) {
    const TvkLight& l = info->lights[i];
    GpuLight& gl = dc.lights[i];
    for (int k = 0; k < 3; ++k) gl.position[k] = static_cast<float>(l.position[k] - origin[k]);
    gl.position[3] = l.type == TVK_LIGHT_SPOT ? 1.0f : 0.0f;
    normalized(l.direction, gl.direction);
    gl.direction[3] = l.range;
    for (int k = 0; k < 3; ++k) gl.color[k] = l.color[k] * l.intensity;
    gl.color[3] = (l.shadowed && shadowed) ? 1.0f : 0.0f;
    gl.cone[0] = std::cos(l.inner_cone);
    gl.cone[1] = std::cos(std::max(l.outer_cone, l.inner_cone + 1e-4f));
  }
  if (shadowed) {
    relative_matrix(info->shadow->view_projection, origin, dc.shadow_proj);
    dc.shadow_params[0] = info->shadow->near_plane;
    dc.shadow_params[1] = info->shadow->far_plane;
    dc.shadow_params[2] = info->shadow->perspective ? 1.0f : 0.0f;
  }
  return TVK_SUCCESS;
}

double hair_bound_radius(const TvkInstance_T& inst) {
  // Skinned: the roots follow the bones of the simulation's last step, which lies between the previous frame's bones
  // and this frame's; the renderer knows only this frame's, so it claims no bound.
  if (inst.frame.bones) return -1.0;
  TvkAsset_T& asset = *inst.asset;
  const asset::HairAsset& a = asset.cpu;
  if (asset.render_guide_reach < 0.0) {
    // A guide vertex lies within its chain's length of its root; 1.25 x the rest length leaves room for a stretch
    // far beyond what the length passes let through.
    double reach = 0.0, offset = 0.0;
    const uint32_t n = a.vertices_per_strand;
    for (uint32_t g = 0; g < a.guide_count(); ++g) {
      const auto& root = a.rest_positions[size_t{g} * n];
      double length = 0.0;
      for (uint32_t v = 0; v + 1 < n; ++v) length += a.rest_lengths[size_t{g} * n + v];
      const double r = std::sqrt(double{root[0]} * root[0] + double{root[1]} * root[1] + double{root[2]} * root[2]);
      reach = std::max(reach, r + 1.25 * length);
    }
    for (const auto& f : a.follow_offsets)
      offset = std::max(offset, std::sqrt(double{f[0]} * f[0] + double{f[1]} * f[1] + double{f[2]} * f[2]));
    asset.render_follow_offset = offset;
    asset.render_guide_reach = reach;
  }
  // Follows: their guide's vertex plus the root offset spread by (1 + tip_separation * t).
  double separation = std::max(0.0, asset.rest.asset_tip_separation);
  for (const TvkSimParams& p : inst.params)
    if (p.tip_separation >= 0.0f) separation = std::max(separation, double{p.tip_separation});
  // Rigid: a root x (relative to the asset origin a) is at R (a + x) + T at the last step, and the simulation origin
  // O is T + R a rounded to 1/1024 m per axis (model/planner.cpp), so |root - O| <= |x| + sqrt(3) / 2048 m whatever
  // the rotation. 1 mm covers that rounding and float rounding.
  return asset.render_guide_reach + (1.0 + separation) * asset.render_follow_offset + 1e-3;
}

VkDeviceSize store_constants(TvkRenderer_T& r, const DrawConstants& dc) {
  const VkDeviceSize offset = (VkDeviceSize{r.slot} * r.max_draws + r.draws_in_frame) * r.block_stride;
  std::memcpy(static_cast<char*>(r.ring.mapped) + offset, &dc, sizeof(dc));
  vmaFlushAllocation(r.ctx->allocator, r.ring.allocation, offset, sizeof(dc));
  ++r.draws_in_frame;
  return offset;
}

TvkResult allocate_set(TvkRenderer_T& r, VkDescriptorPool pool, VkDescriptorSetLayout layout, const char* call,
                       VkDescriptorSet& set) {
  Context& ctx = *r.ctx;
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  set = VK_NULL_HANDLE;
  return ctx.check(ctx.vk.vkAllocateDescriptorSets(ctx.info.device, &ai, &set), call);
}

std::array<VkDescriptorBufferInfo, 5> hair_buffers(const TvkRenderer_T& r, VkDeviceSize offset,
                                                   const TvkInstance_T& inst) {
  return {VkDescriptorBufferInfo{r.ring.buffer, offset, sizeof(DrawConstants)},
          VkDescriptorBufferInfo{inst.positions.buffer, 0, VK_WHOLE_SIZE},
          VkDescriptorBufferInfo{inst.tangents.buffer, 0, VK_WHOLE_SIZE},
          VkDescriptorBufferInfo{inst.asset->statics[sim::kBindingGuideInfo - sim::kBindingRestPositions].buffer, 0,
                                 VK_WHOLE_SIZE},
          VkDescriptorBufferInfo{inst.anchors.buffer, 0, VK_WHOLE_SIZE}};
}

TvkResult check_draw_info(TvkRenderer_T& r, VkCommandBuffer cmd, const TvkDrawInfo* info, const char* fn) {
  Context& ctx = *r.ctx;
  if (!cmd || !info || info->struct_size != sizeof(TvkDrawInfo) || !info->instance || !info->view)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: command buffer, info (struct_size), instance or view missing", fn);
  if (const TvkResult lost = ctx.require_device(fn); lost != TVK_SUCCESS) return lost;
  if (info->instance->ctx != &ctx)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: the instance belongs to another context", fn);
  if (info->instance->frames == 0)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT,
                    "%s: the instance has not been simulated yet (record tressvk_cmd_simulate for it first: its "
                    "positions are undefined until then)", fn);
  if (!finite_view(*info->view))
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: view has a non-finite matrix or a zero viewport", fn);
  if (info->light_count > TVK_MAX_LIGHTS || (info->light_count && !info->lights))
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: light_count %u (at most %u, lights required)", fn,
                    info->light_count, TVK_MAX_LIGHTS);
  return TVK_SUCCESS;
}

namespace {

TvkResult record(TvkRenderer_T& r, VkCommandBuffer cmd, const TvkDrawInfo* info, bool shadow_pass) {
  Context& ctx = *r.ctx;
  const char* fn = shadow_pass ? "tressvk_cmd_draw_shadow" : "tressvk_cmd_draw_hair";
  if (TvkResult res = check_draw_info(r, cmd, info, fn); res != TVK_SUCCESS) return res;
  if (shadow_pass && r.info.shadow.depth_format == VK_FORMAT_UNDEFINED)
    return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: the renderer was created without a shadow target", fn);
  const TvkInstance_T& inst = *info->instance;
  const bool shadowed = !shadow_pass && info->shadow && info->shadow->depth_view && info->shadow->sampler;
  if (TvkResult res = begin_call(r, fn); res != TVK_SUCCESS) return res;

  using render::PipelineKind;
  const PipelineKind kinds[2] = {
      shadow_pass ? PipelineKind::shadow : (shadowed ? PipelineKind::core_shadowed : PipelineKind::core),
      shadowed ? PipelineKind::fringe_shadowed : PipelineKind::fringe};
  for (int i = 0; i < (shadow_pass ? 1 : 2); ++i)
    if (!r.pipelines[static_cast<size_t>(kinds[i])])
      if (TvkResult res = render::create_pipeline(r, kinds[i]); res != TVK_SUCCESS) return res;

  DrawConstants dc;
  uint32_t drawn = 0;
  if (TvkResult res = fill_constants(r, info, shadow_pass, shadowed, fn, dc, drawn); res != TVK_SUCCESS) return res;
  const uint32_t n = dc.counts[0];
  const VkDeviceSize offset = store_constants(r, dc);

  // Descriptors.
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (TvkResult res = allocate_set(r, r.pools[r.slot], shadowed ? r.shadowed_set_layout : r.set_layout,
                                   "vkAllocateDescriptorSets (hair)", set);
      res != TVK_SUCCESS)
    return res;
  const std::array<VkDescriptorBufferInfo, 5> buffers = hair_buffers(r, offset, inst);
  std::array<VkWriteDescriptorSet, 6> writes{};
  for (uint32_t i = 0; i < 6; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    if (i < 5) writes[i].pBufferInfo = &buffers[i];
  }
  VkDescriptorImageInfo image{};
  if (shadowed) {
    image.sampler = info->shadow->sampler;
    image.imageView = info->shadow->depth_view;
    image.imageLayout = info->shadow->layout;
    writes[5].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    writes[5].pImageInfo = &image;
  }
  ctx.vk.vkUpdateDescriptorSets(ctx.info.device, shadowed ? 6u : 5u, writes.data(), 0, nullptr);

  // Draws: the opaque core first (depth written), then the blended fringe over it.
  const uint32_t vertex_count = drawn * (n - 1) * 6;
  const VkPipelineLayout layout = shadowed ? r.shadowed_pipeline_layout : r.pipeline_layout;
  ctx.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
  for (int i = 0; i < (shadow_pass ? 1 : 2); ++i) {
    ctx.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipelines[static_cast<size_t>(kinds[i])]);
    ctx.vk.vkCmdDraw(cmd, vertex_count, 1, 0, 0);
  }
  r.last_drawn_strands = drawn;
  return TVK_SUCCESS;
}

}  // namespace

}  // namespace tressvk::render

extern "C" {

TvkResult tressvk_cmd_draw_shadow(TvkRenderer renderer, VkCommandBuffer command_buffer, const TvkDrawInfo* info) {
  if (!renderer) return TVK_ERROR_INVALID_ARGUMENT;
  return tressvk::render::record(*renderer, command_buffer, info, true);
}

TvkResult tressvk_cmd_draw_hair(TvkRenderer renderer, VkCommandBuffer command_buffer, const TvkDrawInfo* info) {
  if (!renderer) return TVK_ERROR_INVALID_ARGUMENT;
  return tressvk::render::record(*renderer, command_buffer, info, false);
}

}  // extern "C"
