// tressvk-bake: a thin command-line front end over the tressvk::baker library.
// Exit codes: 0 success, 1 usage, 2 invalid input (the message names the file and line or field), 3 I/O.
#include <tressvk/asset_io.hpp>
#include <tressvk/baker/bake.hpp>
#include <tressvk/baker/errors.hpp>
#include <tressvk/baker/export.hpp>
#include <tressvk/baker/groom.hpp>
#include <tressvk/baker/import.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <clocale>
#include <cstdlib>
#include <functional>
#include <memory>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace {

using namespace tressvk;
using nlohmann::ordered_json;

constexpr int kExitOk = 0, kExitUsage = 1, kExitInvalid = 2, kExitIo = 3;

struct CliState {
  std::vector<std::string> inputs;
  std::string output;
  std::string units = "m";
  std::string up = "y";
  std::string bones;
  std::string scalp;
  std::string root_from = "index";
  std::string report;
  bool skip_invalid = false;
  bool verbose = false;
  bool quiet = false;
  bool keep_order = false;
  baker::BakeOptions bake;
};

std::string hex32(uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", v);
  return buf;
}

// Progress lines only help where a person watches a bake that takes a while: stderr is a terminal and the
// inputs are large (16 MB of input takes about a quarter of a second).
constexpr uintmax_t kProgressMinInputBytes = 16u << 20;

bool progress_wanted(const CliState& s) {
  if (s.quiet || !::isatty(2)) return false;
  uintmax_t total = 0;
  for (const auto& in : s.inputs) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(in, ec);
    if (!ec) total += size;
  }
  return total >= kProgressMinInputBytes;
}

void progress(const CliState& s, const std::string& what) {
  static const bool wanted = progress_wanted(s);
  if (wanted) std::cerr << "tressvk-bake: " << what << "...\n";
}

// Names in an asset are bytes; invalid UTF-8 is shown replaced rather than failing the whole output.
std::string dump_json(const ordered_json& j) { return j.dump(2, ' ', false, ordered_json::error_handler_t::replace); }

ordered_json sections_json(const asset::FileInfo& info) {
  ordered_json list = ordered_json::array();
  for (const auto& s : info.sections)
    list.push_back({{"name", s.name}, {"offset", s.offset}, {"size", s.size}, {"stride", s.stride},
                    {"count", s.count}, {"checksum", hex32(s.stored_crc)}, {"checksum_ok", s.crc_ok}});
  return list;
}

ordered_json asset_json(const asset::HairAsset& a, const asset::FileInfo& info) {
  ordered_json j;
  j["format_version"] = std::to_string(info.major) + "." + std::to_string(info.minor);
  j["units"] = "m";
  j["up"] = "y";
  j["guide_strands"] = a.guide_count();
  j["follow_per_guide"] = a.follow_per_guide;
  j["total_strands"] = a.total_strands();
  j["vertices_per_strand"] = a.vertices_per_strand;
  j["total_vertices"] = uint64_t{a.total_strands()} * a.vertices_per_strand;
  j["tip_separation"] = a.tip_separation;
  std::vector<uint64_t> per_group(a.groups.size(), 0);
  for (uint16_t g : a.guide_group) per_group[g] += 1 + a.follow_per_guide;
  ordered_json groups = ordered_json::array();
  for (size_t i = 0; i < a.groups.size(); ++i) groups.push_back({{"name", a.groups[i].name}, {"strands", per_group[i]}});
  j["groups"] = groups;
  const auto b = asset::guide_bounds(a);
  j["bounds"] = {{"min", b.min}, {"max", b.max}};
  j["origin"] = a.origin;
  j["root_uv"] = !a.root_uv.empty();
  j["bones"] = a.bone_names.size();
  // Informational: shown as an object when it parses, as the raw string otherwise (a hand-made asset).
  ordered_json settings = ordered_json::parse(a.bake_settings, nullptr, false);
  j["bake_settings"] = settings.is_discarded() ? ordered_json(a.bake_settings) : settings;
  j["file_size"] = info.file_size;
  j["sections"] = sections_json(info);
  j["checksums_ok"] = info.checksums_ok;
  return j;
}

