// The compute strand rasterizer against its brute-force reference (tressvk/reference/strand_raster.hpp: every
// fragment kept, sorted per pixel by its own depth, composited front to back in double), on the demo's frame
// (the same code tressvk-demo runs), on lavapipe with validation and synchronization validation.
//
// Targets (issue 9, docs/rendering.md): mean error <= 1/255 and 99th percentile <= 8/255 over the hair pixels.
// They are the acceptance targets themselves, not tolerances widened to pass: the rasterizer sorts whole segments
// per tile (by their depth near the tile centre) instead of single fragments, reorders only the last 4 fragments
// of a pixel by their own depth, stops a pixel 4 fragments after alpha >= 1 - 0.5/255 and writes half floats, and those are the
// differences measured here.
#include <tressvk/test/vulkan.hpp>

#include "demo_app.hpp"
#include "still_frame.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/import.hpp>
#include <tressvk/engine/png.hpp>
#include <tressvk/reference/strand_raster.hpp>

#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using tressvk::demo::DemoApp;
using tressvk::demo::Options;
namespace ref = tressvk::reference;

Options scene_options() {
  Options o = tressvk::test::still_frame_options(256, 400, 3);  // rest pose: the same vertices in every run
  o.sample = tressvk::demo::Sample::sphere;  // the renderer's own scene (the head sample has its poster tests)
  return o;
}

struct Captured {
  ref::StrandRasterInput input;
  std::vector<float> vertices, host_depth;
  ref::HairLayer layer;
  TvkRasterStats stats{};
  tressvk::engine::Pixels pixels;
};

Captured capture(const Options& options, uint32_t flags = 0) {
  Options o = options;
  o.raster_flags = TVK_RASTER_CAPTURE | flags;
  DemoApp app(tressvk::test::device(), o);
  Captured c;
  app.run(2, [&](tressvk::demo::FrameReport& f) { c.pixels = std::move(f.pixels); });
  TvkRasterCapture cap{};
  REQUIRE(tressvk_get_raster_capture(app.renderer(), &cap) == TVK_SUCCESS);
  REQUIRE(tressvk_get_raster_stats(app.renderer(), &c.stats) == TVK_SUCCESS);
  c.vertices.assign(cap.vertices, cap.vertices + size_t{8} * cap.strands * cap.vertices_per_strand);
  c.host_depth.assign(cap.host_depth, cap.host_depth + size_t{cap.width} * cap.height);
  c.input = ref::StrandRasterInput{cap.width, cap.height, cap.vertices_per_strand, cap.strands, c.vertices.data(),
                                   c.host_depth.data()};
  c.layer = ref::layer_from_half(cap.width, cap.height, cap.layer);
  return c;
}

std::filesystem::path out_dir() { return TRESSVK_RENDER_TEST_OUT; }

void check_against_reference(const Captured& c, const std::string& name) {
  uint64_t fragments = 0;
  const ref::HairLayer reference = ref::render_strands_reference(c.input, &fragments);
  const ref::LayerError e = ref::compare_layers(c.layer, reference);
  tressvk::engine::write_png(out_dir() / (name + ".compute.png"), c.pixels);
  INFO(name << ": error mean " << e.mean << "/255, p99 " << e.p99 << "/255, max " << e.max << "/255 over "
            << e.hair_pixels << " hair pixels; " << c.stats.fragments << " fragments composited, " << fragments
            << " in the reference; dropped entries " << c.stats.dropped_entries << ", dropped slice entries "
            << c.stats.dropped_slice_entries);
  CHECK(e.hair_pixels > 1000);  // the hair is there
  CHECK(e.mean <= 1.0);
  CHECK(e.p99 <= 8.0);
  CHECK(c.stats.dropped_entries == 0);
  // tressvk_cmd_shadow_hair copied only the rectangle of the shadow map the hair can reach: no hair sample fell
  // outside it (a bound that is not conservative would lose hair shadows there).
  CHECK(c.stats.shadow_samples_outside == 0);
}

}  // namespace

