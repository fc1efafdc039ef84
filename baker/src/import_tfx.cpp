// TressFX .tfx (v3: 296-byte header, float3; v4: 160-byte header, float4 + optional strand UVs) and .tfxbone
// (4.x fixed 4 influences, 5.x counted). Layouts: shared/notes/tressfx-reference.md §2. Every field read is
// bounds-checked; messages name the file, the field and its byte offset.
#include "vec_math.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/import.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tressvk::baker {
namespace {

template <typename T>
T load(std::span<const std::byte> b, uint64_t off) {
  T v{};
  std::memcpy(&v, b.data() + off, sizeof(T));
  return v;
}

std::string stem_of(std::string_view name) {
  std::string_view s = name;
  if (auto slash = s.find_last_of("/\\"); slash != std::string_view::npos) s = s.substr(slash + 1);
  if (auto dot = s.find_last_of('.'); dot != std::string_view::npos && dot > 0) s = s.substr(0, dot);
  return std::string(s);
}

class BinaryCursor {
 public:
  BinaryCursor(std::span<const std::byte> b, std::string_view name) : b_(b), name_(name) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(std::string(name_) + ": " + what + " (byte offset " + std::to_string(pos_) + ")");
  }
  template <typename T>
  T get(const char* field) {
    if (b_.size() - pos_ < sizeof(T)) fail(std::string("file ends inside field ") + field);
    T v = load<T>(b_, pos_);
    pos_ += sizeof(T);
    return v;
  }
  size_t remaining() const { return b_.size() - pos_; }
  size_t pos() const { return pos_; }
  void skip(size_t n) { pos_ += n; }

 private:
  std::span<const std::byte> b_;
  std::string_view name_;
  size_t pos_ = 0;
};

}  // namespace

std::vector<std::byte> read_binary_file(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f) throw IoError(path.string() + ": cannot open");
  const auto size = static_cast<std::streamsize>(f.tellg());
  if (size < 0) throw IoError(path.string() + ": cannot read");
  std::vector<std::byte> bytes(static_cast<size_t>(size));
  f.seekg(0);
  if (size > 0 && !f.read(reinterpret_cast<char*>(bytes.data()), size)) throw IoError(path.string() + ": read error");
  return bytes;
}

RawGroom import_tfx_bytes(std::span<const std::byte> b, std::string_view name) {
  auto fail = [&](const std::string& what) { throw InputError(std::string(name) + ": " + what); };
  if (b.empty()) fail("empty file");
  if (b.size() < 160) fail("file of " + std::to_string(b.size()) + " bytes is shorter than a .tfx header");
  const float version = load<float>(b, 0);
  const bool v3 = version >= 3.0f && version < 4.0f;
  const bool v4 = version >= 4.0f && version < 6.0f;
  if (!v3 && !v4) fail("header field version (offset 0) is " + std::to_string(version) + ": not a .tfx 3.x or 4.x file");
  const uint32_t strands = load<uint32_t>(b, 4);
  const uint32_t n = load<uint32_t>(b, 8);
  uint64_t pos_offset = 0, uv_offset = 0;
  bool both_ends = false;
  uint64_t stride = 0;
  if (v3) {
    if (b.size() < 296) fail("file of " + std::to_string(b.size()) + " bytes is shorter than the .tfx v3 header (296)");
    both_ends = load<int32_t>(b, 16) != 0;
    pos_offset = load<uint32_t>(b, 144);
    if (pos_offset == 0) pos_offset = 296;
    stride = 12;
  } else {
    pos_offset = load<uint32_t>(b, 12);
    uv_offset = load<uint32_t>(b, 16);  // 0 = no strand UVs (never read header bytes as UVs)
    if (pos_offset == 0) pos_offset = 160;
    stride = 16;
  }
  if (strands == 0) fail("header field numHairStrands (offset 4) is 0: no hair");
  if (n < 2 || n > 4096) fail("header field numVerticesPerStrand (offset 8) is " + std::to_string(n) + ": expected 2..4096");
  const uint64_t vertex_count = uint64_t{strands} * n;
  if (pos_offset > b.size() || vertex_count > (b.size() - pos_offset) / stride)
    fail("positions (" + std::to_string(strands) + " strands x " + std::to_string(n) + " vertices at offset " +
         std::to_string(pos_offset) + ") run past the end of the file (" + std::to_string(b.size()) + " bytes)");
  if (uv_offset != 0 && (uv_offset > b.size() || strands > (b.size() - uv_offset) / 8))
    fail("header field offsetStrandUV (offset 16) = " + std::to_string(uv_offset) + ": strand UVs run past the end of the file");

  RawGroom g;
  g.group_names = {stem_of(name)};
  g.points.reserve(vertex_count);
  std::vector<Vec3> strand(n);
  for (uint32_t s = 0; s < strands; ++s) {
    for (uint32_t v = 0; v < n; ++v) {
      const uint64_t at = pos_offset + (uint64_t{s} * n + v) * stride;
      const float x = load<float>(b, at), y = load<float>(b, at + 4), z = load<float>(b, at + 8);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        fail("strand " + std::to_string(s) + " vertex " + std::to_string(v) + ": non-finite position (byte offset " +
             std::to_string(at) + ")");
      strand[v] = {x, y, z};
    }
    g.add_strand(strand.data(), n, 0, both_ends);
  }
  if (uv_offset) {
    g.strand_uv.resize(strands);
    for (uint32_t s = 0; s < strands; ++s) {
      const float u = load<float>(b, uv_offset + 8ull * s), v = load<float>(b, uv_offset + 8ull * s + 4);
      if (!std::isfinite(u) || !std::isfinite(v)) fail("strand " + std::to_string(s) + ": non-finite strand UV");
      g.strand_uv[s] = {u, v};
    }
  }
  g.input_vertices = vertex_count;
  return g;
}

