// docs/integration.md as a test: the walk-through, section by section, with the doc's code (C aggregates written
// as C++), on the shared validated device (validation + synchronization validation on; any message fails the test).
// Keep the two in step: a change to the walk-through changes this file, and the reverse.
#include <tressvk/test/vulkan.hpp>

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/descriptors.hpp>
#include <tressvk/engine/image.hpp>
#include <tressvk/engine/sync.hpp>

#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

std::string g_last_message;
void on_message(TvkMessageSeverity severity, const char* message, void*) {
  if (severity == TVK_MESSAGE_ERROR) g_last_message = message;
}

// An orthographic world -> Vulkan clip matrix (column-major) framing a box: note the Y flip (+y down the
// framebuffer), which docs/integration.md, "The projection's Y flip", asks of every host.
void ortho(const double lo[3], const double hi[3], double out[16]) {
  std::fill(out, out + 16, 0.0);
  const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
  const double half = 0.55 * std::max(hi[0] - lo[0], hi[1] - lo[1]);
  out[0] = 1.0 / half;
  out[5] = -1.0 / half;  // the Y flip
  out[10] = -1.0 / (hi[2] - lo[2] + 2.0);
  out[12] = -cx / half;
  out[13] = cy / half;
  out[14] = (hi[2] + 1.0) / (hi[2] - lo[2] + 2.0);
  out[15] = 1.0;
}

}  // namespace

