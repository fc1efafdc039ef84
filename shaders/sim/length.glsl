// The length pass's per-strand math (see length.comp), shared by the pass-per-dispatch shader and the fused frame
// kernel. write_tangents: the fused kernel writes tangents after its last substep only.
#ifndef TRESSVK_SIM_LENGTH_GLSL
#define TRESSVK_SIM_LENGTH_GLSL
#include "sim/common.glsl"

bool finite3(vec3 x) { return !any(isnan(x)) && !any(isinf(x)); }

// The (unnormalised) direction a length constraint restores along (twin: blended_direction in the reference): the
// segment d itself, except that a compressed or flipped segment is blended with its direction at the previous step
// (was) by the missing length (and the fold guard), which stays defined as the segment vanishes.
vec3 blended_direction(vec3 d, vec3 was, float rest) {
  float len = length(d);
  vec3 dir = d;
  float wl = length(was);
  if (wl > kDirectionEps * rest) {
    vec3 u = was / wl;
    float blend = max(kCollapse * rest - len, 0.0) + fold_guard(d, len, u);
    if (blend > 0.0) dir = d + blend * u;
  }
  return dir;
}
// The same as a unit vector; zero when no direction is defined.
vec3 constraint_direction(vec3 d, vec3 was, float rest) {
  vec3 dir = blended_direction(d, was, rest);
  float dl = length(dir);
  return dl > 0.0 ? dir / dl : vec3(0.0);
}

// Segment v of the strand at b, through memory, with end weights wa (root-ward) and wb (tip-ward); positions only.
void length_segment(uint b, uint v, float wa, float wb) {
  float wsum = wa + wb;
  if (!(wsum > 0.0)) return;
  vec4 x = TVK_POS(b + v * TVK_BLOCK);
  vec4 y = TVK_POS(b + (v + 1u) * TVK_BLOCK);
  vec3 d = y.xyz - x.xyz;
  float rest = rest_info[b + v * TVK_BLOCK].x;
  vec3 dir = blended_direction(d, TVK_PREV(b + (v + 1u) * TVK_BLOCK).xyz - TVK_PREV(b + v * TVK_BLOCK).xyz, rest);
  float dl = length(dir);
  if (!(dl > 0.0)) return;
  vec3 corr = (d - (rest / dl) * dir) / wsum;
  if (wa > 0.0) TVK_POS(b + v * TVK_BLOCK) = vec4(x.xyz + wa * corr, x.w);
  if (wb > 0.0) TVK_POS(b + (v + 1u) * TVK_BLOCK) = vec4(y.xyz - wb * corr, y.w);
}

float free_weight(uint b, uint v) { return TVK_POS(b + v * TVK_BLOCK).w > 0.0 ? 1.0 : 0.0; }

// Gradient of segment v's constraint now, and the direction its correction moves along (midway between the start of
// the step and now; the gradient when the two differ by more than 60 degrees).
vec3 segment_grad(uint b, uint v) {
  return constraint_direction(TVK_POS(b + (v + 1u) * TVK_BLOCK).xyz - TVK_POS(b + v * TVK_BLOCK).xyz,
                              TVK_PREV(b + (v + 1u) * TVK_BLOCK).xyz - TVK_PREV(b + v * TVK_BLOCK).xyz,
                              rest_info[b + v * TVK_BLOCK].x);
}
vec3 segment_mid(uint b, uint v, vec3 g) {
  vec3 d = TVK_POS(b + (v + 1u) * TVK_BLOCK).xyz - TVK_POS(b + v * TVK_BLOCK).xyz;
  vec3 was = TVK_PREV(b + (v + 1u) * TVK_BLOCK).xyz - TVK_PREV(b + v * TVK_BLOCK).xyz;
  vec3 mid = constraint_direction(0.5 * (d + was), was, rest_info[b + v * TVK_BLOCK].x);
  return dot(g, mid) > 0.5 ? mid : g;
}

