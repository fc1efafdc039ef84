// The groom generator's scalp: OBJ faces with optional vertex colours (the length map).
#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/groom.hpp>
#include <tressvk/baker/import.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

namespace tressvk::baker {
namespace {

std::string where(std::string_view name, size_t line) { return std::string(name) + ":" + std::to_string(line); }

bool parse_double(std::string_view tok, double& out) {
  const char* end = tok.data() + tok.size();
  const auto r = std::from_chars(tok.data(), end, out);
  return r.ec == std::errc() && r.ptr == end && std::isfinite(out);
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t b = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > b) out.push_back(line.substr(b, i - b));
  }
  return out;
}

}  // namespace

GroomScalp parse_groom_scalp(std::string_view text, std::string_view name) {
  GroomScalp s;
  std::vector<double> colours;  // per vertex, NaN where the vertex had none
  bool any_colour = false;
  size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    const size_t nl = text.find('\n', pos);
    const std::string_view line = text.substr(pos, nl == std::string_view::npos ? text.size() - pos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++line_no;
    const auto tok = split(line);
    if (tok.empty() || tok[0][0] == '#') continue;
    if (tok[0] == "v") {
      if (tok.size() != 4 && tok.size() != 7)
        throw InputError(where(name, line_no) + ": a vertex needs x y z (and optionally r g b), got " +
                         std::to_string(tok.size() - 1) + " numbers");
      Vec3 p{};
      for (int i = 0; i < 3; ++i)
        if (!parse_double(tok[1 + i], p[i]))
          throw InputError(where(name, line_no) + ": '" + std::string(tok[1 + i]) + "' is not a finite number");
      s.vertices.push_back(p);
      double red = std::nan("");
      if (tok.size() == 7) {
        if (!parse_double(tok[4], red) || red < 0.0)
          throw InputError(where(name, line_no) + ": vertex colour '" + std::string(tok[4]) +
                           "' is not a number >= 0");
        any_colour = true;
      }
      colours.push_back(red);
    } else if (tok[0] == "f") {
      if (tok.size() < 4)
        throw InputError(where(name, line_no) + ": a face needs at least 3 vertices");
      std::vector<uint32_t> idx;
      for (size_t i = 1; i < tok.size(); ++i) {
        const std::string_view t = tok[i].substr(0, tok[i].find('/'));
        long long v = 0;
        const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
        if (r.ec != std::errc() || r.ptr != t.data() + t.size() || v == 0)
          throw InputError(where(name, line_no) + ": '" + std::string(tok[i]) + "' is not a vertex index");
        const long long n = static_cast<long long>(s.vertices.size());
        const long long k = v > 0 ? v - 1 : n + v;
        if (k < 0 || k >= n)
          throw InputError(where(name, line_no) + ": vertex index " + std::to_string(v) + " is out of range (" +
                           std::to_string(n) + " vertices so far)");
        idx.push_back(static_cast<uint32_t>(k));
      }
      for (size_t i = 1; i + 1 < idx.size(); ++i) s.triangles.push_back({idx[0], idx[i], idx[i + 1]});
    }
  }
  if (s.triangles.empty())
    throw InputError(std::string(name) + ": the scalp has no faces (the groom generator grows hair from faces; "
                     "export the scalp as a mesh, not as curves or points)");
  if (any_colour) {
    s.length_map.resize(s.vertices.size());
    for (size_t i = 0; i < colours.size(); ++i) s.length_map[i] = std::isnan(colours[i]) ? 1.0 : colours[i];
  }
  return s;
}

GroomScalp load_groom_scalp(const std::filesystem::path& path) {
  const std::vector<std::byte> bytes = read_binary_file(path);
  return parse_groom_scalp(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                           path.string());
}

std::string groom_scalp_obj(const GroomScalp& s) {
  std::string out = "# scalp for tressvk-bake groom: metres, +Y up, face towards +Z";
  out += s.length_map.empty() ? "\n" : "; vertex colour red = length map\n";
  char buf[160];
  for (size_t i = 0; i < s.vertices.size(); ++i) {
    const Vec3& v = s.vertices[i];
    if (s.length_map.empty())
      std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", v[0], v[1], v[2]);
    else
      std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g %.6g %.6g %.6g\n", v[0], v[1], v[2], s.length_map[i],
                    s.length_map[i], s.length_map[i]);
    out += buf;
  }
  for (const auto& t : s.triangles) {
    std::snprintf(buf, sizeof buf, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1);
    out += buf;
  }
  return out;
}

}  // namespace tressvk::baker
