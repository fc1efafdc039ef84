// OBJ polyline importer. A single hand-written pass over the bytes (line numbers for every message, no
// per-line allocation), then strands are rebuilt by chaining `l` edges through shared vertices, so Blender's
// 2-index edges (any order, either direction) and Maya/Houdini multi-index records give the same strands.
#include "vec_math.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/import.hpp>

#include <algorithm>
#include <charconv>
#include <cstring>

namespace tressvk::baker {
namespace {

constexpr uint32_t kNone = 0xFFFFFFFFu;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

struct Edge {
  uint32_t a, b;
  uint32_t line;
  uint32_t group;
};

class ObjParser {
 public:
  ObjParser(std::string_view text, std::string_view name, bool keep_faces)
      : text_(text), name_(name), keep_faces_(keep_faces) {}

  [[noreturn]] void fail(uint64_t line, const std::string& what) const {
    throw InputError(std::string(name_) + ":" + std::to_string(line) + ": " + what);
  }

  void parse() {
    const char* p = text_.data();
    const char* end = p + text_.size();
    if (text_.size() >= 3 && text_.substr(0, 3) == "\xEF\xBB\xBF") p += 3;  // UTF-8 byte order mark
    uint64_t line = 1;
    while (p < end) {
      const char* eol = p;
      // One scan per line finds its end and rejects control bytes (binary data, UTF-16, NULs).
      while (eol < end && *eol != '\n') {
        const auto c = static_cast<unsigned char>(*eol);
        if (c < 0x20 && c != '\t' && c != '\r' && c != '\v' && c != '\f')
          fail(line, "binary data (byte 0x" + hex(c) + "): this is not a text OBJ file");
        ++eol;
      }
      parse_line(p, eol, line);
      p = eol + 1;
      ++line;
    }
    lines_ = line - 1;
  }

  std::vector<Vec3> verts;
  std::vector<Edge> edges;
  std::vector<uint32_t> record_roots;  // first vertex of each multi-index `l` record
  std::vector<std::string> groups;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<uint64_t> triangle_lines;
  uint64_t face_count = 0;
  uint64_t ignored = 0;
  uint64_t max_face_index = 0, max_face_index_line = 0;
  uint64_t lines_ = 0;

 private:
  static std::string hex(unsigned c) {
    const char* d = "0123456789ABCDEF";
    return {d[c >> 4], d[c & 15]};
  }

  static const char* skip_space(const char* p, const char* e) {
    while (p < e && is_space(*p)) ++p;
    return p;
  }

  double parse_double(const char*& p, const char* e, uint64_t line, const char* field) {
    p = skip_space(p, e);
    const char* start = p;
    if (p < e && *p == '+') ++p;  // from_chars rejects a leading '+', which some exporters write
    double v = 0;
    auto [ptr, ec] = std::from_chars(p, e, v);
    if (ec != std::errc() || (ptr < e && !is_space(*ptr) && *ptr != '#'))
      fail(line, std::string("cannot parse ") + field + " '" + token(start, e) + "' as a number");
    if (!std::isfinite(v)) fail(line, std::string(field) + " is not finite ('" + token(start, e) + "')");
    p = ptr;
    return v;
  }

  static std::string token(const char* p, const char* e) {
    const char* q = p;
    while (q < e && !is_space(*q) && q - p < 40) ++q;
    return std::string(p, q);
  }

  // An `l`/`f` vertex reference: "i", "i/t", "i/t/n" or "i//n"; only i is used. Returns a 0-based index, or
  // kNone at the end of the line. Positive indices are checked against the final vertex count later.
  uint32_t parse_index(const char*& p, const char* e, uint64_t line) {
    p = skip_space(p, e);
    if (p >= e || *p == '#') return kNone;  // end of line or a trailing comment
    const char* start = p;
    long long i = 0;
    auto [ptr, ec] = std::from_chars(p, e, i);
    if (ec != std::errc()) fail(line, "cannot parse vertex index '" + token(start, e) + "'");
    p = ptr;
    while (p < e && (*p == '/' || (*p >= '0' && *p <= '9') || *p == '-')) ++p;  // texture/normal parts
    if (p < e && !is_space(*p) && *p != '#') fail(line, "cannot parse vertex index '" + token(start, e) + "'");
    if (i == 0) fail(line, "vertex index 0 (OBJ indices start at 1)");
    if (i < 0) {
      const long long resolved = static_cast<long long>(verts.size()) + i;
      if (resolved < 0)
        fail(line, "relative vertex index " + std::to_string(i) + " points before the first vertex (only " +
                       std::to_string(verts.size()) + " defined so far)");
      return static_cast<uint32_t>(resolved);
    }
    if (i > 0xFFFFFFF0ll) fail(line, "vertex index " + std::to_string(i) + " out of range");
    return static_cast<uint32_t>(i - 1);
  }

