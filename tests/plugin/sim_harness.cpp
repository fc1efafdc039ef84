#include "sim_harness.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/sync.hpp>
#include <tressvk/host/hair_readback.hpp>

#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cstring>
#include <iterator>

namespace tressvk::test {

TvkAsset load_asset(TvkContext ctx, const asset::HairAsset& hair) {
  // host::load_asset throws with tressvk_last_error's message, which Catch reports.
  return host::load_asset(device(), ctx, asset::write(hair));
}

GpuInstance::GpuInstance(TvkContext ctx, TvkAsset asset, const std::vector<TvkSimParams>& params,
                         const TvkSimSettings& settings)
    : ctx_(ctx) {
  TvkInstanceCreateInfo info{};
  info.struct_size = sizeof(info);
  info.asset = asset;
  info.settings = &settings;
  info.params = params.empty() ? nullptr : &params[0];
  const TvkResult r = tressvk_create_instance(ctx, &info, &instance_);
  INFO(tressvk_last_error(ctx));
  REQUIRE(r == TVK_SUCCESS);
  for (uint32_t g = 0; g < params.size(); ++g) REQUIRE(tressvk_set_sim_params(instance_, g, &params[g]) == TVK_SUCCESS);
}

GpuInstance::~GpuInstance() {
  // The fixture waits for each submission, so the instance's resources are free to go.
  tressvk_destroy_instance(instance_);
}

void GpuInstance::run_frame(const TvkSimFrame& frame) { run_frame_batched(ctx_, {this}, {frame}); }

void run_frame_batched(TvkContext ctx, const std::vector<GpuInstance*>& instances,
                       const std::vector<TvkSimFrame>& frames) {
  std::vector<TvkInstance> handles;
  for (size_t i = 0; i < instances.size(); ++i) {
    REQUIRE(tressvk_set_frame(instances[i]->handle(), &frames[i]) == TVK_SUCCESS);
    handles.push_back(instances[i]->handle());
  }
  REQUIRE(tressvk_new_frame(ctx) == TVK_SUCCESS);
  TvkResult r = TVK_SUCCESS;
  run_commands([&](VkCommandBuffer cmd) {
    TvkSimulateInfo info{};
    info.struct_size = sizeof(info);
    info.instance_count = static_cast<uint32_t>(handles.size());
    info.instances = handles.data();
    r = tressvk_cmd_simulate(ctx, cmd, &info);
  });
  INFO(tressvk_last_error(ctx));
  REQUIRE(r == TVK_SUCCESS);
  for (GpuInstance* inst : instances) inst->read_state();
}

void GpuInstance::read_state() {
  host::HairState s = host::read_hair_state(device(), instance_);
  state_.pos = std::move(s.positions);
  state_.prev = std::move(s.previous);
  state_.prevprev = std::move(s.previous_previous);
  state_.tangent = std::move(s.tangents);
  state_.anchors = std::move(s.anchors);
}

std::vector<std::string> GpuInstance::recorded_passes() const {
  const uint32_t n = tressvk_get_recorded_passes(ctx_, nullptr, 0);
  std::vector<const char*> names(n);
  tressvk_get_recorded_passes(ctx_, names.data(), n);
  return {names.begin(), names.end()};
}

TvkInstanceStats GpuInstance::stats() const {
  TvkInstanceStats s{};
  REQUIRE(tressvk_get_instance_stats(instance_, &s) == TVK_SUCCESS);
  return s;
}

void GpuInstance::poke_position(size_t vertex, const sim::Vec4& value) {
  TvkInstanceBuffers b{};
  REQUIRE(tressvk_get_instance_buffers(instance_, &b) == TVK_SUCCESS);
  run_commands([&](VkCommandBuffer cmd) {
    engine::cmd_memory_barrier(
        cmd, {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT},
        {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT});
    const size_t element = sim::vertex_index(vertex / b.vertices_per_strand, vertex % b.vertices_per_strand,
                                             b.vertices_per_strand);
    vkCmdUpdateBuffer(cmd, b.positions, element * sizeof(sim::Vec4), sizeof(sim::Vec4), value.data());
    engine::cmd_memory_barrier(cmd, {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT},
                               engine::state::kComputeReadWrite);
  });
}

TvkView small_ortho_view() {
  TvkView view{};
  const double vp[16] = {2, 0, 0, 0, 0, -2, 0, 0, 0, 0, -0.5, 0, 0, 0, 0.5, 1};
  std::copy(std::begin(vp), std::end(vp), view.view_projection);
  view.eye[2] = 1.0;
  view.orthographic = 1;
  view.direction[2] = -1.0f;
  view.width = view.height = 32;
  return view;
}

asset::HairAsset small_groom(const std::string& name, uint32_t guides, uint32_t follows) {
  baker::BuiltinGroomOptions options;
  options.guide_count = guides;
  options.follow_per_guide = follows;
  return baker::make_builtin_groom(name, options);
}

TvkResult draw_hair(TvkRenderer renderer, const engine::OffscreenTarget& target, const TvkDrawInfo& draw) {
  TvkResult r = TVK_SUCCESS;
  run_commands([&](VkCommandBuffer cmd) {
    engine::cmd_begin_rendering(cmd, target, {});
    r = tressvk_cmd_draw_hair(renderer, cmd, &draw);
    engine::cmd_end_rendering(cmd);
  });
  return r;
}

TvkResult raster_hair(TvkRenderer renderer, const TvkDrawInfo& draw) {
  TvkRasterInfo info{};
  info.struct_size = sizeof(info);
  info.draw = &draw;
  TvkResult r = TVK_SUCCESS;
  run_commands([&](VkCommandBuffer cmd) { r = tressvk_cmd_raster_hair(renderer, cmd, &info); });
  return r;
}

}  // namespace tressvk::test
