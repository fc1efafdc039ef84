/* TressVK simulation parameters: the public, plain-C types that describe how hair moves.
 *
 * Included by tressvk.h; usable on its own (it needs only <stdint.h>). Plain old data, no functions: every struct
 * has a TVK_*_DEFAULT_INIT initialiser listing its documented defaults, so a C host writes
 *     TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
 * and changes what it needs. The CPU reference (tressvk::reference) and the GPU passes read the same structs.
 * docs/simulation.md explains the model each field drives.
 *
 * Units: metres, seconds, radians, kilograms never (the model is mass-free). "Simulation space" is world-oriented
 * (gravity and wind are world vectors) with its origin at the instance, so distance from the world origin never
 * costs precision. Fields documented as "per step" are converted by TressVK from the per-second values given
 * here with the fixed simulation step h; hosts never see h-dependent numbers.
 */
#ifndef TRESSVK_SIM_TYPES_H
#define TRESSVK_SIM_TYPES_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Hard limits of the GPU layout (shaders/sim/layout.glsl). */
#define TVK_MAX_CAPSULES 8          /* capsules per instance */
#define TVK_MAX_STEPS_PER_FRAME 16  /* upper bound for TvkTimeSettings::max_steps_per_frame and max_steps_sustained */
#define TVK_MAX_ITERATIONS 32       /* upper bound for local_iterations and length_iterations */
#define TVK_ASLEEP_QUIET_FRAMES 3u  /* a guide sleeps (TvkSimSettings::sleep_below) while its anchor's w is at least
                                       this (TvkInstanceBuffers::anchors) */

/* Settings the host may leave to the instance's model (TvkSimModel): each model runs at the rate and iteration count
 * it is made for. tressvk_get_sim_settings and tressvk_get_sim_params report what an instance resolved them to. */
#define TVK_STEP_RATE_BY_MODEL 0.0f        /* TvkTimeSettings::step_rate: follow-the-leader and compliant 240 Hz;
                                              conservative 120 Hz for strands of up to 64 vertices, 240 Hz above */
#define TVK_ITERATIONS_BY_MODEL 0xFFFFFFFFu /* TvkSimParams::local_iterations: follow-the-leader and compliant 2;
                                              conservative 1 */

/* Per strand group (an asset has one or more groups, e.g. "mohawk", "fur"). Stiffnesses are per-iteration
 * fractions as in TressFX, not moduli; with the fixed step (TvkTimeSettings) they do not depend on frame rate. */
typedef struct TvkSimParams {
  float damping;            /* velocity loss; each step keeps exp(-damping * h * 60) of the velocity (TressFX 4.1
                               semantics: 0 = none, 1 = heavy). Dimensionless. Default 0.08 */
  float global_stiffness;   /* 0..1: per step, pull this fraction of the way toward the skinned rest pose.
                               Default 0.15 */
  float global_range;       /* 0..1: fraction of the strand's rest arc length, from the root, that global shape
                               acts on. Default 0.3 */
  float local_stiffness;    /* 0..1: keeps each segment's rest direction relative to its parent's frame; applied
                               as 0.5 * min(local_stiffness, 0.95) per iteration. 0 = no local-shape pass.
                               Default 0.9 */
  uint32_t local_iterations;  /* 0..TVK_MAX_ITERATIONS sweeps of local shape per step, honoured for every vertex
                               count. 0 = no local-shape pass. Default TVK_ITERATIONS_BY_MODEL: 2 on
                               follow-the-leader (1 is not stable on tightly curled strands, as in TressFX), 1 on
                               the conservative model (its shape does not depend on the count) */
  uint32_t length_iterations; /* 1..TVK_MAX_ITERATIONS root-to-tip length-constraint sweeps per step; the last is
                               follow-the-leader (exact lengths), earlier ones share corrections between both
                               ends. Default 1 (more sweeps soften the strand and, with local shape, can make a
                               curled rest pose unstable) */
  float vsp_coefficient;    /* 0..1: velocity shock propagation, the fraction of the root's rigid motion of this
                               step given to the whole strand. 0 = no VSP pass. Default 0.9 (as TressFX 5.x; short
                               strands lag less behind a fast head than at TressFX 4.1's 0.8) */
  float vsp_threshold;      /* m/s^2: root-segment acceleration above which the coefficient becomes 1 (ramping up
                               from 0.75x this value). Converted to a per-step length a*h^2. Default 100 */
  float max_speed;          /* m/s: a real velocity clamp (a vertex moves at most max_speed * h per step). Measured
                               in simulation space, i.e. world velocity. 0 = off. Default 50 */
  float tip_separation;     /* >= 0: follow hairs spread from their guide by (1 + tip_separation * t), t = 0 at the
                               root and 1 at the tip. Negative = use the value baked into the asset. Default -1 */
  float rigid_below;        /* m: strands of this group shorter than this (rest arc length) are carried rigidly by
                               the skinning, every vertex pinned: a few millimetres of hair barely bends under its
                               own weight, and resolved into N vertices its sub-millimetre segments mostly amplify
                               float rounding. 0 = none. Negative = 45 % of the asset's median strand length.
                               Default -1 */
} TvkSimParams;

