// Pipeline building, in one place for every room: shader modules from embedded SPIR-V, compute pipelines with
// uint32 specialisation constants, and the graphics pipelines drawn into the host's target (dynamic rendering
// formats or its VkRenderPass), all through the host's VkPipelineCache (TvkContextCreateInfo::pipeline_cache).
// Failures are recorded on the context with the `what` label and returned.
#pragma once

#include "core/context.hpp"

#include <tressvk/render.h>

#include <cstddef>
#include <cstdint>
#include <span>

namespace tressvk {

struct ShaderCode {
  const uint32_t* code = nullptr;  // nullptr: no shader (a depth-only pass has no fragment stage)
  size_t bytes = 0;
};
template <size_t N>
ShaderCode spirv(const uint32_t (&code)[N]) {
  return {code, sizeof(code)};
}

TvkResult create_shader_module(Context& ctx, ShaderCode code, const char* what, VkShaderModule& out);

// Specialisation constant i (0, 1, ...) is spec[i].
TvkResult create_compute_pipeline(Context& ctx, VkPipelineLayout layout, ShaderCode code,
                                  std::span<const uint32_t> spec, const char* what, VkPipeline& out);

// A triangle-list pipeline without vertex input, viewport and scissor dynamic, no culling.
struct GraphicsPipelineDesc {
  ShaderCode vertex;
  ShaderCode fragment;                     // none: depth only, no colour attachment
  std::span<const uint32_t> fragment_spec; // the fragment stage's specialisation constants
  const TvkRenderTarget* target = nullptr; // formats, samples, or the render pass and subpass
  VkPipelineLayout layout = VK_NULL_HANDLE;
  bool depth_test = false;                 // LESS_OR_EQUAL
  bool depth_write = false;
  bool premultiplied_over = false;         // blend: src + (1 - src.a) * dst
};
TvkResult create_graphics_pipeline(Context& ctx, const GraphicsPipelineDesc& desc, const char* module_what,
                                   const char* what, VkPipeline& out);

}  // namespace tressvk