// One Newton step of every segment's length constraint of a strand pinned at both ends (twin: solve_tip_pinned in
// the reference, which writes the system out): a tridiagonal solve (Thomas algorithm) for the multipliers, then each
// free vertex moves by lambda_v m_v - lambda_{v-1} m_{v-1}. Rare strands: read through memory.
void solve_tip_pinned(uint b) {
  float cp[N];
  float dp[N];
  vec3 g_here = segment_grad(b, 0u);
  vec3 m_here = segment_mid(b, 0u, g_here);
  vec3 m_before = vec3(0.0);
  float cp_before = 0.0, dp_before = 0.0;
  for (uint v = 0u; v + 1u < N; ++v) {
    vec3 g_next = vec3(0.0), m_next = vec3(0.0);
    if (v + 2u < N) {
      g_next = segment_grad(b, v + 1u);
      m_next = segment_mid(b, v + 1u, g_next);
    }
    float wa = free_weight(b, v), wb = free_weight(b, v + 1u);
    bool live = wa + wb > 0.0;
    float diag = live ? (wa + wb) * dot(g_here, m_here) : 1.0;
    float c = live ? dot(TVK_POS(b + (v + 1u) * TVK_BLOCK).xyz - TVK_POS(b + v * TVK_BLOCK).xyz, g_here) -
                           rest_info[b + v * TVK_BLOCK].x
                     : 0.0;
    float sub = live && v > 0u ? -wa * dot(g_here, m_before) : 0.0;
    float sup = live && v + 2u < N ? -wb * dot(g_here, m_next) : 0.0;
    float den = max(diag - sub * cp_before, kSolvePivotMin * diag);
    cp[v] = sup / den;
    dp[v] = (c - sub * dp_before) / den;
    cp_before = cp[v];
    dp_before = dp[v];
    m_before = m_here;
    g_here = g_next;
    m_here = m_next;
  }
  for (uint v = N - 2u; v-- > 0u;) dp[v] -= cp[v] * dp[v + 1u];  // now lambda
  // A damped Newton step: when the linearisation asks a vertex to move more than half of its shorter segment, the
  // whole update is scaled down to that (1 in ordinary motion), so the iteration cannot diverge.
  float scale = 1.0;
  vec3 m_prev = vec3(0.0);
  for (uint v = 0u; v < N; ++v) {
    vec3 m_v = v + 1u < N ? segment_mid(b, v, segment_grad(b, v)) : vec3(0.0);
    if (TVK_POS(b + v * TVK_BLOCK).w > 0.0) {
      float reach = 0.5 * min(v > 0u ? rest_info[b + (v - 1u) * TVK_BLOCK].x : 1.0 / 0.0,
                              v + 1u < N ? rest_info[b + v * TVK_BLOCK].x : 1.0 / 0.0);
      vec3 dx = vec3(0.0);
      if (v + 1u < N) dx += dp[v] * m_v;
      if (v > 0u) dx -= dp[v - 1u] * m_prev;
      float len = length(dx);
      if (len * scale > reach) scale = reach / len;
    }
    m_prev = m_v;
  }
  m_prev = vec3(0.0);
  for (uint v = 0u; v < N; ++v) {
    vec3 m_v = v + 1u < N ? segment_mid(b, v, segment_grad(b, v)) : vec3(0.0);  // v and v + 1 not yet moved
    vec4 x = TVK_POS(b + v * TVK_BLOCK);
    if (x.w > 0.0) {
      vec3 dx = vec3(0.0);
      if (v + 1u < N) dx += dp[v] * m_v;
      if (v > 0u) dx -= dp[v - 1u] * m_prev;
      TVK_POS(b + v * TVK_BLOCK) = vec4(x.xyz + scale * dx, x.w);
    }
    m_prev = m_v;
  }
}

// Vertex v's tangent t of guide g (strand base b). Tangents are the guides' only: a follow hair's tangent is its
// guide's, which the renderer reads at the guide's index (layout.glsl, binding 3).
#define write_tangent(g, b, v, t) tangent[(b) + (v) * TVK_BLOCK] = (t)

