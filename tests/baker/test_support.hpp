// Helpers shared by the baker tests: the real-data directory, temporary files and running tressvk-bake.
#pragma once

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/import.hpp>

#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace tvk_test {

namespace fs = std::filesystem;

// TRESSVK_DATA_DIR, or ../shared/data next to the repository; empty when absent.
inline fs::path data_dir() {
  const char* env = std::getenv("TRESSVK_DATA_DIR");
  fs::path p = env ? fs::path(env) : fs::path(TRESSVK_SOURCE_DIR) / ".." / "shared" / "data";
  return fs::exists(p / "README.md") ? p : fs::path();
}

#define TVK_REQUIRE_DATA(dir)                                                                         \
  const auto dir = ::tvk_test::data_dir();                                                            \
  if (dir.empty()) SKIP("real hair data not found: set TRESSVK_DATA_DIR to the shared/data directory")

// A fresh directory per test process, removed when the process ends.
inline fs::path temp_dir() {
  struct Dir {
    fs::path path = fs::temp_directory_path() / ("tressvk-baker-test-" + std::to_string(::getpid()));
    Dir() { fs::create_directories(path); }
    ~Dir() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  };
  static const Dir dir;
  return dir.path;
}

inline fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

inline std::vector<std::byte> read_bytes(const fs::path& p) { return tressvk::baker::read_binary_file(p); }

inline void write_bytes(const fs::path& p, const std::vector<std::byte>& b) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// Runs tressvk-bake with the given argument string (already quoted); returns its exit code, or -signal when it
// was killed by a signal (a crash).
inline int run_bake(const std::string& args, bool quiet_output = true) {
  std::string cmd = std::string("\"") + TRESSVK_BAKE_EXE + "\" " + args;
  if (quiet_output) cmd += " >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  if (status == -1) return -1000;
  if (WIFSIGNALED(status)) return -WTERMSIG(status);
  return WEXITSTATUS(status);
}

inline std::string quoted(const fs::path& p) { return "\"" + p.string() + "\""; }

inline tressvk::asset::HairAsset bake_obj(const std::string& text, tressvk::baker::BakeOptions options = {},
                                          tressvk::baker::ObjImportOptions import_options = {}) {
  options.shuffle = false;  // hand-written tests check strands in file order
  return tressvk::baker::bake(tressvk::baker::import_obj_text(text, "test.obj", import_options), options);
}

// Guide vertex position in asset space (origin added), double.
inline std::array<double, 3> position(const tressvk::asset::HairAsset& a, uint32_t guide, uint32_t v) {
  const auto& p = a.rest_positions[guide * a.vertices_per_strand + v];
  return {a.origin[0] + p[0], a.origin[1] + p[1], a.origin[2] + p[2]};
}

inline double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

inline double guide_length(const tressvk::asset::HairAsset& a, uint32_t guide) {
  double l = 0;
  for (uint32_t v = 0; v + 1 < a.vertices_per_strand; ++v) l += a.rest_lengths[guide * a.vertices_per_strand + v];
  return l;
}

}  // namespace tvk_test
