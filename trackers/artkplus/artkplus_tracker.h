// `artkplus`: a faithful re-implementation of ARToolKitPlus 2.2's single-marker pipeline
// (Wagner and Schmalstieg 2007; baselines.md), not a wrapper: its code is GPL-3 and not in
// Debian. Per frame: a global threshold (fixed, or auto from the last decoded pattern with
// seeded random retries when no square is found), 8-connected dark regions, contour,
// 4-vertex split, PCA side lines, the 6x6 BCH or simple-id code in 4 orientations, then
// Robust Planar Pose (or the classic arGetTransMat search). Its defaults are the original's;
// ArtkPlusOptions::Improved() is `artkplus-improved`, the same markers with our detector.
// Unlike the original's calc(), no marker seen in an earlier frame is ever re-injected.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "trackers/artkplus/classic_square_pose.h"
#include "trackers/artkplus/dark_regions.h"
#include "trackers/artkplus/pattern_reader.h"
#include "trackers/artkplus/quad_fit.h"
#include "trackers/artkplus/robust_planar_pose.h"
#include "trackers/tracker.h"

namespace markerbench {

class YamlMap;

enum class ArtkPlusThreshold { kFixed, kAuto };
enum class ArtkPlusPose { kRobustPlanar, kClassic };

struct ArtkPlusOptions {
  // kAuto (as the paper's runs of the original) starts at `threshold`, moves to the mean of
  // the last decoded pattern's darkest and brightest cells, and retries up to
  // auto_threshold_retries random thresholds in [10, 240) in the same frame after a miss.
  // Reset() restores the start and the retry seed, so sweep frames stay independent.
  ArtkPlusThreshold threshold_mode = ArtkPlusThreshold::kAuto;
  int threshold = 100;  // the original's default
  int auto_threshold_retries = 2;
  int auto_threshold_seed = 1;  // >= 0
  // The original retries only when the labelling finds no square at all (arDetectMarker),
  // so on independent frames it mostly stays at `threshold`; false retries whenever no
  // marker decodes.
  bool retry_only_without_squares = true;
  DarkRegionOptions regions;  // min_area_px 70, max_area_px 100000 (the original's)
  QuadFitOptions quad;        // side_trim 0.05; subpixel_edges (our addition) off
  // Reading the 6x6 code. The original: one sample per cell at truncated coordinates
  // through the homography of the contour's vertex pixels (not of the fitted corners),
  // cells white above the labelling threshold, at most 2 corrected bits.
  PatternReadOptions pattern{true, 1, -1.0, 2, 0.0};
  // bits_at_threshold: pattern.bit_threshold follows the frame's labelling threshold;
  // false thresholds at the cells' mid-level.
  bool bits_at_threshold = true;
  double min_confidence = 0.5;
  ArtkPlusPose pose = ArtkPlusPose::kRobustPlanar;
  RobustPlanarPoseOptions robust_planar;
  ClassicSquarePoseOptions classic;

  // `artkplus-improved`: sub-pixel edges, cells averaged over 3 x 3 bilinear samples
  // through the fitted corners and thresholded at their mid-level, retries whenever no
  // marker decodes, at most 2 corrected bits and a code contrast of at least 0.3 (without
  // either, the paper sweeps gave wrong ids).
  static ArtkPlusOptions Improved();

  bool IsValid(std::string* error) const;
  // Flat keys: threshold_mode (auto, fixed), threshold, auto_threshold_retries,
  // auto_threshold_seed, retry_only_without_squares, min_area_px, max_area_px, side_trim,
  // subpixel_edges, truncated_samples, pattern_samples, bits_at_threshold,
  // max_corrected_bits, min_code_contrast, min_confidence, pose (rpp, classic), each
  // defaulting to `base`'s (the original's in the one-argument form). Throws ConfigError
  // naming the file and key.
  static ArtkPlusOptions FromYaml(const YamlMap& map, const ArtkPlusOptions& base);
  static ArtkPlusOptions FromYaml(const YamlMap& map) { return FromYaml(map, ArtkPlusOptions()); }
};

std::unique_ptr<Tracker> MakeArtkPlusTracker(const ArtkPlusOptions& options);

}  // namespace markerbench