#define TVK_SIM_PARAMS_DEFAULT_INIT \
  { 0.08f, 0.15f, 0.3f, 0.9f, TVK_ITERATIONS_BY_MODEL, 1u, 0.9f, 100.0f, 50.0f, -1.0f, -1.0f }

/* Wind: a world-space acceleration acting on each segment perpendicular to it (so it bends hair, never
 * stretches it), pointing WITH `direction`, spread over a cone so neighbouring strands differ, and gusting as
 *   strength * (1 + gust_amplitude * sin(2 pi gust_frequency t)).
 * Independent of segment length and units (unlike TressFX's |e|^2 displacement). strength 0 = no wind pass term. */
typedef struct TvkWind {
  float direction[3];       /* world direction (need not be unit; zero = no wind). Default (1, 0, 0) */
  float strength;           /* m/s^2, mean perpendicular acceleration. 0 = off. Default 0 */
  float gust_amplitude;     /* 0..1 fraction of strength. Default 0.5 */
  float gust_frequency;     /* Hz. Default 0.5 */
  float cone_angle;         /* radians, half-angle of the spread of directions across strands. Default 0.35 */
} TvkWind;

#define TVK_WIND_DEFAULT_INIT { { 1.0f, 0.0f, 0.0f }, 0.0f, 0.5f, 0.5f, 0.35f }

/* A tapered capsule in the instance's space (moves with the instance's rigid transform): the swept sphere from
 * (p0, r0) to (p1, r1), radius interpolated linearly along the axis. Pinned vertices are never moved; a contact
 * removes only the velocity into the surface (tangential motion slides). */
typedef struct TvkCapsule {
  float p0[3];              /* m, instance space */
  float r0;                 /* m, >= 0 */
  float p1[3];              /* m, instance space (p1 == p0 makes a sphere) */
  float r1;                 /* m, >= 0 */
} TvkCapsule;

/* Time policy: a fixed step with an accumulator. Each frame adds its dt; whole steps of 1/step_rate run, at most
 * max_steps_per_frame of them. When the cap is hit, the surplus steps are dropped and the instance's motion
 * during them moves the hair rigidly, as a teleport does; the kept steps simulate the end of the frame's motion
 * at its real speed (a 0.25 s hitch never explodes, never whips the hair, and leaves no catch-up debt). The head
 * motion of the frame is interpolated across its steps. A frame shorter than one step runs no step and carries
 * its motion over.
 * A hitch and a low frame rate are told apart: when the host's rate stays low (the median dt of its last 8 frames,
 * this one's included, needs more than max_steps_per_frame steps), a frame may run up to max_steps_sustained
 * steps, so a 24 fps host simulates in real time at the same steps per second as a 60 fps one; a single long
 * frame among short ones is still a hitch. */