TEST_CASE("docs/integration.md: the walk-through runs under synchronization validation", "[plugin][integration]") {
  tressvk::engine::Device& dev = tressvk::test::device();
  REQUIRE(dev.sync_validation_enabled());

  // ---- 1. Before creating the device: the fixture's device merged these (tressvk::host::with_plugin_requirements).
  TvkDeviceRequirements req;
  tressvk_get_device_requirements(&req);
  CHECK(dev.api_version() >= req.min_api_version);

  // ---- 2. The context.
  REQUIRE(TVK_CHECK_VERSION() == TVK_SUCCESS);
  TvkContextCreateInfo info = {};
  info.struct_size = sizeof info;
  info.api_version = VK_API_VERSION_1_3;
  info.instance = dev.instance();
  info.physical_device = dev.physical_device();
  info.device = dev.device();
  info.queue_family_index = dev.queue_family();
  info.get_instance_proc_addr = vkGetInstanceProcAddr;
  info.frames_in_flight = 2;
  info.message_callback = on_message;
  info.enable_timestamps = VK_TRUE;
  TvkContext ctx = nullptr;
  REQUIRE(tressvk_create_context(&info, &ctx) == TVK_SUCCESS);

  // ---- 3. Assets: from a file, uploaded through the host's command buffer.
  tressvk::baker::BuiltinGroomOptions groom;
  groom.guide_count = 128;
  groom.follow_per_guide = 1;
  const tressvk::asset::HairAsset hair = tressvk::baker::make_builtin_groom("straight", groom);
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "tressvk_integration_test.tvkhair";
  {
    const std::vector<std::byte> bytes = tressvk::asset::write(hair);
    std::FILE* f = std::fopen(path.string().c_str(), "wb");
    REQUIRE(f != nullptr);
    REQUIRE(std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size());
    std::fclose(f);
  }
  TvkAsset asset = nullptr;
  tressvk::test::run_commands([&](VkCommandBuffer cmd) {
    TvkAssetLoadInfo load = {};
    load.struct_size = sizeof load;
    const std::string p = path.string();
    load.path = p.c_str();
    load.upload_command_buffer = cmd;
    REQUIRE(tressvk_load_asset(ctx, &load, &asset) == TVK_SUCCESS);
  });
  std::filesystem::remove(path);

  // ---- 4. Instances and parameters.
  TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
  TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
  TvkInstanceCreateInfo ci = {};
  ci.struct_size = sizeof ci;
  ci.asset = asset;
  ci.settings = &settings;
  ci.params = &params;
  TvkInstance head = nullptr;
  REQUIRE(tressvk_create_instance(ctx, &ci, &head) == TVK_SUCCESS);
  REQUIRE(tressvk_set_sim_params(head, TVK_ALL_GROUPS, &params) == TVK_SUCCESS);
  // What it runs: the rate and iterations the defaults leave to the model, resolved.
  TvkSimSettings runs;
  TvkSimParams group0;
  REQUIRE(tressvk_get_sim_settings(head, &runs) == TVK_SUCCESS);
  REQUIRE(tressvk_get_sim_params(head, 0, &group0) == TVK_SUCCESS);
  CHECK(runs.time.step_rate >= 30.0f);
  CHECK(runs.model != TVK_SIM_MODEL_DEFAULT);
  CHECK((group0.local_iterations >= 1u && group0.local_iterations <= TVK_MAX_ITERATIONS));

  // ---- 6 (creation). A renderer for the main pass and the shadow map, prewarmed.
  TvkRendererCreateInfo ri = {};
  ri.struct_size = sizeof ri;
  ri.shading.color_format = VK_FORMAT_R8G8B8A8_UNORM;
  ri.shading.depth_format = VK_FORMAT_D32_SFLOAT;
  ri.shading.samples = VK_SAMPLE_COUNT_1_BIT;
  ri.shading.render_pass = VK_NULL_HANDLE;
  ri.shading.subpass = 0;
  ri.shadow.depth_format = VK_FORMAT_D32_SFLOAT;
  TvkRenderer renderer = nullptr;
  REQUIRE(tressvk_create_renderer(ctx, &ri, &renderer) == TVK_SUCCESS);
  REQUIRE(tressvk_prewarm_renderer(renderer) == TVK_SUCCESS);

  // The host's targets: a main pass and a shadow map, with a non-comparison sampler.
  const auto target = tressvk::engine::create_offscreen_target(dev, 96, 96, VK_FORMAT_R8G8B8A8_UNORM);
  const auto shadow = tressvk::engine::create_offscreen_target(dev, 128, 128, VK_FORMAT_UNDEFINED);
  tressvk::engine::SamplerDesc nearest;
  nearest.filter = VK_FILTER_NEAREST;
  const auto sampler = tressvk::engine::create_sampler(dev, nearest);

  // A camera and a light framing the groom (identity transform: the groom is where it was baked).
  double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (size_t i = 0; i < hair.rest_positions.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], hair.origin[c] + hair.rest_positions[i][c]);
      hi[c] = std::max(hi[c], hair.origin[c] + hair.rest_positions[i][c]);
    }
  TvkView camera = {};
  ortho(lo, hi, camera.view_projection);
  camera.eye[0] = 0.5 * (lo[0] + hi[0]);
  camera.eye[1] = 0.5 * (lo[1] + hi[1]);
  camera.eye[2] = hi[2] + 1.0;
  camera.orthographic = 1;
  camera.direction[2] = -1.0f;
  camera.width = camera.height = 96;
  TvkView light = camera;
  light.width = light.height = 128;
  const TvkHairMaterial material = TVK_HAIR_MATERIAL_DEFAULT_INIT;
  TvkLight key = {};
  key.type = TVK_LIGHT_DIRECTIONAL;
  key.color[0] = key.color[1] = key.color[2] = 1.0f;
  key.intensity = 3.0f;
  key.direction[2] = -1.0f;
  key.shadowed = 1;

  // ---- 5. Every frame (and 6: the shadow pass, the host's barrier, the main pass).
  uint32_t lit_pixels = 0;
  for (uint32_t n = 0; n < 4; ++n) {
    TvkSimFrame frame = TVK_SIM_FRAME_DEFAULT_INIT;
    frame.dt = 1.0f / 60.0f;
    frame.transform.translation[0] = 0.01 * n;  // the head moves a little
    frame.capsule_count = 2;
    frame.capsules[0] = TvkCapsule{{0, 1.60f, 0}, 0.09f, {0, 1.75f, 0}, 0.09f};
    frame.capsules[1] = TvkCapsule{{0, 1.45f, 0}, 0.06f, {0, 1.58f, 0}, 0.06f};
    frame.wind.strength = 1.0f;
    frame.wind.direction[0] = 1.0f;
    frame.teleport = 0;
    if (n == 0) REQUIRE(tressvk_prewarm_instance(head, &frame) == TVK_SUCCESS);
    REQUIRE(tressvk_set_frame(head, &frame) == TVK_SUCCESS);
    // The main pass's draw, shadowed by the map the shadow pass below fills.
    TvkShadowMap map = {};
    map.depth_view = shadow.depth.view();
    map.sampler = sampler;
    map.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    std::copy(std::begin(light.view_projection), std::end(light.view_projection), map.view_projection);
    map.near_plane = 0.0f;
    map.far_plane = static_cast<float>(hi[2] - lo[2] + 2.0);
    TvkDrawInfo hd = {};
    hd.struct_size = sizeof hd;
    hd.instance = head;
    hd.view = &camera;
    hd.materials = &material;
    hd.material_count = 1;
    hd.light_count = 1;
    hd.lights = &key;
    hd.ambient[0] = hd.ambient[1] = hd.ambient[2] = 0.17f;
    hd.shadow = &map;
    // With LOD, follow hairs only for the strands that draw takes (here without LOD: every strand).
    uint32_t drawn = 0;
    REQUIRE(tressvk_get_draw_strands(renderer, &hd, &drawn) == TVK_SUCCESS);
    REQUIRE(tressvk_set_draw_strands(head, drawn) == TVK_SUCCESS);
    REQUIRE(tressvk_new_frame(ctx) == TVK_SUCCESS);

    tressvk::test::run_commands([&](VkCommandBuffer cmd) {
      TvkSimulateInfo sim = {};
      sim.struct_size = sizeof sim;
      sim.instance_count = 1;
      sim.instances = &head;
      REQUIRE(tressvk_cmd_simulate(ctx, cmd, &sim) == TVK_SUCCESS);

      // The host's shadow pass: the hair draws into the same shadow map as its meshes would.
      tressvk::engine::cmd_begin_rendering(cmd, shadow, {});
      TvkDrawInfo sd = {};
      sd.struct_size = sizeof sd;
      sd.instance = head;
      sd.view = &light;
      sd.lod_view = &camera;
      sd.materials = &material;
      sd.material_count = 1;
      REQUIRE(tressvk_cmd_draw_shadow(renderer, cmd, &sd) == TVK_SUCCESS);
      tressvk::engine::cmd_end_rendering(cmd);
      // The host's barrier: shadow map from depth writes to fragment-shader sampling.
      tressvk::engine::cmd_image_barrier(cmd, shadow.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT,
                                         tressvk::engine::state::kDepthAttachment,
                                         tressvk::engine::state::kFragmentSampled);

      // The main pass.
      tressvk::engine::cmd_begin_rendering(cmd, target, {});
      REQUIRE(tressvk_cmd_draw_hair(renderer, cmd, &hd) == TVK_SUCCESS);
      tressvk::engine::cmd_end_rendering(cmd);
    });
    const char* names[16];
    const uint32_t passes = tressvk_get_recorded_passes(ctx, names, 16);
    // The fused frame kernel (the default) records one pass per frame; TRESSVK_SIM_PATH=passes one per pass.
    CHECK(passes >= 1);
    CHECK(tressvk_get_recorded_dispatches(ctx) >= passes);  // every pass dispatched at least once
    bool collision = false;
    for (uint32_t i = 0; i < passes && i < 16; ++i)
      collision |= std::string(names[i]).find("+collision") != std::string::npos;
    CHECK(collision);  // the capsules compiled the collision term in
    if (n == 3) {
      const tressvk::engine::Pixels px =
          tressvk::engine::read_image(dev, target.color, tressvk::engine::state::kColorAttachment);
      for (uint32_t y = 0; y < px.height; ++y)
        for (uint32_t x = 0; x < px.width; ++x)
          if (px.rgba8(x, y)[0] > 0 || px.rgba8(x, y)[1] > 0 || px.rgba8(x, y)[2] > 0) ++lit_pixels;
    }
  }
  INFO("hair pixels: " << lit_pixels);
  CHECK(lit_pixels > 50);

  // Pass timings of the last frame: readable once the GPU is done and frames_in_flight more promises are made
  // (until then they are those of the frame frames_in_flight back).
  dev.wait_idle();
  for (uint32_t i = 0; i < info.frames_in_flight; ++i) REQUIRE(tressvk_new_frame(ctx) == TVK_SUCCESS);
  std::vector<TvkPassTiming> timings(16);
  const uint32_t timed = tressvk_get_pass_timings(ctx, timings.data(), 16);
  INFO("timed passes: " << timed << " (0 when the queue has no timestamps)");
  CHECK((timed > 0 || dev.timestamp_valid_bits() == 0));

  // ---- Destruction: after the GPU is done with everything.
  dev.wait_idle();
  tressvk_destroy_renderer(renderer);
  tressvk_destroy_instance(head);
  tressvk_destroy_asset(asset);
  tressvk_destroy_context(ctx);
  CHECK(g_last_message.empty());
}
