#include "demo_app.hpp"

#include <tressvk/engine/frame_loop.hpp>
#include <tressvk/host/hair_readback.hpp>
#include <tressvk/engine/sync.hpp>
#include <tressvk/engine/timestamps.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace tressvk::demo {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;  // shaders write linear colour; PNG gets sRGB
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
// begin, after simulation, after shadow, after shading; then around the hair's shadow call (4, 5) and from the
// start of the hair's shading calls to the end of shading (6 -> 3).
constexpr uint32_t kTimestamps = 7;

// Where the previous frame left the shared targets. Old contents are discarded (layout UNDEFINED, every frame
// clears), but the execution dependency on the previous frame's last use stays: its readback copy for colour,
// its depth writes for depth, its fragment-shader reads of the shadow map.
constexpr engine::ResourceState kColorAfterReadback{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                                                    VK_IMAGE_LAYOUT_UNDEFINED};
constexpr engine::ResourceState kDepthAfterFrame{VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                                                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                                                 VK_IMAGE_LAYOUT_UNDEFINED};
constexpr engine::ResourceState kShadowAfterFrame{
    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE,
    VK_IMAGE_LAYOUT_UNDEFINED};
// The shadow map while the main pass's fragment shaders and the compute rasterizer's vertex shading sample it.
constexpr engine::ResourceState kShadowSampled{
    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
// The shadow map as tressvk_cmd_shadow_hair takes it (copied out) and leaves it (copied back).
constexpr engine::ResourceState kShadowToHair{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                              VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
constexpr engine::ResourceState kShadowFromHair{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
// The opaque depth while the compute rasterizer reads it (render.h, tressvk_cmd_raster_hair).
constexpr engine::ResourceState kDepthForRaster{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                                VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL};

void to_array(const glm::dmat4& m, double (&out)[16]) { std::memcpy(out, glm::value_ptr(m), sizeof(out)); }

glm::dmat4 instance_matrix(const TvkInstanceTransform& x) {
  const glm::dquat q(x.rotation[3], x.rotation[0], x.rotation[1], x.rotation[2]);
  glm::dmat4 m = glm::mat4_cast(q);
  m[3] = glm::dvec4(x.translation[0], x.translation[1], x.translation[2], 1.0);
  return m;
}

}  // namespace

DemoApp::DemoApp(engine::Device& device, const Options& options, PassFlavour flavour)
    : device_(device),
      options_(options),
      flavour_(flavour),
      scene_(build_scene(options)),
      target_(engine::create_offscreen_target(device, options.width, options.height, kColorFormat, kDepthFormat)),
      plugin_(device, kFramesInFlight, options.pass_timestamps || options.pass_timings) {
  if (flavour_ == PassFlavour::render_pass) {
    render_pass_ = engine::RenderPassTarget(device, target_);
    render_pass_load_ = engine::RenderPassTarget(device, target_, /*load=*/true);
  }
  scene_renderer_ = std::make_unique<SceneRenderer>(device, kColorFormat, kDepthFormat, kShadowMapSize,
                                                    kFramesInFlight, scene_.head, scene_.floor,
                                                    render_pass_.render_pass());
  TvkRendererCreateInfo ri{};
  ri.struct_size = sizeof(ri);
  ri.shading.color_format = kColorFormat;
  ri.shading.depth_format = kDepthFormat;
  ri.shading.samples = VK_SAMPLE_COUNT_1_BIT;
  ri.shading.render_pass = render_pass_.render_pass();  // VK_NULL_HANDLE: dynamic rendering
  ri.shading.subpass = 0;
  ri.shadow.depth_format = SceneRenderer::kShadowFormat;
  hair_ = std::make_unique<HairHost>(device, plugin_.get(), scene_.asset_bytes, ri);

  // Parameters: the file's where given; the scene's strand width and taper and --wind otherwise.
  if (!options.params_file.empty()) params_ = load_params(options.params_file);
  if (!params_.has_wind) {
    params_.wind.direction[0] = 1.0f;
    params_.wind.direction[2] = -0.4f;
    params_.wind.strength = options.wind;
  }
  material_ = params_.material;
  if (!params_.has_strand_width) material_.strand_width = scene_.strand_width;
  if (!params_.has_tip_width_ratio && scene_.tip_width_ratio >= 0.0f) material_.tip_width_ratio = scene_.tip_width_ratio;
  params_.material = material_;
  if (!options.params_file.empty()) {
    const TvkContext ctx = plugin_.get();
    for (uint32_t g = 0; g < hair_->info().group_count; ++g)
      check_tvk(tressvk_set_sim_params(hair_->instance(), g, &params_.simulation), ctx, "tressvk_set_sim_params");
    check_tvk(tressvk_set_sim_settings(hair_->instance(), &params_.settings), ctx, "tressvk_set_sim_settings");
  }
  for (uint32_t i = 0; i < kFramesInFlight; ++i)
    readback_.push_back(engine::create_buffer(device, VkDeviceSize{4} * options.width * options.height,
                                              VK_BUFFER_USAGE_TRANSFER_DST_BIT, engine::MemoryUsage::readback));
  if (options.step_error) probe_ = std::make_unique<StepErrorProbe>(scene_.asset_bytes, params_);
  strands_.assign(kFramesInFlight, 0);
  view_proj_.assign(kFramesInFlight, glm::dmat4(1.0));
}

DemoApp::~DemoApp() { device_.wait_idle(); }

void DemoApp::apply_params() {
  const TvkContext ctx = plugin_.get();
  for (uint32_t g = 0; g < hair_->info().group_count; ++g)
    check_tvk(tressvk_set_sim_params(hair_->instance(), g, &params_.simulation), ctx, "tressvk_set_sim_params");
  check_tvk(tressvk_set_sim_settings(hair_->instance(), &params_.settings), ctx, "tressvk_set_sim_settings");
  material_ = params_.material;
}

std::vector<TvkPassTiming> DemoApp::pass_timings() const {
  std::vector<TvkPassTiming> t(32);
  t.resize(tressvk_get_pass_timings(plugin_.get(), t.data(), static_cast<uint32_t>(t.size())));
  return t;
}

void DemoApp::run(uint32_t frames, const std::function<void(FrameReport&)>& on_frame) {
  uint32_t f = 0;
  run_while([&] { return f++ < frames; }, on_frame);
}

void DemoApp::run_while(const std::function<bool()>& next_frame, const std::function<void(FrameReport&)>& on_frame) {
  engine::FrameLoop loop(device_, kFramesInFlight, kTimestamps, [&](const engine::FrameLoop::Frame& done) {
    FrameReport report;
    report.index = static_cast<uint32_t>(done.number);
    report.pixels = engine::pixels_from_buffer(readback_[done.slot], target_.color);
    report.simulation_ms = done.timestamps->elapsed_ms(0, 1);
    report.shadow_ms = done.timestamps->elapsed_ms(1, 2);
    report.shading_ms = done.timestamps->elapsed_ms(2, 3);
    if (options_.shadows) report.hair_shadow_ms = done.timestamps->elapsed_ms(4, 5);
    report.hair_ms = done.timestamps->elapsed_ms(6, 3);
    report.strands_drawn = strands_[done.slot];
    report.view_proj = view_proj_[done.slot];
    on_frame(report);
  });
  while (next_frame()) {
    record(loop.begin());
    loop.end();
  }
  loop.finish();
}

void DemoApp::record(const engine::FrameLoop::Frame& frame) {
  const TvkContext ctx = plugin_.get();
  // The clock counts the frames that were not paused: frame n of an unpaused run is at (n + 1) * frame_time
  // exactly, as the golden images expect (a running sum of frame_time would drift in the last bits).
  if (!view_.paused) ++clock_frames_;
  const double dt = view_.paused ? 0.0 : options_.frame_time;
  const double t = static_cast<double>(clock_frames_) * options_.frame_time;
  time_ = t;

  // ---- The frame's simulation input: head motion, colliders, wind.
  TvkSimFrame sim{};
  sim.dt = static_cast<float>(dt);
  sim.transform = animate(options_.animate, t);
  for (int i = 0; i < 3; ++i) sim.transform.translation[i] += options_.world_offset[i];
  sim.capsule_count = static_cast<uint32_t>(std::min<size_t>(scene_.capsules.size(), TVK_MAX_CAPSULES));
  std::copy_n(scene_.capsules.begin(), sim.capsule_count, sim.capsules);
  sim.wind = wind_at(options_.animate, t, params_.wind);
  if (probe_) {  // step error: the GPU state around one frame, compared with the reference's step
    if (step_error_pending_) {
      device_.wait_idle();
      step_error_ = probe_->finish(host::read_hair_state(device_, hair_->instance()), draw_strands_);
      step_error_pending_ = false;
    }
    if (step_error_requested_) {
      device_.wait_idle();
      probe_->start(sim, host::read_hair_state(device_, hair_->instance()), params_);
      step_error_requested_ = false;
      step_error_pending_ = true;
    } else {
      probe_->track(sim);
    }
  }
  check_tvk(tressvk_set_frame(hair_->instance(), &sim), ctx, "tressvk_set_frame");
  check_tvk(tressvk_new_frame(ctx), ctx, "tressvk_new_frame");
  if (options_.pass_timestamps) {
    std::array<TvkPassTiming, 64> timings{};
    const uint32_t count = std::min<uint32_t>(tressvk_get_pass_timings(ctx, timings.data(), 64), 64);
    for (uint32_t i = 0; i < count; ++i) pass_ms_[timings[i].name].push_back(timings[i].milliseconds);
  }

  // ---- Camera and light, in double (world).
  const glm::dmat4 model = instance_matrix(sim.transform);
  const glm::dvec3 center = glm::dvec3(model * glm::dvec4(scene_.center[0], scene_.center[1], scene_.center[2], 1.0));
  const double fov = glm::radians(30.0);
  const double aspect = static_cast<double>(options_.width) / options_.height;
  const double distance = view_.zoom * (options_.camera_distance > 0.0f
                                            ? double{options_.camera_distance}
                                            : 0.9 * scene_.radius / std::sin(0.5 * fov * std::min(1.0, aspect)));
  glm::dvec3 dir =
      glm::normalize(glm::dvec3(scene_.view_direction[0], scene_.view_direction[1], scene_.view_direction[2]));
  if (view_.yaw != 0.0 || view_.pitch != 0.0) {  // orbit: yaw about +y, then pitch, clamped short of the poles
    const double yaw = std::atan2(dir.x, dir.z) + view_.yaw;
    const double pitch = std::clamp(std::asin(std::clamp(dir.y, -1.0, 1.0)) + view_.pitch, -1.45, 1.45);
    dir = glm::dvec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  }
  const glm::dvec3 eye = center + dir * distance;
  glm::dmat4 proj = glm::perspectiveRH_ZO(fov, aspect, 0.02 * distance, 10.0 * distance + 4.0 * scene_.radius);
  proj[1][1] *= -1.0;  // Vulkan clip space: +y is down
  SceneFrame sf;
  sf.view_proj = proj * glm::lookAtRH(eye, center, glm::dvec3(0, 1, 0));
  sf.eye = eye;
  sf.head_model = model;
  const glm::dvec3 offset(options_.world_offset[0], options_.world_offset[1], options_.world_offset[2]);
  sf.floor_model = glm::translate(glm::dmat4(1.0), offset);
  sf.lights = scene_.lights;
  for (TvkLight& l : sf.lights)
    for (int i = 0; i < 3; ++i) l.position[i] += offset[i];
  sf.ambient = glm::vec3(0.16f, 0.17f, 0.2f);
  sf.shadows = options_.shadows;
  sf.head_color = scene_.skin_color;
  view_proj_[frame.slot] = sf.view_proj;
  const TvkLight& key = scene_.lights[0];
  const glm::dvec3 light_dir = glm::normalize(glm::dvec3(key.direction[0], key.direction[1], key.direction[2]));
  const double r = double{options_.shadow_extent} * scene_.radius;
  const glm::dvec3 light_eye = center - light_dir * (2.0 * r);
  const glm::dvec3 up = std::abs(light_dir.y) > 0.95 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const double near_plane = 0.0, far_plane = 4.0 * r;
  sf.shadow_proj = glm::orthoRH_ZO(-r, r, -r, r, near_plane, far_plane) * glm::lookAtRH(light_eye, center, up);
  scene_renderer_->update(frame.slot, sf);

  TvkView camera{};
  to_array(sf.view_proj, camera.view_projection);
  for (int i = 0; i < 3; ++i) camera.eye[i] = eye[i];
  camera.width = options_.width;
  camera.height = options_.height;
  TvkView light{};
  to_array(sf.shadow_proj, light.view_projection);
  for (int i = 0; i < 3; ++i) {
    light.eye[i] = light_eye[i];
    light.direction[i] = static_cast<float>(light_dir[i]);
  }
  light.orthographic = 1;
  light.width = light.height = kShadowMapSize;
  TvkLodSettings lod{};
  if (params_.has_lod && options_.lod_start <= 0.0f && options_.lod_target_px <= 0.0f &&
      (params_.lod.end_distance > params_.lod.start_distance || params_.lod.target_width_px > 0.0f))
    lod = params_.lod;
  if (options_.lod_target_px > 0.0f) {
    lod = TvkLodSettings{};
    lod.target_width_px = options_.lod_target_px;
    lod.min_fraction = options_.lod_min_fraction;
  } else if (options_.lod_start > 0.0f && options_.lod_end > options_.lod_start) {
    lod.start_distance = options_.lod_start;
    lod.end_distance = options_.lod_end;
    lod.min_fraction = options_.lod_min_fraction;
  }

  // ---- Recording.
  const VkCommandBuffer cmd = frame.cmd;
  frame.timestamps->cmd_write(cmd, 0, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
  const TvkInstance instance = hair_->instance();
  TvkDrawInfo shadow_di{};
  shadow_di.struct_size = sizeof(shadow_di);
  shadow_di.instance = instance;
  shadow_di.view = &light;
  shadow_di.lod_view = &camera;  // the same strands as the camera sees
  shadow_di.materials = &material_;
  shadow_di.material_count = 1;
  shadow_di.lod = lod;
  // Follow hairs only for the strands this frame draws: the camera's LOD count, which both draws take.
  check_tvk(tressvk_get_draw_strands(hair_->renderer(), &shadow_di, &draw_strands_), ctx, "tressvk_get_draw_strands");
  check_tvk(tressvk_set_draw_strands(instance, draw_strands_), ctx, "tressvk_set_draw_strands");
  check_tvk(host::record_simulate(ctx, cmd, instance), ctx, "tressvk_cmd_simulate");
  frame.timestamps->cmd_write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);

  // Shadow pass: the engine's shadow map; the head and the hair both draw into it. Always cleared (and
  // transitioned) so the main pass samples a defined image even with --no-shadows.
  const engine::OffscreenTarget& shadow = scene_renderer_->shadow_target();
  engine::ClearValues clear_shadow;
  engine::cmd_begin_rendering(cmd, shadow, clear_shadow, engine::state::kUndefined, kShadowAfterFrame);
  const bool compute_path = options_.hair_path == HairPath::compute;
  if (options_.shadows) {
    scene_renderer_->cmd_draw_shadow(cmd, frame.slot, sf);
    if (!compute_path) {
      frame.timestamps->cmd_write(cmd, 4, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      check_tvk(tressvk_cmd_draw_shadow(hair_->renderer(), cmd, &shadow_di), ctx, "tressvk_cmd_draw_shadow");
      frame.timestamps->cmd_write(cmd, 5, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }
  }
  engine::cmd_end_rendering(cmd);
  engine::ResourceState shadow_state = engine::state::kDepthAttachment;
  if (options_.shadows && compute_path) {
    // The compute path merges the hair's depth into the map outside the pass (render.h, tressvk_cmd_shadow_hair).
    engine::cmd_image_barrier(cmd, shadow.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, shadow_state, kShadowToHair);
    frame.timestamps->cmd_write(cmd, 4, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    TvkShadowRasterInfo sri{};
    sri.struct_size = sizeof(sri);
    sri.draw = &shadow_di;
    sri.shadow_image = shadow.depth.handle();
    check_tvk(tressvk_cmd_shadow_hair(hair_->renderer(), cmd, &sri), ctx, "tressvk_cmd_shadow_hair");
    frame.timestamps->cmd_write(cmd, 5, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    shadow_state = kShadowFromHair;
  }
  frame.timestamps->cmd_write(cmd, 2, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
  engine::cmd_image_barrier(cmd, shadow.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, shadow_state, kShadowSampled);

  // Main pass: meshes first (opaque), then the hair over them.
  engine::ClearValues clear;
  clear.color = {0.05f, 0.055f, 0.065f, 1.0f};
  if (flavour_ == PassFlavour::render_pass)
    engine::cmd_begin_render_pass(cmd, render_pass_, clear);
  else
    engine::cmd_begin_rendering(cmd, target_, clear, kColorAfterReadback, kDepthAfterFrame);
  scene_renderer_->cmd_draw(cmd, frame.slot, sf);
  TvkShadowMap shadow_map{};
  if (options_.shadows) {
    shadow_map.depth_view = shadow.depth.view();
    shadow_map.sampler = scene_renderer_->hair_shadow_sampler();
    shadow_map.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    to_array(sf.shadow_proj, shadow_map.view_projection);
    shadow_map.perspective = 0;
    shadow_map.near_plane = static_cast<float>(near_plane);
    shadow_map.far_plane = static_cast<float>(far_plane);
  }
  std::vector<TvkLight> lights = sf.lights;
  if (!options_.shadows)
    for (TvkLight& l : lights) l.shadowed = 0;
  TvkDrawInfo di{};
  di.struct_size = sizeof(di);
  di.instance = instance;
  di.view = &camera;
  di.materials = &material_;
  di.material_count = 1;
  di.lod = lod;
  di.light_count = static_cast<uint32_t>(lights.size());
  di.lights = lights.data();
  di.ambient[0] = sf.ambient.x;
  di.ambient[1] = sf.ambient.y;
  di.ambient[2] = sf.ambient.z;
  di.shadow = options_.shadows ? &shadow_map : nullptr;
  const bool pass_flavour = flavour_ == PassFlavour::render_pass;
  if (!options_.draw_hair) {
    // The same frame without the hair (tests: what the hair covers); the hair's timestamp still brackets nothing.
    frame.timestamps->cmd_write(cmd, 6, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
  } else if (options_.hair_path == HairPath::raster) {
    frame.timestamps->cmd_write(cmd, 6, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    check_tvk(tressvk_cmd_draw_hair(hair_->renderer(), cmd, &di), ctx, "tressvk_cmd_draw_hair");
  } else {
    // The opaque depth is final: end the pass, let the compute rasterizer read the depth, and composite the hair
    // layer in a second pass that keeps the colour.
    if (pass_flavour)
      engine::cmd_end_render_pass(cmd);
    else
      engine::cmd_end_rendering(cmd);
    const engine::ResourceState depth_written =
        pass_flavour ? engine::state::kDepthStencilAttachment : engine::state::kDepthAttachment;
    frame.timestamps->cmd_write(cmd, 6, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    engine::cmd_image_barrier(cmd, target_.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, depth_written, kDepthForRaster);
    TvkRasterInfo ri{};
    ri.struct_size = sizeof(ri);
    ri.draw = &di;
    ri.depth_view = target_.depth.view();
    ri.depth_layout = kDepthForRaster.layout;
    ri.flags = options_.raster_flags;
    check_tvk(tressvk_cmd_raster_hair(hair_->renderer(), cmd, &ri), ctx, "tressvk_cmd_raster_hair");
    if (pass_flavour) {
      engine::cmd_image_barrier(cmd, target_.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, kDepthForRaster,
                                engine::state::kDepthStencilAttachment);
      engine::cmd_begin_render_pass(cmd, render_pass_load_, clear);
    } else {
      engine::cmd_begin_rendering(cmd, target_, clear, engine::state::kColorAttachment, kDepthForRaster,
                                  /*load=*/true);
    }
    check_tvk(tressvk_cmd_composite_hair(hair_->renderer(), cmd), ctx, "tressvk_cmd_composite_hair");
  }
  strands_[frame.slot] = tressvk_get_last_drawn_strands(hair_->renderer());
  if (pass_flavour)
    engine::cmd_end_render_pass(cmd);
  else
    engine::cmd_end_rendering(cmd);
  frame.timestamps->cmd_write(cmd, 3, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
  engine::cmd_readback_image(cmd, target_.color, engine::state::kColorAttachment, readback_[frame.slot]);
}

}  // namespace tressvk::demo
