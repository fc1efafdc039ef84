/* TressVK rendering: two ways to draw the hair.
 * - The raster path (this comment down to TvkRenderer's calls): shadow and shading passes of camera-facing quads
 *   recorded inside the host's own passes.
 * - The compute path ("The compute strand rasterizer" below): tressvk_cmd_shadow_hair and tressvk_cmd_raster_hair
 *   outside the host's passes, tressvk_cmd_composite_hair inside; order-independent, and the fast path on GPUs
 *   with little raster hardware.
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
  double view_projection[16];         /* world -> light clip space, column-major, Vulkan Y down, depth 0..1 */
  uint32_t perspective;               /* 0: orthographic projection; 1: perspective (spot light) */
  float near_plane, far_plane;        /* m, of the light projection (to turn depth into metres) */
} TvkShadowMap;

/* A camera (or a light, for the shadow call): world matrices in double; TressVK makes them relative to the
 * instance's simulation origin in double before anything reaches the GPU, so hair 10 km from the world origin
 * renders as precisely as at the origin. */
typedef struct TvkView {
  double view_projection[16];         /* world -> Vulkan clip space, column-major (glm layout): +y points down the
                                         framebuffer, depth 0..1; a glm::perspective* matrix needs proj[1][1] *= -1 */
  double eye[3];                      /* m, world; for an orthographic light, a point far back along the light */
  uint32_t orthographic;              /* 1: quads face -direction instead of the eye */
  float direction[3];                 /* view direction (orthographic) */
  uint32_t width, height;             /* viewport in pixels (quad widths and coverage are computed in pixels) */
} TvkView;

/* Level of detail: fewer strands are drawn, each wider by 1/fraction so that the hair keeps its coverage. The strands
 * drawn are a prefix of the baked LOD order (an even thinning). Two modes:
 * - by distance (target_width_px = 0): beyond start_distance (eye to the instance's origin), down to min_fraction
 *   of the strands at end_distance;
 * - by coverage (target_width_px > 0): the fraction is the strands' projected root width in pixels at the
 *   instance's origin (the widest material's strand_width, in the camera's view) over target_width_px, clamped to
 *   [min_fraction, 1]: sub-pixel strands are thinned until the drawn ones are about target_width_px wide, wider
 *   strands are all drawn (start_distance and end_distance are not used; min_fraction 0 = no floor).
 * Zero-initialised = LOD off. docs/rendering.md "Level of detail" gives the error of each against all strands. */
