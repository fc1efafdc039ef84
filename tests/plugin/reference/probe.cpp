// Prints, per built-in groom and scene, what the reference does at default settings: stretch, NaN and exploded
// strands, and the largest distance of a vertex from its rest pose. Diagnostic only.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "helpers.hpp"

int main(int argc, char** argv) {
  using namespace tvk_test;
  const uint32_t frames = argc > 1 ? static_cast<uint32_t>(std::atoi(argv[1])) : 240;
  const uint32_t guides = argc > 2 ? static_cast<uint32_t>(std::atoi(argv[2])) : 256;
  for (const char* name : {"straight", "curly", "long128"}) {
    auto a = groom(name, guides, 1);
    for (const std::string& scene : scene_names()) {
      Simulator sim = make_sim(a);
      SceneGeometry geo = scene_geometry(sim.rest());
      double smax = 0, smean = 0;
      HealthStats worst;
      for (uint32_t f = 0; f < frames; ++f) {
        sim.advance(scene_frame(scene, f, geo));
        StretchStats s = stretch(sim.positions(), sim.rest());
        smax = std::max(smax, s.max);
        smean += s.mean / frames;
        HealthStats h = health(sim.positions(), sim.rest());
        worst.nan_strands = std::max(worst.nan_strands, h.nan_strands);
        worst.exploded_strands = std::max(worst.exploded_strands, h.exploded_strands);
      }
      std::printf("%-9s %-9s stretch mean %.4f max %.4f nan %u exploded %u resets %llu (head r %.3f)\n", name,
                  scene.c_str(), smean, smax, worst.nan_strands, worst.exploded_strands,
                  static_cast<unsigned long long>(sim.nonfinite_resets()), geo.head_radius);
    }
  }
  return 0;
}
