// The per-draw constant block of the hair passes, laid out as std140 DrawConstants in
// shaders/render/hair_layout.glsl (every member a vec4 or mat4, so std140 adds no padding).
#pragma once

#include <tressvk/model/gpu_layout.h>
#include <tressvk/render.h>

#include <array>
#include <cstdint>

namespace tressvk::render {

struct alignas(16) GpuLight {
  float position[4];   // xyz relative to the instance origin; w: type
  float direction[4];  // xyz unit; w: range
  float color[4];      // rgb * intensity; w: shadowed
  float cone[4];       // x: cos inner, y: cos outer
};

struct alignas(16) GpuMaterial {
  float base[4];   // rgb, kd
  float tip[4];    // rgb, ks1
  float spec[4];   // ex1, ks2, ex2, shift1
  float shape[4];  // shift2, width, tip ratio, opacity
  float fiber[4];  // spacing, alpha, colour variation
};

struct alignas(16) DrawConstants {
  float view_proj[16];
  float shadow_proj[16];
  float eye[4];
  float view_dir[4];
  float viewport[4];
  uint32_t counts[4];  // N, guides, strands drawn, lights
  float lod[4];        // width scale, margin px, minimum half width px
  float shadow_params[4];
  float ambient[4];
  GpuLight lights[TVK_MAX_LIGHTS];
  GpuMaterial materials[TVK_MAX_MATERIALS];
};
static_assert(TVK_DRAW_MAX_LIGHTS == TVK_MAX_LIGHTS && TVK_DRAW_MAX_MATERIALS == TVK_MAX_MATERIALS);
static_assert(sizeof(GpuLight) == 64 && sizeof(GpuMaterial) == 80);
static_assert(sizeof(DrawConstants) == 2 * 64 + 7 * 16 + TVK_MAX_LIGHTS * 64 + TVK_MAX_MATERIALS * 80);

}  // namespace tressvk::render
