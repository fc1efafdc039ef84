#include "scene.hpp"

#include "head.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/groom.hpp>
#include <tressvk/baker/import.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/check.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>

namespace tressvk::demo {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

constexpr double kPi = 3.14159265358979323846;

TvkLight directional(std::array<float, 3> travel, std::array<float, 3> color, float intensity, bool shadowed) {
  TvkLight l{};
  l.type = TVK_LIGHT_DIRECTIONAL;
  for (int i = 0; i < 3; ++i) {
    l.direction[i] = travel[i];
    l.color[i] = color[i];
  }
  l.intensity = intensity;
  l.shadowed = shadowed ? 1u : 0u;
  return l;
}

// One vertical capsule through the middle of the mesh's bounding box, as wide as its narrower horizontal side
// allows: a rough but safe collider for an arbitrary head mesh (documented in docs/rendering.md).
TvkCapsule fit_capsule(const engine::MeshBounds& b) {
  const double cx = 0.5 * (b.min[0] + b.max[0]), cz = 0.5 * (b.min[2] + b.max[2]);
  const double r = 0.45 * std::min(b.max[0] - b.min[0], b.max[2] - b.min[2]);
  const double y0 = std::min(b.min[1] + r, 0.5 * (b.min[1] + b.max[1]));
  const double y1 = std::max(b.max[1] - r, y0);
  TvkCapsule c{};
  c.p0[0] = static_cast<float>(cx);
  c.p0[1] = static_cast<float>(y0);
  c.p0[2] = static_cast<float>(cz);
  c.p1[0] = static_cast<float>(cx);
  c.p1[1] = static_cast<float>(y1);
  c.p1[2] = static_cast<float>(cz);
  c.r0 = c.r1 = static_cast<float>(r);
  return c;
}

void add_capsule(Scene& scene, std::array<float, 3> p0, float r0, std::array<float, 3> p1, float r1,
                 bool collider) {
  scene.head.append(engine::make_capsule_mesh(p0, r0, p1, r1));
  if (!collider) return;
  TvkCapsule c{};
  for (int i = 0; i < 3; ++i) {
    c.p0[i] = p0[i];
    c.p1[i] = p1[i];
  }
  c.r0 = r0;
  c.r1 = r1;
  scene.capsules.push_back(c);
}

}  // namespace