typedef struct TvkTimeSettings {
  float step_rate;          /* Hz, 30..480, or TVK_STEP_RATE_BY_MODEL (0, the default): 240 Hz on follow-the-leader
                               (4 steps at 60 fps: gravity moves a free vertex 0.17 mm per step, well under the
                               sub-millimetre segments of real grooms such as the Ratboy mohawk, where 120 Hz
                               (0.68 mm per step) made the model's response to float32 rounding 10x larger; and
                               30/60/120/144 fps hosts all simulate on the same grid); 120 Hz on the conservative
                               model for strands of up to 64 vertices, 240 Hz above */
  uint32_t max_steps_per_frame; /* 1..TVK_MAX_STEPS_PER_FRAME, the reset step of a resetting frame included.
                               Default 8 (a 30 fps frame still runs in full) */
  uint32_t max_steps_sustained; /* 0..TVK_MAX_STEPS_PER_FRAME: the cap while the host's rate stays low (at least
                               max_steps_per_frame; 0 = max_steps_per_frame, i.e. a sustained rate under
                               step_rate / max_steps_per_frame runs in slow motion). Default 16 (real time down
                               to 15 fps at 240 Hz steps) */
} TvkTimeSettings;

#define TVK_TIME_SETTINGS_DEFAULT_INIT { TVK_STEP_RATE_BY_MODEL, 8u, 16u }

/* An instance's rigid placement in the world: world = translation + rotation * instance_point. Double precision
 * so a character far from the origin keeps full precision: TressVK subtracts the translation in double and the
 * GPU only ever sees groom-sized numbers. */
typedef struct TvkInstanceTransform {
  double translation[3];    /* m, world. Default (0, 0, 0) */
  double rotation[4];       /* unit quaternion (x, y, z, w), instance -> world. Default (0, 0, 0, 1) */
} TvkInstanceTransform;

#define TVK_INSTANCE_TRANSFORM_DEFAULT_INIT { { 0.0, 0.0, 0.0 }, { 0.0, 0.0, 0.0, 1.0 } }

/* A bone's current transform relative to the instance, mapping the asset's bind space to instance space:
 * instance_point = rows * (bind_point, 1). Row-major 3x4; the 3x3 part must be a rotation (no scale or shear).
 * Strands blend up to 4 bones with the asset's per-strand weights (the root's weights drive the whole strand). */
typedef struct TvkBoneMatrix {
  float rows[3][4];
} TvkBoneMatrix;

#define TVK_BONE_MATRIX_IDENTITY_INIT { { { 1.0f, 0.0f, 0.0f, 0.0f }, { 0.0f, 1.0f, 0.0f, 0.0f }, \
                                          { 0.0f, 0.0f, 1.0f, 0.0f } } }

/* Per instance, per frame: everything the simulation of one frame needs besides per-group TvkSimParams. */
typedef struct TvkSimFrame {
  float dt;                      /* s, this frame's duration (>= 0; 0 = nothing advances) */
  TvkInstanceTransform transform;/* where the instance is at the end of this frame */
  const TvkBoneMatrix* bones;    /* NULL = rigid: every strand follows `transform` alone. Otherwise one matrix per
                                    asset bone (HairAsset::bone_names order) at the end of this frame */
  uint32_t bone_count;           /* entries in `bones` (must equal the asset's bone count when bones != NULL) */
  uint32_t teleport;             /* 1 = the instance jumped (cut, respawn): the hair is moved rigidly with it,
                                    current and previous state alike, so the jump adds no velocity. Default 0 */
  uint32_t reset;                /* 1 = put every strand back to its skinned rest pose, at rest. Default 0 (the
                                    first frame of an instance always resets) */
  uint32_t capsule_count;        /* 0..TVK_MAX_CAPSULES; 0 = no collision pass term */
  TvkCapsule capsules[TVK_MAX_CAPSULES];
  TvkWind wind;
} TvkSimFrame;

