// Conditioning probe: how much one frame of the double-precision model amplifies float32-sized input noise.
// Two reference simulators advance the same scene; before each frame both load the first one's state rounded to
// float (as the GPU holds it), the second with every coordinate moved by one float ulp in a random direction. The
// largest vertex distance after the frame, over the median strand length, is a CPU proxy for the GPU step error.
// Diagnostic only: usage conditioning_probe (FILE.tfx [FILE.tfxbone] | straight|curly|long128) [frames] [scenes...]
// Environment: PROBE_PASSES=1 replays the worst frame pass by pass (PROBE_GUIDE=g: show guide g's segments);
// PROBE_DETAIL=1 shows the worst strand; PROBE_NOCAPS=1 drops capsules; PROBE_VSP, PROBE_LOCAL, PROBE_GLOBAL,
// PROBE_VSP_THRESHOLD, PROBE_MAX_SPEED, PROBE_LIT (local iterations), PROBE_DAMPING override parameters; PROBE_FIRST=1
// probes the first frame too (below); PROBE_PIN_TIPS=1 pins every other guide's tip too (TressFX 3's
// bothEndsImmovable, as the simulation tests' strands pinned at both ends); PROBE_GUIDES=G builds G guides;
// PROBE_RESET_PRE=S moves the first frame's reset pose by S ulps of each offset from the strand's root before the
// reset step's passes instead (what the GPU's skinned rest pose carries); PROBE_STEP_ULP=S moves every position by S
// ulps after each step too (the rounding inside a frame); PROBE_MAX_STEPS caps the steps a frame; PROBE_SEED seeds
// the ulps' directions.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/import.hpp>

#include "helpers.hpp"

using namespace tvk_test;