Scene build_scene(const Options& options) {
  Scene scene;
  asset::HairAsset hair;
  const bool head_sample = options.asset.empty() && options.sample == Sample::head;
  if (head_sample) {
    // The bundled sample: the procedural head with a face, and hair grown on its scalp by the groom generator
    // (what `tressvk-bake groom --scalp scalp.obj --preset NAME` does with the exported scalp).
    SampleHead head = make_sample_head();
    baker::GroomParams groom = baker::groom_preset(options.groom);
    groom.guides = options.guides;
    groom.follow = options.follows;
    hair = baker::make_groom(head.scalp, groom, options.groom);
    scene.asset_name = "bundled head, " + options.groom + " groom (" + std::to_string(groom.guides) +
                       " guides x " + std::to_string(1 + groom.follow) + ")";
    scene.asset_bytes = asset::write(hair);
    scene.tip_width_ratio = static_cast<float>(groom.taper);
    scene.head = std::move(head.skin);
    scene.head.append(head.eyes);
    scene.capsules = head.colliders;
    scene.face_landmarks = {head.left_eye, head.right_eye, head.nose_tip, head.mouth, head.chin, head.brow};
    scene.view_direction = {0.42, 0.1, 1.0};
    scene.skin_color = {0.5f, 0.32f, 0.24f};
  } else if (options.asset.empty()) {
    // The bundled sample: long hair grown on the procedural head sphere (r = 0.1 m at the origin), made in memory.
    baker::BuiltinGroomOptions groom;
    groom.guide_count = options.guides;
    groom.follow_per_guide = options.follows;
    groom.vertices_per_strand = 48;
    hair = baker::make_builtin_groom("long128", groom);
    scene.asset_name = "bundled long128 groom (" + std::to_string(groom.guide_count) + " guides x " +
                       std::to_string(1 + groom.follow_per_guide) + ")";
    scene.asset_bytes = asset::write(hair);
  } else if (const std::string ext = lower_extension(options.asset); ext == ".tfx" || ext == ".obj") {
    // Raw curves (TressFX .tfx, OBJ line elements): baked in memory with the baker's defaults and K = 3 follow
    // hairs, so a groom can be looked at before choosing bake options (tressvk-bake for the asset to ship).
    baker::BakeOptions bake{};
    bake.follow_per_guide = 3;
    bake.units_to_metres = options.mesh_scale;
    hair = baker::bake(baker::import_file(options.asset), bake);
    scene.asset_bytes = asset::write(hair);
    scene.asset_name = options.asset + " (baked in memory)";
  } else {
    scene.asset_bytes = baker::read_binary_file(options.asset);
    asset::ReadResult r = asset::read(scene.asset_bytes);
    if (!r.ok()) throw engine::Error(options.asset + ": " + r.error);
    hair = std::move(r.asset);
    scene.asset_name = options.asset;
  }
  const asset::Bounds hb = asset::guide_bounds(hair);
  std::array<double, 3> lo = hb.min, hi = hb.max;

  if (!options.mesh.empty()) {
    scene.head = engine::load_obj_mesh(options.mesh);
    for (engine::MeshVertex& v : scene.head.vertices)
      for (int i = 0; i < 3; ++i) v.position[i] *= options.mesh_scale;
    scene.capsules.push_back(fit_capsule(engine::mesh_bounds(scene.head)));
  } else if (options.asset.empty() && !head_sample) {
    // Head sphere (the scalp the groom grows on, a hair's breadth inside it), neck and nose; the colliders are
    // the same capsules.
    add_capsule(scene, {0, 0, 0}, 0.099f, {0, 0, 0}, 0.099f, true);
    add_capsule(scene, {0, -0.05f, 0.0f}, 0.05f, {0, -0.22f, -0.01f}, 0.045f, true);
    add_capsule(scene, {0, -0.005f, 0.095f}, 0.01f, {0, -0.035f, 0.112f}, 0.014f, false);
  }
  if (!scene.head.vertices.empty()) {
    const engine::MeshBounds mb = engine::mesh_bounds(scene.head);
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], mb.min[i]);
      hi[i] = std::max(hi[i], mb.max[i]);
    }
  }
  double r2 = 0;
  for (int i = 0; i < 3; ++i) {
    scene.center[i] = 0.5 * (lo[i] + hi[i]);
    r2 += 0.25 * (hi[i] - lo[i]) * (hi[i] - lo[i]);
  }
  scene.radius = std::sqrt(r2);
  if (head_sample) {
    // Frame the head and the hair to the shoulders, not the whole torso.
    scene.center = {0.0, -0.06, 0.0};
    scene.radius = 0.21;
  }

  // Strand width from the groom's density: about as wide as the spacing of the strands drawn over the scalp
  // would need to cover it twice, kept between 0.15 mm and 1.2 mm.
  double median = 0;
  {
    std::vector<double> lengths;
    const uint32_t n = hair.vertices_per_strand;
    for (uint32_t g = 0; g < hair.guide_count(); ++g) {
      double len = 0;
      for (uint32_t v = 0; v + 1 < n; ++v) len += hair.rest_lengths[size_t{g} * n + v];
      lengths.push_back(len);
    }
    std::nth_element(lengths.begin(), lengths.begin() + static_cast<long>(lengths.size() / 2), lengths.end());
    median = lengths.empty() ? 0.1 : lengths[lengths.size() / 2];
  }
  scene.hair_length = static_cast<float>(median);
  const double extent = std::max({hb.max[0] - hb.min[0], hb.max[2] - hb.min[2], 1e-3});
  const double spacing = extent * kPi / std::sqrt(static_cast<double>(hair.total_strands()));
  scene.strand_width = static_cast<float>(std::clamp(0.35 * spacing, 0.00015, 0.002));

  // Floor a little below the lowest point.
  if (head_sample) scene.strand_width = std::min(scene.strand_width, 0.0005f);
  const float floor_y = static_cast<float>(lo[1] - 0.05 * scene.radius);
  scene.floor = engine::make_floor_mesh(
      {static_cast<float>(scene.center[0]), floor_y, static_cast<float>(scene.center[2])},
      static_cast<float>(4.0 * scene.radius));

  // Key light (shadowed) from the upper front left, a warm fill spot from the right, a cool rim from behind.
  scene.lights.push_back(directional({0.45f, -0.75f, -0.5f}, {1.0f, 0.96f, 0.9f}, 2.2f, options.shadows));
  TvkLight fill{};
  fill.type = TVK_LIGHT_SPOT;
  const double fr = 3.0 * scene.radius;
  fill.position[0] = scene.center[0] + fr;
  fill.position[1] = scene.center[1] + 0.3 * fr;
  fill.position[2] = scene.center[2] + 0.9 * fr;
  for (int i = 0; i < 3; ++i) fill.direction[i] = static_cast<float>(scene.center[i] - fill.position[i]);
  fill.color[0] = 1.0f;
  fill.color[1] = 0.85f;
  fill.color[2] = 0.7f;
  fill.intensity = static_cast<float>(0.9 * fr * fr);  // ~0.9 at the head
  fill.inner_cone = 0.35f;
  fill.outer_cone = 0.6f;
  scene.lights.push_back(fill);
  scene.lights.push_back(directional({0.2f, -0.3f, 1.0f}, {0.6f, 0.7f, 1.0f}, 0.9f, false));
  if (head_sample) {
    // Three-point light for the face: key from above the camera's left, a weaker warm fill from its right, a
    // strong cool rim from behind and above that outlines the hair.
    scene.lights[0] = directional({0.55f, -0.6f, -0.7f}, {1.0f, 0.95f, 0.88f}, 2.0f, options.shadows);
    scene.lights[1].intensity *= 0.55f;
    scene.lights[2] = directional({-0.35f, -0.5f, 1.0f}, {0.65f, 0.75f, 1.0f}, 1.8f, false);
  }
  return scene;
}