// The walk that ends a step (after the length sweeps): the velocity clamp, the non-finite check and the tangents
// (along the edge leaving v, arriving for the tip; an edge too short to have a direction reuses the previous tangent,
// and the root falls back to the current root frame's +X). Steps v = 0 .. N-1 in order, each with vertex v and
// vertex v + 1 (v itself for the tip) final.
struct FinishWalk {
  uint g;
  bool clamp;
  bool write_tangents;
  float max_step;
  float min_len;
  vec3 last;    // the tangent carried over a too-short edge
  vec4 before;  // vertex v - 1
  bool ok;      // every vertex so far finite
};
FinishWalk finish_begin(uint g, uint b, GroupParams gp, bool write_tangents) {
  FinishWalk w;
  w.g = g;
  w.clamp = TVK_HAS(TVK_FEATURE_MAX_SPEED) && gp.max_step > 0.0;
  w.write_tangents = write_tangents;
  w.max_step = gp.max_step;
  w.min_len = kDirectionEps * strand_rest_length(g) / float(N - 1u);
  w.last = vec3(0.0);
  w.before = vec4(0.0);
  w.ok = true;
  return w;
}
void finish_step(inout FinishWalk w, uint b, uint v, vec4 p, vec4 next) {
  if (v == 0u) {
    w.before = p;
    // The root frame reads vertices 0 and 1 through memory: both are final by the time the walk is at the root.
    if (w.write_tangents) w.last = quat_rotate(current_root_frame(w.g), vec3(1, 0, 0));
  }
  vec3 q = TVK_PREV(b + v * TVK_BLOCK).xyz;
  if (w.clamp && p.w > 0.0) {
    vec3 step = p.xyz - q;
    float len = length(step);
    if (len > w.max_step) {
      q = p.xyz - step * (w.max_step / len);
      TVK_PREV(b + v * TVK_BLOCK) = vec4(q, p.w);
    }
  }
  w.ok = w.ok && finite3(p.xyz) && finite3(q);
  vec3 e = v + 1u < N ? next.xyz - p.xyz : p.xyz - w.before.xyz;
  float len = length(e);
  if (len > w.min_len) w.last = e / len;
  if (w.write_tangents) write_tangent(w.g, b, v, vec4(w.last, 0.0));
  w.before = p;
}

// Wind, a walk from the root: per strand a fixed blend of the wind pyramid; the segment arriving at v takes the
// component of the wind perpendicular to it (wind bends hair, it does not stretch it). Scale-free: an acceleration
// times h^2. Steps v = 1 .. N-1 in order, each once vertex v is final for the passes before.
struct WindWalk {
  vec3 w;
  vec3 before;  // vertex v - 1 as pushed, carried (reloading it would wait on its own store)
};
WindWalk wind_begin(uint g, uint b) {
  float a = float(g % 20u) / 20.0;
  vec3 w = a * (step_params[TVK_STEP].wind[0].xyz + step_params[TVK_STEP].wind[2].xyz) +
           (1.0 - a) * (step_params[TVK_STEP].wind[1].xyz + step_params[TVK_STEP].wind[3].xyz);
  return WindWalk(w, TVK_POS(b).xyz);
}
void wind_step(inout WindWalk ww, uint b, uint v) {
  vec4 p = TVK_POS(b + v * TVK_BLOCK);
  if (p.w > 0.0) {
    vec3 e = p.xyz - ww.before;
    float len = length(e);
    vec3 push = ww.w;
    if (len > kDirectionEps * rest_info[b + (v - 1u) * TVK_BLOCK].x) {
      vec3 t = e / len;
      push = ww.w - dot(ww.w, t) * t;
    }
    p = vec4(p.xyz + push, p.w);
    TVK_POS(b + v * TVK_BLOCK) = p;
  }
  ww.before = p.xyz;
}