/* A still frame: dt 0, identity transform, no bones, no teleport or reset, no capsules, no wind. Every number in a
 * frame must be finite (and rotations unit quaternions, radii >= 0): tressvk_set_frame refuses anything else with a
 * message naming the field, so one bad host value never reaches the GPU. */
#define TVK_SIM_FRAME_DEFAULT_INIT                                                                  \
  { 0.0f, TVK_INSTANCE_TRANSFORM_DEFAULT_INIT, 0, 0u, 0u, 0u, 0u,                                   \
    { { { 0.0f, 0.0f, 0.0f }, 0.0f, { 0.0f, 0.0f, 0.0f }, 0.0f } }, TVK_WIND_DEFAULT_INIT }

/* The strand model an instance runs (docs/accuracy.md, "Which model, at which rate" and "What to choose today").
 * Every model keeps the same state, so an instance may change model between frames; the new model's GPU kernel is
 * built on its first frame unless tressvk_prewarm_instance ran after the change. */
typedef enum TvkSimModel {
  TVK_SIM_MODEL_DEFAULT = 0,           /* follow-the-leader, unless the TRESSVK_SIM_MODEL environment variable names
                                          another model (follow-the-leader, conservative, compliant): a switch for
                                          test and benchmark runs, read once per process */
  TVK_SIM_MODEL_FOLLOW_THE_LEADER = 1, /* TressFX's model: local shape and lengths as serial sweeps along the strand.
                                          Its stiffness is a fraction per step and per iteration, so the look changes
                                          with the step rate and the iteration count */
  TVK_SIM_MODEL_CONSERVATIVE = 2,      /* shape and lengths as compliant constraints solved along the whole strand:
                                          the look stays the same across step rates and iteration counts, and hair at
                                          rest comes to rest; recommended at 120 Hz with 1 local iteration for
                                          strands of up to 64 vertices (60 Hz for less time, where its solve is
                                          refined: the same hard cases pass, with more error in violent motion),
                                          240 Hz for longer ones, which TVK_STEP_RATE_BY_MODEL and
                                          TVK_ITERATIONS_BY_MODEL (the defaults) give it; below 60 Hz (240 Hz above
                                          64 vertices) an instance gets a warning */
  TVK_SIM_MODEL_COMPLIANT = 3,         /* the conservative model's constraints with targets held while it solves:
                                          faster, but curly hair never comes to rest */
  TVK_SIM_MODEL_MAX_ENUM = 0x7FFFFFFF  /* keeps the enum 32 bits wide; not a model */
} TvkSimModel;

/* Per instance, fixed for the instance's life (changing them is allowed between frames). */
typedef struct TvkSimSettings {
  float gravity[3];              /* m/s^2, world. Default (0, -9.81, 0) */
  TvkTimeSettings time;
  float sleep_below;             /* 0..1e-3, a fraction of the groom's median strand length per step: in still
                                    frames (every input the same as in the frame before: transform, bones, wind,
                                    capsules, parameters), a guide none of whose vertices moved more than this per
                                    step through 3 frames in a row sleeps: it costs almost nothing and keeps its state
                                    until a frame is not still. A groom at rest under a still head then costs far
                                    less than a moving one. Once the still frames have lasted long enough for the
                                    group's damping to bring any motion the inputs gave a strand below this (an
                                    amplitude keeps exp(-30 * damping * t) of itself: 5.8 s at the default damping),
                                    a guide that moves less than 1e-2 of the median strand length per step sleeps
                                    too: what it still moves is the model's own cycle (follow-the-leader's curls),
                                    not motion. No damping, no such sleep. 0 = never sleep. Default 1e-6 */
  TvkSimModel model;             /* Default TVK_SIM_MODEL_DEFAULT (follow-the-leader) */
} TvkSimSettings;

#define TVK_SIM_SETTINGS_DEFAULT_INIT { { 0.0f, -9.81f, 0.0f }, TVK_TIME_SETTINGS_DEFAULT_INIT, 1e-6f, TVK_SIM_MODEL_DEFAULT }

#ifdef __cplusplus
}
#endif

#endif /* TRESSVK_SIM_TYPES_H */
