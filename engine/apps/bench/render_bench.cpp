// tressvk-bench render: renders the demo's scene (the same frame code as tressvk-demo) with the chosen hair path,
// times `frames` frames back to back with the GPU warm (no readback or PNG writing between them is waited for:
// two frames stay in flight), then renders one more frame with TVK_RASTER_CAPTURE and compares the hair layer
// with the brute-force reference computed on the CPU from the same captured vertices and host depth.
#include "render_bench.hpp"

#include "common.hpp"

#include "demo_app.hpp"

#include <tressvk/asset_io.hpp>
#include <tressvk/baker/procedural.hpp>
#include <tressvk/engine/device.hpp>
#include <tressvk/engine/png.hpp>
#include <tressvk/reference/strand_raster.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

namespace tressvk::bench {

namespace {

// The last raster call's capture (its vertices, host depth and layer); the plugin's message as an exception if none.
TvkRasterCapture raster_capture(demo::DemoApp& app) {
  TvkRasterCapture cap{};
  if (tressvk_get_raster_capture(app.renderer(), &cap) != TVK_SUCCESS)
    throw std::runtime_error(tressvk_last_error(app.plugin()));
  return cap;
}

// The brute-force reference's input: the captured vertices and host depth.
reference::StrandRasterInput reference_input(const TvkRasterCapture& c) {
  return {c.width, c.height, c.vertices_per_strand, c.strands, c.vertices, c.host_depth};
}

// An error against the reference as JSON keys PREFIXmean, PREFIXp99, PREFIXmax (1/255 units).
void put_error(nlohmann::json& j, const std::string& prefix, const reference::LayerError& e) {
  j[prefix + "mean"] = e.mean;
  j[prefix + "p99"] = e.p99;
  j[prefix + "max"] = e.max;
}

double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }
double srgb_encode(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

// The raster path's frame against the sorted reference: the reference layer (premultiplied linear) blended over
// the same frame drawn without the hair (the host's target blends in linear), both as displayed, per RGB channel
// in 1/255 over the pixels where the reference or the compute path's layer has hair.
reference::LayerError compare_frame(const engine::Pixels& frame, const engine::Pixels& background,
                                    const reference::HairLayer& ref, const reference::HairLayer& compute) {
  reference::LayerError e;
  std::vector<double> errors;
  for (uint32_t y = 0; y < ref.height; ++y) {
    for (uint32_t x = 0; x < ref.width; ++x) {
      const size_t p = size_t{y} * ref.width + x;
      const double* r = &ref.rgba[4 * p];
      if (r[3] < 0.5 / 255.0 && compute.rgba[4 * p + 3] < 0.5 / 255.0) continue;
      ++e.hair_pixels;
      const auto f = frame.rgba8(x, y), b = background.rgba8(x, y);
      for (int c = 0; c < 3; ++c) {
        const double expected = srgb_encode(r[c] + (1.0 - std::clamp(r[3], 0.0, 1.0)) * srgb_decode(b[c] / 255.0));
        errors.push_back(std::abs(255.0 * expected - f[c]));
      }
    }
  }
  reference::summarise_errors(std::move(errors), e);
  return e;
}

}  // namespace

CLI::App* add_render_subcommand(CLI::App& app, RenderBenchOptions& o) {
  CLI::App* c = app.add_subcommand("render", "hair rendering speed and its error against the sorted reference");
  c->add_option("--asset", o.asset, "a baked .tvkhair file (default: the bundled sample)")->check(CLI::ExistingFile);
  c->add_option("--mesh", o.mesh, "an OBJ head mesh in the asset's space")->check(CLI::ExistingFile);
  c->add_option("--mesh-scale", o.mesh_scale, "OBJ units to metres")->check(CLI::PositiveNumber);
  c->add_option("--width", o.width)->check(CLI::Range(16u, 8192u))->capture_default_str();
  c->add_option("--height", o.height)->check(CLI::Range(16u, 8192u))->capture_default_str();
  c->add_option("--path", o.path, "compute or raster")->check(CLI::IsMember({"compute", "raster"}))
      ->capture_default_str();
  c->add_option("--frames", o.frames, "timed frames")->check(CLI::Range(1u, 100000u))->capture_default_str();
  c->add_option("--warmup", o.warmup, "frames before timing")->capture_default_str();
  c->add_option("--sample", o.sample, "no --asset: the bundled head sample, or the sphere sample (long128 groom)")
      ->check(CLI::IsMember({"head", "sphere"}))->capture_default_str();
  c->add_option("--guides", o.guides, "sphere sample: guides")->check(CLI::Range(16u, 1000000u))->capture_default_str();
  c->add_option("--follows", o.follows, "sphere sample: follows per guide")->check(CLI::Range(0u, 16u))
      ->capture_default_str();
  c->add_option("--vertices", o.vertices, "sphere sample: vertices per strand")->check(CLI::Range(4u, 128u))
      ->capture_default_str();
  c->add_option("--lod-fraction", o.lod_fraction, "draw this fraction of the strands, widened to keep coverage")
      ->check(CLI::Range(0.01f, 1.0f));
  c->add_option("--lod-target-px", o.lod_target_px,
                "coverage-driven LOD: thin sub-pixel strands until the drawn ones are about this many pixels wide")
      ->check(CLI::Range(0.0f, 64.0f));
  c->add_flag("--error-vs-full", o.error_vs_full,
              "compute path: also compare the drawn layer with the sorted reference of ALL strands (the same frame "
              "rendered without LOD; error_vs_full_*), so a LOD row states what thinning costs");
  c->add_option("--zoom", o.zoom, "camera distance over the distance that frames the scene")
      ->check(CLI::Range(0.05, 100.0))->capture_default_str();
  c->add_option("--shadow-extent", o.shadow_extent,
                "the shadow map's half-size over the scene radius (larger: the hair covers less of the map, as in a "
                "cascade)")
      ->check(CLI::Range(0.5f, 100.0f))->capture_default_str();
  c->add_option("--animate", o.animate, "none, turn, shake or run")->check(CLI::IsMember({"none", "turn", "shake", "run"}))
      ->capture_default_str();
  c->add_option("--json", o.json, "write the results as JSON");
  c->add_option("--png", o.png, "write the compared frame as PNG");
  c->add_option("--device", o.device, "device index or name substring");
  c->add_flag("--validation", o.validation, "Vulkan validation + synchronization validation (any message fails)");
  c->add_flag("--no-reference", o.no_reference, "skip the reference (speed only)");
  c->add_flag("--no-pass-timestamps", o.no_pass_timestamps,
              "compute path: no per-pass timestamps inside the calls (gpu_ms_passes absent; each timestamp waits "
              "for the work before it, so the calls run as a host without timestamps runs them)");
  c->add_option("--shade", o.shade, "compute path: Kajiya-Kay per vertex or per fragment (the reference shades per vertex)")
      ->check(CLI::IsMember({"vertex", "fragment"}))
      ->capture_default_str();
  return c;
}

int run_render_bench(const RenderBenchOptions& o) {
  try {
    engine::Device dev(host::tool_device_options("tressvk-bench", o.device, o.validation, o.validation));

    demo::Options d;
    d.width = o.width;
    d.height = o.height;
    d.mesh = o.mesh;
    d.mesh_scale = o.mesh_scale;
    d.hair_path = o.path == "raster" ? demo::HairPath::raster : demo::HairPath::compute;
    const std::map<std::string, demo::Animation> anim{{"none", demo::Animation::none},
                                                      {"turn", demo::Animation::turn},
                                                      {"shake", demo::Animation::shake},
                                                      {"run", demo::Animation::run}};
    d.animate = anim.at(o.animate);
    // Where the hair's time goes, pass by pass (gpu_ms_passes), unless --no-pass-timestamps.
    d.pass_timestamps = o.path == "compute" && !o.no_pass_timestamps;
    d.sample = o.sample == "sphere" ? demo::Sample::sphere : demo::Sample::head;
    d.shadow_extent = o.shadow_extent;
    demo::ViewControl view;
    view.zoom = o.zoom;
    std::string groom = o.asset.empty() ? (o.sample == "sphere" ? "sphere sample" : "bundled head sample")
                                        : std::filesystem::path(o.asset).filename().string();
    std::filesystem::path temp;
    if (!o.asset.empty()) {
      d.asset = o.asset;
    } else if (d.sample == demo::Sample::sphere && o.vertices != 48) {
      // The demo builds its bundled groom with 48 vertices; other counts go through a baked file (no head mesh).
      baker::BuiltinGroomOptions g;
      g.guide_count = o.guides;
      g.follow_per_guide = o.follows;
      g.vertices_per_strand = o.vertices;
      const std::vector<std::byte> bytes = asset::write(baker::make_builtin_groom("long128", g));
      temp = std::filesystem::temp_directory_path() / ("tressvk-bench-" + std::to_string(o.guides) + "x" +
                                                        std::to_string(o.vertices) + ".tvkhair");
      std::ofstream(temp, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                  static_cast<std::streamsize>(bytes.size()));
      d.asset = temp.string();
      groom = "long128 " + std::to_string(o.guides * (1 + o.follows)) + " strands x " + std::to_string(o.vertices) +
              " (no head mesh)";
    } else {
      d.guides = o.guides;
      d.follows = o.follows;
    }
    if (o.lod_fraction < 1.0f && o.lod_target_px > 0.0f)
      throw std::runtime_error("--lod-fraction and --lod-target-px are two LOD modes: give one");
    if (o.lod_fraction < 1.0f) {  // full thinning from the start: every frame draws lod_fraction of the strands
      d.lod_start = 1e-4f;
      d.lod_end = 2e-4f;
      d.lod_min_fraction = o.lod_fraction;
    }
    if (o.lod_target_px > 0.0f) {
      d.lod_target_px = o.lod_target_px;
      d.lod_min_fraction = 0.0f;  // no floor: the coverage alone decides
    }

    demo::DemoApp app(dev, d);
    app.set_view(view);
    const uint32_t shade_flag = o.shade == "fragment" ? TVK_RASTER_SHADE_PER_FRAGMENT : 0u;
    app.set_raster_flags(shade_flag);
    std::vector<double> hair_shadow, hair, shadow, shading;
    uint32_t strands = 0;
    app.run(o.warmup, [](demo::FrameReport&) {});
    app.pass_ms().clear();
    app.run(o.frames, [&](demo::FrameReport& f) {
      if (f.hair_shadow_ms) hair_shadow.push_back(*f.hair_shadow_ms);
      if (f.hair_ms) hair.push_back(*f.hair_ms);
      if (f.shadow_ms) shadow.push_back(*f.shadow_ms);
      if (f.shading_ms) shading.push_back(*f.shading_ms);
      strands = f.strands_drawn;
    });

    nlohmann::json j;
    j["device"] = dev.description();
    j["path"] = o.path;
    j["shading"] = o.path == "compute" ? "per " + o.shade : "per fragment";
    j["groom"] = groom;
    j["width"] = o.width;
    j["height"] = o.height;
    j["frames"] = o.frames;
    j["zoom"] = o.zoom;
    j["shadow_extent"] = o.shadow_extent;
    j["pass_timestamps"] = d.pass_timestamps;
    j["strands_drawn"] = strands;
    j["strands_total"] = app.asset_info().total_strands;
    j["vertices_per_strand"] = app.asset_info().vertices_per_strand;
    j["gpu_ms_shadow"] = median(hair_shadow);
    j["gpu_ms_shading"] = median(hair);
    j["gpu_ms_hair_total"] = median(hair_shadow) + median(hair);
    j["gpu_ms_shadow_pass_with_meshes"] = median(shadow);
    j["gpu_ms_shading_pass_with_meshes"] = median(shading);
    // Medians per pass of the same frames (timestamps between the passes; tile_depth runs beside vertex).
    j["gpu_ms_passes"] = nlohmann::json::object();
    for (const auto& [name, ms] : app.pass_ms())
      if (name.starts_with("render.")) j["gpu_ms_passes"][name.substr(7)] = median(ms);
    j["k"] = nullptr;
    for (const char* key : {"error_mean", "error_p99", "error_max", "hair_pixels", "fragments_per_pixel_mean",
                            "memory_bytes"})
      j[key] = nullptr;

    if (o.path == "compute") {
      TvkRasterStats stats{};
      tressvk_get_raster_stats(app.renderer(), &stats);
      j["k"] = stats.slice_capacity;  // segments sorted at once per tile slice
      j["memory_bytes"] = stats.memory_bytes;
      j["entry_capacity"] = stats.entry_capacity;
      if (!o.no_reference) {
        app.set_raster_flags(TVK_RASTER_CAPTURE | shade_flag);
        engine::Pixels frame;
        app.run(1, [&](demo::FrameReport& f) { frame = std::move(f.pixels); });
        if (!o.png.empty()) engine::write_png(o.png, frame);
        const TvkRasterCapture cap = raster_capture(app);
        tressvk_get_raster_stats(app.renderer(), &stats);
        const reference::StrandRasterInput in = reference_input(cap);
        const auto t0 = std::chrono::steady_clock::now();
        uint64_t ref_fragments = 0;
        const reference::HairLayer ref = reference::render_strands_reference(in, &ref_fragments);
        const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const reference::LayerError e =
            reference::compare_layers(reference::layer_from_half(cap.width, cap.height, cap.layer), ref);
        put_error(j, "error_", e);
        j["hair_pixels"] = e.hair_pixels;
        j["fragments_per_pixel_mean"] =
            stats.hair_pixels ? double(stats.fragments) / double(stats.hair_pixels) : 0.0;
        j["reference_fragments_per_pixel_mean"] = e.hair_pixels ? double(ref_fragments) / double(e.hair_pixels) : 0.0;
        j["reference_cpu_s"] = ref_s;
        if (o.error_vs_full) {
          // The same frame (same options and frame count; the simulation is deterministic) drawn with every strand
          // and captured: its reference is what the scene is, so the LOD layer's error against it is what LOD costs
          // (the full layer's own error against it, full_error_*, is the rasterizer's share).
          demo::Options df = d;
          df.lod_start = df.lod_end = 0.0f;
          df.lod_target_px = 0.0f;
          df.raster_flags = TVK_RASTER_CAPTURE | shade_flag;
          df.pass_timestamps = false;
          const reference::HairLayer layer = reference::layer_from_half(cap.width, cap.height, cap.layer);
          demo::DemoApp full_app(dev, df);
          full_app.set_view(view);
          full_app.run(o.warmup + o.frames + 1, [](demo::FrameReport&) {});
          const TvkRasterCapture full = raster_capture(full_app);
          const reference::HairLayer full_ref = reference::render_strands_reference(reference_input(full));
          const reference::LayerError ef = reference::compare_layers(layer, full_ref);
          const reference::LayerError ff =
              reference::compare_layers(reference::layer_from_half(full.width, full.height, full.layer), full_ref);
          put_error(j, "error_vs_full_", ef);
          j["error_vs_full_hair_pixels"] = ef.hair_pixels;
          j["full_strands"] = full.strands;
          j["full_error_mean"] = ff.mean;
          j["full_error_p99"] = ff.p99;
          // Coverage: the summed alpha of the drawn layer over that of the full reference.
          double sum = 0.0, sum_full = 0.0;
          for (size_t p = 3; p < layer.rgba.size(); p += 4) sum += layer.rgba[p];
          for (size_t p = 3; p < full_ref.rgba.size(); p += 4) sum_full += full_ref.rgba[p];
          j["coverage_vs_full"] = sum_full > 0.0 ? sum / sum_full : 0.0;
        }
        j["dropped_entries"] = stats.dropped_entries;
        j["dropped_slice_entries"] = stats.dropped_slice_entries;
        j["sliced_tiles"] = stats.sliced_tiles;
        j["split_tiles"] = stats.split_tiles;
        j["shadow_samples_outside"] = stats.shadow_samples_outside;
        j["entries"] = stats.entries_requested;
      }
    }
    if (o.path == "raster" && !o.no_reference) {
      // The same frame (same options, same number of frames: the simulation is deterministic) drawn by the compute
      // path with a capture, for the reference layer, and by the raster path without the hair, for what lies behind
      // it; then the raster path's own next frame.
      const uint32_t before = o.warmup + o.frames;
      engine::Pixels frame, background;
      app.run(1, [&](demo::FrameReport& f) { frame = std::move(f.pixels); });
      if (!o.png.empty()) engine::write_png(o.png, frame);
      demo::Options dc = d;
      dc.hair_path = demo::HairPath::compute;
      dc.raster_flags = TVK_RASTER_CAPTURE;
      dc.pass_timestamps = false;
      demo::DemoApp capture_app(dev, dc);
      capture_app.set_view(view);
      engine::Pixels compute_frame;
      uint32_t kc = 0;
      capture_app.run(before + 1, [&](demo::FrameReport& f) {
        if (++kc == before + 1) compute_frame = std::move(f.pixels);
      });
      const TvkRasterCapture cap = raster_capture(capture_app);
      const reference::HairLayer ref = reference::render_strands_reference(reference_input(cap));
      const reference::HairLayer compute = reference::layer_from_half(cap.width, cap.height, cap.layer);
      demo::Options db = d;
      db.draw_hair = false;
      db.pass_timestamps = false;
      demo::DemoApp background_app(dev, db);
      background_app.set_view(view);
      uint32_t k = 0;
      background_app.run(before + 1, [&](demo::FrameReport& f) {
        if (++k == before + 1) background = std::move(f.pixels);
      });
      const reference::LayerError e = compare_frame(frame, background, ref, compute);
      // The measure's own check: the compute path's frame over its own frame without hair must come out at about
      // its layer error (a frame that does not line up, or a wrong blend, shows here first).
      demo::Options dcb = dc;
      dcb.draw_hair = false;
      dcb.raster_flags = 0;
      demo::DemoApp compute_background_app(dev, dcb);
      compute_background_app.set_view(view);
      engine::Pixels compute_background;
      uint32_t kb = 0;
      compute_background_app.run(before + 1, [&](demo::FrameReport& f) {
        if (++kb == before + 1) compute_background = std::move(f.pixels);
      });
      const reference::LayerError check = compare_frame(compute_frame, compute_background, ref, compute);
      j["check_compute_frame_error_mean"] = check.mean;
      j["check_compute_frame_error_p99"] = check.p99;
      put_error(j, "error_", e);
      j["hair_pixels"] = e.hair_pixels;
      j["error_measure"] = "displayed frame RGB against the reference layer over the frame without hair";
    }
    std::printf("%s\n", j.dump(2).c_str());
    if (!o.json.empty() && !write_json(j, o.json, "tressvk-bench")) return kExitCannotWrite;
    if (!temp.empty()) std::filesystem::remove(temp);
    if (validation_failed(dev, o.validation, "tressvk-bench")) return kExitValidation;
  } catch (const std::exception& e) {
    return report_failure(e, "tressvk-bench");
  }
  return 0;
}

}  // namespace tressvk::bench
