// Root orientation against a scalp mesh, and loading the scalp's faces.
#include "vec_math.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/import.hpp>

#include <algorithm>
#include <limits>

namespace tressvk::baker {
namespace {

// Squared distance from p to triangle abc: project onto the plane when the projection is inside, otherwise
// the nearest of the three edges (each as a clamped segment).
double distance_sq_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
  const Vec3 d = p - (a + ab * t);
  return dot(d, d);
}

double distance_sq_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  const double n2 = dot(n, n);
  if (n2 > 0) {
    const double s = dot(p - a, n) / n2;
    const Vec3 q = p - n * s;  // projection onto the plane
    // Inside test: q is on the same side of all three edges.
    const bool inside = dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 &&
                        dot(cross(a - c, q - c), n) >= 0;
    if (inside) return s * s * n2;
  }
  return std::min({distance_sq_to_segment(p, a, b), distance_sq_to_segment(p, b, c), distance_sq_to_segment(p, c, a)});
}

// floor/ceil results clamped to [lo, hi] before the conversion to int: a coordinate far outside the grid (or an
// extent that overflows to infinity for coordinates near the double range) must not overflow the cast (UB).
int clamp_to_int(double v, int lo, int hi) {
  if (!(v > lo)) return lo;  // also NaN
  if (v >= hi) return hi;
  return static_cast<int>(v);
}

// Uniform grid over the scalp's triangles (each listed in every cell its bounding box touches), searched in
// growing shells of cells around the query point until no unvisited cell can hold anything nearer. Turns the
// O(strands x triangles) brute force into roughly O(strands) for real scalps.
class TriangleGrid {
 public:
  explicit TriangleGrid(const ScalpMesh& m) : mesh_(m) {
    lo_ = {1e300, 1e300, 1e300};
    Vec3 hi{-1e300, -1e300, -1e300};
    for (const auto& t : m.triangles)
      for (uint32_t i : t)
        for (size_t a = 0; a < 3; ++a) {
          lo_[a] = std::min(lo_[a], m.vertices[i][a]);
          hi[a] = std::max(hi[a], m.vertices[i][a]);
        }
    const double extent = std::max({hi[0] - lo_[0], hi[1] - lo_[1], hi[2] - lo_[2], 1e-300});
    // About one triangle per cell along the largest axis: cbrt(T) cells there, at most 128.
    const double per_axis = std::clamp(std::cbrt(static_cast<double>(m.triangles.size())), 1.0, 128.0);
    h_ = extent / per_axis;
    for (size_t a = 0; a < 3; ++a) dims_[a] = clamp_to_int(std::ceil((hi[a] - lo_[a]) / h_), 1, 128);
    std::vector<uint32_t> counts(cell_count() + 1, 0);
    for_each_cell_of_triangles([&](size_t cell, uint32_t) { ++counts[cell + 1]; });
    for (size_t c = 1; c < counts.size(); ++c) counts[c] += counts[c - 1];
    start_ = counts;
    items_.resize(counts.back());
    for_each_cell_of_triangles([&](size_t cell, uint32_t t) { items_[counts[cell]++] = t; });
  }

  // An incremental nearest-triangle search: each step() visits one more shell of cells around the query point.
  struct Search {
    Vec3 p{};
    std::array<int, 3> c{};
    double outside_sq = 0.0;  // squared distance from p to the grid box
    double best = std::numeric_limits<double>::infinity();
    int next_ring = 0;
    bool done = false;
    // Nothing not yet visited can be nearer than this (squared). With p' the projection of p onto the grid box
    // (it lies in cell c), any point q in a ring >= next_ring has |p'-q| >= (next_ring-1)*h, and
    // |p-q|^2 >= |p-p'|^2 + |p'-q|^2 (projection onto a convex set).
    double unseen_bound_sq(double h) const {
      if (done) return std::numeric_limits<double>::infinity();
      const double reach = std::max(0, next_ring - 1) * h;
      return outside_sq + reach * reach;
    }
  };

  Search start(const Vec3& p) const {
    Search s;
    s.p = p;
    for (size_t a = 0; a < 3; ++a) {
      s.c[a] = cell_coord(p[a], a);
      const double below = lo_[a] - p[a], above = p[a] - (lo_[a] + dims_[a] * h_);
      if (below > 0) s.outside_sq += below * below;
      if (above > 0) s.outside_sq += above * above;
    }
    return s;
  }

