// Asset loading: read and verify a .tvkhair file, derive the model's rest data, and record the upload of the
// static buffers into the host's command buffer.
#include "core/objects.hpp"

#include <tressvk/asset_io.hpp>

#include <algorithm>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <span>

using tressvk::Context;
using tressvk::GpuBuffer;
using tressvk::Memory;

void TvkAsset_T::release() {
  if (--users > 0) return;
  for (GpuBuffer& b : statics) tressvk::destroy_buffer_deferred(*ctx, b);
  delete this;
}

namespace {

template <class T>
std::span<const std::byte> bytes_of(const std::vector<T>& v) {
  return std::as_bytes(std::span<const T>(v));
}

TvkResult upload_statics(Context& ctx, TvkAsset_T& a, VkCommandBuffer cmd) {
  const tressvk::model::GpuStatic gpu = tressvk::model::build_gpu_static(a.rest);
  const std::array<std::span<const std::byte>, 8> sections = {
      bytes_of(gpu.rest_positions), bytes_of(gpu.rest_info),  bytes_of(gpu.rest_edge_local),
      bytes_of(gpu.root_frames),    bytes_of(gpu.follow_offsets), bytes_of(gpu.guide_info),
      bytes_of(gpu.bone_indices),   bytes_of(gpu.bone_weights)};
  static constexpr const char* kNames[8] = {"rest positions", "rest info",   "rest edges",   "root frames",
                                            "follow offsets", "guide info",  "bone indices", "bone weights"};
  VkDeviceSize total = 0;
  std::array<VkDeviceSize, 8> offsets{};
  for (size_t i = 0; i < sections.size(); ++i) {
    offsets[i] = total;
    total += (sections[i].size() + 255) & ~VkDeviceSize{255};
  }
  // Every buffer is made and filled before anything is recorded: a failure then leaves the host's command buffer
  // untouched, so the host can submit it (or retry the load) without referencing a destroyed buffer.
  GpuBuffer staging;
  if (TvkResult r = create_buffer(ctx, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Memory::host_upload,
                                  "asset upload staging", staging);
      r != TVK_SUCCESS)
    return r;
  for (size_t i = 0; i < sections.size(); ++i) {
    if (TvkResult r = create_buffer(ctx, sections[i].size(),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    Memory::device, kNames[i], a.statics[i]);
        r != TVK_SUCCESS) {
      destroy_buffer(ctx, staging);
      return r;
    }
    std::memcpy(static_cast<std::byte*>(staging.mapped) + offsets[i], sections[i].data(), sections[i].size());
  }
  if (TvkResult r = ctx.check(vmaFlushAllocation(ctx.allocator, staging.allocation, 0, VK_WHOLE_SIZE),
                              "vmaFlushAllocation (asset upload staging)");
      r != TVK_SUCCESS) {
    destroy_buffer(ctx, staging);
    return r;
  }
  std::vector<VkBufferMemoryBarrier2> barriers;
  for (size_t i = 0; i < sections.size(); ++i) {
    const VkBufferCopy region{offsets[i], 0, sections[i].size()};
    if (region.size) ctx.vk.vkCmdCopyBuffer(cmd, staging.buffer, a.statics[i].buffer, 1, &region);
    VkBufferMemoryBarrier2 b{};
    b.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2;
    b.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    b.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = a.statics[i].buffer;
    b.size = VK_WHOLE_SIZE;
    barriers.push_back(b);
  }
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.bufferMemoryBarrierCount = static_cast<uint32_t>(barriers.size());
  dep.pBufferMemoryBarriers = barriers.data();
  ctx.vk.vkCmdPipelineBarrier2(cmd, &dep);
  destroy_buffer_deferred(ctx, staging);
  return TVK_SUCCESS;
}

}  // namespace

