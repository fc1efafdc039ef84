// Does the double reference come to rest? A groom (built-in, or a baked .tvkhair) settles under a still head for
// `frames` frames at the default settings; then prints, per guide, the largest move of a vertex per step over the
// next frame relative to the median strand length (quantiles), and the guides that move most with their length,
// segments and group. The GPU's sleeping (TvkSimSettings::sleep_below) needs the model at rest to be still; a guide
// the double model keeps moving is the model's, not float32's. Diagnostic, not a test:
//   tressvk_rest_probe curly 64 1500 [ITERATIONS [LOCAL_STIFFNESS [DAMPING]]]
//   tressvk_rest_probe path/to/groom.tvkhair 0 1500
// TVK_GLOBAL and TVK_GLOBAL_RANGE set global_stiffness and global_range; TVK_STEP_RATE sets the step rate (Hz); TVK_GRAVITY_Y sets gravity's y (9.81: hair hanging against its groom, as under a head upside down); TVK_DUMP_GUIDE=G
// prints guide G's shape at rest, per edge: pinned or free, its rest bend to the next edge and the angle between its
// current and its rest direction. TVK_ONLY_GUIDES=G1,G2,... simulates only those guides of the groom (a strand does
// not interact with the others; short strands are still carried rigidly by the whole groom's median), in seconds
// where the whole Ratboy takes minutes. TVK_SAVE_POSE=FILE writes the settled guide vertices; TVK_COMPARE_POSE=FILE
// prints how far they are from another run's (rms, largest, mean tip height; docs/accuracy.md "The settled look
// against the settings").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "helpers.hpp"

#include <tressvk/asset_io.hpp>

