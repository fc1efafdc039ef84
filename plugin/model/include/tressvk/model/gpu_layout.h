// The GPU layout in one place, for both languages: plain #defines that glslang (shaders/sim/layout.glsl,
// shaders/render/hair_layout.glsl) and C++ (gpu_layout.hpp, plugin/src/render/constants.hpp) include, as the
// FidelityFX SDK shares its constants between HLSL and C++. Only preprocessor lines and comments here, so that
// the file reads the same in GLSL and C++. The structs stay written in each language; the C++ side asserts every
// size and offset, and the public constants (tressvk.h, render.h) are asserted equal to these.
#ifndef TRESSVK_MODEL_GPU_LAYOUT_H
#define TRESSVK_MODEL_GPU_LAYOUT_H

// ---- simulation: per-vertex buffers hold strands in blocks of TVK_BLOCK, vertex-major within a block ----------
// Vertex v of strand s (N vertices per strand) is at TVK_VERTEX_INDEX(s, v, N); buffers hold whole blocks. The
// public TVK_STRAND_BLOCK (tressvk.h) is this number.
#define TVK_BLOCK 32u
#define TVK_VERTEX_INDEX(s, v, n) (((s) / TVK_BLOCK) * (TVK_BLOCK * (n)) + (v) * TVK_BLOCK + (s) % TVK_BLOCK)

// ---- simulation: descriptor set 0 bindings (all storage buffers) ---------------------------------------------
#define TVK_BINDING_POSITIONS 0
#define TVK_BINDING_PREV_POSITIONS 1
#define TVK_BINDING_PREV_PREV_POSITIONS 2
#define TVK_BINDING_TANGENTS 3
#define TVK_BINDING_REST_POSITIONS 4
#define TVK_BINDING_REST_INFO 5
#define TVK_BINDING_REST_EDGE_LOCAL 6
#define TVK_BINDING_ROOT_FRAMES 7
#define TVK_BINDING_FOLLOW_OFFSETS 8
#define TVK_BINDING_GUIDE_INFO 9
#define TVK_BINDING_BONE_INDICES 10
#define TVK_BINDING_BONE_WEIGHTS 11
#define TVK_BINDING_SKIN 12
#define TVK_BINDING_GROUPS 13
#define TVK_BINDING_STEPS 14
#define TVK_BINDING_COUNTERS 15
#define TVK_BINDING_ANCHORS 16
#define TVK_BINDING_COUNT 17

// ---- simulation: specialization constant ids ---------------------------------------------------------------
#define TVK_SPEC_WORKGROUP_SIZE 0
#define TVK_SPEC_VERTICES_PER_STRAND 1  // N
#define TVK_SPEC_FOLLOW_PER_GUIDE 2     // K
#define TVK_SPEC_FEATURES 3             // TVK_FEATURE_* bits
#define TVK_SPEC_CAPSULE_COUNT 4

// ---- simulation: feature bits (the FEATURES specialization constant) ---------------------------------------
#define TVK_FEATURE_GLOBAL_SHAPE 1u  // integrate: pull toward the skinned rest pose
#define TVK_FEATURE_WIND 2u          // length: wind displacement
#define TVK_FEATURE_COLLISION 4u     // length: capsule collision (CAPSULE_COUNT capsules)
#define TVK_FEATURE_SKINNING 8u      // bone weights blended (otherwise one rigid transform: bone 0)
#define TVK_FEATURE_MAX_SPEED 16u    // length: velocity clamp
#define TVK_FEATURE_PINNED_TIPS 32u  // length: strands pinned at both ends (the tridiagonal length solve)
#define TVK_FEATURE_VSP 64u          // fused frame kernel only: run velocity shock propagation
#define TVK_FEATURE_LOCAL_SHAPE 128u // fused frame kernel only: run local shape constraints
#define TVK_FEATURE_CONSERVATIVE 256u // lane kernel only: the conservative local shape (TRESSVK_SIM_MODEL=conservative)
#define TVK_FEATURE_REFINE 512u      // lane kernel only: the conservative shape solve refined once (slow step rates)
#define TVK_FEATURE_REFINE_THRICE 1024u  // with TVK_FEATURE_REFINE: refined three times (the slowest rates)

// ---- simulation: per-frame data ----------------------------------------------------------------------------
#define TVK_SKIN_VEC4 9u        // vec4 per (substep, bone) in the Skin buffer
#define TVK_STEP_RESET 1u       // StepParams.flags.x: put every strand at its skinned rest pose with zero velocity
#define TVK_STEP_MOVE_STATE 2u  // StepParams.flags.x: turn pos/prev/prevprev by the teleport before integrating
#define TVK_STEP_MAX_CAPSULES 8u  // capsules per instance (StepParams holds 2 vec4 each) = TVK_MAX_CAPSULES (sim_types.h)
#define TVK_COUNTER_AWAKE_BIT 0x80000000u  // counters[slot]: the frame slot's awake bit; bits 0-30 count resets
#define TVK_QUIET_FRAMES 3u     // anchor[g].w: measured still frames in a row, then the guide sleeps (layout.glsl)

// ---- rendering (the rasterised hair passes): descriptor set 0 and the limits of DrawConstants --------------
#define TVK_DRAW_BINDING_CONSTANTS 0
#define TVK_DRAW_BINDING_POSITIONS 1
#define TVK_DRAW_BINDING_TANGENTS 2
#define TVK_DRAW_BINDING_GUIDE_INFO 3
#define TVK_DRAW_BINDING_ANCHORS 4
#define TVK_DRAW_BINDING_SHADOW_MAP 5  // the shadowed shading pass only
#define TVK_DRAW_MAX_LIGHTS 8          // = TVK_MAX_LIGHTS (render.h)
#define TVK_DRAW_MAX_MATERIALS 16      // = TVK_MAX_MATERIALS (render.h)

#endif
