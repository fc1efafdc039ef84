// Mutates valid inputs many times: the importers and the bake must only ever succeed or report invalid input
// (InputError; exit 2 from the CLI), never crash, hang or throw anything else. Runs under ASan/UBSan too.
#include "test_support.hpp"

#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/procedural.hpp>

#include "vec_math.hpp"  // baker/src: baker::Random

#include <algorithm>
#include <cstdlib>
#include <cstring>

using namespace tressvk;

namespace {

// Its random numbers are the baker's own deterministic generator (SplitMix64), so a seed is one input everywhere.
class Mutator {
 public:
  explicit Mutator(uint64_t seed) : random_(seed) {}
  size_t below(size_t n) { return static_cast<size_t>(random_.below(n)); }

  // One to four random edits: flip, overwrite with an interesting byte, insert, delete, duplicate a span,
  // truncate. Text-aware choices (digits, '-', spaces, newlines, 'l', '/') make OBJ mutations reach deeper.
  std::vector<std::byte> mutate(std::vector<std::byte> b) {
    static constexpr unsigned char kInteresting[] = {'0', '1', '9', '-', ' ', '\n', '\r', 'l', 'v', 'f', '/', 'e',
                                                     '.', 'n', 0, 0xFF, 0x7F, 0x80};
    const size_t edits = 1 + below(4);
    for (size_t e = 0; e < edits; ++e) {
      const size_t at = below(b.size() + 1);
      switch (below(6)) {
        case 0:
          if (at < b.size()) b[at] ^= std::byte{static_cast<unsigned char>(1u << below(8))};
          break;
        case 1:
          if (at < b.size()) b[at] = std::byte{kInteresting[below(sizeof kInteresting)]};
          break;
        case 2:
          b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), std::byte{kInteresting[below(sizeof kInteresting)]});
          break;
        case 3:
          if (at < b.size()) b.erase(b.begin() + static_cast<std::ptrdiff_t>(at), b.begin() + static_cast<std::ptrdiff_t>(std::min(b.size(), at + 1 + below(16))));
          break;
        case 4: {
          if (at >= b.size()) break;
          const size_t len = std::min(b.size() - at, 1 + below(64));
          std::vector<std::byte> span(b.begin() + static_cast<std::ptrdiff_t>(at), b.begin() + static_cast<std::ptrdiff_t>(at + len));
          b.insert(b.begin() + static_cast<std::ptrdiff_t>(below(b.size())), span.begin(), span.end());
          break;
        }
        default:
          b.resize(below(b.size() + 1));
      }
    }
    return b;
  }

 private:
  baker::Random random_;
};

// TRESSVK_FUZZ_SCALE multiplies the iteration counts for a longer local run (CI keeps the default of 1).
int scaled(int n) {
  const char* env = std::getenv("TRESSVK_FUZZ_SCALE");
  return env ? n * std::max(1, std::atoi(env)) : n;
}

std::vector<std::byte> to_bytes(const std::string& s) {
  std::vector<std::byte> b(s.size());
  std::memcpy(b.data(), s.data(), s.size());
  return b;
}

std::string obj_seed() {
  return "# groom\r\no hair\nv 0 0 0\nv 0 0.1 0.001\nv 0 0.2 0.003\nv 0 0.3 0.006\nl 1 2\nl 2 3\nl 3 4\n"
         "g two\nv 1 0 0\nv 1 0.1 0\nv 1 0.2 0\nl -3 -2 -1\nvn 0 1 0\nvt 0.5 0.5\nf 1 2 5\n"
         "v 2 0 0\nv 2 0.1 0\nv 2 0.2 0\nv 2 0.3 0\nl 8/1 9/1 10/1 11/1\n";
}

// A small .tfx v4 with UVs, and a matching .tfxbone in the 5.x layout.
std::vector<std::byte> tfx_seed() {
  const uint32_t strands = 3, n = 4;
  std::vector<std::byte> b(160 + strands * n * 16 + strands * 8);
  const float version = 4.0f;
  const uint32_t header[] = {strands, n, 160, 160 + strands * n * 16};
  std::memcpy(b.data(), &version, 4);
  std::memcpy(b.data() + 4, header, sizeof header);
  for (uint32_t s = 0; s < strands; ++s)
    for (uint32_t v = 0; v < n; ++v) {
      const auto fs = static_cast<float>(s), fv = static_cast<float>(v);
      const float p[4] = {0.1f * fs, 0.05f * fv, 0.01f * fv * fv, v < 2 ? 0.0f : 1.0f};
      std::memcpy(b.data() + 160 + (s * n + v) * 16, p, 16);
    }
  return b;
}

std::vector<std::byte> tfxbone_seed() {
  std::vector<std::byte> b;
  auto put = [&](auto v) {
    const size_t at = b.size();
    b.resize(at + sizeof v);
    std::memcpy(b.data() + at, &v, sizeof v);
  };
  put(int32_t{2});
  for (int32_t i = 0; i < 2; ++i) {
    put(i);
    put(int32_t{3});
    put('b');
    put(static_cast<char>('0' + i));
    put('\0');
  }
  put(int32_t{3});
  for (int32_t s = 0; s < 3; ++s) {
    put(s);
    put(int32_t{2});
    put(int32_t{0});
    put(0.7f);
    put(int32_t{1});
    put(0.3f);
  }
  return b;
}