namespace {
// Parameter overrides for experiments: PROBE_VSP, PROBE_LOCAL (stiffness), PROBE_GLOBAL (stiffness).
// PROBE_RATE overrides the step rate (Hz).
TvkSimSettings probe_settings() {
  TvkSimSettings s = TVK_SIM_SETTINGS_DEFAULT_INIT;
  if (const char* e = std::getenv("PROBE_RATE")) s.time.step_rate = std::strtof(e, nullptr);
  if (const char* e = std::getenv("PROBE_MAX_STEPS")) s.time.max_steps_per_frame = static_cast<uint32_t>(std::atoi(e));
  return s;
}

TvkSimParams probe_params() {
  TvkSimParams p = default_params();
  if (const char* e = std::getenv("PROBE_VSP")) p.vsp_coefficient = std::strtof(e, nullptr);
  if (const char* e = std::getenv("PROBE_LOCAL")) p.local_stiffness = std::strtof(e, nullptr);
  if (const char* e = std::getenv("PROBE_GLOBAL")) p.global_stiffness = std::strtof(e, nullptr);
  if (const char* e = std::getenv("PROBE_VSP_THRESHOLD")) p.vsp_threshold = std::strtof(e, nullptr);
  if (const char* e = std::getenv("PROBE_MAX_SPEED")) p.max_speed = std::strtof(e, nullptr);
  if (const char* e = std::getenv("PROBE_LIT")) p.local_iterations = static_cast<uint32_t>(std::atoi(e));
  if (const char* e = std::getenv("PROBE_DAMPING")) p.damping = std::strtof(e, nullptr);
  return p;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s (FILE.tfx [FILE.tfxbone] | builtin) [frames] [scenes...]\n", argv[0]);
    return 2;
  }
  std::string src = argv[1];
  int arg = 2;
  tressvk::asset::HairAsset hair;
  if (src.size() > 4 && src.substr(src.size() - 4) == ".tfx") {
    tressvk::baker::RawGroom raw = tressvk::baker::import_tfx(src);
    if (argc > 2 && std::string(argv[2]).find(".tfxbone") != std::string::npos) {
      tressvk::baker::apply_tfxbone(raw, argv[2]);
      arg = 3;
    }
    tressvk::baker::BakeOptions options;
    options.follow_per_guide = 2;
    hair = tressvk::baker::bake(raw, options);
  } else {
    const char* guides = std::getenv("PROBE_GUIDES");
    hair = groom(src, guides ? static_cast<uint32_t>(std::atoi(guides)) : (src == "long128" ? 16u : 32u),
                 src == "straight" ? 1 : 0);
  }
  if (std::getenv("PROBE_PIN_TIPS") != nullptr) {
    const uint32_t n = hair.vertices_per_strand;
    for (uint32_t g = 0; g < hair.guide_count(); g += 2) hair.rest_positions[size_t{g} * n + n - 1][3] = 0.0f;
  }
  const uint32_t frames = argc > arg ? static_cast<uint32_t>(std::atoi(argv[arg])) : 40;
  std::vector<std::string> scenes;
  for (int i = arg + 1; i < argc; ++i) scenes.emplace_back(argv[i]);
  if (scenes.empty()) scenes = scene_names();
  for (const std::string& scene : scenes) {
    // PROBE_FIRST=1: the first frame as well. It starts from the skinned rest (each simulator resets to it), so the
    // second one's groom has every rest coordinate moved by one float ulp instead: the GPU computes that start in
    // float, the reference in double.
    tressvk::asset::HairAsset hair_b = hair;
    const bool first = std::getenv("PROBE_FIRST") != nullptr;
    if (first) {
      std::mt19937 jitter(11);
      for (auto& p : hair_b.rest_positions)
        for (int c = 0; c < 3; ++c) p[c] = std::nextafter(p[c], (jitter() & 1u) ? INFINITY : -INFINITY);
    }
    Simulator a = make_sim(hair, probe_params(), probe_settings()), b = make_sim(hair_b, probe_params(), probe_settings());
    const SceneGeometry geo = scene_geometry(a.rest());
    const double median = a.median_strand_length();
    std::mt19937 rng(std::getenv("PROBE_SEED") ? static_cast<unsigned>(std::atoi(std::getenv("PROBE_SEED"))) : 7u);
    // A simulator's guide positions with each offset from its strand's root moved by `scale` float ulps, up or down.
    const auto moved_by_ulps = [&rng](const Simulator& sim, double scale) {
      const size_t nn = sim.rest().vertices_per_strand;
      std::vector<Vec3> out(sim.positions().begin(), sim.positions().end());
      for (size_t i = 0; i < size_t{sim.rest().guide_count} * nn; ++i) {
        const Vec3 root = sim.positions()[i / nn * nn];
        for (int c = 0; c < 3; ++c) {
          const float x = static_cast<float>(out[i][c] - root[c]);
          const double d = static_cast<double>(std::nextafter(x, INFINITY)) - static_cast<double>(x);
          out[i][c] += ((rng() & 1u) ? scale : -scale) * d;
        }
      }
      return out;
    };
    double worst = 0;
    uint32_t worst_frame = 0;
    size_t worst_vertex = 0;
    for (uint32_t f = 0; f < frames; ++f) {
      TvkSimFrame frame = scene_frame(scene, f, geo);
      if (std::getenv("PROBE_NOCAPS") != nullptr) frame.capsule_count = 0;
      if (f > 0) {
        // PROBE_RELATIVE=1: the state held as a float anchor per strand (its root) plus float offsets from it.
        const bool relative = std::getenv("PROBE_RELATIVE") != nullptr;
        const size_t nn = a.rest().vertices_per_strand;
        auto pack = [&](std::span<const Vec3> s, bool jitter) {
          std::vector<Vec3> out(s.size());
          for (size_t i = 0; i < s.size(); ++i) {
            const Vec3 root = s[(i / nn) * nn];
            for (int c = 0; c < 3; ++c) {
              const double anchor = relative ? static_cast<double>(static_cast<float>(root[c])) : 0.0;
              float x = static_cast<float>(s[i][c] - anchor);
              if (jitter) x = std::nextafter(x, (rng() & 1u) ? INFINITY : -INFINITY);
              out[i][c] = anchor + static_cast<double>(x);
            }
          }
          return out;
        };
        const auto p = pack(a.positions(), false), q = pack(a.prev_positions(), false), r = pack(a.prevprev_positions(), false);
        auto pj = pack(a.positions(), true), qj = pack(a.prev_positions(), true), rj = pack(a.prevprev_positions(), true);
        if (std::getenv("PROBE_ANCHOR") != nullptr) {
          // The GPU's anchor rounding alone: every strand (with its history) moved rigidly by its root's float
          // rounding, as a state read back as float anchor + offsets is; compared below after removing the new
          // anchor's rounding, which the GPU adds to its result.
          const size_t guides = a.rest().guide_count;
          pj = p;
          qj = q;
          rj = r;
          for (std::vector<Vec3>* v : {&pj, &qj, &rj}) {
            for (size_t i = 0; i < v->size(); ++i) {
              const Vec3 root = p[((i / nn) % guides) * nn];
              for (int c = 0; c < 3; ++c) (*v)[i][c] += static_cast<double>(static_cast<float>(root[c])) - root[c];
            }
          }
        }
        a.set_state(p, q, r);
        b.set_state(pj, qj, rj);
      }
      a.advance(frame);
      if (f == 0 && std::getenv("PROBE_RESET_PRE") != nullptr) {
        // The reset pose's rounding before the reset step's passes (a capsule's push, the length solve): the skinned
        // rest pose with each offset from its strand's root moved by S float ulps (positions and histories alike), then
        // the reset step's passes as a plain step from it (no velocity, no gravity, which a reset step does not apply;
        // the global pull draws the moved pose a fraction back; 0 reproduces the first simulator's frame), then the
        // frame's other steps.
        const double scale = std::strtod(std::getenv("PROBE_RESET_PRE"), nullptr);
        FramePlan plan = b.planner().plan(frame);
        b.integrate(plan.steps.front());  // the reset: every vertex at its skinned rest pose
        const std::vector<Vec3> pj = moved_by_ulps(b, scale);
        b.set_state(std::span<const Vec3>(pj), std::span<const Vec3>(pj), std::span<const Vec3>(pj));
        plan.steps.front().reset = false;
        plan.steps.front().gravity_h2 = Vec3{};
        b.simulate(plan);
      } else if (const char* step_ulp = std::getenv("PROBE_STEP_ULP")) {
        // Rounding inside the frame too: the second simulator runs the frame's steps one at a time and, after each,
        // moves every position's offset from its strand's root by S float ulps up or down (a float32 kernel rounds
        // its state at every step; the histories it keeps are copies of rounded positions).
        const double scale = std::strtod(step_ulp, nullptr);
        const FramePlan plan = b.planner().plan(frame);
        for (size_t k = 0; k < plan.steps.size(); ++k) {
          FramePlan one;
          one.steps.push_back(plan.steps[k]);
          b.simulate(one);  // (and the follow pass after each step: it only reads the guides)
          const std::vector<Vec3> pj = moved_by_ulps(b, scale);
          b.set_state(std::span<const Vec3>(pj), b.prev_positions(), b.prevprev_positions());
        }
      } else {
        b.advance(frame);
      }
      const auto pa = a.positions(), pb = b.positions();
      const bool anchor_probe = std::getenv("PROBE_ANCHOR") != nullptr;
      const size_t n_per = a.rest().vertices_per_strand, g_count = a.rest().guide_count;
      for (size_t i = 0; i < pa.size(); ++i) {
        Vec3 e1{};
        if (anchor_probe) {
          const Vec3 root = pa[((i / n_per) % g_count) * n_per];
          for (int c = 0; c < 3; ++c) e1[c] = static_cast<double>(static_cast<float>(root[c])) - root[c];
        }
        const double d = length(pa[i] + e1 - pb[i]) / median;
        if (d > worst) {
          worst = d;
          worst_frame = f;
          worst_vertex = i;
        }
      }
    }
    if (std::getenv("PROBE_PASSES") != nullptr) {
      // Replay to the worst frame twice (clean, and with the same 1-ulp jitter), then step the passes one by one
      // and print the largest response after each: where the model amplifies.
      Simulator c = make_sim(hair, probe_params(), probe_settings());
      for (uint32_t f = 0; f < worst_frame; ++f) c.advance(scene_frame(scene, f, geo));
      std::mt19937 rng2(11);
      auto pack2 = [&](std::span<const Vec3> s2, bool jitter) {
        std::vector<tressvk::sim::Vec4> out(s2.size());
        for (size_t i = 0; i < s2.size(); ++i) {
          for (int k = 0; k < 3; ++k) {
            float x = static_cast<float>(s2[i][k]);
            if (jitter) x = std::nextafter(x, (rng2() & 1u) ? INFINITY : -INFINITY);
            out[i][static_cast<size_t>(k)] = x;
          }
        }
        return out;
      };
      Simulator d = c;
      d.set_state(pack2(c.positions(), true), pack2(c.prev_positions(), true), pack2(c.prevprev_positions(), true));
      c.set_state(pack2(c.positions(), false), pack2(c.prev_positions(), false), pack2(c.prevprev_positions(), false));
      Simulator e = c;
      const FramePlan plan = e.advance(scene_frame(scene, worst_frame, geo));
      auto report = [&](const char* what, size_t k) {
        double m = 0, mv = 0;
        size_t am = 0;
        for (size_t i = 0; i < c.prev_positions().size(); ++i) {
          const double di = length(c.positions()[i] - d.positions()[i]) / median;
          if (di > m) am = i;
          m = std::max(m, di);
          mv = std::max(mv, length((c.positions()[i] - c.prev_positions()[i]) - (d.positions()[i] - d.prev_positions()[i])) / median);
        }
        std::printf("  step %zu %-12s pos %.3g vel %.3g (vertex %zu)\n", k, what, m, mv, am);
      };
      for (size_t k = 0; k < plan.steps.size(); ++k) {
        const Substep& stp = plan.steps[k];
        c.integrate(stp); d.integrate(stp); report("integrate", k);
        c.vsp(stp); d.vsp(stp); report("vsp", k);
        c.local_shape(stp); d.local_shape(stp); report("local_shape", k);
        if (k + 1 == plan.steps.size()) {
          const uint32_t nn = c.rest().vertices_per_strand;
          // The worst vertex's guide, or the one named by PROBE_GUIDE: its segments before the length pass.
          const size_t gg = (worst_vertex / nn) % c.rest().guide_count;
          const size_t g2 = std::getenv("PROBE_GUIDE") ? static_cast<size_t>(std::atoi(std::getenv("PROBE_GUIDE"))) : gg;
          for (uint32_t v = 0; v + 1 < nn; ++v) {
            const size_t i = g2 * nn + v;
            const Vec3 dd = c.positions()[i + 1] - c.positions()[i];
            const Vec3 was = c.prev_positions()[i + 1] - c.prev_positions()[i];
            std::string caps;
            for (uint32_t cc = 0; cc < stp.capsule_count; ++cc) {
              const CapsuleSim& cap = stp.capsules[cc];
              const Vec3 axis = cap.p1 - cap.p0;
              const double aa = dot(axis, axis);
              const double t = aa > 0.0 ? std::clamp(dot(c.positions()[i] - cap.p0, axis) / aa, 0.0, 1.0) : 0.0;
              const double rr = cap.r0 + t * (cap.r1 - cap.r0);
              caps += " " + std::to_string(length(c.positions()[i] - (cap.p0 + t * axis)) / rr);
            }
            std::printf("    v%2u rest %.3g len %.3g caps%s cos(was) %.3f diff %.3g\n", v, c.rest().rest_length[i], length(dd), caps.c_str(),
                        dot(dd, was) / (length(dd) * length(was) + 1e-30), length(c.positions()[i + 1] - d.positions()[i + 1]) / median);
          }
        }
        c.length_and_collision(stp); d.length_and_collision(stp); report("length", k);
      }
    }
    const auto st = stretch(a.positions(), a.rest());
    if (std::getenv("PROBE_DETAIL") != nullptr) {
      // Replay to the worst frame and show that strand: rest and current segment lengths around the vertex.
      Simulator c = make_sim(hair, probe_params(), probe_settings());
      for (uint32_t f = 0; f <= worst_frame; ++f) c.advance(scene_frame(scene, f, geo));
      const uint32_t n = c.rest().vertices_per_strand;
      const size_t g = (worst_vertex / n) % c.rest().guide_count, sb = g * n;
      std::printf("  guide %zu v %zu: strand %.4g m (median %.4g)\n", g, worst_vertex % n, c.rest().strand_length[g], median);
      for (uint32_t v = 0; v + 1 < n; ++v) {
        std::printf("   %2u rest %.3g len %.3g w %.0f\n", v, c.rest().rest_length[sb + v],
                    length(c.positions()[sb + v + 1] - c.positions()[sb + v]), c.rest().inv_mass[sb + v]);
      }
    }
    std::printf("%-9s response %.3g (frame %u, vertex %zu), stretch max %.4f, rigid strands %u of %u\n", scene.c_str(),
                worst, worst_frame, worst_vertex, st.max, a.rest().rigid_strands, a.rest().guide_count);
  }
  return 0;
}
