#include <tressvk/reference/strand_raster.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace tressvk::reference {

namespace {

double coverage(double d, double w) { return std::clamp(std::min(d + 0.5 * w, 0.5) - std::max(d - 0.5 * w, -0.5), 0.0, 1.0); }

struct Fragment {
  double depth;
  double r, g, b, a;
};

double half_to_double(uint16_t h) {
  const uint32_t sign = (h >> 15) & 1u, exponent = (h >> 10) & 0x1fu, mantissa = h & 0x3ffu;
  double v;
  if (exponent == 0)
    v = std::ldexp(static_cast<double>(mantissa), -24);
  else if (exponent == 31)
    v = mantissa ? std::nan("") : INFINITY;
  else
    v = std::ldexp(static_cast<double>(mantissa | 0x400u), static_cast<int>(exponent) - 25);
  return sign ? -v : v;
}

double srgb(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

}  // namespace

HairLayer render_strands_reference(const StrandRasterInput& in, uint64_t* fragments_out) {
  HairLayer out;
  out.width = in.width;
  out.height = in.height;
  out.rgba.assign(size_t{4} * in.width * in.height, 0.0);
  const uint32_t n = in.vertices_per_strand;
  if (n < 2 || in.strands == 0) return out;
  const uint64_t segments = uint64_t{in.strands} * (n - 1);
  // Bands of rows, one thread per band at a time: each band gathers every fragment of its pixels, sorts them and
  // composites.
  constexpr uint32_t kBand = 16;
  const uint32_t bands = (in.height + kBand - 1) / kBand;
  const uint32_t threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 32u));
  std::vector<uint64_t> fragment_counts(threads, 0);
  auto work = [&](uint32_t worker) {
    std::vector<std::vector<Fragment>> pixels(size_t{kBand} * in.width);
    for (uint32_t band = worker; band < bands; band += threads) {
      const uint32_t y0 = band * kBand, y1 = std::min(in.height, y0 + kBand);
      for (auto& p : pixels) p.clear();
      for (uint64_t seg = 0; seg < segments; ++seg) {
        const uint32_t i = static_cast<uint32_t>(seg % (n - 1));
        const uint64_t va = seg / (n - 1) * n + i;
        const float* a = in.vertices + 8 * va;
        const float* b = a + 8;
        if (a[2] < 0.0f || b[2] < 0.0f || std::min(a[2], b[2]) > 1.0f) continue;
        const double dx = double{b[0]} - a[0], dy = double{b[1]} - a[1];
        const double len2 = dx * dx + dy * dy;
        if (len2 < 1e-8) continue;
        const double reach = 0.5 * std::max(a[3], b[3]) + 0.5;
        const double ylo = std::min(a[1], b[1]) - reach, yhi = std::max(a[1], b[1]) + reach;
        if (yhi < y0 || ylo > y1) continue;
        const double xlo = std::min(a[0], b[0]) - reach, xhi = std::max(a[0], b[0]) + reach;
        const int px0 = std::max(0, static_cast<int>(std::floor(xlo)));
        const int px1 = std::min(static_cast<int>(in.width) - 1, static_cast<int>(std::ceil(xhi)));
        const int py0 = std::max(static_cast<int>(y0), static_cast<int>(std::floor(ylo)));
        const int py1 = std::min(static_cast<int>(y1) - 1, static_cast<int>(std::ceil(yhi)));
        const bool last = i + 2 >= n;
        for (int py = py0; py <= py1; ++py) {
          for (int px = px0; px <= px1; ++px) {
            const double cx = px + 0.5, cy = py + 0.5;
            const double t = ((cx - a[0]) * dx + (cy - a[1]) * dy) / len2;
            if (t < 0.0 || t > 1.0 || (t == 1.0 && !last)) continue;
            const double qx = a[0] + t * dx - cx, qy = a[1] + t * dy - cy;
            const double cov = coverage(std::sqrt(qx * qx + qy * qy), a[3] + t * (double{b[3]} - a[3]));
            if (cov <= 0.0) continue;
            const double z = a[2] + t * (double{b[2]} - a[2]);
            if (z > in.host_depth[size_t{static_cast<uint32_t>(py)} * in.width + static_cast<uint32_t>(px)]) continue;
            const double alpha = cov * (a[7] + t * (double{b[7]} - a[7]));
            pixels[size_t{static_cast<uint32_t>(py) - y0} * in.width + static_cast<uint32_t>(px)].push_back(
                {z, alpha * (a[4] + t * (double{b[4]} - a[4])), alpha * (a[5] + t * (double{b[5]} - a[5])),
                 alpha * (a[6] + t * (double{b[6]} - a[6])), alpha});
          }
        }
      }
      for (uint32_t y = y0; y < y1; ++y) {
        for (uint32_t x = 0; x < in.width; ++x) {
          auto& f = pixels[size_t{y - y0} * in.width + x];
          std::sort(f.begin(), f.end(), [](const Fragment& l, const Fragment& r) { return l.depth < r.depth; });
          double c[4] = {0, 0, 0, 0};
          for (const Fragment& g : f) {
            const double k = 1.0 - c[3];
            c[0] += k * g.r;
            c[1] += k * g.g;
            c[2] += k * g.b;
            c[3] += k * g.a;
          }
          fragment_counts[worker] += f.size();
          std::memcpy(&out.rgba[4 * (size_t{y} * in.width + x)], c, sizeof(c));
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (uint32_t w = 1; w < threads; ++w) pool.emplace_back(work, w);
  work(0);
  for (auto& t : pool) t.join();
  if (fragments_out) {
    *fragments_out = 0;
    for (uint64_t c : fragment_counts) *fragments_out += c;
  }
  return out;
}

HairLayer layer_from_half(uint32_t width, uint32_t height, const uint16_t* halves) {
  HairLayer out;
  out.width = width;
  out.height = height;
  out.rgba.resize(size_t{4} * width * height);
  for (size_t i = 0; i < out.rgba.size(); ++i) out.rgba[i] = half_to_double(halves[i]);
  return out;
}

LayerError compare_layers(const HairLayer& actual, const HairLayer& reference) {
  if (actual.width != reference.width || actual.height != reference.height)
    throw std::invalid_argument("compare_layers: the layers differ in size");
  LayerError e;
  std::vector<double> errors;
  const size_t pixels = size_t{actual.width} * actual.height;
  for (size_t p = 0; p < pixels; ++p) {
    const double* a = &actual.rgba[4 * p];
    const double* r = &reference.rgba[4 * p];
    if (a[3] < 0.5 / 255.0 && r[3] < 0.5 / 255.0) continue;
    ++e.hair_pixels;
    for (int c = 0; c < 4; ++c) {
      const double va = c < 3 ? srgb(a[c]) : std::clamp(a[c], 0.0, 1.0);
      const double vr = c < 3 ? srgb(r[c]) : std::clamp(r[c], 0.0, 1.0);
      errors.push_back(255.0 * std::abs(va - vr));
    }
  }
  summarise_errors(std::move(errors), e);
  return e;
}

void summarise_errors(std::vector<double> errors, LayerError& e) {
  if (errors.empty()) return;
  double sum = 0;
  for (double v : errors) sum += v;
  e.mean = sum / static_cast<double>(errors.size());
  std::sort(errors.begin(), errors.end());
  e.p99 = errors[std::min(errors.size() - 1, static_cast<size_t>(0.99 * static_cast<double>(errors.size())))];
  e.max = errors.back();
}

}  // namespace tressvk::reference
