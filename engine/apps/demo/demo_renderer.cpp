#include "demo_renderer.hpp"

#include <tressvk/engine/shaders.hpp>
#include <tressvk/engine/sync.hpp>
#include <tressvk/engine/timestamps.hpp>

#include <cmath>

namespace tressvk::demo {

namespace {
constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;  // shaders write linear colour; PNG gets sRGB
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr double kPi = 3.14159265358979323846;

// Where the previous frame left the shared target. Old contents are discarded (layout UNDEFINED, every frame
// clears), but the execution dependency on the previous frame's last use stays: its readback copy for colour,
// its depth writes for depth.
constexpr engine::ResourceState kColorAfterReadback{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                                                    VK_IMAGE_LAYOUT_UNDEFINED};
constexpr engine::ResourceState kDepthAfterFrame{VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                                                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                                                 VK_IMAGE_LAYOUT_UNDEFINED};
}  // namespace

DemoRenderer::DemoRenderer(engine::Device& device, uint32_t width, uint32_t height, uint32_t frames_in_flight)
    : device_(device), target_(engine::create_offscreen_target(device, width, height, kColorFormat, kDepthFormat)) {
  engine::GraphicsPipelineDesc desc;
  desc.vertex_spirv = engine::shaders::triangle_vert();
  desc.fragment_spirv = engine::shaders::triangle_frag();
  desc.layout.push_constant_size = sizeof(engine::shaders::TrianglePush);
  desc.color_formats = {kColorFormat};
  desc.depth_format = kDepthFormat;
  desc.debug_name = "demo triangle";
  triangle_ = engine::create_graphics_pipeline(device, desc);
  const VkDeviceSize bytes = VkDeviceSize{4} * width * height;
  for (uint32_t i = 0; i < frames_in_flight; ++i)
    readback_.push_back(engine::create_buffer(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                              engine::MemoryUsage::readback));
}

void DemoRenderer::record(const engine::FrameLoop::Frame& frame) {
  // The triangle turns a little each frame so that a multi-frame run shows motion.
  engine::shaders::TrianglePush push{};
  const double turn = 0.1 * static_cast<double>(frame.number);
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

  const VkCommandBuffer cmd = frame.cmd;
  frame.timestamps->cmd_write(cmd, 0, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
  engine::ClearValues clear;
  clear.color = {0.06f, 0.07f, 0.09f, 1.0f};
  engine::cmd_begin_rendering(cmd, target_, clear, kColorAfterReadback, kDepthAfterFrame);
  triangle_.cmd_bind(cmd);
  triangle_.cmd_push(cmd, push);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  engine::cmd_end_rendering(cmd);
  frame.timestamps->cmd_write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
  engine::cmd_readback_image(cmd, target_.color, engine::state::kColorAttachment, readback_[frame.slot]);
}

FrameResult DemoRenderer::result(const engine::FrameLoop::Frame& frame) const {
  FrameResult out;
  out.gpu_ms = frame.timestamps->elapsed_ms(0, 1);
  out.pixels = engine::pixels_from_buffer(readback_[frame.slot], target_.color);
  return out;
}

}  // namespace tressvk::demo
