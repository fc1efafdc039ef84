// libFuzzer target: the plugin's asset load on a real Vulkan device (lavapipe under scripts/fuzz.sh) with the
// validation layer and synchronization validation on. Bytes (checksums fixed up) -> tressvk_load_asset; an asset
// that loads is also instanced and, when its (N, K) is one of the first few seen, simulated for one frame, all
// recorded into one submitted command buffer. (Each new N and K means new compute pipelines, which lavapipe
// compiles in about a second under ASan: simulating every variant would bring the target to 1 input/s. Assets with
// strands pinned at both ends are loaded and instanced but not simulated: their length pass compiles in the
// tridiagonal solve, which lavapipe takes about 14 s to compile, and over a minute under ASan; the analytic tests
// simulate such strands.)
// Findings: a crash or sanitizer report, a validation message, a failure without a message, or device memory
// that is not back to where it started once the frames have been retired.
#include "fuzz_common.hpp"

#include <tressvk/engine/device.hpp>
#include <tressvk/host/plugin_host.hpp>

#include <memory>
#include <set>
#include <utility>

using namespace tressvk;

namespace {

// Whether the asset has a strand whose tip is pinned while another of its vertices is free (TressFX
// bothEndsImmovable): the plugin then builds its pinned-tips pipeline variant.
bool has_pinned_tips(const void* data, size_t size) {
  const asset::ReadResult r = asset::read(std::span<const std::byte>(static_cast<const std::byte*>(data), size));
  if (!r.ok()) return false;
  const uint32_t n = r.asset.vertices_per_strand;
  for (uint32_t g = 0; n && g < r.asset.guide_count(); ++g) {
    bool any_free = false;
    for (uint32_t v = 0; v < n; ++v) any_free = any_free || r.asset.rest_positions[size_t{g} * n + v][3] > 0.0f;
    if (any_free && r.asset.rest_positions[size_t{g} * n + n - 1][3] == 0.0f) return true;
  }
  return false;
}

struct Harness {
  std::unique_ptr<engine::Device> device;
  TvkContext ctx = nullptr;
  uint64_t baseline_allocations = 0;
  std::set<std::pair<uint32_t, uint32_t>> simulated;  // (N, K) variants whose pipelines exist

  Harness() {
    engine::DeviceOptions options;
    options.app_name = "tressvk-fuzz";
    options.validation = true;
    options.sync_validation = true;
    device = std::make_unique<engine::Device>(host::with_plugin_requirements(options));
    TvkContextCreateInfo info = host::context_info(*device);
    info.frames_in_flight = 2;
    if (tressvk_create_context(&info, &ctx) != TVK_SUCCESS) fuzz::finding("tressvk_create_context failed");
    TvkMemoryUsage usage{};
    tressvk_get_memory_usage(ctx, &usage);
    baseline_allocations = usage.allocation_count;
  }
  // Left to the process exit on purpose (libFuzzer exits without running it when it stops on a finding).
};

Harness& harness() {
  static Harness* h = new Harness();
  return *h;
}

}  // namespace

// The device, the validation layer and the context come up before the first input (not counted in -timeout).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  harness();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* raw, size_t raw_size) {
  Harness& h = harness();
  // Checksums recomputed, so that mutations reach the sections (the reader's own target covers the CRCs).
  const std::vector<std::byte> bytes = fuzz::with_fixed_checksums(raw, raw_size);
  const void* data = bytes.data();
  const size_t size = bytes.size();
  const uint64_t messages_before = h.device->messages().count();
  TvkResult load = TVK_SUCCESS, sim = TVK_SUCCESS;
  std::string error;
  h.device->run_commands([&](VkCommandBuffer cmd) {
    TvkAssetLoadInfo li{};
    li.struct_size = sizeof(li);
    li.data = data;
    li.size = size;
    li.upload_command_buffer = cmd;
    TvkAsset asset = nullptr;
    load = tressvk_load_asset(h.ctx, &li, &asset);
    if (load != TVK_SUCCESS) {
      if (asset) fuzz::finding("a failed load returned an asset");
      error = tressvk_last_error(h.ctx);
      return;
    }
    TvkAssetInfo ai{};
    if (tressvk_get_asset_info(asset, &ai) != TVK_SUCCESS) fuzz::finding("tressvk_get_asset_info failed");
    TvkInstanceCreateInfo ci{};
    ci.struct_size = sizeof(ci);
    ci.asset = asset;
    TvkInstance instance = nullptr;
    const std::pair<uint32_t, uint32_t> variant{ai.vertices_per_strand, ai.follow_per_guide};
    const bool simulate = (h.simulated.count(variant) || h.simulated.size() < 6) && !has_pinned_tips(data, size);
    if (tressvk_create_instance(h.ctx, &ci, &instance) != TVK_SUCCESS) {
      error = tressvk_last_error(h.ctx);
      sim = TVK_ERROR_INVALID_ARGUMENT;
    } else if (!simulate) {
      tressvk_destroy_instance(instance);
    } else {
      h.simulated.insert(variant);
      TvkSimFrame frame{};
      frame.dt = 1.0f / 60.0f;
      frame.transform.rotation[3] = 1.0;
      frame.wind = TvkWind TVK_WIND_DEFAULT_INIT;
      if (tressvk_set_frame(instance, &frame) != TVK_SUCCESS) fuzz::finding("tressvk_set_frame failed");
      if (tressvk_new_frame(h.ctx) != TVK_SUCCESS) fuzz::finding("tressvk_new_frame failed");
      TvkSimulateInfo si{};
      si.struct_size = sizeof(si);
      si.instance_count = 1;
      si.instances = &instance;
      sim = tressvk_cmd_simulate(h.ctx, cmd, &si);
      if (sim != TVK_SUCCESS) error = tressvk_last_error(h.ctx);
      tressvk_destroy_instance(instance);
    }
    tressvk_destroy_asset(asset);
  });
  if ((load != TVK_SUCCESS || sim != TVK_SUCCESS) && error.empty()) fuzz::finding("a failure without a message");
  // An asset that passed the reader's validation must simulate: the reader is the plugin's only gate.
  if (load == TVK_SUCCESS && sim != TVK_SUCCESS) fuzz::finding("a loaded asset failed to simulate: " + error);
  // Everything was submitted and waited for: retire the frames, then memory is back to the baseline.
  for (int i = 0; i < 3; ++i) tressvk_new_frame(h.ctx);
  TvkMemoryUsage usage{};
  tressvk_get_memory_usage(h.ctx, &usage);
  if (usage.allocation_count != h.baseline_allocations)
    fuzz::finding("device allocations did not return to the baseline: " + std::to_string(usage.allocation_count));
  if (h.device->messages().count() != messages_before) fuzz::finding("a validation message (printed above)");
  return 0;
}