RawGroom import_tfx(const std::filesystem::path& path) {
  const auto bytes = read_binary_file(path);
  return import_tfx_bytes(bytes, path.string());
}

namespace {

struct BoneRecords {
  std::vector<asset::BoneInfluences> bones;
  uint64_t dropped = 0;
};

// Per-strand records of either layout; must use up the file exactly.
BoneRecords parse_bone_records(BinaryCursor& c, bool layout4, int32_t strand_count, int32_t bone_count) {
  BoneRecords out;
  out.bones.resize(static_cast<size_t>(strand_count));
  std::vector<uint8_t> assigned(out.bones.size(), 0);
  std::vector<std::pair<float, uint32_t>> infl;
  const char* layout = layout4 ? " (4.x layout)" : " (5.x layout)";
  for (int32_t s = 0; s < strand_count; ++s) {
    const int32_t index = c.get<int32_t>("strand index");
    if (index < 0 || index >= strand_count)
      c.fail("strand record " + std::to_string(s) + ": strand index " + std::to_string(index) + " out of range" + layout);
    const int32_t count = layout4 ? 4 : c.get<int32_t>("influence count");
    if (count < 0 || count > 64)
      c.fail("strand " + std::to_string(index) + ": influence count " + std::to_string(count) + " out of range" + layout);
    infl.clear();
    for (int32_t k = 0; k < count; ++k) {
      const int32_t bone = c.get<int32_t>("bone index");
      const float w = c.get<float>("bone weight");
      if (!std::isfinite(w) || w < 0)
        c.fail("strand " + std::to_string(index) + ": weight " + std::to_string(w) + " is not finite and >= 0" + layout);
      if (w == 0) continue;  // unused slot (4.x pads with zero weights, often with bone index -1)
      if (bone < 0 || bone >= bone_count)
        c.fail("strand " + std::to_string(index) + ": bone index " + std::to_string(bone) + " out of range" + layout);
      infl.emplace_back(w, static_cast<uint32_t>(bone));
    }
    if (infl.empty()) c.fail("strand " + std::to_string(index) + ": no bone influence with a positive weight" + layout);
    if (assigned[static_cast<size_t>(index)]) c.fail("strand " + std::to_string(index) + " has two records" + layout);
    assigned[static_cast<size_t>(index)] = 1;
    // Largest first; equal weights by bone index, so the result never depends on the file's slot order.
    std::sort(infl.begin(), infl.end(),
              [](const auto& x, const auto& y) { return x.first != y.first ? x.first > y.first : x.second < y.second; });
    if (infl.size() > asset::kMaxBoneInfluences) {
      out.dropped += infl.size() - asset::kMaxBoneInfluences;
      infl.resize(asset::kMaxBoneInfluences);
    }
    double sum = 0;
    for (const auto& i : infl) sum += i.first;
    auto& bones = out.bones[static_cast<size_t>(index)];
    for (size_t k = 0; k < infl.size(); ++k) {
      bones.bone[k] = infl[k].second;
      bones.weight[k] = static_cast<float>(infl[k].first / sum);
    }
  }
  if (c.remaining() != 0)
    c.fail(std::to_string(c.remaining()) + " unexpected bytes after the last strand record" + layout);
  return out;
}

}  // namespace