int run_info(const std::string& file, bool json) {
  const auto r = asset::read_file(file);
  if (r.status == asset::ReadStatus::kIoError) {
    std::cerr << "tressvk-bake: error: " << r.error << "\n";
    return kExitIo;
  }
  if (!r.ok()) {
    if (r.info.major == 0) {
      std::cerr << "tressvk-bake: error: " << r.error << "\n";
      return kExitInvalid;
    }
    ordered_json j;
    j["format_version"] = std::to_string(r.info.major) + "." + std::to_string(r.info.minor);
    j["file_size"] = r.info.file_size;
    j["sections"] = sections_json(r.info);
    j["checksums_ok"] = false;
    j["error"] = r.error;
    if (json) std::cout << dump_json(j) << "\n";
    std::cerr << "tressvk-bake: error: " << r.error << "\n";
    return kExitInvalid;
  }
  const auto j = asset_json(r.asset, r.info);
  if (json) {
    std::cout << dump_json(j) << "\n";
    return kExitOk;
  }
  std::cout << file << ": .tvkhair " << j["format_version"].get<std::string>() << ", " << j["file_size"] << " bytes\n"
            << "  guides " << j["guide_strands"] << " x " << j["vertices_per_strand"] << " vertices, "
            << j["follow_per_guide"] << " follows per guide, " << j["total_strands"] << " strands in all\n"
            << "  origin " << j["origin"].dump() << " m, bounds " << j["bounds"].dump() << "\n";
  for (const auto& g : j["groups"]) std::cout << "  group " << g["name"].get<std::string>() << ": " << g["strands"] << " strands\n";
  for (const auto& s : j["sections"])
    std::cout << "  section " << s["name"].get<std::string>() << " offset " << s["offset"] << " size " << s["size"]
              << " crc " << s["checksum"].get<std::string>() << (s["checksum_ok"].get<bool>() ? "" : " BAD") << "\n";
  std::cout << "  checksums " << (r.info.checksums_ok ? "ok" : "BAD") << "\n";
  return kExitOk;
}

int run_validate(const std::string& file) {
  const auto r = asset::read_file(file);
  if (r.ok()) {
    std::cout << file << ": valid (" << r.asset.guide_count() << " guides, " << r.info.sections.size()
              << " sections, checksums ok)\n";
    return kExitOk;
  }
  std::cerr << "tressvk-bake: error: " << r.error << "\n";
  return r.status == asset::ReadStatus::kIoError ? kExitIo : kExitInvalid;
}

int run_export(const std::string& file, const std::string& out, bool follows) {
  const auto r = asset::read_file(file);
  if (!r.ok()) {
    std::cerr << "tressvk-bake: error: " << r.error << "\n";
    return r.status == asset::ReadStatus::kIoError ? kExitIo : kExitInvalid;
  }
  const std::string text = baker::export_obj(r.asset, follows);
  const auto err = asset::write_file(out, std::as_bytes(std::span(text.data(), text.size())));
  if (!err.empty()) throw baker::IoError(err);
  return kExitOk;
}