  void step(Search& s) const {
    const int r = s.next_ring++;
    if (r > std::max({dims_[0], dims_[1], dims_[2]})) {
      s.done = true;
      return;
    }
    auto visit = [&](int x, int y, int z) {
      const size_t cell = index(x, y, z);
      for (uint32_t i = start_[cell]; i < start_[cell + 1]; ++i) {
        const auto& t = mesh_.triangles[items_[i]];
        s.best = std::min(s.best, distance_sq_to_triangle(s.p, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]));
      }
    };
    // The cells at Chebyshev distance r from c, clipped to the grid: only the shell, never its inside.
    const auto& c = s.c;
    const int x0 = std::max(0, c[0] - r), x1 = std::min(dims_[0] - 1, c[0] + r);
    const int y0 = std::max(0, c[1] - r), y1 = std::min(dims_[1] - 1, c[1] + r);
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y) {
        if (std::abs(x - c[0]) == r || std::abs(y - c[1]) == r) {
          for (int z = std::max(0, c[2] - r); z <= std::min(dims_[2] - 1, c[2] + r); ++z) visit(x, y, z);
        } else {
          if (c[2] - r >= 0) visit(x, y, c[2] - r);
          if (r > 0 && c[2] + r < dims_[2]) visit(x, y, c[2] + r);
        }
      }
    if (s.best <= s.unseen_bound_sq(h_)) s.done = true;
  }

  double distance_sq(const Vec3& p) const {
    Search s = start(p);
    while (!s.done) step(s);
    return s.best;
  }

  // Whether b is strictly nearer the surface than a, searching both only as far as needed to decide (a strand's
  // root is usually on the scalp and its tip far away: the tip's search then stops after a shell or two).
  bool strictly_nearer(const Vec3& a, const Vec3& b) const {
    Search sa = start(a), sb = start(b);
    while (true) {
      if (sb.best < sa.unseen_bound_sq(h_) && sb.best < sa.best) return true;  // b's distance beats anything a can reach
      if (sa.best <= sb.unseen_bound_sq(h_) && sa.best <= sb.best) return false;
      // Advance the search that can still come lower.
      if (!sa.done && (sb.done || sa.unseen_bound_sq(h_) <= sb.unseen_bound_sq(h_))) {
        step(sa);
      } else if (!sb.done) {
        step(sb);
      } else {
        return sb.best < sa.best;
      }
    }
  }

 private:
  int cell_coord(double v, size_t a) const {
    return clamp_to_int(std::floor((v - lo_[a]) / h_), 0, dims_[a] - 1);
  }
  size_t cell_count() const { return static_cast<size_t>(dims_[0]) * dims_[1] * dims_[2]; }
  size_t index(int x, int y, int z) const {
    return (static_cast<size_t>(z) * dims_[1] + static_cast<size_t>(y)) * dims_[0] + static_cast<size_t>(x);
  }
  template <typename F>
  void for_each_cell_of_triangles(F&& f) const {
    for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
      std::array<int, 3> a{}, b{};
      for (size_t k = 0; k < 3; ++k) {
        double mn = 1e300, mx = -1e300;
        for (uint32_t i : mesh_.triangles[t]) {
          mn = std::min(mn, mesh_.vertices[i][k]);
          mx = std::max(mx, mesh_.vertices[i][k]);
        }
        a[k] = cell_coord(mn, k);
        b[k] = cell_coord(mx, k);
      }
      for (int x = a[0]; x <= b[0]; ++x)
        for (int y = a[1]; y <= b[1]; ++y)
          for (int z = a[2]; z <= b[2]; ++z) f(index(x, y, z), t);
    }
  }

  const ScalpMesh& mesh_;
  Vec3 lo_{};
  double h_ = 1.0;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<uint32_t> start_, items_;
};

}  // namespace

double distance_to_scalp(const Vec3& p, const ScalpMesh& scalp) {
  if (scalp.triangles.empty()) return std::numeric_limits<double>::infinity();
  return std::sqrt(TriangleGrid(scalp).distance_sq(p));
}

double distance_to_scalp_brute_force(const Vec3& p, const ScalpMesh& m) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles)
    best = std::min(best, distance_sq_to_triangle(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]));
  return std::sqrt(best);
}

void orient_to_scalp(RawGroom& groom, const ScalpMesh& scalp) {
  if (scalp.triangles.empty()) return;
  const TriangleGrid grid(scalp);
  for (size_t s = 0; s < groom.strand_count(); ++s) {
    auto first = groom.points.begin() + groom.strand_begin[s];
    auto last = groom.points.begin() + groom.strand_begin[s + 1];
    if (grid.strictly_nearer(*first, *(last - 1))) std::reverse(first, last);
  }
}

ScalpMesh load_scalp(const std::filesystem::path& path) {
  const auto bytes = read_binary_file(path);
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  ScalpMesh mesh;
  import_obj_text(text, path.string(), {}, &mesh);
  if (mesh.triangles.empty()) throw InputError(path.string() + ": the scalp file has no faces");
  return mesh;
}

}  // namespace tressvk::baker