// Capsule collision of vertex v (capsules are in simulation space; the strand is relative to its anchor).
void collide_vertex(uint g, uint b, uint v) {
  vec3 a = TVK_ANCHOR(g).xyz;
  vec4 p = TVK_POS(b + v * TVK_BLOCK);
  if (!(p.w > 0.0)) return;
  vec3 x = p.xyz;
  vec3 y = TVK_PREV(b + v * TVK_BLOCK).xyz;
  bool hit = false;
  for (uint c = 0u; c < CAPSULE_COUNT; ++c) {
    vec4 c0 = step_params[TVK_STEP].capsule[2u * c];
    vec4 c1 = step_params[TVK_STEP].capsule[2u * c + 1u];
    c0.xyz -= a;
    c1.xyz -= a;
    vec3 m0 = step_params[TVK_STEP].capsule_move[2u * c].xyz;
    vec3 m1 = step_params[TVK_STEP].capsule_move[2u * c + 1u].xyz;
    vec3 axis = c1.xyz - c0.xyz;
    float aa = dot(axis, axis);
    float t = aa > 0.0 ? clamp(dot(x - c0.xyz, axis) / aa, 0.0, 1.0) : 0.0;
    vec3 centre = c0.xyz + t * axis;
    float radius = mix(c0.w, c1.w, t);
    vec3 d = x - centre;
    float dist = length(d);
    if (!(dist < radius)) continue;
    // Push out along the offset from the axis; on the axis itself (no direction), back the way it came.
    vec3 nrm;
    if (dist > kDirectionEps * radius) {
      nrm = d / dist;
    } else {
      vec3 back = y - centre;
      float bl = length(back);
      nrm = bl > kDirectionEps * radius ? back / bl : vec3(0, 1, 0);
    }
    // Remove only velocity into the surface relative to the surface's own move this step (tangential motion
    // slides on; hair resting on a moving head keeps the head's velocity), fully once the vertex was deeper
    // than kContactBand * radius and in proportion below that, so the response is continuous in the state.
    float depth = radius - dist;
    x = centre + radius * nrm;
    float vn = dot((x - y) - (m0 + t * (m1 - m0)), nrm);
    if (vn < 0.0) y += min(depth / (kContactBand * radius), 1.0) * vn * nrm;
    hit = true;
  }
  if (hit) {
    TVK_POS(b + v * TVK_BLOCK) = vec4(x, p.w);
    TVK_PREV(b + v * TVK_BLOCK) = vec4(y, p.w);
  }
}

// One step of a length sweep: segment v between p (vertex v, as the step before left it) and n (vertex v + 1 as the
// passes before left it), with pn and the walk's pp the two vertices' previous positions. The last sweep moves only
// the tip-ward end (follow the leader), so every step ends with each segment at its rest length; the sweeps before it
// share the correction between both ends. Returns vertex v, final for this sweep, and carries n as the next p.
struct SweepWalk {
  vec4 p;
  vec3 pp;
  bool last_sweep;
};
vec4 sweep_step(inout SweepWalk sw, uint b, uint v, vec4 n, vec3 pn, float rest) {
  vec4 p = sw.p;
  vec3 pp = sw.pp;
  bool last_sweep = sw.last_sweep;
  float wb = n.w > 0.0 ? 1.0 : 0.0;
  float wa = (p.w > 0.0 && !(last_sweep && wb > 0.0)) ? 1.0 : 0.0;
  float wsum = wa + wb;
  if (wsum > 0.0) {
    vec3 d = n.xyz - p.xyz;
    float len = length(d);
    vec3 dir = d;
    // Compressed: restored along its direction blended with its direction at the previous step by the missing
    // length, which stays defined as the segment vanishes (normalize(d) would not); turned back on that
    // direction (a flip within one step), also by the fold guard, so that the blend never nears zero.
    vec3 was = pn - pp;
    float wl = length(was);
    if (wl > kDirectionEps * rest) {
      vec3 u = was / wl;
      float blend = max(kCollapse * rest - len, 0.0) + fold_guard(d, len, u);
      if (blend > 0.0) dir = d + blend * u;
    }
    float dl = length(dir);
    if (dl > 0.0) {
      vec3 corr = (d - (rest / dl) * dir) / wsum;
      if (wa > 0.0) p = vec4(p.xyz + wa * corr, p.w);
      if (wb > 0.0) n = vec4(n.xyz - wb * corr, n.w);
      // Follow-the-leader moved only the child; its parent gets the opposite of that move as velocity (DFTL),
      // which keeps the strand's momentum plausible and removes FTL's energy gain.
      if (last_sweep && wa == 0.0 && wb > 0.0 && p.w > 0.0) {
        TVK_PREV(b + v * TVK_BLOCK) = vec4(pp - kFtlVelocityCorrection * corr, p.w);
      }
    }
  }
  sw.p = n;
  sw.pp = pn;
  return p;
}