TEST_CASE("render: compute path matches the sorted reference on the demo scene", "[render][vulkan][compute]") {
  const Captured c = capture(scene_options());
  check_against_reference(c, "compute_demo_scene");
}

TEST_CASE("render: compute path with hair in front of and behind the opaque head", "[render][vulkan][compute]") {
  // The demo's camera looks at the head with hair on both sides of it: hair behind the head must be hidden by its
  // depth, hair in front drawn over it. Measured here: the host depth test removes fragments the reference would
  // otherwise keep, and the image still matches the reference with that test.
  Options o = scene_options();
  o.camera_distance = 0.9f;  // close: the head fills the centre and hides much of the back hair
  const Captured c = capture(o);
  check_against_reference(c, "compute_front_behind");
  std::vector<float> no_depth(c.host_depth.size(), 1.0f);
  ref::StrandRasterInput without = c.input;
  without.host_depth = no_depth.data();
  uint64_t with_test = 0, without_test = 0;
  ref::render_strands_reference(c.input, &with_test);
  ref::render_strands_reference(without, &without_test);
  INFO("reference fragments with the host depth test " << with_test << ", without " << without_test);
  CHECK(with_test < without_test * 9 / 10);  // at least a tenth of the hair is behind the head
  CHECK(with_test > without_test / 10);      // and plenty of it in front
}

TEST_CASE("render: compute path is independent of the strand order", "[render][vulkan][compute]") {
  // The same strands submitted in reversed order: segment indices, atomics, tile lists and sort inputs all come
  // in another order. Each tile sorts its segments by a total order of their own (depth key, then a key made of
  // the segment's screen position), so the composite runs in the same order and gives the same bits; the
  // tolerance (mean 0.01/255, max 0.5/255, half the 8-bit output step) only allows for two different segments
  // with identical depth and position keys, which were never seen (measured: 0 difference). The raster path's
  // fringe, blended in strand order, cannot pass this.
  const Captured forward = capture(scene_options());
  const Captured reversed = capture(scene_options(), TVK_RASTER_REVERSE_STRANDS);
  const ref::LayerError e = ref::compare_layers(reversed.layer, forward.layer);
  INFO("reversed vs forward: mean " << e.mean << "/255, max " << e.max << "/255 over " << e.hair_pixels
                                    << " hair pixels");
  CHECK(e.hair_pixels > 1000);
  CHECK(e.mean <= 0.01);
  CHECK(e.max <= 0.5);
}

TEST_CASE("render: over-full tiles split across workgroups match the sorted reference, in any strand order",
          "[render][vulkan][compute]") {
  // A dense groom in a small view: heavy tiles are composited by several workgroups, each a share of the tile's
  // depth range, merged front to back by the last one to finish. Both rules of the scan: few tiles over 2,048
  // entries (kSplitFewAt; all 256 tiles of this view are few) are all split, before the fine pass; a dense groom's
  // many split only over 8,192 (kSplitAt), after it (TVK_RASTER_SPLIT_AS_DENSE takes that path here). The same
  // error targets as the whole tiles above, and the same bits for the strands submitted in reversed order (the
  // shares are cut from the tile's own depth histogram and merged in depth order, never in finishing order).
  Options o = scene_options();
  // 2,400 guides (9,600 strands) in 128 x 128: since binning takes a tile only where the segment's footprint meets
  // its pixel centres, 1,200 guides left no tile over 8,192 entries.
  o.guides = 2400;
  o.width = 128;
  o.height = 128;
  uint64_t split_few = 0;
  for (const uint32_t rule : {0u, uint32_t{TVK_RASTER_SPLIT_AS_DENSE}}) {
    const std::string name = rule ? "compute_split_tiles_dense" : "compute_split_tiles";
    const Captured forward = capture(o, rule);
    INFO(name << ": split tiles " << forward.stats.split_tiles << ", sliced tiles " << forward.stats.sliced_tiles);
    CHECK(forward.stats.split_tiles > 0);
    if (rule)  // only the tiles over 8,192 entries: fewer than over 2,048 (measured 24 and 60)
      CHECK(forward.stats.split_tiles < split_few);
    else
      split_few = forward.stats.split_tiles;
    check_against_reference(forward, name);
    const Captured reversed = capture(o, rule | TVK_RASTER_REVERSE_STRANDS);
    const ref::LayerError e = ref::compare_layers(reversed.layer, forward.layer);
    INFO("reversed vs forward: mean " << e.mean << "/255, max " << e.max << "/255");
    CHECK(reversed.stats.split_tiles == forward.stats.split_tiles);
    CHECK(e.mean <= 0.01);
    CHECK(e.max <= 0.5);
  }
}

