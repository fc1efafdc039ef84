// The host engine's own scene passes: the shadow map (a D32 depth target that the meshes AND the hair draw into),
// and the lit meshes (head, floor) in the main pass. Per frame slot a constant buffer and descriptor sets.
#pragma once

#include <tressvk/engine/buffer.hpp>
#include <tressvk/engine/descriptors.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/engine/image.hpp>
#include <tressvk/engine/mesh.hpp>
#include <tressvk/engine/pipeline.hpp>
#include <tressvk/tressvk.h>

#include <glm/glm.hpp>

#include <vector>

namespace tressvk::demo {

// What a frame's scene passes need, in world space and double. The meshes are drawn camera-relative: matrices,
// model transforms and light positions are made relative to the eye in double before they become float, so the
// scene renders the same 10 km from the world origin (the hair gets its matrices in double through TvkView).
struct SceneFrame {
  glm::dmat4 view_proj{1.0};
  glm::dmat4 shadow_proj{1.0};
  glm::dvec3 eye{0.0};
  glm::dmat4 head_model{1.0};   // the instance's rigid transform
  glm::dmat4 floor_model{1.0};  // the floor's placement (the scene's world offset)
  std::vector<TvkLight> lights;
  glm::vec3 ambient{0.0f};
  bool shadows = true;
  glm::vec3 head_color{0.45f, 0.32f, 0.26f};  // the head mesh's albedo (skin)
};

class SceneRenderer {
 public:
  static constexpr VkFormat kShadowFormat = VK_FORMAT_D32_SFLOAT;

  SceneRenderer(engine::Device& device, VkFormat color_format, VkFormat depth_format, uint32_t shadow_size,
                uint32_t frames_in_flight, const engine::Mesh& head, const engine::Mesh& floor,
                VkRenderPass render_pass = VK_NULL_HANDLE);  // main pass: dynamic rendering or this render pass

  const engine::OffscreenTarget& shadow_target() const { return shadow_; }
  VkSampler hair_shadow_sampler() const { return raw_sampler_.get(); }  // non-comparison (fibre counting)

  // Writes this slot's constants (call before recording the slot's passes).
  void update(uint32_t slot, const SceneFrame& frame);
  // Inside the shadow pass (depth-only dynamic rendering on shadow_target()).
  void cmd_draw_shadow(VkCommandBuffer cmd, uint32_t slot, const SceneFrame& frame) const;
  // Inside the main pass.
  void cmd_draw(VkCommandBuffer cmd, uint32_t slot, const SceneFrame& frame) const;

 private:
  struct Push {
    float model[16];
    float color[4];
  };
  void draw_mesh(VkCommandBuffer cmd, const engine::Pipeline& p, VkDescriptorSet set, const glm::dmat4& model,
                 const glm::vec4& color, uint32_t vertices) const;

  engine::Device& device_;
  engine::OffscreenTarget shadow_;
  engine::DeviceHandle<VkSampler> compare_sampler_, raw_sampler_;
  engine::DeviceHandle<VkDescriptorSetLayout> layout_, shadow_layout_;
  engine::Pipeline mesh_, mesh_shadow_;
  engine::DescriptorPool pool_;
  engine::Buffer head_vertices_, floor_vertices_;
  uint32_t head_count_ = 0, floor_count_ = 0;
  std::vector<engine::Buffer> constants_;  // per slot
  // per slot: [head main, floor main, head shadow]
  std::vector<std::array<VkDescriptorSet, 3>> sets_;
};

}  // namespace tressvk::demo
