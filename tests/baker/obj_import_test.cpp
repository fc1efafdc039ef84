// Every OBJ input form the issue lists, and every refusal, on small hand-written files.
#include "test_support.hpp"

#include <tressvk/baker/errors.hpp>

#include <catch2/matchers/catch_matchers_string.hpp>

using namespace tressvk;
using Catch::Matchers::ContainsSubstring;

namespace {

baker::RawGroom import(const std::string& text, baker::ObjImportOptions o = {}) {
  return baker::import_obj_text(text, "test.obj", o);
}

std::vector<baker::Vec3> strand(const baker::RawGroom& g, size_t s) {
  return {g.points.begin() + g.strand_begin[s], g.points.begin() + g.strand_begin[s + 1]};
}

// Two strands of three vertices along +Y at x = 0 and x = 1, vertices 1-3 and 4-6.
const std::string kVerts =
    "v 0 0 0\nv 0 1 0\nv 0 2 0\n"
    "v 1 0 0\nv 1 1 0\nv 1 2 0\n";

void check_two_strands(const baker::RawGroom& g, bool reversed_second = false) {
  REQUIRE(g.strand_count() == 2);
  const auto a = strand(g, 0), b = strand(g, 1);
  REQUIRE(a.size() == 3);
  REQUIRE(b.size() == 3);
  CHECK(a.front() == baker::Vec3{0, 0, 0});
  CHECK(a.back() == baker::Vec3{0, 2, 0});
  CHECK(b.front() == (reversed_second ? baker::Vec3{1, 2, 0} : baker::Vec3{1, 0, 0}));
}

std::string message_of(const std::string& text, baker::ObjImportOptions o = {}) {
  try {
    import(text, o);
  } catch (const baker::InputError& e) {
    return e.what();
  }
  return "<no error>";
}

}  // namespace

TEST_CASE("OBJ: Blender-style 2-index edges, strand after strand", "[baker][obj]") {
  check_two_strands(import(kVerts + "l 1 2\nl 2 3\nl 4 5\nl 5 6\n"));
}

TEST_CASE("OBJ: 2-index edges in any order and either direction are chained", "[baker][obj]") {
  // Root = the end with the lower vertex index, whatever the edge directions.
  check_two_strands(import(kVerts + "l 6 5\nl 2 1\nl 4 5\nl 3 2\n"));
}

TEST_CASE("OBJ: one multi-index record per strand; its first index is the root", "[baker][obj]") {
  check_two_strands(import(kVerts + "l 1 2 3\nl 6 5 4\n"), /*reversed_second=*/true);
}

TEST_CASE("OBJ: relative (negative) indices", "[baker][obj]") {
  check_two_strands(import("v 0 0 0\nv 0 1 0\nv 0 2 0\nl -3 -2 -1\nv 1 0 0\nv 1 1 0\nv 1 2 0\nl -3 -2\nl -2 -1\n"));
}

TEST_CASE("OBJ: CRLF, comments, normals, texture coordinates and other noise", "[baker][obj]") {
  const std::string text =
      "# exported\r\nmtllib hair.mtl\r\nv 0 0 0\r\nv 0 1 0\r\nv 0 2 0\r\nvt 0 0\r\nvt 0 1\r\nvn 0 1 0\r\n"
      "usemtl hairmat\r\ns off\r\nv 1 0 0 1.0\r\nv 1 1 0 1.0\r\nv 1 2 0 1.0\r\n"
      "l 1/1 2/2 3/1\r\n  l\t4 5   6  \r\n# end\r\n";
  const auto g = import(text);
  check_two_strands(g);
  CHECK(g.ignored_records >= 5);
}

TEST_CASE("OBJ: a UTF-8 byte order mark and trailing comments", "[baker][obj]") {
  check_two_strands(import("\xEF\xBB\xBF" + kVerts + "l 1 2 3 # first strand\nl 4 5 6# second\n"));
}

TEST_CASE("OBJ: faces of other objects are not hair; o/g names become groups", "[baker][obj]") {
  const std::string text = kVerts + "v 5 5 5\nv 6 5 5\nv 5 6 5\n" +
                           "o head\nf 7 8 9\ng fringe\nl 1 2 3\ng crown\nl 4 5 6\n";
  const auto g = import(text);
  REQUIRE(g.strand_count() == 2);
  REQUIRE(g.group_names == std::vector<std::string>{"fringe", "crown"});
  CHECK(g.strand_group == std::vector<uint32_t>{0, 1});
  const auto a = tvk_test::bake_obj(text);
  REQUIRE(a.groups.size() == 2);
  CHECK(a.groups[0].name == "fringe");
  CHECK(a.guide_group == std::vector<uint16_t>{0, 1});
}

TEST_CASE("OBJ: strands outside any o/g take the file's stem as group name", "[baker][obj]") {
  const auto g = baker::import_obj_text(kVerts + "l 1 2 3\n", "dir/my_hair.obj");
  CHECK(g.group_names == std::vector<std::string>{"my_hair"});
}