TEST_CASE("render: compute path matches the sorted reference on the baked Ratboy mohawk", "[render][vulkan][compute]") {
  const char* env = std::getenv("TRESSVK_DATA_DIR");
  const std::filesystem::path tfx =
      std::filesystem::path(env ? env : TRESSVK_DATA_DIR) / "tressfx" / "ratboy" / "Ratboy_mohawk.tfx";
  if (!std::filesystem::exists(tfx)) SKIP(tfx.string() << " is absent (set TRESSVK_DATA_DIR to the shared data)");
  const tressvk::baker::RawGroom groom = tressvk::baker::import_tfx(tfx.string());
  tressvk::baker::BakeOptions bake;
  bake.vertices_per_strand = 32;
  bake.follow_per_guide = 2;
  const std::filesystem::path baked = out_dir() / "ratboy_mohawk.tvkhair";
  std::filesystem::create_directories(out_dir());
  REQUIRE(tressvk::asset::write_file(baked.string(), tressvk::baker::bake(groom, bake)).empty());
  Options o = scene_options();
  o.asset = baked.string();
  o.width = 256;
  o.height = 192;
  const Captured c = capture(o);
  check_against_reference(c, "compute_ratboy");
}

TEST_CASE("render: per-fragment shading draws the same hair, shaded near the per-vertex colours",
          "[render][vulkan][compute]") {
  // TVK_RASTER_SHADE_PER_FRAGMENT evaluates the lighting at each fragment instead of interpolating vertex colours;
  // coverage, order and depth test are the same code. The reference shades per vertex, so the difference is the
  // shading choice itself: within a segment the highlight and the deep-opacity shadow vary, and measured here
  // that moves the image by a mean of about 0.5/255 (docs/rendering.md: 1.1/255 on the H100 sample at 1080p). The
  // bound of 3/255 is not a tolerance of the rasterizer: it is what catches a broken per-fragment path (unlit,
  // black or wrongly indexed hair moves the mean by tens of levels), while the coverage must match exactly.
  const Captured vertex = capture(scene_options());
  const Captured fragment = capture(scene_options(), TVK_RASTER_SHADE_PER_FRAGMENT);
  uint64_t fragments = 0;
  const ref::HairLayer reference = ref::render_strands_reference(fragment.input, &fragments);
  const ref::LayerError e = ref::compare_layers(fragment.layer, reference);
  tressvk::engine::write_png(out_dir() / "compute_per_fragment.compute.png", fragment.pixels);
  INFO("per fragment vs per-vertex reference: mean " << e.mean << "/255, p99 " << e.p99 << "/255 over "
                                                     << e.hair_pixels << " hair pixels");
  CHECK(e.hair_pixels > 1000);
  CHECK(e.mean <= 3.0);
  CHECK(fragment.stats.fragments == vertex.stats.fragments);  // same coverage and order: the same fragments
  CHECK(fragment.stats.hair_pixels == vertex.stats.hair_pixels);
  // The strand's material and tint are looked up from the fragment's segment: reversed submission still gives
  // the same bits (as in the per-vertex order test above).
  const Captured reversed = capture(scene_options(), TVK_RASTER_SHADE_PER_FRAGMENT | TVK_RASTER_REVERSE_STRANDS);
  const ref::LayerError r = ref::compare_layers(reversed.layer, fragment.layer);
  INFO("per fragment, reversed vs forward: mean " << r.mean << "/255, max " << r.max << "/255");
  CHECK(r.mean <= 0.01);
  CHECK(r.max <= 0.5);
}

