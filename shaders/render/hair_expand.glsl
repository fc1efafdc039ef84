// Vertex-shader quad expansion. Every strand segment is a quad of two triangles (6 vertices, no vertex or index
// buffer): vertex id -> (strand, segment, corner). Corners sit on the hair vertices, so neighbouring segments
// share their edge exactly (no cracks at bends). The quad is perpendicular to the strand IN SCREEN SPACE, as wide
// as the strand's projected width plus a margin, so a strand thinner than a pixel still covers the pixels it
// touches and the fragment shader turns its true width into coverage.
invariant gl_Position;

struct Expanded {
  vec3 position;      // simulation space
  vec3 tangent;
  float offset_px;    // signed distance of this corner from the centre line, pixels
  float width_px;     // projected strand width, pixels
  float along;        // 0 at the root, 1 at the tip
  uint group;
  float tint;         // per-strand colour factor (colour variation)
};

#include "render/strand_hash.glsl"
#include "render/strand_layout.glsl"

Expanded expand_vertex(uint vertex_id) {
  const uint kEnd[6] = uint[6](0u, 0u, 1u, 1u, 0u, 1u);
  const float kSide[6] = float[6](-1.0, 1.0, -1.0, -1.0, 1.0, 1.0);
  const uint n = dc.counts.x;
  const uint corner = vertex_id % 6u;
  const uint segment = vertex_id / 6u;
  const uint strand = segment / (n - 1u);
  const uint v = segment % (n - 1u) + kEnd[corner];
  const uint g = strand % dc.counts.y;  // its guide

  Expanded e;
  e.position = anchors[g].xyz + positions[strand_element(strand, v, n)].xyz;
  e.tangent = tangents[strand_element(g, v, n)].xyz;
  e.along = float(v) / float(n - 1u);
  e.group = min(guide_info[g].x, 15u);
  const Material m = dc.materials[e.group];
  e.tint = 1.0 + m.fiber.z * (2.0 * strand_hash(strand) - 1.0);
  const float width = m.shape.y * mix(1.0, m.shape.z, e.along) * dc.lod.x;

  const vec4 clip = dc.view_proj * vec4(e.position, 1.0);
  const vec2 half_viewport = 0.5 * dc.viewport.xy;
  const float w = max(abs(clip.w), 1e-6);
  // Screen-space derivative of the projection along a world direction d (pixels per metre of d).
  const vec4 ct = dc.view_proj * vec4(e.tangent, 0.0);
  vec2 screen_t = (ct.xy * w - clip.xy * ct.w) / (w * w) * half_viewport;
  const vec3 to_eye = dc.eye.w > 0.5 ? -dc.view_dir.xyz : dc.eye.xyz - e.position;
  vec3 right = cross(e.tangent, to_eye);
  const float right_len = length(right);
  right = right_len > 1e-12 ? right / right_len : vec3(0.0);
  const vec4 cr = dc.view_proj * vec4(right, 0.0);
  const vec2 screen_r = (cr.xy * w - clip.xy * cr.w) / (w * w) * half_viewport;
  e.width_px = width * length(screen_r);

  const float t_len = length(screen_t);
  // A strand pointing at the camera has no screen direction: any perpendicular will do.
  const vec2 dir = t_len > 1e-6 ? screen_t / t_len : vec2(1.0, 0.0);
  const vec2 perp = vec2(-dir.y, dir.x);
  const float half_px = max(0.5 * e.width_px, dc.lod.z) + dc.lod.y;
  e.offset_px = kSide[corner] * half_px;
  gl_Position = clip + vec4(perp * e.offset_px / half_viewport * w, 0.0, 0.0);
  return e;
}