void apply_tfxbone_bytes(RawGroom& groom, std::span<const std::byte> b, std::string_view name) {
  BinaryCursor c(b, name);
  if (b.empty()) c.fail("empty file");
  const int32_t bone_count = c.get<int32_t>("numBones");
  // Each bone entry takes at least 9 bytes, so a larger count cannot be right (and must not be allocated).
  if (bone_count <= 0 || static_cast<uint64_t>(bone_count) > c.remaining() / 9)
    c.fail("field numBones = " + std::to_string(bone_count) + " is not a plausible bone count");
  std::vector<std::string> names(static_cast<size_t>(bone_count));
  std::vector<uint8_t> named(names.size(), 0);
  for (int32_t i = 0; i < bone_count; ++i) {
    const int32_t index = c.get<int32_t>("bone index");
    const int32_t len = c.get<int32_t>("bone name length");
    if (index < 0 || index >= bone_count) c.fail("bone " + std::to_string(i) + ": index " + std::to_string(index) + " out of range");
    if (len <= 0 || static_cast<size_t>(len) > c.remaining() || len > 4096)
      c.fail("bone " + std::to_string(i) + ": name length " + std::to_string(len) + " is invalid");
    std::string s(reinterpret_cast<const char*>(b.data() + c.pos()), static_cast<size_t>(len));
    c.skip(static_cast<size_t>(len));
    s = s.substr(0, s.find('\0'));
    if (named[static_cast<size_t>(index)]) c.fail("bone index " + std::to_string(index) + " appears twice");
    named[static_cast<size_t>(index)] = 1;
    names[static_cast<size_t>(index)] = s;
  }
  const int32_t strand_count = c.get<int32_t>("numStrands");
  if (strand_count < 0 || static_cast<uint64_t>(strand_count) != groom.strand_count())
    c.fail("field numStrands = " + std::to_string(strand_count) + " but the hair has " +
           std::to_string(groom.strand_count()) + " strands");
  // The two layouts have no version field. 4.x is exactly 36 bytes per strand; when the size fits, try it first
  // and fall back to 5.x if the records do not make sense as 4.x (a 5.x file can have that size by chance).
  BoneRecords result;
  if (c.remaining() == 36ull * static_cast<uint64_t>(strand_count)) {
    BinaryCursor c4 = c;
    try {
      result = parse_bone_records(c4, true, strand_count, bone_count);
    } catch (const InputError& error4) {
      try {
        BinaryCursor c5 = c;
        result = parse_bone_records(c5, false, strand_count, bone_count);
      } catch (const InputError&) {
        throw error4;
      }
    }
  } else {
    result = parse_bone_records(c, false, strand_count, bone_count);
  }
  groom.bone_influences_dropped += result.dropped;
  groom.bone_names = std::move(names);
  groom.strand_bones = std::move(result.bones);
}

void apply_tfxbone(RawGroom& groom, const std::filesystem::path& path) {
  const auto bytes = read_binary_file(path);
  apply_tfxbone_bytes(groom, bytes, path.string());
}

namespace {

// Read-only memory map of a whole file: OBJ grooms reach hundreds of megabytes, and mapping avoids zero-filling
// and copying them (measured: about a fifth of the bake's time at 3.2 M vertices).
class MappedFile {
 public:
  explicit MappedFile(const std::filesystem::path& path) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw IoError(path.string() + ": cannot open");
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd_);
      throw IoError(path.string() + ": not a readable regular file");
    }
    size_ = static_cast<size_t>(st.st_size);
    if (size_ > 0) {
      data_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd_, 0);
      if (data_ == MAP_FAILED) {
        ::close(fd_);
        throw IoError(path.string() + ": cannot map the file");
      }
    }
  }
  ~MappedFile() {
    if (data_ && data_ != MAP_FAILED) ::munmap(data_, size_);
    if (fd_ >= 0) ::close(fd_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::string_view text() const { return size_ ? std::string_view(static_cast<const char*>(data_), size_) : std::string_view(); }

 private:
  int fd_ = -1;
  void* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace

RawGroom import_obj(const std::filesystem::path& path, const ObjImportOptions& options) {
  const MappedFile file(path);
  return import_obj_text(file.text(), path.string(), options);
}

RawGroom import_file(const std::filesystem::path& path, const ObjImportOptions& options) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (ext == ".tfx") return import_tfx(path);
  if (ext == ".obj") return import_obj(path, options);
  if (std::filesystem::is_directory(path)) throw IoError(path.string() + ": is a directory, not a hair file");
  // Unknown extension: a .tfx starts with a float version 3.x/4.x, an OBJ is text.
  const auto bytes = read_binary_file(path);
  if (bytes.size() >= 4) {
    const float v = load<float>(bytes, 0);
    if (v >= 3.0f && v < 6.0f) return import_tfx_bytes(bytes, path.string());
  }
  return import_obj_text(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path.string(), options);
}

}  // namespace tressvk::baker