  void parse_line(const char* p, const char* e, uint64_t line) {
    p = skip_space(p, e);
    if (p >= e || *p == '#') return;
    const char* k = p;
    while (p < e && !is_space(*p)) ++p;
    const std::string_view key(k, static_cast<size_t>(p - k));
    if (key == "v") {
      Vec3 v;
      v[0] = parse_double(p, e, line, "x");
      v[1] = parse_double(p, e, line, "y");
      v[2] = parse_double(p, e, line, "z");
      verts.push_back(v);  // further values (w, vertex colours) are ignored
    } else if (key == "l") {
      const uint32_t first = parse_index(p, e, line);
      if (first == kNone) fail(line, "`l` record without vertex indices");
      uint32_t prev = first;
      uint32_t count = 1;
      for (uint32_t i; (i = parse_index(p, e, line)) != kNone; prev = i, ++count)
        edges.push_back({prev, i, static_cast<uint32_t>(std::min<uint64_t>(line, kNone)), current_group()});
      if (count < 2) fail(line, "`l` record with a single vertex (a strand needs at least two)");
      if (count > 2) record_roots.push_back(first);
    } else if (key == "f") {
      std::array<uint32_t, 3> tri{};
      uint32_t count = 0;
      for (uint32_t i; (i = parse_index(p, e, line)) != kNone; ++count) {
        if (i + uint64_t{1} > max_face_index) {
          max_face_index = i + uint64_t{1};
          max_face_index_line = line;
        }
        if (!keep_faces_) continue;
        if (count < 2) {
          tri[count] = i;
        } else {  // fan triangulation
          tri[2] = i;
          triangles.push_back(tri);
          triangle_lines.push_back(line);
          tri[1] = i;
        }
      }
      if (count < 3) fail(line, "face with fewer than 3 vertices");
      ++face_count;
    } else if (key == "o" || key == "g") {
      p = skip_space(p, e);
      const char* q = e;
      while (q > p && is_space(q[-1])) --q;
      group_name_.assign(p, q);
      group_index_ = kNone;
    } else {
      ++ignored;  // vn, vt, s, usemtl, mtllib, p, and anything else that is not hair
    }
  }

  uint32_t current_group() {
    if (group_index_ == kNone) {
      const std::string name = group_name_.empty() ? std::string(stem()) : group_name_;
      auto it = std::find(groups.begin(), groups.end(), name);
      if (it == groups.end()) {
        groups.push_back(name);
        group_index_ = static_cast<uint32_t>(groups.size() - 1);
      } else {
        group_index_ = static_cast<uint32_t>(it - groups.begin());
      }
    }
    return group_index_;
  }

  std::string_view stem() const {
    std::string_view s = name_;
    if (auto slash = s.find_last_of("/\\"); slash != std::string_view::npos) s = s.substr(slash + 1);
    if (auto dot = s.find_last_of('.'); dot != std::string_view::npos && dot > 0) s = s.substr(0, dot);
    return s;
  }

