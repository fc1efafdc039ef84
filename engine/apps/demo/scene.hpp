// The demo's scene: the hair asset (bundled procedural groom or a .tvkhair file), the head mesh (procedural, or
// an OBJ) with capsule colliders that fit it, a floor, lights, the camera framing, and the head's motion.
#pragma once

#include "demo_options.hpp"

#include <tressvk/engine/mesh.hpp>
#include <tressvk/tressvk.h>

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace tressvk::demo {

struct Scene {
  std::vector<std::byte> asset_bytes;   // a .tvkhair file's bytes
  std::string asset_name;
  engine::Mesh head;                    // instance space (asset coordinates); moves with the instance
  engine::Mesh floor;                   // world
  std::vector<TvkCapsule> capsules;     // instance space, the same shapes as the head mesh (procedural) or fitted
  std::vector<TvkLight> lights;         // [0] is the shadowed key light
  std::array<double, 3> center{};       // framed centre, instance space
  double radius = 0.5;                  // m, bounding radius of hair + head around `center`
  float strand_width = 0.0006f;         // m, scaled with the groom
  float hair_length = 0.5f;             // m, median strand length (scale for everything relative)
  float tip_width_ratio = -1.0f;        // the groom's taper when it records one (< 0: the material default)
  std::array<double, 3> view_direction{0.9, 0.12, 0.75};  // from the framed centre towards the camera
  glm::vec3 skin_color{0.45f, 0.32f, 0.26f};
  // The bundled head's face (instance space): eyes, nose tip, mouth, chin, brow. Empty for other scenes.
  std::vector<std::array<float, 3>> face_landmarks;
};

// The frame's wind for the animation at time t: `base` (the parameter file's, or --wind), plus the showcase's gust.
TvkWind wind_at(Animation animation, double t, const TvkWind& base);

// Builds the scene the options ask for. Throws engine::Error (naming the file) on unreadable input.
Scene build_scene(const Options& options);

// The instance's rigid transform at time t (seconds) for the animation.
TvkInstanceTransform animate(Animation animation, double t);

}  // namespace tressvk::demo
