#include "scene_renderer.hpp"

#include "tressvk_demo_spirv.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tressvk::demo {

namespace {

// std140 SceneConstants of shaders/render/scene/scene_layout.glsl.
struct SceneConstants {
  float view_proj[16];
  float shadow_proj[16];
  float eye[4];
  float ambient[4];
  float shadow_info[4];
  float light_pos[4][4];
  float light_dir[4][4];
  float light_color[4][4];
  float light_cone[4][4];
  uint32_t counts[4];
};

void store(const glm::dmat4& m, float (&out)[16]) {
  const glm::mat4 f(m);
  std::memcpy(out, glm::value_ptr(f), sizeof(out));
}

engine::Buffer vertex_buffer(engine::Device& device, const engine::Mesh& mesh) {
  std::vector<engine::MeshVertex> v = mesh.vertices;
  if (v.empty()) v.push_back(engine::MeshVertex{});  // a bindable buffer for an empty mesh
  return engine::create_buffer_with_data(device, std::span<const engine::MeshVertex>(v),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

}  // namespace

SceneRenderer::SceneRenderer(engine::Device& device, VkFormat color_format, VkFormat depth_format,
                             uint32_t shadow_size, uint32_t frames_in_flight, const engine::Mesh& head,
                             const engine::Mesh& floor, VkRenderPass render_pass)
    : device_(device),
      shadow_(engine::create_offscreen_target(device, shadow_size, shadow_size, VK_FORMAT_UNDEFINED, kShadowFormat)) {
  engine::SamplerDesc cmp;
  cmp.filter = VK_FILTER_LINEAR;
  cmp.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  cmp.compare = true;
  compare_sampler_ = engine::create_sampler(device, cmp);
  engine::SamplerDesc raw;
  raw.filter = VK_FILTER_NEAREST;
  raw_sampler_ = engine::create_sampler(device, raw);

  const VkShaderStageFlags vs = VK_SHADER_STAGE_VERTEX_BIT, fs = VK_SHADER_STAGE_FRAGMENT_BIT;
  layout_ = engine::create_set_layout(device, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, vs | fs},
                                               {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, vs},
                                               {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs}});
  shadow_layout_ = engine::create_set_layout(device, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, vs | fs},
                                                      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, vs}});
  engine::GraphicsPipelineDesc desc;
  desc.vertex_spirv = k_spv_mesh_vert;
  desc.fragment_spirv = k_spv_mesh_frag;
  desc.layout.set_layouts = {layout_.get()};
  desc.layout.push_constant_size = sizeof(Push);
  desc.color_formats = {color_format};
  desc.depth_format = depth_format;
  desc.render_pass = render_pass;
  desc.cull_mode = VK_CULL_MODE_BACK_BIT;
  desc.debug_name = "demo mesh";
  mesh_ = engine::create_graphics_pipeline(device, desc);
  engine::GraphicsPipelineDesc sdesc;
  sdesc.vertex_spirv = k_spv_mesh_shadow_vert;
  sdesc.layout.set_layouts = {shadow_layout_.get()};
  sdesc.layout.push_constant_size = sizeof(Push);
  sdesc.depth_format = kShadowFormat;
  sdesc.cull_mode = VK_CULL_MODE_NONE;
  sdesc.debug_name = "demo mesh shadow";
  mesh_shadow_ = engine::create_graphics_pipeline(device, sdesc);

  head_vertices_ = vertex_buffer(device, head);
  floor_vertices_ = vertex_buffer(device, floor);
  head_count_ = static_cast<uint32_t>(head.vertices.size());
  floor_count_ = static_cast<uint32_t>(floor.vertices.size());

  pool_ = engine::DescriptorPool(device, 3 * frames_in_flight);
  for (uint32_t s = 0; s < frames_in_flight; ++s) {
    constants_.push_back(engine::create_buffer(device, sizeof(SceneConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                               engine::MemoryUsage::upload));
    std::array<VkDescriptorSet, 3> sets{pool_.allocate(layout_.get()), pool_.allocate(layout_.get()),
                                        pool_.allocate(shadow_layout_.get())};
    const VkBuffer vb[3] = {head_vertices_.handle(), floor_vertices_.handle(), head_vertices_.handle()};
    for (int i = 0; i < 3; ++i) {
      engine::write_buffer_descriptor(device, sets[i], 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, constants_[s].handle());
      engine::write_buffer_descriptor(device, sets[i], 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, vb[i]);
      if (i < 2)
        engine::write_image_descriptor(device, sets[i], 2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                       shadow_.depth.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                       compare_sampler_.get());
    }
    sets_.push_back(sets);
  }
}

