// The demo's frame, the way a studio engine integrates TressVK:
//   simulate (outside passes) -> shadow pass [meshes + tressvk_cmd_draw_shadow] -> barrier (shadow map to
//   sampled) -> main pass [meshes + tressvk_cmd_draw_hair] -> readback.
// With the compute path (default) the main pass is split where the opaque depth is final:
//   main pass [meshes] -> tressvk_cmd_raster_hair (compute, reads depth) -> pass [tressvk_cmd_composite_hair].
// Frames run in flight (engine::FrameLoop): the GPU renders frame n+1 while the CPU writes the PNG of frame n.
// GPU timestamps separate simulation, shadow and shading time. Used by tressvk-demo and the golden-image tests.
#pragma once

#include "demo_options.hpp"
#include "params.hpp"
#include <tressvk/host/plugin_host.hpp>
#include "scene.hpp"
#include "scene_renderer.hpp"
#include "step_error.hpp"

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/engine/image.hpp>

#include <glm/glm.hpp>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tressvk::demo {

using host::check_tvk;
using host::HairHost;
using host::PluginContext;

struct FrameReport {
  uint32_t index = 0;
  engine::Pixels pixels;
  std::optional<double> simulation_ms, shadow_ms, shading_ms;  // empty when the queue has no timestamps
  std::optional<double> hair_shadow_ms, hair_ms;  // the hair calls alone (inside the shadow and shading times)
  uint32_t strands_drawn = 0;
  glm::dmat4 view_proj{1.0};  // the camera's world -> clip transform of this frame (Vulkan clip space)
};

// What an interactive host changes between frames (tressvk-viewer): an orbit around the framed centre, a zoom
// factor on the framing distance, and a pause that holds the animation clock (the hair then settles in place).
struct ViewControl {
  double yaw = 0.0;    // radians about world +y, added to the scene's view direction
  double pitch = 0.0;  // radians up (+) or down, clamped short of the poles
  double zoom = 1.0;   // multiplies the camera distance
  bool paused = false;
};

enum class PassFlavour { dynamic_rendering, render_pass };

class DemoApp {
 public:
  static constexpr uint32_t kFramesInFlight = 2;
  static constexpr uint32_t kShadowMapSize = 1024;

  DemoApp(engine::Device& device, const Options& options, PassFlavour flavour = PassFlavour::dynamic_rendering);
  ~DemoApp();

  // Renders `frames` frames; on_frame gets each finished frame in order.
  void run(uint32_t frames, const std::function<void(FrameReport&)>& on_frame);
  // Renders frames while next_frame() says so (a windowed host polls its events there).
  void run_while(const std::function<bool()>& next_frame, const std::function<void(FrameReport&)>& on_frame);

  void set_view(const ViewControl& view) { view_ = view; }
  const ViewControl& view() const { return view_; }
  double time() const { return time_; }  // s of animation shown

  const Scene& scene() const { return scene_; }
  TvkContext plugin() const { return plugin_.get(); }
  const TvkAssetInfo& asset_info() const { return hair_->info(); }
  TvkRenderer renderer() const { return hair_->renderer(); }
  TvkInstance instance() const { return hair_->instance(); }
  // TVK_RASTER_* flags of the compute path for the frames recorded from now on (tressvk-bench, tests).
  void set_raster_flags(uint32_t flags) { options_.raster_flags = flags; }
  // The parameters in effect (the file's, completed with the scene's and the command line's choices).
  const Params& params() const { return params_; }
  // With Options::pass_timestamps: the plugin's per-pass GPU times of the frames completed so far, per pass name
  // (collected when each frame is recorded, for the frame the plugin's promise says is complete).
  std::map<std::string, std::vector<double>>& pass_ms() { return pass_ms_; }
  // Live tuning (the viewer's panel): edit tuning(), then apply_params() hands simulation, settings and material
  // to the plugin; wind and LOD are read every frame.
  Params& tuning() { return params_; }
  void apply_params();
  // The plugin's per-pass GPU times of the newest complete frame (Options::pass_timings; empty without).
  std::vector<TvkPassTiming> pass_timings() const;
  // Step error against the double reference (Options::step_error): measure the next frame (it waits for the
  // device and runs the reference on the CPU: seconds, not per frame). The last result, relative to the median
  // strand length; empty until one was measured.
  void request_step_error() { step_error_requested_ = true; }
  std::optional<double> step_error() const { return step_error_; }

 private:
  void record(const engine::FrameLoop::Frame& frame);

  engine::Device& device_;
  Options options_;
  PassFlavour flavour_;
  Scene scene_;
  engine::OffscreenTarget target_;
  engine::RenderPassTarget render_pass_;
  engine::RenderPassTarget render_pass_load_;  // compute path, VkRenderPass flavour: the composite pass
  PluginContext plugin_;
  std::unique_ptr<SceneRenderer> scene_renderer_;
  std::unique_ptr<HairHost> hair_;
  std::vector<engine::Buffer> readback_;  // one per frame slot
  std::vector<uint32_t> strands_;         // strands drawn, per slot
  std::vector<glm::dmat4> view_proj_;     // camera, per slot
  std::map<std::string, std::vector<double>> pass_ms_;
  TvkHairMaterial material_{};
  Params params_;
  ViewControl view_;
  double time_ = 0.0;
  uint64_t clock_frames_ = 0;
  std::unique_ptr<StepErrorProbe> probe_;
  bool step_error_requested_ = false, step_error_pending_ = false;
  uint32_t draw_strands_ = 0;  // what the last recorded frame gave tressvk_set_draw_strands (its camera's LOD)
  std::optional<double> step_error_;
};

}  // namespace tressvk::demo