TEST_CASE("render: coverage-driven LOD thins sub-pixel strands, keeps their coverage, and says what it costs",
          "[render][vulkan][compute][lod]") {
  // TvkLodSettings::target_width_px: the drawn fraction is the strands' projected width at the instance's origin
  // over the target, each drawn strand widened by total / drawn. Here the strands are about 0.32 px wide (3 m from
  // a 256 px view), so a 1 px target draws about a third of them. Checked: the fraction follows the width (twice
  // the distance, half the strands), the summed alpha (the hair's coverage) stays within 3 % of the sorted
  // reference of ALL strands (measured +1.2 %), and the error against that reference, which is what thinning
  // costs. That error is large on this sparse view and is bounded here, not claimed small: the thinned image is
  // another sample of the same hair (a third of the strands, three times as wide, where the others were), so a
  // pixel crossed by a dropped strand misses its ~0.3 alpha. Measured mean 7.3/255, p99 63/255 (the full frame
  // against the same reference: 0.04 / 0.25); docs/rendering.md "Level of detail" has the GPU scenes. The bounds
  // (mean <= 10/255, p99 <= 90/255) catch a LOD that loses or doubles coverage (the mean moves by tens of levels).
  Options full = scene_options();
  full.guides = 1200;
  full.camera_distance = 3.0f;
  Options lod = full;
  lod.lod_target_px = 1.0f;
  lod.lod_min_fraction = 0.0f;
  Options far = lod;
  far.camera_distance = 6.0f;
  const Captured all = capture(full);
  const Captured thin = capture(lod);
  const Captured thin_far = capture(far);
  const ref::HairLayer reference = ref::render_strands_reference(all.input);
  const ref::LayerError e = ref::compare_layers(thin.layer, reference);
  const ref::LayerError e_full = ref::compare_layers(all.layer, reference);
  double alpha = 0.0, alpha_full = 0.0;
  for (size_t p = 3; p < thin.layer.rgba.size(); p += 4) alpha += thin.layer.rgba[p];
  for (size_t p = 3; p < reference.rgba.size(); p += 4) alpha_full += reference.rgba[p];
  tressvk::engine::write_png(out_dir() / "compute_lod_coverage_full.png", all.pixels);
  tressvk::engine::write_png(out_dir() / "compute_lod_coverage_thin.png", thin.pixels);
  INFO("strands drawn " << thin.input.strands << " of " << all.input.strands << " (at twice the distance "
                        << thin_far.input.strands << "); LOD vs all strands: mean " << e.mean << "/255, p99 " << e.p99
                        << "/255, max " << e.max << "/255 over " << e.hair_pixels
                        << " hair pixels (the full frame: mean " << e_full.mean << ", p99 " << e_full.p99
                        << "); summed alpha " << alpha << " vs " << alpha_full);
  CHECK(e.hair_pixels > 1000);
  CHECK(thin.input.strands < all.input.strands / 2);
  CHECK(thin.input.strands > all.input.strands / 5);
  // The projected width halves at twice the distance (perspective), so does the fraction (ceil: one strand of slack).
  CHECK(std::abs(2.0 * thin_far.input.strands - thin.input.strands) <= 0.02 * thin.input.strands + 2.0);
  CHECK(std::abs(alpha / alpha_full - 1.0) <= 0.03);
  CHECK(e.mean <= 10.0);
  CHECK(e.p99 <= 90.0);
}