TEST_CASE("OBJ: --root-from faces picks the end nearer the file's own faces", "[baker][obj]") {
  // The strand is written tip first (lower index at the far end); the scalp triangle sits at y = 2.
  const std::string text = "v 0 0 0\nv 0 1 0\nv 0 2.1 0\nv -1 2 -1\nv 1 2 -1\nv 0 2 1\nf 4 5 6\nl 1 2 3\n";
  baker::ObjImportOptions o;
  o.root_from = baker::RootFrom::kFaces;
  const auto g = import(text, o);
  REQUIRE(g.strand_count() == 1);
  CHECK(strand(g, 0).front() == baker::Vec3{0, 2.1, 0});
  CHECK(strand(import(text), 0).front() == baker::Vec3{0, 0, 0});  // default: lower index
}

TEST_CASE("OBJ: --scalp orients strands toward a separate mesh", "[baker][obj]") {
  auto g = import(kVerts + "l 1 2 3\nl 4 5 6\n");
  const auto scalp_path = tvk_test::write_text("scalp.obj", "v -5 2.5 -5\nv 5 2.5 -5\nv 0 2.5 5\nf 1 2 3\n");
  baker::orient_to_scalp(g, baker::load_scalp(scalp_path));
  CHECK(strand(g, 0).front() == baker::Vec3{0, 2, 0});
  CHECK(strand(g, 1).front() == baker::Vec3{1, 2, 0});
}

TEST_CASE("OBJ: duplicate edges and repeated vertices in a record are harmless", "[baker][obj]") {
  check_two_strands(import(kVerts + "l 1 2\nl 2 1\nl 2 3\nl 4 5 5 6\n"));
}

TEST_CASE("OBJ refusals name the file and line", "[baker][obj]") {
  CHECK_THAT(message_of(""), ContainsSubstring("test.obj") && ContainsSubstring("empty"));
  CHECK_THAT(message_of("# only a comment\n\n"), ContainsSubstring("empty"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), ContainsSubstring("no hair") && ContainsSubstring("faces"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 0 0\n"), ContainsSubstring("no hair"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 0 0\nl 1 3\n"), ContainsSubstring("test.obj:3:") && ContainsSubstring("out of range"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 0 0\nl -3 -1\n"), ContainsSubstring("test.obj:3:") && ContainsSubstring("before the first"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 0 0\nl 0 1\n"), ContainsSubstring("test.obj:3:") && ContainsSubstring("index 0"));
  CHECK_THAT(message_of("v 0 0 0\nv nan 0 0\nl 1 2\n"), ContainsSubstring("test.obj:2:") && ContainsSubstring("not finite"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 inf 0\nl 1 2\n"), ContainsSubstring("test.obj:2:") && ContainsSubstring("not finite"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 abc 0\nl 1 2\n"), ContainsSubstring("test.obj:2:") && ContainsSubstring("cannot parse"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 0\nl 1 2\n"), ContainsSubstring("test.obj:2:"));
  CHECK_THAT(message_of("v 0 0 0\nv 1 0 0\nl 1 x\n"), ContainsSubstring("test.obj:3:") && ContainsSubstring("index"));
  CHECK_THAT(message_of("v 0 0 0\nl 1\n"), ContainsSubstring("test.obj:2:") && ContainsSubstring("single vertex"));
  CHECK_THAT(message_of(std::string("v 0 0 0\n\x89PNG\x00\x01\x02", 15)), ContainsSubstring("test.obj:2:") && ContainsSubstring("binary"));
  // A vertex joining three edges, and a closed loop.
  CHECK_THAT(message_of("v 0 0 0\nv 0 1 0\nv 0 2 0\nv 1 1 0\nl 1 2\nl 2 3\nl 2 4\n"),
             ContainsSubstring("test.obj:") && ContainsSubstring("branch"));
  CHECK_THAT(message_of(kVerts + "l 1 2 3 1\n"), ContainsSubstring("test.obj:7:") && ContainsSubstring("loop"));
}

TEST_CASE("OBJ: --skip-invalid drops branching and looping strands and counts them", "[baker][obj]") {
  const std::string text = kVerts + "v 5 0 0\nv 5 1 0\nv 5 2 0\nv 6 1 0\nv 7 0 0\nv 7 1 0\nv 7 2 0\n" +
                           "l 1 2 3\nl 7 8\nl 8 9\nl 8 10\nl 11 12 13 11\nl 4 5 6\n";
  baker::ObjImportOptions o;
  o.skip_invalid = true;
  const auto g = import(text, o);
  check_two_strands(g);
  CHECK(g.skipped_invalid == 2);
  // Without the flag the same file is refused.
  CHECK_THROWS_AS(import(text), baker::InputError);
  // Nothing valid left is still an error.
  CHECK_THROWS_AS(import("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3 1\n", o), baker::InputError);
}
