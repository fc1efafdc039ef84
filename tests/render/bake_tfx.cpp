// Test helper: bakes a TressFX .tfx groom (metres) into a .tvkhair with the baker library.
//   tressvk_render_bake_tfx IN.tfx OUT.tvkhair
#include <tressvk/asset_io.hpp>
#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/import.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s IN.tfx OUT.tvkhair\n", argv[0]);
    return 2;
  }
  try {
    const tressvk::baker::RawGroom groom = tressvk::baker::import_tfx(argv[1]);
    tressvk::baker::BakeOptions options;
    options.vertices_per_strand = 32;
    options.follow_per_guide = 2;
    const tressvk::asset::HairAsset asset = tressvk::baker::bake(groom, options);
    if (const std::string error = tressvk::asset::write_file(argv[2], asset); !error.empty()) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    std::printf("baked %s: %u guides x %u vertices -> %s\n", argv[1], asset.guide_count(), asset.vertices_per_strand,
                argv[2]);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
    return 1;
  }
}