int run_bake(CliState& s) {
  if (s.inputs.empty()) {
    std::cerr << "tressvk-bake: error: no INPUT given (run tressvk-bake --help)\n";
    return kExitUsage;
  }
  if (s.output.empty()) {
    std::cerr << "tressvk-bake: error: no output given: -o OUT.tvkhair\n";
    return kExitUsage;
  }
  if (!s.bones.empty() && s.inputs.size() != 1) {
    std::cerr << "tressvk-bake: error: --bones needs exactly one .tfx INPUT\n";
    return kExitUsage;
  }
  if (!s.scalp.empty() && s.root_from == "faces") {
    std::cerr << "tressvk-bake: error: --scalp and --root-from faces exclude each other\n";
    return kExitUsage;
  }
  const double unit = s.units == "cm" ? 0.01 : s.units == "mm" ? 0.001 : s.units == "in" ? 0.0254 : 1.0;
  s.bake.units_to_metres = unit;
  s.bake.up = s.up == "z" ? baker::UpAxis::kZ : baker::UpAxis::kY;
  s.bake.shuffle = !s.keep_order;

  baker::ObjImportOptions obj_options;
  obj_options.skip_invalid = s.skip_invalid;
  obj_options.root_from = s.root_from == "faces" ? baker::RootFrom::kFaces : baker::RootFrom::kIndex;
  baker::RawGroom groom;
  for (const auto& in : s.inputs) {
    progress(s, "reading " + in);
    baker::RawGroom part = baker::import_file(in, obj_options);
    if (!s.bones.empty()) baker::apply_tfxbone(part, s.bones);
    groom.append(part);
  }
  if (!s.scalp.empty()) {
    progress(s, "orienting strands to " + s.scalp);
    baker::orient_to_scalp(groom, baker::load_scalp(s.scalp));
  }
  progress(s, "baking " + std::to_string(groom.strand_count()) + " strands");
  baker::BakeReport rep;
  const asset::HairAsset a = baker::bake(groom, s.bake, &rep);
  const auto problems = asset::validate(a);
  if (!problems.empty()) throw std::runtime_error("internal error: the baked asset is inconsistent: " + problems.front());
  asset::FileInfo info;
  const auto err = asset::write_file(s.output, a, &info);
  if (!err.empty()) throw baker::IoError(err);

  if (!s.quiet) {
    if (rep.dropped_short)
      std::cerr << "tressvk-bake: warning: dropped " << rep.dropped_short << " strands shorter than "
                << rep.min_strand_length << " m (" << s.bake.min_length_fraction << " x median length)\n";
    if (rep.skipped_invalid)
      std::cerr << "tressvk-bake: warning: skipped " << rep.skipped_invalid << " invalid strands (--skip-invalid)\n";
    if (rep.bone_influences_dropped)
      std::cerr << "tressvk-bake: warning: dropped " << rep.bone_influences_dropped
                << " bone influences beyond the 4 largest per strand (weights renormalised)\n";
  }
  ordered_json j;
  j["input"] = {{"files", s.inputs}, {"strands", rep.input_strands}, {"vertices", rep.input_vertices},
                {"skipped_invalid", rep.skipped_invalid}, {"merged_vertices", rep.merged_vertices},
                {"dropped_short", rep.dropped_short}, {"bone_influences_dropped", rep.bone_influences_dropped},
                {"median_segment_length_m", rep.median_segment_length},
                {"median_strand_length_m", rep.median_strand_length}};
  j["thresholds"] = {{"merge_tolerance_m", rep.merge_tolerance}, {"min_strand_length_m", rep.min_strand_length},
                     {"follow_radius_m", rep.follow_radius}};
  j["resampling_error"] = {{"max_m", rep.max_resample_error}, {"rms_m", rep.rms_resample_error},
                           {"max_relative", rep.max_relative_resample_error}};
  j["output"] = asset_json(a, info);
  if (s.verbose) {
    std::cout << "input:  " << rep.input_strands << " strands, " << rep.input_vertices << " vertices ("
              << rep.merged_vertices << " merged, " << rep.dropped_short << " strands dropped as too short, "
              << rep.skipped_invalid << " skipped as invalid)\n"
              << "output: " << rep.guides << " guides x " << s.bake.vertices_per_strand << " vertices, "
              << s.bake.follow_per_guide << " follows per guide, " << info.file_size << " bytes\n"
              << "resampling error: max " << rep.max_resample_error << " m (" << 100.0 * rep.max_relative_resample_error
              << " % of its strand), rms " << rep.rms_resample_error << " m\n";
    for (const auto& sec : info.sections) std::cout << "section " << sec.name << ": " << sec.size << " bytes\n";
  }
  if (!s.report.empty()) {
    const std::string text = dump_json(j) + "\n";
    const auto rerr = asset::write_file(s.report, std::as_bytes(std::span(text.data(), text.size())));
    if (!rerr.empty()) throw baker::IoError(rerr);
  }
  return kExitOk;
}

// `tressvk-bake groom`: the preset's values, then every option given on the command line over them.
struct GroomCli {
  std::string scalp, preset, output, parting;
  baker::GroomParams p;
  std::vector<std::pair<CLI::Option*, std::function<void()>>> overrides;
};

