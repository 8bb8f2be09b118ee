// `artkplus`: a faithful re-implementation of ARToolKitPlus 2.2's single-marker pipeline
// (Wagner and Schmalstieg 2007; baselines.md), not a wrapper: its code is GPL-3 and not in
// Debian. Per frame: a global threshold (fixed, or auto from the last decoded pattern with
// seeded random retries after a miss), 8-connected dark regions, contour, 4-vertex split,
// PCA side lines, the 6x6 BCH or simple-id code in 4 orientations, then Robust Planar Pose
// (or the classic arGetTransMat search). Deliberate differences are listed in the README.
// Unlike the original's calc(), no marker seen in an earlier frame is ever re-injected.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "trackers/artkplus/classic_square_pose.h"
#include "trackers/artkplus/dark_regions.h"
#include "trackers/artkplus/quad_fit.h"
#include "trackers/artkplus/robust_planar_pose.h"
#include "trackers/tracker.h"

namespace markerbench {

class YamlMap;

enum class ArtkPlusThreshold { kFixed, kAuto };
enum class ArtkPlusPose { kRobustPlanar, kClassic };

struct ArtkPlusOptions {
  // kAuto (the harness default; the original's default is fixed) starts at `threshold`,
  // moves to the mean of the last decoded pattern's darkest and brightest cells, and after
  // a miss retries up to auto_threshold_retries random thresholds in [10, 240) in the same
  // frame. Reset() restores the start and the retry seed, so sweep frames stay independent.
  ArtkPlusThreshold threshold_mode = ArtkPlusThreshold::kAuto;
  int threshold = 100;  // the original's default
  int auto_threshold_retries = 2;
  int auto_threshold_seed = 1;  // >= 0
  DarkRegionOptions regions;    // min_area_px 70, max_area_px 100000 (the original's)
  QuadFitOptions quad;          // side_trim 0.05; subpixel_edges (our addition) on
  // Samples per cell side when reading the 6x6 code: 1 = the nearest pixel to the cell
  // centre, as the original, which with it breaks down from noise σ² = 0.1 as measured on
  // the side; 3 averages 9 bilinear samples and reads the code through σ² = 0.3.
  int pattern_samples = 1;
  double min_confidence = 0.5;
  ArtkPlusPose pose = ArtkPlusPose::kRobustPlanar;
  RobustPlanarPoseOptions robust_planar;
  ClassicSquarePoseOptions classic;

  bool IsValid(std::string* error) const;
  // Flat keys: threshold_mode (auto, fixed), threshold, auto_threshold_retries,
  // auto_threshold_seed, min_area_px, max_area_px, side_trim, subpixel_edges,
  // pattern_samples, min_confidence, pose (rpp, classic). Throws ConfigError naming the file and
  // key.
  static ArtkPlusOptions FromYaml(const YamlMap& map);
};

std::unique_ptr<Tracker> MakeArtkPlusTracker(const ArtkPlusOptions& options);

}  // namespace markerbench