// Runs `bake_input` (import and bake): true when it gives a valid asset, false on a reported invalid input;
// anything else escapes and fails the test.
template <class Bake>
bool bakes_or_refuses(Bake&& bake_input) {
  try {
    const asset::HairAsset a = bake_input();
    const auto issues = asset::validate(a);
    INFO((issues.empty() ? std::string() : issues.front()));
    REQUIRE(issues.empty());
    return true;
  } catch (const baker::InputError&) {
    return false;
  }
}

bool bake_obj_bytes(const std::vector<std::byte>& b) {
  return bakes_or_refuses([&] {
    auto g = baker::import_obj_text(std::string_view(reinterpret_cast<const char*>(b.data()), b.size()), "m.obj");
    baker::BakeOptions o;
    o.vertices_per_strand = 5;
    o.follow_per_guide = 1;
    return baker::bake(g, o);
  });
}

bool bake_tfx_bytes(const std::vector<std::byte>& tfx, const std::vector<std::byte>& bone) {
  return bakes_or_refuses([&] {
    auto g = baker::import_tfx_bytes(tfx, "m.tfx");
    if (!bone.empty()) baker::apply_tfxbone_bytes(g, bone, "m.tfxbone");
    return baker::bake(g, {});
  });
}

}  // namespace

TEST_CASE("Robustness: the seeds themselves are valid", "[baker][robustness]") {
  CHECK(bake_obj_bytes(to_bytes(obj_seed())));
  CHECK(bake_tfx_bytes(tfx_seed(), tfxbone_seed()));
}

TEST_CASE("Robustness: mutated OBJ text never crashes the importer or the bake", "[baker][robustness]") {
  Mutator m(1);
  const auto seed = to_bytes(obj_seed());
  int ok = 0;
  for (int i = 0; i < scaled(3000); ++i) ok += bake_obj_bytes(m.mutate(seed));
  CHECK(ok > 0);  // the mutations are gentle enough that some inputs stay valid
}

TEST_CASE("Robustness: mutated .tfx and .tfxbone never crash", "[baker][robustness]") {
  Mutator m(2);
  const auto tfx = tfx_seed(), bone = tfxbone_seed();
  for (int i = 0; i < scaled(1500); ++i) bake_tfx_bytes(m.mutate(tfx), {});
  for (int i = 0; i < scaled(1500); ++i) bake_tfx_bytes(tfx, m.mutate(bone));
  SUCCEED("no crash, no unexpected exception");
}

TEST_CASE("Robustness: mutated real OBJ data never crashes", "[baker][robustness]") {
  const auto dir = tvk_test::data_dir();
  if (dir.empty()) SKIP("real hair data not found: set TRESSVK_DATA_DIR to the shared/data directory");
  // Cube_Hair.obj (Blender edges, 1,000 strands), mutated; most mutants stay bakeable.
  const auto bytes = tvk_test::read_bytes(dir / "unity" / "Cube_Hair.obj");
  Mutator m(5);
  int ok = 0;
  for (int i = 0; i < scaled(100); ++i) ok += bake_obj_bytes(m.mutate(bytes));
  CHECK(ok > 0);
}

TEST_CASE("Robustness: mutated .tvkhair files are refused cleanly by the reader", "[baker][robustness]") {
  Mutator m(3);
  baker::BuiltinGroomOptions o;
  o.guide_count = 8;
  o.vertices_per_strand = 4;
  o.follow_per_guide = 1;
  const auto bytes = asset::write(baker::make_builtin_groom("straight", o));
  int refused = 0;
  const int runs = scaled(2000);
  for (int i = 0; i < runs; ++i) {
    const auto r = asset::read(m.mutate(bytes));
    if (!r.ok()) {
      ++refused;
      CHECK_FALSE(r.error.empty());
    } else {
      CHECK(asset::validate(r.asset).empty());
    }
  }
  CHECK(refused > runs * 95 / 100);  // checksums catch nearly everything; the rest must still be consistent
}

TEST_CASE("Robustness: the CLI exits 0 or 2 on mutated inputs, never crashes", "[baker][robustness][cli]") {
  Mutator m(4);
  const auto out = tvk_test::temp_dir() / "robust.tvkhair";
  const auto obj = tvk_test::temp_dir() / "robust.obj";
  const auto tfx = tvk_test::temp_dir() / "robust.tfx";
  const auto bone = tvk_test::temp_dir() / "robust.tfxbone";
  tvk_test::write_bytes(bone, tfxbone_seed());
  for (int i = 0; i < scaled(12); ++i) {
    tvk_test::write_bytes(obj, m.mutate(to_bytes(obj_seed())));
    const int rc = tvk_test::run_bake(tvk_test::quoted(obj) + " -o " + tvk_test::quoted(out) + " --follow 2");
    INFO("obj mutation " << i);
    CHECK((rc == 0 || rc == 2));
    tvk_test::write_bytes(tfx, m.mutate(tfx_seed()));
    const int rc2 = tvk_test::run_bake(tvk_test::quoted(tfx) + " --bones " + tvk_test::quoted(bone) + " -o " + tvk_test::quoted(out));
    CHECK((rc2 == 0 || rc2 == 2));
    if (rc == 0 || rc2 == 0) {
      const int rc3 = tvk_test::run_bake("validate " + tvk_test::quoted(out));
      CHECK(rc3 == 0);
    }
  }
}
