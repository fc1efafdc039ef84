/* TressVK rendering: hair shadow and shading passes recorded inside the host's own passes.
 *
 * Included by tressvk.h. A TvkRenderer draws instances (their simulated `positions` and `tangents` storage
 * buffers) as camera-facing quads expanded in the vertex shader; there are no vertex or index buffers. One
 * renderer serves one shading target description and one shadow-map description; its pipelines are built on
 * first use. docs/rendering.md explains the shading model, LOD and the transparency choice; docs/integration.md
 * the frame and the synchronization contract.
 *
 * Synchronization contract of both recording calls:
 * - They are recorded INSIDE a render pass instance the host began (dynamic rendering or the VkRenderPass and
 *   subpass given at creation) and record no barrier, no query and no pass begin/end.
 * - Positions and tangents are read by the VERTEX_SHADER stage (storage reads): tressvk_cmd_simulate's exit
 *   barrier already makes them visible there. A host that writes them otherwise orders its writes itself.
 * - tressvk_cmd_draw_hair samples the shadow map in the FRAGMENT_SHADER stage: the host transitions it from its
 *   depth-attachment writes to `shadow.layout` (e.g. DEPTH_READ_ONLY_OPTIMAL or SHADER_READ_ONLY_OPTIMAL) with
 *   a FRAGMENT_SHADER / SHADER_SAMPLED_READ barrier before beginning the shading pass.
 * - Per-call constants live in a host-visible ring of frames_in_flight slices inside the renderer; the slice of
 *   frame F is reused at frame F + frames_in_flight, on the promise tressvk_new_frame stands for.
 * State disturbed: the bound graphics pipeline and graphics descriptor set 0 (no push constants); viewport,
 * scissor and depth bias are NOT set (the host's viewport and scissor are used as they are).
 */
#ifndef TRESSVK_RENDER_H
#define TRESSVK_RENDER_H

#include "tressvk/tressvk.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TVK_MAX_LIGHTS 8
#define TVK_MAX_MATERIALS 16  /* strand groups with their own material; later groups use the last one */

typedef struct TvkRenderer_T* TvkRenderer;

/* Where a pipeline draws. render_pass == VK_NULL_HANDLE: dynamic rendering with the formats below. Otherwise the
 * pipeline is built for that render pass and subpass (the formats must still describe its attachments). */
typedef struct TvkRenderTarget {
  VkFormat color_format;              /* shading target: one colour attachment; UNDEFINED for the shadow target */
  VkFormat depth_format;              /* required (hair is depth tested) */
  VkSampleCountFlagBits samples;      /* 0 means 1 */
  VkRenderPass render_pass;
  uint32_t subpass;
} TvkRenderTarget;

typedef struct TvkRendererCreateInfo {
  size_t struct_size;                 /* sizeof(TvkRendererCreateInfo) */
  const void* next;
  TvkRenderTarget shading;            /* target of tressvk_cmd_draw_hair */
  TvkRenderTarget shadow;             /* target of tressvk_cmd_draw_shadow (depth only); depth_format UNDEFINED:
                                         no shadow pass */
  uint32_t max_draws_per_frame;       /* shadow + shading calls per frame; 0 means 64 */
} TvkRendererCreateInfo;

/* Per strand group. Colours are linear RGB. TVK_HAIR_MATERIAL_DEFAULT_INIT lists the defaults. */
typedef struct TvkHairMaterial {
  float base_color[3];                /* at the root */
  float tip_color[3];                 /* at the tip; blended in linearly along the strand */
  float kd;                           /* Kajiya-Kay diffuse weight */
  float ks1, ex1;                     /* primary highlight (light-coloured): weight, exponent */
  float ks2, ex2;                     /* secondary highlight (tinted by the hair colour): weight, exponent */
  float shift1, shift2;               /* radians added to the tangent-light angle of each highlight (cuticle tilt:
                                         primary toward the root, secondary toward the tip) */
  float strand_width;                 /* m, at the root */
  float tip_width_ratio;              /* width at the tip / width at the root (thin tips), 0..1 */
  float opacity;                      /* 0..1, multiplies the pixel coverage */
  float fiber_spacing;                /* self-shadowing: depth per occluding fibre, in strand widths */
  float fiber_alpha;                  /* self-shadowing: light absorbed by one fibre, 0..1 */
  float color_variation;              /* 0..1: each strand's colour is scaled by a fixed per-strand factor in
                                         [1 - v, 1 + v] (real hair is never one flat colour) */
} TvkHairMaterial;
#define TVK_HAIR_MATERIAL_DEFAULT_INIT \
  { { 0.045f, 0.022f, 0.011f }, { 0.10f, 0.056f, 0.03f }, 0.7f, 0.15f, 80.0f, 0.45f, 20.0f, 0.10f, -0.20f, \
    0.0006f, 0.3f, 1.0f, 5.0f, 0.35f, 0.25f }