extern "C" {

TvkResult tressvk_load_asset(TvkContext context, const TvkAssetLoadInfo* info, TvkAsset* out_asset) {
  constexpr const char* kCall = "tressvk_load_asset";
  if (out_asset) *out_asset = nullptr;
  if (!context) return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "%s: context is NULL", kCall);
  Context& ctx = *context;
  return tressvk::guarded(ctx, kCall, [&]() -> TvkResult {
    if (const TvkResult lost = ctx.require_device(kCall); lost != TVK_SUCCESS) return lost;
    if (!out_asset) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: out_asset is NULL", kCall);
    if (!info) return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: info is NULL", kCall);
    if (info->struct_size != sizeof(TvkAssetLoadInfo))
      return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: struct_size is %zu, expected %zu", kCall, info->struct_size,
                      sizeof(TvkAssetLoadInfo));
    if (!info->upload_command_buffer)
      return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: upload_command_buffer is VK_NULL_HANDLE", kCall);
    if (!info->path && (!info->data || info->size == 0))
      return ctx.fail(TVK_ERROR_INVALID_ARGUMENT, "%s: neither path nor data (with size > 0) given", kCall);

    tressvk::asset::ReadResult read =
        info->path ? tressvk::asset::read_file(info->path)
                   : tressvk::asset::read(std::span<const std::byte>(static_cast<const std::byte*>(info->data),
                                                                     info->size));
    const char* source = info->path ? info->path : "<memory>";
    if (!read.ok()) {
      const TvkResult code =
          read.status == tressvk::asset::ReadStatus::kIoError ? TVK_ERROR_IO : TVK_ERROR_INVALID_ASSET;
      if (read.error.find(source) != std::string::npos) return ctx.fail(code, "%s", read.error.c_str());
      return ctx.fail(code, "%s: %s", source, read.error.c_str());
    }
    // Owned until handed to the host; buffers made before a failure are destroyed at once (upload_statics
    // records nothing until every buffer exists).
    struct FreeNow {
      void operator()(TvkAsset_T* a) const {
        for (GpuBuffer& b : a->statics) destroy_buffer(*a->ctx, b);
        delete a;
      }
    };
    std::unique_ptr<TvkAsset_T, FreeNow> a(new TvkAsset_T());
    a->ctx = &ctx;
    a->cpu = std::move(read.asset);
    a->rest = tressvk::model::build_model_rest(a->cpu);
    a->median_strand_length = static_cast<float>(a->rest.median_length);
    if (TvkResult r = upload_statics(ctx, *a, info->upload_command_buffer); r != TVK_SUCCESS) return r;
    ctx.message(TVK_MESSAGE_INFO, "loaded %s: %u guides x %u vertices, %u follows per guide", source,
                a->rest.guide_count, a->rest.vertices_per_strand, a->rest.follow_per_guide);
    if (a->rest.respaced_strands > 0) {
      ctx.message(TVK_MESSAGE_WARNING,
                  "%s: %u strands have a segment under %g %% of their mean segment; their free vertices were respaced "
                  "evenly along them (tressvk-bake resamples strands so that this never happens)",
                  source, a->rest.respaced_strands, 100.0 * tressvk::model::kRespaceBelowRel);
    }
    *out_asset = a.release();
    return TVK_SUCCESS;
  });
}

void tressvk_destroy_asset(TvkAsset asset) {
  if (asset) asset->release();
}

TvkResult tressvk_get_asset_info(TvkAsset asset, TvkAssetInfo* out) {
  if (!asset) return tressvk::fail_without_context(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_asset_info: asset is NULL");
  if (!out) return asset->ctx->fail(TVK_ERROR_INVALID_ARGUMENT, "tressvk_get_asset_info: out_info is NULL");
  *out = TvkAssetInfo{};
  out->guide_count = asset->rest.guide_count;
  out->follow_per_guide = asset->rest.follow_per_guide;
  out->total_strands = asset->rest.guide_count * (1 + asset->rest.follow_per_guide);
  out->vertices_per_strand = asset->rest.vertices_per_strand;
  out->group_count = static_cast<uint32_t>(asset->cpu.groups.size());
  out->bone_count = static_cast<uint32_t>(asset->cpu.bone_names.size());
  for (int i = 0; i < 3; ++i) out->origin[i] = asset->cpu.origin[static_cast<size_t>(i)];
  out->median_strand_length = asset->median_strand_length;
  return TVK_SUCCESS;
}

const char* tressvk_get_asset_group_name(TvkAsset asset, uint32_t group) {
  if (!asset || group >= asset->cpu.groups.size()) return "";
  return asset->cpu.groups[group].name.c_str();
}

}  // extern "C"
