// The bake pipeline: RawGroom (any units, any up axis) -> HairAsset (metres, +Y up), in double precision.
//
// Steps, in order: unit/axis conversion; merging of repeated vertices and segments shorter than a fraction of
// the median segment length; dropping strands shorter than a fraction of the median strand length; arc-length
// resampling to N vertices; origin at the bounds centre rounded to a millimetre; pins and inverse masses; rest
// lengths and parallel-transport rest frames (asset.hpp); follow hairs as root-frame offsets; a seeded
// level-of-detail order (bit-reversed Z-order of the roots, so every prefix covers the scalp evenly); bone weights
// and root UVs carried along.
#pragma once

#include <tressvk/asset.hpp>
#include <tressvk/baker/raw_groom.hpp>

#include <cstdint>
#include <string>

namespace tressvk::baker {

enum class UpAxis { kY, kZ };

struct BakeOptions {
  uint32_t vertices_per_strand = 32;  // N, 4..128, any value
  uint32_t pin = 2;                   // root vertices held (inverse mass 0); also at the tip of pin-tip strands
  uint32_t follow_per_guide = 0;      // K
  double follow_radius = -1.0;        // metres; < 0: 5 % of the median strand length
  float tip_separation = 0.5f;        // dimensionless, stored in the asset
  uint64_t seed = 1;                  // follow placement and the LOD order
  double units_to_metres = 1.0;       // m 1, cm 0.01, mm 0.001, in 0.0254
  double scale = 1.0;                 // extra uniform scale, applied after units
  UpAxis up = UpAxis::kY;
  bool shuffle = true;                // LOD order; false keeps the input strand order (debugging, round trips)
  // Scale-aware cleaning thresholds (fractions, never lengths in scene units).
  double merge_fraction = 1e-3;       // merge consecutive vertices closer than this x median segment length
  double min_length_fraction = 0.01;  // drop strands shorter than this x median strand length
};

struct BakeReport {
  uint64_t input_strands = 0;
  uint64_t input_vertices = 0;
  uint64_t skipped_invalid = 0;
  uint64_t merged_vertices = 0;       // repeated vertices / sub-tolerance segments merged away
  uint64_t dropped_short = 0;         // strands below the length threshold
  uint64_t bone_influences_dropped = 0;
  double median_segment_length = 0.0;  // metres, input
  double median_strand_length = 0.0;   // metres, input (after merging)
  double merge_tolerance = 0.0;        // metres
  double min_strand_length = 0.0;      // metres
  double follow_radius = 0.0;          // metres actually used
  // Resampling error: distance of each input vertex from the resampled polyline at the same arc length.
  double max_resample_error = 0.0;     // metres
  double max_relative_resample_error = 0.0;  // the same divided by the strand's length (worst strand)
  double rms_resample_error = 0.0;     // metres
  uint64_t guides = 0;
  uint64_t output_vertices = 0;        // guide vertices G*N
};

// Throws InputError when nothing is left to bake (every strand dropped) or an option is out of range.
asset::HairAsset bake(const RawGroom& groom, const BakeOptions& options, BakeReport* report = nullptr);

// The bake options as the deterministic JSON stored in HairAsset::bake_settings (follow_radius: metres).
std::string bake_settings_json(const BakeOptions& options);

}  // namespace tressvk::baker