TvkWind wind_at(Animation animation, double t, const TvkWind& base) {
  TvkWind w = base;
  const float strength = base.strength;
  if (animation == Animation::showcase) {
    // A gust from the front and the camera's right, rising and falling around t = 2.1 s (as the turn ends),
    // on top of any --wind.
    const double g = std::exp(-std::pow((t - 2.1) / 0.45, 2.0));
    if (9.0 * g > strength) {  // the gust's direction while it is the stronger
      w.direction[0] = -0.35f;
      w.direction[1] = 0.1f;
      w.direction[2] = -1.0f;
    }
    w.strength = strength + static_cast<float>(9.0 * g);
  }
  return w;
}

TvkInstanceTransform animate(Animation animation, double t) {
  TvkInstanceTransform x = TVK_INSTANCE_TRANSFORM_DEFAULT_INIT;
  double yaw = 0, pitch = 0;
  switch (animation) {
    case Animation::none: break;
    case Animation::turn: yaw = 0.8 * std::sin(2 * kPi * t / 3.0); break;
    case Animation::showcase: {
      // Still for 0.3 s (the hair settles), then one look to each side and back over 1.6 s, then still.
      const double u = std::clamp((t - 0.3) / 1.6, 0.0, 1.0);
      yaw = 0.6 * std::sin(2 * kPi * u) * std::sin(kPi * u);
      break;
    }
    case Animation::shake: yaw = 0.45 * std::sin(2 * kPi * 2.5 * t); break;
    case Animation::run:
      x.translation[0] = 2.5 * t;
      x.translation[1] = 0.03 * std::abs(std::sin(2 * kPi * 1.4 * t));
      pitch = 0.12;
      yaw = 0.5 * kPi;  // facing the direction of travel
      break;
  }
  // q = yaw about y, then pitch about x.
  const double cy = std::cos(0.5 * yaw), sy = std::sin(0.5 * yaw);
  const double cp = std::cos(0.5 * pitch), sp = std::sin(0.5 * pitch);
  x.rotation[0] = cy * sp;
  x.rotation[1] = sy * cp;
  x.rotation[2] = -sy * sp;
  x.rotation[3] = cy * cp;
  return x;
}

}  // namespace tressvk::demo