void add_groom_options(CLI::App& cmd, GroomCli& g) {
  cmd.add_option("--scalp", g.scalp, "OBJ scalp mesh (metres, +Y up, face towards +Z); vertex colours = length map")
      ->required();
  cmd.add_option("--preset", g.preset, "Starting point: straight (shoulder length, side parting) or curly")
      ->required()->check(CLI::IsMember(baker::groom_preset_names()));
  cmd.add_option("-o,--output", g.output, "Output .tvkhair (written to a temporary file, then renamed)")->required();
  auto over = [&](const char* name, auto& field, const char* help, CLI::Validator check) {
    auto value = std::make_shared<std::decay_t<decltype(field)>>();
    CLI::Option* o = cmd.add_option(name, *value, help)->check(check);
    g.overrides.emplace_back(o, [value, &field] { field = *value; });
  };
  over("--guides", g.p.guides, "Guide strands", CLI::Range(1u, 200000u));
  over("--follow", g.p.follow, "Follow hairs per guide", CLI::Range(0u, 64u));
  over("--vertices", g.p.vertices, "Vertices per strand", CLI::Range(4u, 128u));
  over("--seed", g.p.seed, "Seed: the same inputs and seed give the same bytes", CLI::NonNegativeNumber);
  over("--length", g.p.length, "Strand length in metres (times the length map)", CLI::Range(1e-4, 10.0));
  over("--length-variation", g.p.length_variation, "Random length variation, +- fraction", CLI::Range(0.0, 1.0));
  cmd.add_option("--parting", g.parting, "Parting x over the scalp's half width (-1..1), or 'none'");
  over("--gravity", g.p.gravity, "How soon strands fall (0 = keep the combed direction, 1 = straight hair falls)",
       CLI::Range(0.0, 10.0));
  over("--lift", g.p.lift, "Root lift off the scalp, 0..1", CLI::Range(0.0, 1.0));
  over("--clump", g.p.clump, "Clumping at the tips, 0..1", CLI::Range(0.0, 1.0));
  over("--clump-size", g.p.clump_size, "Guides per clump", CLI::Range(1.0, 1e6));
  over("--curl-radius", g.p.curl_radius, "Curl radius in metres (0 = straight)", CLI::Range(0.0, 1.0));
  over("--curl-frequency", g.p.curl_frequency, "Curl turns per metre of strand", CLI::Range(0.0, 1000.0));
  over("--frizz", g.p.frizz, "Frizz amplitude at the tip in metres", CLI::Range(0.0, 1.0));
  over("--taper", g.p.taper, "Tip width / root width, recorded for the renderer's material", CLI::Range(0.0, 1.0));
}

int run_groom(GroomCli& g, bool verbose) {
  const baker::GroomParams defaults = baker::groom_preset(g.preset);
  g.p = defaults;
  for (auto& [option, apply] : g.overrides)
    if (option->count() > 0) apply();
  if (!g.parting.empty()) {
    if (g.parting == "none") {
      g.p.parting_on = false;
    } else {
      char* end = nullptr;
      const double v = std::strtod(g.parting.c_str(), &end);
      if (end == g.parting.c_str() || *end != '\0' || !(v >= -1.0 && v <= 1.0)) {
        std::cerr << "tressvk-bake: error: --parting: '" << g.parting << "' is not a number in -1..1 or 'none'\n";
        return kExitUsage;
      }
      g.p.parting_on = true;
      g.p.parting = v;
    }
  }
  const baker::GroomScalp scalp = baker::load_groom_scalp(g.scalp);
  baker::GroomReport rep;
  const asset::HairAsset a = baker::make_groom(scalp, g.p, g.preset, &rep);
  const auto problems = asset::validate(a);
  if (!problems.empty()) throw std::runtime_error("internal error: the groom is inconsistent: " + problems.front());
  asset::FileInfo info;
  const auto err = asset::write_file(g.output, a, &info);
  if (!err.empty()) throw baker::IoError(err);
  if (verbose)
    std::cout << "groom " << g.preset << ": " << a.guide_count() << " guides x " << a.vertices_per_strand
              << " vertices, " << a.follow_per_guide << " follows per guide, on " << rep.scalp_triangles
              << " scalp triangles (" << rep.scalp_area * 1e4 << " cm^2), mean length " << rep.mean_length
              << " m, " << info.file_size << " bytes\n";
  return kExitOk;
}

