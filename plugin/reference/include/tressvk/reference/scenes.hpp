// Scripted scenes for the tests and the bench (docs/simulation.md describes each): a function of the frame index
// giving that frame's inputs. The geometry they move and collide with is derived from the groom (a sphere fitted to
// the roots stands for the head), so the same script works for every groom.
//
//   settle    static head, gravity only
//   shake     head turning +-60 degrees about the vertical at 2 Hz (about the head centre)
//   run       running forward at 3 m/s, head bobbing 4 cm at 2.8 Hz and nodding 8 degrees; capsules for the
//             head (inside the scalp) and the shoulders
//   teleport  static, and every 60 frames a jump of 1 m and 90 degrees in one frame (flagged as a teleport)
//   wind      static head in gusty wind (4 m/s^2, gusts +-80% at 0.5 Hz)
//   hitch     head turning +-60 degrees at 0.7 Hz while walking at 1.5 m/s, frame times alternating 1/60 s and 0.25 s
//   far       shake, 10 km from the world origin
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tressvk/model/math.hpp"
#include "tressvk/model/model.hpp"
#include "tressvk/sim_types.h"

namespace tressvk::reference {

// The reference is written in the runtime model's terms (planner, rest data, math: tressvk::model).
using namespace tressvk::model;

struct SceneGeometry {
  Vec3 head_centre;        // instance space
  double head_radius = 0;  // m
  double inner_radius = 0; // m, the head collider's radius: inside the scalp (90% of the 10th-percentile root distance)
};

// A sphere fitted to the root positions when they cover one cleanly (a scalp); otherwise (e.g. a mohawk strip)
// the point where the root directions converge, with the mean root distance as radius.
SceneGeometry scene_geometry(const ModelRest& rest);

std::vector<std::string> scene_names();
inline constexpr double kSceneFrameDt = 1.0 / 60.0;
inline constexpr double kFarDistance = 10000.0;  // m, the far scene's offset along +X

// Throws std::invalid_argument for an unknown scene name. Bones are not set (rigid head).
TvkSimFrame scene_frame(std::string_view name, uint32_t frame_index, const SceneGeometry& geometry);

// Bone matrices for an asset with bone weights (TvkSimFrame::bones, bind space -> instance space): every bone turns
// about the vertical through the head centre by up to 0.15 rad at 1.5 Hz, each with its own phase (0.37 rad a bone),
// so that strands blending several bones see different motions. origin: the asset's origin (bind space is relative to
// it). Set on a scene's frame, the bones move the hair within the scene's head transform.
std::vector<TvkBoneMatrix> rocking_bones(uint32_t bone_count, const std::array<double, 3>& origin,
                                         uint32_t frame_index, const SceneGeometry& geometry);

}  // namespace tressvk::reference
