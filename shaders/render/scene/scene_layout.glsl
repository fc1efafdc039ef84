// The demo scene's mesh passes (host engine code, not the plugin): per-frame scene constants, mesh vertices from
// a storage buffer (position, normal interleaved), per-draw push constants. Matches SceneConstants in
// engine/apps/demo/scene_renderer.cpp.
layout(std140, set = 0, binding = 0) uniform SceneConstants {
  mat4 view_proj;
  mat4 shadow_proj;
  vec4 eye;           // xyz world
  vec4 ambient;       // rgb
  vec4 shadow_info;   // x: 1 = shadow map bound and used
  vec4 light_pos[4];  // xyz world (spot); w: type (0 directional, 1 spot)
  vec4 light_dir[4];  // xyz unit direction of travel; w: range
  vec4 light_color[4];// rgb * intensity; w: shadowed
  vec4 light_cone[4]; // x: cos inner, y: cos outer
  uvec4 counts;       // x: lights
} scene;

layout(std430, set = 0, binding = 1) readonly buffer Vertices { vec4 vertex_data[]; };

layout(push_constant) uniform Push {
  mat4 model;
  vec4 color;         // rgb albedo; w: roughness-like highlight weight
} pc;