  std::string_view text_;
  std::string_view name_;
  bool keep_faces_;
  std::string group_name_;
  uint32_t group_index_ = kNone;
};

}  // namespace

RawGroom import_obj_text(std::string_view text, std::string_view name, const ObjImportOptions& options,
                         ScalpMesh* faces_out) {
  const bool want_faces = faces_out || options.root_from == RootFrom::kFaces;
  ObjParser obj(text, name, want_faces);
  obj.parse();
  const auto nv = static_cast<uint32_t>(obj.verts.size());
  auto fail = [&](uint64_t line, const std::string& what) -> void {
    throw InputError(std::string(name) + ":" + std::to_string(line) + ": " + what);
  };
  if (obj.max_face_index > nv)
    fail(obj.max_face_index_line, "face vertex index " + std::to_string(obj.max_face_index) + " out of range (" +
                                      std::to_string(nv) + " vertices)");
  for (const auto& e : obj.edges)
    if (e.a >= nv || e.b >= nv)
      fail(e.line, "vertex index " + std::to_string(std::max(e.a, e.b) + uint64_t{1}) + " out of range (the file has " +
                       std::to_string(nv) + " vertices)");
  ScalpMesh faces;
  if (want_faces) {
    faces.vertices = obj.verts;
    faces.triangles = std::move(obj.triangles);
  }
  if (obj.edges.empty()) {
    if (obj.verts.empty() && obj.face_count == 0) throw InputError(std::string(name) + ": empty file (no OBJ records)");
    if (obj.face_count > 0 && !faces_out)
      throw InputError(std::string(name) + ": no hair: the file has " + std::to_string(obj.face_count) +
                       " faces but no `l` polyline records");
    if (!faces_out) throw InputError(std::string(name) + ": no hair: the file has no `l` polyline records");
  }

  // Adjacency (CSR) without self-edges or duplicate edges.
  std::vector<uint32_t> deg(nv + 1, 0);
  for (const auto& e : obj.edges)
    if (e.a != e.b) {
      ++deg[e.a];
      ++deg[e.b];
    }
  std::vector<uint32_t> start(nv + 1, 0);
  for (uint32_t v = 0; v < nv; ++v) start[v + 1] = start[v] + deg[v];
  std::vector<uint32_t> adj(start[nv]), adj_edge(start[nv]);
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (uint32_t i = 0; i < obj.edges.size(); ++i) {
    const auto& e = obj.edges[i];
    if (e.a == e.b) continue;
    adj[fill[e.a]] = e.b;
    adj_edge[fill[e.a]++] = i;
    adj[fill[e.b]] = e.a;
    adj_edge[fill[e.b]++] = i;
  }
  for (uint32_t v = 0; v < nv; ++v) {
    // Duplicates are rare; only vertices with more than two neighbour entries need a look.
    if (deg[v] <= 1) continue;
    uint32_t* b = adj.data() + start[v];
    uint32_t* eb = adj_edge.data() + start[v];
    uint32_t n = deg[v];
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t j = i + 1; j < n;)
        if (b[j] == b[i]) {
          b[j] = b[n - 1];
          eb[j] = eb[n - 1];
          --n;
        } else {
          ++j;
        }
    deg[v] = n;
  }
  std::vector<uint8_t> is_record_root(nv, 0);
  for (uint32_t r : obj.record_roots) is_record_root[r] = 1;

  RawGroom groom;
  groom.group_names = obj.groups;
  groom.ignored_records = obj.ignored + obj.face_count;
  std::vector<uint8_t> seen(nv, 0);
  std::vector<uint32_t> stack, component;
  std::vector<Vec3> strand;
  for (uint32_t s = 0; s < nv; ++s) {
    if (seen[s] || deg[s] == 0) continue;
    // Collect the component.
    component.clear();
    stack.assign(1, s);
    seen[s] = 1;
    uint32_t ends[2] = {kNone, kNone};
    uint32_t end_count = 0, branch = kNone;
    while (!stack.empty()) {
      const uint32_t v = stack.back();
      stack.pop_back();
      component.push_back(v);
      if (deg[v] == 1) {
        if (end_count < 2) ends[end_count] = v;
        ++end_count;
      }
      if (deg[v] > 2 && branch == kNone) branch = v;
      for (uint32_t i = start[v]; i < start[v] + deg[v]; ++i)
        if (!seen[adj[i]]) {
          seen[adj[i]] = 1;
          stack.push_back(adj[i]);
        }
    }
    groom.input_vertices += component.size();
    if (branch != kNone || end_count != 2) {
      if (options.skip_invalid) {
        ++groom.skipped_invalid;
        continue;
      }
      if (branch != kNone)
        fail(obj.edges[adj_edge[start[branch]]].line,
             "vertex " + std::to_string(branch + uint64_t{1}) + " joins " + std::to_string(deg[branch]) +
                 " edges: strands must not branch (use --skip-invalid to drop such strands)");
      fail(obj.edges[adj_edge[start[s]]].line, "the strand through vertex " + std::to_string(s + uint64_t{1}) +
                                                   " closes into a loop (use --skip-invalid to drop such strands)");
    }
    uint32_t root = std::min(ends[0], ends[1]);
    const uint32_t other = std::max(ends[0], ends[1]);
    if (!is_record_root[root] && is_record_root[other]) root = other;
    // Walk root to tip.
    strand.clear();
    uint32_t prev = kNone, cur = root;
    const uint32_t group = obj.edges[adj_edge[start[root]]].group;
    while (true) {
      strand.push_back(obj.verts[cur]);
      uint32_t next = kNone;
      for (uint32_t i = start[cur]; i < start[cur] + deg[cur]; ++i)
        if (adj[i] != prev) next = adj[i];
      if (next == kNone) break;
      prev = cur;
      cur = next;
    }
    groom.add_strand(strand.data(), strand.size(), group);
  }
  if (groom.strand_count() == 0 && !faces_out)
    throw InputError(std::string(name) + ": no valid strand (" + std::to_string(groom.skipped_invalid) +
                     " skipped as invalid)");
  if (options.root_from == RootFrom::kFaces) {
    if (faces.triangles.empty())
      throw InputError(std::string(name) + ": --root-from faces, but the file has no faces");
    orient_to_scalp(groom, faces);
  }
  if (faces_out) *faces_out = std::move(faces);
  return groom;
}

}  // namespace tressvk::baker