// The reset of a strand found non-finite, vertex by vertex (every kernel's): the rest pose, its history carried back
// by this step's rigid motion (back = the inverse of the strand's skinning delta, reset_back), so the strand moves on
// with the head (VSP assumes that integration carries the head's previous motion), from q0, the root's history (zero
// where that is not finite).
vec4 reset_back(uint g) {
  vec4 back = skin_delta(g);
  return vec4(-back.xyz, back.w);
}
void reset_vertex(uint g, uint b, uint v, vec3 q0, vec4 back, bool rigid) {
  if (!finite3(q0)) q0 = vec3(0.0);
  float inv_mass = rigid ? 0.0 : rest_pos[b + v * TVK_BLOCK].w;
  vec3 r = skin_offset(g, v);  // relative to the anchor, where the root's rest pose is
  vec4 y = vec4(q0 + quat_rotate(back, r), inv_mass);
  TVK_POS(b + v * TVK_BLOCK) = vec4(r, inv_mass);
  TVK_PREV(b + v * TVK_BLOCK) = y;
  TVK_PREVPREV(b + v * TVK_BLOCK) = y;
}

// A strand found non-finite at the end of a step is reset, counted and its tangents written again.
void length_reset_if_not_finite(uint g, uint b, bool ok, bool write_tangents, float min_len) {
  if (!ok) {
    vec3 q0 = TVK_PREV(b).xyz;
    vec4 back = reset_back(g);
    bool rigid = strand_rigid(g, guide_params(g));
    for (uint v = 0u; v < N; ++v) {
      reset_vertex(g, b, v, q0, back, rigid);
#ifdef TVK_FRAME_KERNEL
      // The fused kernel stores the last substep's second history as it is made (frame.glsl): this one replaces it.
      if (write_tangents && TVK_HAS(TVK_FEATURE_VSP)) prevprev[b + v * TVK_BLOCK] = TVK_PREVPREV(b + v * TVK_BLOCK);
#endif
    }
    atomicAdd(counters[pc.counter_index], 1u);
    if (!write_tangents) return;
    vec3 last = quat_rotate(current_root_frame(g), vec3(1, 0, 0));
    for (uint v = 0u; v < N; ++v) {
      vec3 e = v + 1u < N ? TVK_POS(b + (v + 1u) * TVK_BLOCK).xyz - TVK_POS(b + v * TVK_BLOCK).xyz
                          : TVK_POS(b + v * TVK_BLOCK).xyz - TVK_POS(b + (v - 1u) * TVK_BLOCK).xyz;
      float len = length(e);
      if (len > min_len) last = e / len;
      write_tangent(g, b, v, vec4(last, 0.0));
    }
  }
}

