// Shared by the hair shadow and shading passes: the per-draw constants (one block of the renderer's ring) and the
// simulation's storage buffers. Must match DrawConstants in plugin/src/render/constants.hpp.
#extension GL_EXT_control_flow_attributes : enable

#include "tressvk/model/gpu_layout.h"  // bindings and limits, shared with C++

struct Light {
  vec4 position;   // xyz: relative to the instance origin (spot); w: type (0 directional, 1 spot)
  vec4 direction;  // xyz: unit direction the light travels; w: range (m, 0 = none)
  vec4 color;      // rgb: colour * intensity; w: 1 = shadowed
  vec4 cone;       // x: cos(inner), y: cos(outer)
};

struct Material {
  vec4 base;       // rgb root colour, w: kd
  vec4 tip;        // rgb tip colour, w: ks1
  vec4 spec;       // x: ex1, y: ks2, z: ex2, w: shift1
  vec4 shape;      // x: shift2, y: strand width (m), z: tip width ratio, w: opacity
  vec4 fiber;      // x: fibre spacing (strand widths), y: fibre alpha, z: colour variation
};

layout(std140, set = 0, binding = TVK_DRAW_BINDING_CONSTANTS) uniform DrawConstants {
  mat4 view_proj;      // simulation space -> clip (camera, or the light for the shadow pass)
  mat4 shadow_proj;    // simulation space -> light clip (shading pass, shadowed)
  vec4 eye;            // xyz: eye relative to the origin; w: 1 = orthographic view
  vec4 view_dir;       // xyz: unit view direction (orthographic)
  vec4 viewport;       // x: width, y: height (pixels)
  uvec4 counts;        // x: vertices per strand, y: guides, z: strands drawn, w: lights
  vec4 lod;            // x: width scale (LOD), y: margin in pixels around the strand, z: minimum half width (px)
  vec4 shadow_params;  // x: near, y: far (m), z: 1 = perspective light, w: unused
  vec4 ambient;        // rgb
  Light lights[TVK_DRAW_MAX_LIGHTS];
  Material materials[TVK_DRAW_MAX_MATERIALS];
} dc;

layout(std430, set = 0, binding = TVK_DRAW_BINDING_POSITIONS) readonly buffer Positions { vec4 positions[]; };  // offsets from the anchors
layout(std430, set = 0, binding = TVK_DRAW_BINDING_TANGENTS) readonly buffer Tangents { vec4 tangents[]; };
layout(std430, set = 0, binding = TVK_DRAW_BINDING_GUIDE_INFO) readonly buffer GuideInfo { uvec4 guide_info[]; };  // x: strand group
layout(std430, set = 0, binding = TVK_DRAW_BINDING_ANCHORS) readonly buffer Anchors { vec4 anchors[]; };  // per guide, simulation space