typedef struct TvkLodSettings {
  float start_distance;               /* m */
  float end_distance;                 /* m, > start_distance */
  float min_fraction;                 /* 0..1 */
  float target_width_px;              /* > 0: coverage-driven LOD (see above); 0: by distance */
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
/* Builds every pipeline the renderer's calls can use (the rasterised passes, the compute rasterizer and its
 * composite, and the shadow passes when a shadow target was given) ahead of the first frame, as FidelityFX builds its
 * pipelines at context creation; otherwise each is built by the first call that needs it (15 ms of the first draw on
 * lavapipe). Records nothing; optional. */
TVK_API TvkResult tressvk_prewarm_renderer(TvkRenderer renderer);

/* Draws hair depth into the host's shadow map (inside the host's depth-only pass). */
TVK_API TvkResult tressvk_cmd_draw_shadow(TvkRenderer renderer, VkCommandBuffer command_buffer,
                                          const TvkDrawInfo* info);
/* Draws shaded, anti-aliased hair into the host's colour and depth targets (inside the host's pass). */
TVK_API TvkResult tressvk_cmd_draw_hair(TvkRenderer renderer, VkCommandBuffer command_buffer,
                                        const TvkDrawInfo* info);

/* ---- The compute strand rasterizer (docs/rendering.md "The compute path") -----------------------------------
 * Two calls per frame and instance:
 *   1. tressvk_cmd_raster_hair, recorded OUTSIDE any render pass once the host's opaque depth is final: shades
 *      the strands per vertex, bins their segments into 8 x 8 pixel tiles, sorts each tile's segments by depth
 *      and composites them front to back with analytic coverage, depth-tested against the host's depth, into a
 *      renderer-owned hair layer (premultiplied linear RGBA, half floats, one per pixel of the view).
 *   2. tressvk_cmd_composite_hair, recorded INSIDE the host's pass on its colour target (the shading target the
 *      renderer was created for: dynamic rendering or its VkRenderPass/subpass): one indirect draw, a quad per tile
 *      with hair, that blends the layer over the colour attachment (ONE, ONE_MINUS_SRC_ALPHA). It neither tests nor
 *      writes depth.
 *
 * Synchronization contract of tressvk_cmd_raster_hair (it records its own barriers, none of which names a host
 * resource):
 * - Reads `depth_view` in the COMPUTE_SHADER stage as a sampled image (texelFetch, SHADER_SAMPLED_READ) in
 *   `depth_layout` (DEPTH_READ_ONLY_OPTIMAL, DEPTH_STENCIL_READ_ONLY_OPTIMAL or SHADER_READ_ONLY_OPTIMAL): the host
 *   transitions it from its depth-attachment writes with a barrier to COMPUTE_SHADER / SHADER_SAMPLED_READ first,
 *   and back afterwards if it draws into it again (the call only reads it).
 * - Reads the shadow map of draw->shadow (if any) in the COMPUTE_SHADER stage the same way, in shadow->layout.
 * - Reads positions, tangents and anchors in the COMPUTE_SHADER stage (tressvk_cmd_simulate's exit barrier covers
 *   it).
 * - Its own buffers are shared by the frames in flight: its first barrier (COMPUTE_SHADER | FRAGMENT_SHADER |
 *   ALL_TRANSFER -> COMPUTE_SHADER | ALL_TRANSFER) orders it after the previous frame's raster and composite calls of
 *   this renderer on the same queue, so it also waits for all earlier compute and fragment work of that queue.
 * - Its last barrier makes the hair layer visible to FRAGMENT_SHADER storage reads: the composite call may follow
 *   in any later pass of the same queue with nothing more from the host.
 * State disturbed: the bound compute pipeline and compute descriptor set 0, push constants.
 *
 * tressvk_cmd_composite_hair: inside the host's pass (dynamic rendering or the render pass and subpass of
 * `shading`), after the opaque draws; reads the layer in the FRAGMENT_SHADER stage; records no barrier. State
 * disturbed: the bound graphics pipeline, graphics descriptor set 0, push constants; viewport and scissor are the
 * host's (they must cover the view given to the raster call).
 *
 * Memory (allocated on first use, grown when a larger view or groom comes, never per frame; old buffers are
 * released frames_in_flight frames later): 8 bytes per pixel for the layer (16.6 MB at 1920x1080, 66.4 MB at
 * 3840x2160) + 16 bytes per 8x8 tile (0.5 MB at 1080p) + 32 bytes per strand vertex + 8 bytes per tile entry
 * (capacity: 12 entries per segment of the groom, at least 2^20, at most what one storage buffer binding allows;
 * measured: 5 per segment for 100,000 x 32 strands at 1080p, 9.5 at 4K) + 5.2 MB for the deep opacity map, and
 * for tressvk_cmd_shadow_hair 4 bytes per shadow-map texel.
 * Overflow is defined: entries past the capacity are dropped (the farthest-binned segments of some tiles go
 * missing), counted in TvkRasterStats.dropped_entries, and never written out of bounds. */
#define TVK_RASTER_CAPTURE 0x1u          /* keep a copy of this call's vertices, host depth and layer (tests) */
#define TVK_RASTER_REVERSE_STRANDS 0x2u  /* submit the strands in reversed order (order-independence test) */
#define TVK_RASTER_SHADE_PER_FRAGMENT 0x4u /* Kajiya-Kay per fragment instead of per vertex (slower, see
                                            docs/rendering.md; the default shades per vertex) */
#define TVK_RASTER_SPLIT_AS_DENSE 0x8u   /* split tiles across workgroups as for a dense groom (only those over 8,192
                                            entries, after the fine pass) even where few are heavy (tests: that
                                            path in a small view; docs/rendering.md, "The fine pass's timeline") */

typedef struct TvkRasterInfo {
  size_t struct_size;                 /* sizeof(TvkRasterInfo) */
  const void* next;
  const TvkDrawInfo* draw;            /* instance, camera view, materials, LOD, lights, ambient, shadow map */
  VkImageView depth_view;             /* the host's opaque depth (single-sample, depth aspect), view-sized */
  VkImageLayout depth_layout;
  uint32_t flags;                     /* TVK_RASTER_* */
} TvkRasterInfo;

TVK_API TvkResult tressvk_cmd_raster_hair(TvkRenderer renderer, VkCommandBuffer command_buffer,
                                          const TvkRasterInfo* info);
TVK_API TvkResult tressvk_cmd_composite_hair(TvkRenderer renderer, VkCommandBuffer command_buffer);