void length_strand(uint g, bool write_tangents) {
  GroupParams gp = guide_params(g);
  uint b = strand_base(g);  // vertex v at b + v * TVK_BLOCK

  if (TVK_HAS(TVK_FEATURE_WIND)) {
    WindWalk ww = wind_begin(g, b);
    for (uint v = 1u; v < N; ++v) wind_step(ww, b, v);
  }

  if (TVK_HAS(TVK_FEATURE_COLLISION)) {
    for (uint v = 0u; v < N; ++v) collide_vertex(g, b, v);
  }

  // A strand pinned at its tip too (TressFX bothEndsImmovable; see the reference's length_and_collision): Newton steps
  // of the whole strand's constraints, then a positions-only follow-the-leader clean-up from both ends toward the
  // middle segment. Follow-the-leader from the root alone would leave the step's whole error next to the pinned tip.
  bool tip_pinned = TVK_HAS(TVK_FEATURE_PINNED_TIPS) && !(TVK_POS(b + (N - 1u) * TVK_BLOCK).w > 0.0);
  if (tip_pinned) {
    for (uint it = 0u; it < gp.length_iterations; ++it) solve_tip_pinned(b);
    uint split = (N - 1u) / 2u;
    for (uint v = 0u; v < split; ++v) {
      float wb = free_weight(b, v + 1u);
      length_segment(b, v, (free_weight(b, v) > 0.0 && !(wb > 0.0)) ? 1.0 : 0.0, wb);
    }
    for (uint v = N - 2u; v > split; --v) {
      float wa = free_weight(b, v);
      length_segment(b, v, wa, (free_weight(b, v + 1u) > 0.0 && !(wa > 0.0)) ? 1.0 : 0.0);
    }
    length_segment(b, split, free_weight(b, split), free_weight(b, split + 1u));
  }
  // One walk for the velocity clamp, the non-finite check and the tangents (FinishWalk): without a pinned tip it
  // rides along the last sweep one vertex behind it (the last sweep's step v + 1 can still move vertex v + 1, and its
  // step v the history of v), so the strand is walked once; with a pinned tip it walks alone after the clean-up.
  FinishWalk fw = finish_begin(g, b, gp, write_tangents);
  for (uint it = 0u; it < (tip_pinned ? 0u : gp.length_iterations); ++it) {
    bool last_sweep = it + 1u == gp.length_iterations;
    // The sweep carries the vertex it just moved (and its previous position) to the next edge in registers:
    // reloading it would wait on its own store, a round trip through the memory hierarchy at every vertex of the
    // serial walk. The arithmetic is exactly the same.
    SweepWalk sw = SweepWalk(TVK_POS(b), TVK_PREV(b).xyz, last_sweep);
    // The next vertex is fetched one edge ahead (it is not written before its turn), so its memory latency overlaps
    // this edge's arithmetic.
    vec4 n_next = TVK_POS(b + TVK_BLOCK);
    vec3 pn_next = TVK_PREV(b + TVK_BLOCK).xyz;
    float rest_next = rest_info[b].x;
    vec4 finished = sw.p;  // the vertex before v, final: the finish walk's vertex while this sweep steps v
    for (uint v = 0u; v + 1u < N; ++v) {
      vec4 n = n_next;
      vec3 pn = pn_next;
      float rest = rest_next;
      if (v + 2u < N) {
        n_next = TVK_POS(b + (v + 2u) * TVK_BLOCK);
        pn_next = TVK_PREV(b + (v + 2u) * TVK_BLOCK).xyz;
        rest_next = rest_info[b + (v + 1u) * TVK_BLOCK].x;
      }
      vec4 p = sweep_step(sw, b, v, n, pn, rest);
      TVK_POS(b + v * TVK_BLOCK) = p;  // final for this sweep
      if (last_sweep && v > 0u) finish_step(fw, b, v - 1u, finished, p);
      finished = p;
    }
    vec4 p = sw.p;
    TVK_POS(b + (N - 1u) * TVK_BLOCK) = p;
    if (last_sweep) {
      finish_step(fw, b, N - 2u, finished, p);
      finish_step(fw, b, N - 1u, p, p);
    }
  }
  if (tip_pinned || gp.length_iterations == 0u) {
    vec4 p = TVK_POS(b);
    for (uint v = 0u; v < N; ++v) {
      vec4 next = v + 1u < N ? TVK_POS(b + (v + 1u) * TVK_BLOCK) : p;
      finish_step(fw, b, v, p, next);
      p = next;
    }
  }
  bool ok = fw.ok;

  length_reset_if_not_finite(g, b, ok, write_tangents, fw.min_len);
}

#endif