typedef enum TvkLightType { TVK_LIGHT_DIRECTIONAL = 0, TVK_LIGHT_SPOT = 1 } TvkLightType;

typedef struct TvkLight {
  TvkLightType type;
  float color[3];                     /* linear RGB, times intensity */
  float intensity;
  double position[3];                 /* m, world (spot) */
  float direction[3];                 /* world direction the light travels (need not be unit) */
  float range;                        /* m (spot): light fades to 0 at this distance; 0 = no range limit */
  float inner_cone, outer_cone;       /* radians, half-angles (spot) */
  uint32_t shadowed;                  /* 1 = attenuate with the shadow map of TvkShadowMap (one light only) */
} TvkLight;

/* The host's shadow map as the shading call reads it. Hair and meshes draw into it with the same light matrix. */
typedef struct TvkShadowMap {
  VkImageView depth_view;             /* VK_NULL_HANDLE: no shadowing */
  VkSampler sampler;                  /* a NON-comparison sampler (depth values are read to count fibres) */
  VkImageLayout layout;               /* layout of the image while the shading call reads it */
  double view_projection[16];         /* world -> light clip space, column-major, Vulkan depth 0..1 */
  uint32_t perspective;               /* 0: orthographic projection; 1: perspective (spot light) */
  float near_plane, far_plane;        /* m, of the light projection (to turn depth into metres) */
} TvkShadowMap;

/* A camera (or a light, for the shadow call): world matrices in double; TressVK makes them relative to the
 * instance's simulation origin in double before anything reaches the GPU, so hair 10 km from the world origin
 * renders as precisely as at the origin. */
typedef struct TvkView {
  double view_projection[16];         /* world -> clip, column-major (glm layout), Vulkan depth 0..1 */
  double eye[3];                      /* m, world; for an orthographic light, a point far back along the light */
  uint32_t orthographic;              /* 1: quads face -direction instead of the eye */
  float direction[3];                 /* view direction (orthographic) */
  uint32_t width, height;             /* viewport in pixels (quad widths and coverage are computed in pixels) */
} TvkView;

/* Level of detail: beyond start_distance (eye to the instance's origin), fewer strands are drawn, down to
 * min_fraction of them at end_distance, each wider by 1/fraction so that the hair keeps its coverage. The strands
 * drawn are a prefix of the baked LOD order (an even thinning). Zero-initialised = LOD off. */
typedef struct TvkLodSettings {
  float start_distance;               /* m */
  float end_distance;                 /* m, > start_distance */
  float min_fraction;                 /* 0..1 */
} TvkLodSettings;

typedef struct TvkDrawInfo {
  size_t struct_size;                 /* sizeof(TvkDrawInfo) */
  const void* next;
  TvkInstance instance;
  const TvkView* view;                /* camera (shading) or light (shadow) */
  const TvkHairMaterial* materials;   /* one per strand group, or 1 for all; NULL = defaults */
  uint32_t material_count;
  TvkLodSettings lod;
  /* shading only */
  uint32_t light_count;               /* 0..TVK_MAX_LIGHTS */
  const TvkLight* lights;
  float ambient[3];                   /* linear RGB ambient light (times kd * colour) */
  const TvkShadowMap* shadow;         /* NULL = unshadowed */
  /* shadow only: the camera whose distance picks the LOD of the shadow (so both passes draw the same strands);
     NULL = the light's view */
  const TvkView* lod_view;
} TvkDrawInfo;

TVK_API TvkResult tressvk_create_renderer(TvkContext context, const TvkRendererCreateInfo* info,
                                          TvkRenderer* out_renderer);
/* The host must make sure the GPU no longer uses the renderer (e.g. vkDeviceWaitIdle) first. Destroy renderers
 * before their context. To resize, nothing is needed (sizes come with each TvkView); to change formats, create a
 * new renderer. */
TVK_API void tressvk_destroy_renderer(TvkRenderer renderer);

/* Draws hair depth into the host's shadow map (inside the host's depth-only pass). */
TVK_API TvkResult tressvk_cmd_draw_shadow(TvkRenderer renderer, VkCommandBuffer command_buffer,
                                          const TvkDrawInfo* info);
/* Draws shaded, anti-aliased hair into the host's colour and depth targets (inside the host's pass). */
TVK_API TvkResult tressvk_cmd_draw_hair(TvkRenderer renderer, VkCommandBuffer command_buffer,
                                        const TvkDrawInfo* info);

/* Strands the last draw call of `renderer` drew (after LOD), for statistics and tests. */
TVK_API uint32_t tressvk_get_last_drawn_strands(TvkRenderer renderer);

#ifdef __cplusplus
}
#endif

#endif /* TRESSVK_RENDER_H */
