#include "demo_renderer.hpp"

#include <tressvk/engine/shaders.hpp>
#include <tressvk/engine/sync.hpp>

#include <cmath>

namespace tressvk::demo {

namespace {
constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;  // shaders write linear colour; PNG gets sRGB
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

DemoRenderer::DemoRenderer(engine::Device& device, uint32_t width, uint32_t height)
    : device_(device),
      target_(engine::create_offscreen_target(device, width, height, kColorFormat, kDepthFormat)),
      timestamps_(device, 2) {
  engine::GraphicsPipelineDesc desc;
  desc.vertex_spirv = engine::shaders::triangle_vert();
  desc.fragment_spirv = engine::shaders::triangle_frag();
  desc.layout.push_constant_size = sizeof(engine::shaders::TrianglePush);
  desc.color_formats = {kColorFormat};
  desc.depth_format = kDepthFormat;
  desc.debug_name = "demo triangle";
  triangle_ = engine::create_graphics_pipeline(device, desc);
}

FrameResult DemoRenderer::render(uint32_t frame_index) {
  // The triangle turns a little each frame so that a multi-frame run shows motion.
  engine::shaders::TrianglePush push{};
  const double turn = 0.1 * frame_index;
  const float aspect = static_cast<float>(target_.extent().height) / static_cast<float>(target_.extent().width);
  const float colors[3][4] = {{0.9f, 0.35f, 0.1f, 1.0f}, {0.25f, 0.8f, 0.3f, 1.0f}, {0.2f, 0.35f, 0.95f, 1.0f}};
  for (int i = 0; i < 3; ++i) {
    const double a = turn + kPi / 2 + 2 * kPi * i / 3;
    push.position[i][0] = static_cast<float>(0.7 * std::cos(a)) * aspect;
    push.position[i][1] = static_cast<float>(-0.7 * std::sin(a));  // Vulkan clip space: +y is down
    push.position[i][2] = 0.5f;
    push.position[i][3] = 1.0f;
    for (int c = 0; c < 4; ++c) push.color[i][c] = colors[i][c];
  }

  device_.run_commands([&](VkCommandBuffer cmd) {
    timestamps_.cmd_reset(cmd);
    timestamps_.cmd_write(cmd, 0, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
    engine::ClearValues clear;
    clear.color = {0.06f, 0.07f, 0.09f, 1.0f};
    engine::cmd_begin_rendering(cmd, target_, clear);
    triangle_.cmd_bind(cmd);
    triangle_.cmd_push(cmd, push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    engine::cmd_end_rendering(cmd);
    timestamps_.cmd_write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
  });
  FrameResult result;
  result.gpu_ms = timestamps_.elapsed_ms(0, 1);
  result.pixels = engine::read_image(device_, target_.color, engine::state::kColorAttachment);
  return result;
}

}  // namespace tressvk::demo
