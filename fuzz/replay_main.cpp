// Replays fuzz inputs through a target without libFuzzer, in any build (gcc, the ci preset): every argument is
// a file or a directory of files, each passed once to LLVMFuzzerTestOneInput. A finding aborts with its message,
// so ctest fails naming the input just printed. This is how ./scripts/test.sh replays fuzz/regressions/.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace fs = std::filesystem;

static void run_file(const fs::path& p, size_t& count) {
  std::ifstream in(p, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "cannot read %s\n", p.string().c_str());
    std::exit(2);
  }
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::printf("replay %s (%zu bytes)\n", p.string().c_str(), bytes.size());
  std::fflush(stdout);
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  ++count;
}

int main(int argc, char** argv) {
  size_t count = 0;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg = argv[i];
    if (fs::is_directory(arg)) {
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(arg))
        if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const auto& f : files) run_file(f, count);
    } else if (fs::exists(arg)) {
      run_file(arg, count);
    }
  }
  std::printf("replayed %zu input(s) without a finding\n", count);
  // A replay that found nothing to replay proves nothing (a moved or misspelt directory).
  if (count == 0) {
    std::fprintf(stderr, "no input found in the arguments\n");
    return 1;
  }
  return 0;
}