int main(int argc, char** argv) {
  using namespace tvk_test;
  const std::string name = argc > 1 ? argv[1] : "curly";
  const uint32_t guides = argc > 2 ? static_cast<uint32_t>(std::atoi(argv[2])) : 64;
  const uint32_t frames = argc > 3 ? static_cast<uint32_t>(std::atoi(argv[3])) : 1500;
  const uint32_t iterations = argc > 4 ? static_cast<uint32_t>(std::atoi(argv[4])) : 2;
  const float local_stiffness = argc > 5 ? static_cast<float>(std::atof(argv[5])) : -1.0f;  // < 0: the default
  const float damping = argc > 6 ? static_cast<float>(std::atof(argv[6])) : -1.0f;
  tressvk::asset::HairAsset a;
  if (name.find(".tvkhair") != std::string::npos) {
    tressvk::asset::ReadResult r = tressvk::asset::read_file(name);
    if (!r.ok()) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), r.error.c_str());
      return 1;
    }
    a = std::move(r.asset);
  } else {
    a = groom(name, guides, 0);
  }
  double whole_median = -1.0;  // the whole groom's median strand length, when only some guides are kept
  if (const char* only = std::getenv("TVK_ONLY_GUIDES")) a = only_guides(a, only, whole_median);
  TvkSimParams p = default_params();
  if (whole_median > 0.0) p.rigid_below = static_cast<float>(0.45 * whole_median);
  p.local_iterations = iterations;
  if (local_stiffness >= 0.0f) p.local_stiffness = local_stiffness;
  if (damping >= 0.0f) p.damping = damping;
  if (const char* e = std::getenv("TVK_GLOBAL")) p.global_stiffness = static_cast<float>(std::atof(e));
  if (const char* e = std::getenv("TVK_GLOBAL_RANGE")) p.global_range = static_cast<float>(std::atof(e));
  std::vector<TvkSimParams> params(std::max<size_t>(1, a.groups.size()), p);
  TvkSimSettings settings = default_settings();
  if (const char* gy = std::getenv("TVK_GRAVITY_Y")) settings.gravity[1] = static_cast<float>(std::atof(gy));
  if (const char* r = std::getenv("TVK_STEP_RATE")) settings.time.step_rate = static_cast<float>(std::atof(r));
  Simulator sim(a, params, settings);
  const SceneGeometry geo = scene_geometry(sim.rest());
  for (uint32_t f = 0; f < frames; ++f) sim.advance(scene_frame("settle", f, geo));
  const std::vector<Vec3> before(sim.positions().begin(), sim.positions().end());
  if (const char* save = std::getenv("TVK_SAVE_POSE")) {
    if (std::FILE* f = std::fopen(save, "wb")) {
      std::fwrite(before.data(), sizeof(Vec3), before.size(), f);
      std::fclose(f);
    }
  }
  if (const char* other = std::getenv("TVK_COMPARE_POSE")) {
    // The settled pose against another run's (TVK_SAVE_POSE): rms and max vertex distance and the mean tip height
    // difference, relative to the median strand length.
    std::vector<Vec3> them(before.size());
    std::FILE* f = std::fopen(other, "rb");
    const size_t got = f ? std::fread(them.data(), sizeof(Vec3), them.size(), f) : 0;
    if (f) std::fclose(f);
    if (got == them.size()) {
      const uint32_t nn = sim.rest().vertices_per_strand;
      double sum = 0, worst = 0, tip = 0;
      for (size_t i = 0; i < them.size(); ++i) {
        const double d = length(before[i] - them[i]);
        sum += d * d;
        worst = std::max(worst, d);
        if (i % nn == nn - 1) tip += before[i].y - them[i].y;
      }
      const double med = sim.rest().median_length;
      std::printf("pose against %s: rms %.3g, max %.3g, mean tip height %+.3g (of the median strand length)\n", other,
                  std::sqrt(sum / static_cast<double>(them.size())) / med, worst / med,
                  tip / (static_cast<double>(them.size()) / nn) / med);
    }
  }
  const FramePlan plan = sim.advance(scene_frame("settle", frames, geo));
  if (const char* dump = std::getenv("TVK_DUMP_GUIDE")) {
    const uint32_t g = static_cast<uint32_t>(std::atoi(dump)), n = sim.rest().vertices_per_strand;
    const auto degrees = [](Vec3 x, Vec3 y) {
      return std::acos(std::clamp(dot(x, y) / (length(x) * length(y)), -1.0, 1.0)) * 180.0 / 3.14159265358979;
    };
    std::printf("guide %u at rest, edge by edge:\n", g);
    for (uint32_t v = 0; v + 1 < n; ++v) {
      const size_t i = size_t{g} * n + v;
      const Vec3 rest = sim.rest().rest_pos[i + 1] - sim.rest().rest_pos[i];
      const Vec3 now = sim.positions()[i + 1] - sim.positions()[i];
      const double bend = v + 2 < n ? degrees(rest, sim.rest().rest_pos[i + 2] - sim.rest().rest_pos[i + 1]) : 0.0;
      std::printf("  edge %2u (vertex %s): rest bend to the next %5.1f deg, now %5.1f deg from its rest direction\n", v,
                  sim.rest().inv_mass[i] > 0.0 ? "free" : "pinned", bend, degrees(rest, now));
    }
  }
  const uint32_t n = sim.rest().vertices_per_strand, g_count = sim.rest().guide_count;
  const double median = sim.rest().median_length;
  const double steps = static_cast<double>(plan.steps.size());
  struct Row { double move; uint32_t g; };
  std::vector<Row> rows;
  for (uint32_t g = 0; g < g_count; ++g) {
    double m = 0;
    for (uint32_t v = 0; v < n; ++v) m = std::max(m, length(sim.positions()[g * n + v] - before[g * n + v]));
    rows.push_back({m / steps / median, g});
  }
  std::sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) { return x.move < y.move; });
  std::printf("%s: %u guides x %u vertices, %u local iterations (stiffness %g, damping %g), after %u frames (%.1f s) "
              "of settle: move per step / median strand length\n", name.c_str(), g_count, n, iterations,
              static_cast<double>(p.local_stiffness), static_cast<double>(p.damping), frames, frames / 60.0);
  for (double q : {0.0, 0.5, 0.9, 0.99, 0.999, 1.0})
    std::printf("  q%-5g %.3g\n", q, rows[static_cast<size_t>(q * static_cast<double>(rows.size() - 1))].move);
  size_t above = 0;
  for (const Row& r : rows) above += r.move > 1e-6 ? 1 : 0;
  std::printf("  guides above 1e-6 (the default sleep_below): %zu\n", above);
  // Oscillating or drifting: the same guides' largest net move over the next second (60 frames).
  const std::vector<Vec3> at(sim.positions().begin(), sim.positions().end());
  for (uint32_t f = 1; f <= 60; ++f) sim.advance(scene_frame("settle", frames + f, geo));
  const auto net = [&](uint32_t g) {
    double m = 0;
    for (uint32_t v = 0; v < n; ++v) m = std::max(m, length(sim.positions()[g * n + v] - at[g * n + v]));
    return m / median;
  };
  for (size_t k = 0; k < std::min<size_t>(8, rows.size()); ++k) {
    const Row& r = rows[rows.size() - 1 - k];
    double shortest = 1e30;
    for (uint32_t v = 0; v + 1 < n; ++v) shortest = std::min(shortest, sim.rest().rest_length[r.g * n + v]);
    std::printf("  guide %u: move %.3g per step, net over the next second %.3g; length %.4g m (%.2f x median), shortest "
                "segment %.3g m, group %u\n", r.g, r.move, net(r.g), sim.rest().strand_length[r.g],
                sim.rest().strand_length[r.g] / median, shortest, sim.rest().group[r.g]);
  }
  return 0;
}