void SceneRenderer::update(uint32_t slot, const SceneFrame& frame) {
  SceneConstants c{};
  const glm::dmat4 from_eye = glm::translate(glm::dmat4(1.0), frame.eye);  // eye-relative -> world
  store(frame.view_proj * from_eye, c.view_proj);
  store(frame.shadow_proj * from_eye, c.shadow_proj);
  for (int i = 0; i < 3; ++i) c.ambient[i] = frame.ambient[i];  // c.eye stays 0: the eye is the origin
  c.shadow_info[0] = frame.shadows ? 1.0f : 0.0f;
  c.shadow_info[1] = 1.5f / static_cast<float>(shadow_.extent().width);  // ~1.5 texels of depth (ortho, unit box)
  const uint32_t n = std::min<uint32_t>(4, static_cast<uint32_t>(frame.lights.size()));
  for (uint32_t i = 0; i < n; ++i) {
    const TvkLight& l = frame.lights[i];
    const glm::vec3 d = glm::normalize(glm::vec3(l.direction[0], l.direction[1], l.direction[2]));
    for (int k = 0; k < 3; ++k) {
      c.light_pos[i][k] = static_cast<float>(l.position[k] - frame.eye[k]);
      c.light_dir[i][k] = d[k];
      c.light_color[i][k] = l.color[k] * l.intensity;
    }
    c.light_pos[i][3] = l.type == TVK_LIGHT_SPOT ? 1.0f : 0.0f;
    c.light_dir[i][3] = l.range;
    c.light_color[i][3] = (l.shadowed && frame.shadows) ? 1.0f : 0.0f;
    c.light_cone[i][0] = std::cos(l.inner_cone);
    c.light_cone[i][1] = std::cos(std::max(l.outer_cone, l.inner_cone + 1e-4f));
  }
  c.counts[0] = n;
  std::memcpy(constants_[slot].mapped(), &c, sizeof(c));
  vmaFlushAllocation(constants_[slot].allocator(), constants_[slot].allocation(), 0, sizeof(c));
}

void SceneRenderer::draw_mesh(VkCommandBuffer cmd, const engine::Pipeline& p, VkDescriptorSet set,
                              const glm::dmat4& model, const glm::vec4& color, uint32_t vertices) const {
  if (vertices == 0) return;
  Push push{};
  store(model, push.model);
  for (int i = 0; i < 4; ++i) push.color[i] = color[i];
  p.cmd_bind(cmd);
  p.cmd_bind_set(cmd, 0, set);
  p.cmd_push(cmd, push);
  vkCmdDraw(cmd, vertices, 1, 0, 0);
}

void SceneRenderer::cmd_draw_shadow(VkCommandBuffer cmd, uint32_t slot, const SceneFrame& frame) const {
  const glm::dmat4 to_eye = glm::translate(glm::dmat4(1.0), -frame.eye);
  draw_mesh(cmd, mesh_shadow_, sets_[slot][2], to_eye * frame.head_model, glm::vec4(0.0f), head_count_);
}

void SceneRenderer::cmd_draw(VkCommandBuffer cmd, uint32_t slot, const SceneFrame& frame) const {
  const glm::dmat4 to_eye = glm::translate(glm::dmat4(1.0), -frame.eye);
  draw_mesh(cmd, mesh_, sets_[slot][0], to_eye * frame.head_model, glm::vec4(frame.head_color, 0.1f), head_count_);
  draw_mesh(cmd, mesh_, sets_[slot][1], to_eye * frame.floor_model, glm::vec4(0.16f, 0.165f, 0.18f, 0.02f),
            floor_count_);
}

}  // namespace tressvk::demo