int run(int argc, char** argv) {
  CliState s;
  CLI::App app{"tressvk-bake: bakes OBJ polylines and TressFX .tfx hair into .tvkhair assets (metres, +Y up).\n"
               "Exit codes: 0 ok, 1 usage, 2 invalid input, 3 I/O."};
  app.set_version_flag("--version", "tressvk-bake 0.1.0 (.tvkhair 1.0)");
  app.add_option("INPUT", s.inputs, "OBJ (polylines) or TressFX .tfx files; several are merged into one asset");
  app.add_option("-o,--output", s.output, "Output .tvkhair file (written to a temporary file, then renamed)");
  app.add_option("--vertices", s.bake.vertices_per_strand, "Vertices per strand after resampling")
      ->check(CLI::Range(4, 128))->capture_default_str();
  app.add_option("--follow", s.bake.follow_per_guide, "Follow hairs per guide")->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--follow-radius", s.bake.follow_radius,
                 "Follow root spread around the guide root, in input units (default: 5 % of the median strand length)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--tip-separation", s.bake.tip_separation, "Follow spreading toward the tip (dimensionless)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--units", s.units, "Input units")->check(CLI::IsMember({"m", "cm", "mm", "in"}))->capture_default_str();
  app.add_option("--up", s.up, "Input up axis")->check(CLI::IsMember({"y", "z"}))->capture_default_str();
  app.add_option("--scale", s.bake.scale, "Extra uniform scale after units")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--pin", s.bake.pin, "Pinned root vertices (inverse mass 0)")->check(CLI::Range(0, 128))->capture_default_str();
  app.add_option("--bones", s.bones, ".tfxbone weights (4.x or 5.x layout) for a single .tfx INPUT");
  app.add_option("--scalp", s.scalp, "OBJ mesh: each strand's root is the end nearer its surface");
  app.add_option("--root-from", s.root_from, "Root end for OBJ strands: lower vertex index, or nearer the file's own faces")
      ->check(CLI::IsMember({"index", "faces"}))->capture_default_str();
  app.add_option("--seed", s.bake.seed, "Seed for follow placement and the level-of-detail order")->capture_default_str();
  app.add_flag("--skip-invalid", s.skip_invalid, "Drop branching or looping OBJ strands (reported) instead of failing");
  app.add_flag("--keep-order", s.keep_order, "Keep the input strand order (no level-of-detail order)");
  app.add_option("--report", s.report, "Write a JSON report of the bake");
  app.add_flag("-v,--verbose", s.verbose, "Print input and output statistics");
  app.add_flag("-q,--quiet", s.quiet, "No warnings or progress");

  std::string info_file, validate_file, export_file, export_out;
  bool info_json = false, export_follows = false;
  auto* info = app.add_subcommand("info", "Describe a .tvkhair file");
  info->add_option("FILE", info_file, ".tvkhair file")->required();
  info->add_flag("--json", info_json, "Machine-readable output");
  auto* validate = app.add_subcommand("validate", "Exit 0 only if the file is whole and consistent");
  validate->add_option("FILE", validate_file, ".tvkhair file")->required();
  auto* exporter = app.add_subcommand("export", "Write guides (and follows) back as OBJ polylines in metres");
  exporter->add_option("FILE", export_file, ".tvkhair file")->required();
  exporter->add_option("-o,--output", export_out, "Output .obj")->required();
  exporter->add_flag("--follow", export_follows, "Include follow hairs");
  GroomCli groom_cli;
  bool groom_verbose = false;
  auto* groom = app.add_subcommand("groom", "Grow hair on a scalp mesh from a preset (deterministic from --seed)");
  add_groom_options(*groom, groom_cli);
  groom->add_flag("-v,--verbose", groom_verbose, "Print what was grown");
  app.require_subcommand(0, 1);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  try {
    if (info->parsed()) return run_info(info_file, info_json);
    if (validate->parsed()) return run_validate(validate_file);
    if (exporter->parsed()) return run_export(export_file, export_out, export_follows);
    if (groom->parsed()) return run_groom(groom_cli, groom_verbose);
    return run_bake(s);
  } catch (const baker::IoError& e) {
    std::cerr << "tressvk-bake: error: " << e.what() << "\n";
    return kExitIo;
  } catch (const baker::InputError& e) {
    std::cerr << "tressvk-bake: error: " << e.what() << "\n";
    return kExitInvalid;
  } catch (const std::bad_alloc&) {
    std::cerr << "tressvk-bake: error: out of memory (input too large or damaged)\n";
    return kExitInvalid;
  } catch (const std::exception& e) {
    std::cerr << "tressvk-bake: error: " << e.what() << "\n";
    return kExitInvalid;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::setlocale(LC_ALL, "C");  // locale-independent number parsing and printing: deterministic output
  return run(argc, argv);
}