/* Hair depth into the host's shadow map in compute, in place of tressvk_cmd_draw_shadow where raster hardware is
 * scarce (data-centre GPUs): recorded OUTSIDE any render pass, after the host drew its meshes into the map and
 * before anything samples it. draw->view is the light (its width x height = the map's size), draw->lod_view the
 * camera, as for tressvk_cmd_draw_shadow; strands are at least 1.5 texels wide, as there.
 * Synchronization contract: the map (D32_SFLOAT, single sample, created with TRANSFER_SRC and TRANSFER_DST usage)
 * comes in VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: the host makes its depth writes visible to ALL_TRANSFER /
 * TRANSFER_READ with that transition first. The call copies the rectangle of the map the hair can reach this frame
 * (computed on the CPU, conservative; the whole map for a skinned instance; docs/rendering.md) into a renderer-owned
 * buffer, transitions the image to TRANSFER_DST_OPTIMAL (an image barrier of its own), keeps the nearer of the map
 * and the hair per texel in compute, and copies the rectangle back (texels outside it are not written; with no
 * rectangle, only the transition is recorded): the map is left in TRANSFER_DST_OPTIMAL, and the host orders the
 * call's ALL_TRANSFER / TRANSFER_WRITE before its own reads with its transition to its read layout. Its first barrier
 * orders it after the previous frame's copies of this renderer. State disturbed: the bound compute
 * pipeline, compute descriptor set 0, push constants. */
typedef struct TvkShadowRasterInfo {
  size_t struct_size;                 /* sizeof(TvkShadowRasterInfo) */
  const void* next;
  const TvkDrawInfo* draw;
  VkImage shadow_image;
} TvkShadowRasterInfo;
TVK_API TvkResult tressvk_cmd_shadow_hair(TvkRenderer renderer, VkCommandBuffer command_buffer,
                                          const TvkShadowRasterInfo* info);

/* Counts of the last raster call whose commands the GPU has finished (copied at its end into host memory; read
 * them after the host waited for that frame). */
typedef struct TvkRasterStats {
  uint64_t entries_requested;         /* (tile, segment) pairs binned */
  uint64_t dropped_entries;           /* of those, over the entry capacity (not drawn) */
  uint64_t dropped_slice_entries;     /* dropped because one depth bin of a tile held more than a slice */
  uint64_t segments_binned;
  uint64_t fragments;                 /* fragments composited (coverage > 0, in front of the host depth) */
  uint64_t hair_pixels;               /* pixels with alpha > 0 */
  uint64_t sliced_tiles;              /* tiles that needed depth slices */
  uint64_t memory_bytes;              /* device memory of the compute path's buffers */
  uint32_t entry_capacity;
  uint32_t slice_capacity;            /* segments sorted at once per tile */
  uint64_t split_tiles;               /* over-full tiles composited in depth shares by several workgroups */
  uint64_t shadow_samples_outside;    /* tressvk_cmd_shadow_hair (its last call that copied a rectangle): hair samples
                                         inside the map but outside the rectangle it copied, i.e. not written. The
                                         rectangle is conservative, so this is 0; tests check it */
} TvkRasterStats;
TVK_API TvkResult tressvk_get_raster_stats(TvkRenderer renderer, TvkRasterStats* out_stats);

/* What the last raster call with TVK_RASTER_CAPTURE saw and produced, once the GPU has finished it (tests and
 * tressvk-bench compare it with a brute-force reference). Pointers stay valid until the next capture. */
typedef struct TvkRasterCapture {
  uint32_t width, height;
  uint32_t vertices_per_strand, strands;  /* strands drawn (after LOD) */
  const float* vertices;              /* strands * vertices_per_strand * 8: x px, y px, depth, width px, r, g, b,
                                         opacity (depth < 0: behind the eye) */
  const float* host_depth;            /* width * height */
  const uint16_t* layer;              /* width * height * 4 half floats: premultiplied r, g, b, alpha */
} TvkRasterCapture;
TVK_API TvkResult tressvk_get_raster_capture(TvkRenderer renderer, TvkRasterCapture* out_capture);

/* The strands a draw with `info` would draw by its LOD (a prefix of the rendered strands), before the simulation's
 * limit (tressvk_set_draw_strands): call it with the frame's camera before tressvk_cmd_simulate and hand the largest
 * count of the frame's draws to tressvk_set_draw_strands. */
TVK_API TvkResult tressvk_get_draw_strands(TvkRenderer renderer, const TvkDrawInfo* info, uint32_t* out_strands);
/* Strands the last draw call of `renderer` drew (after LOD), for statistics and tests. */
TVK_API uint32_t tressvk_get_last_drawn_strands(TvkRenderer renderer);

#ifdef __cplusplus
}
#endif

#endif /* TRESSVK_RENDER_H */
