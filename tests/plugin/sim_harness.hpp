// Test harness: one simulated hair instance driven through the plugin's C interface on the shared validated
// device, with its GPU state read back after every frame, next to the double-precision reference.
#pragma once

#include <tressvk/asset.hpp>
#include <tressvk/engine/image.hpp>
#include <tressvk/reference/simulator.hpp>
#include <tressvk/test/vulkan.hpp>
#include <tressvk/tressvk.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace tressvk::test {

using Point = std::array<double, 3>;

// Positions in simulation space, each the GPU's anchor + offset summed in double (host::read_hair_state).
struct GpuState {
  std::vector<Point> pos;           // G*(K+1)*N
  std::vector<Point> prev;          // G*N
  std::vector<Point> prevprev;      // G*N
  std::vector<sim::Vec4> tangent;   // G*(K+1)*N
  std::vector<std::array<float, 4>> anchors;  // G, as the GPU holds them (w: the quiet-frame count, tressvk.h)
};

// Serialises an asset and loads it through the plugin (exercising the reader and the recorded upload).
TvkAsset load_asset(TvkContext ctx, const asset::HairAsset& hair);
// Owns a loaded asset, so that a failed REQUIRE (an exception) still destroys it before its context: otherwise the
// context's teardown reports it leaked and the device's reports its buffers, outside the failing test.
struct AssetDeleter {
  void operator()(TvkAsset a) const { tressvk_destroy_asset(a); }
};
using AssetHandle = std::unique_ptr<TvkAsset_T, AssetDeleter>;

class GpuInstance {
 public:
  GpuInstance(TvkContext ctx, TvkAsset asset, const std::vector<TvkSimParams>& params,
              const TvkSimSettings& settings);
  ~GpuInstance();
  GpuInstance(const GpuInstance&) = delete;
  GpuInstance& operator=(const GpuInstance&) = delete;

  TvkInstance handle() const { return instance_; }
  // set_frame + new_frame + simulate, submitted and waited for; then the state is read back.
  void run_frame(const TvkSimFrame& frame);
  const GpuState& state() const { return state_; }
  std::vector<std::string> recorded_passes() const;
  TvkInstanceStats stats() const;
  // Overwrites one position on the GPU (fault injection; `vertex` is strand * N + v, the value an offset from the
  // strand's anchor), recorded with the barriers it needs.
  void poke_position(size_t vertex, const sim::Vec4& value);
  // Copies positions, previous positions and tangents back (after a frame).
  void read_state();

 private:
  TvkContext ctx_;
  TvkInstance instance_ = nullptr;
  GpuState state_;
};

// Runs several instances in one simulate call (batched recording), then reads each one back.
void run_frame_batched(TvkContext ctx, const std::vector<GpuInstance*>& instances,
                       const std::vector<TvkSimFrame>& frames);

// A small built-in groom for lavapipe-sized tests.
asset::HairAsset small_groom(const std::string& name, uint32_t guides, uint32_t follows = 0);

// tressvk_cmd_draw_hair into `target` (a dynamic-rendering pass around it) and tressvk_cmd_raster_hair, each
// recorded into its own command buffer, submitted and waited for; they return the plugin's result.
TvkResult draw_hair(TvkRenderer renderer, const engine::OffscreenTarget& target, const TvkDrawInfo& draw);
TvkResult raster_hair(TvkRenderer renderer, const TvkDrawInfo& draw);

// A 32x32 orthographic view looking down -z at the origin (the draw calls' smallest valid view).
TvkView small_ortho_view();

}  // namespace tressvk::test
