// ArUco through OpenCV 4.6 contrib (baselines.md): detectMarkers with explicit corner
// refinement, pose from IPPE_SQUARE with both hypotheses. OpenCV types stay in the .cc.
#pragma once

#include <memory>
#include <string>

#include "trackers/tracker.h"

namespace markerbench {

class YamlMap;

// Mirrors cv::aruco::DetectorParameters (4.6 defaults) except cornerRefinementMethod, which
// defaults to subpix here (NONE and CONTOUR bias corners 0.68 px inwards, baselines.md).
struct ArucoOptions {
  std::string dictionary = "DICT_6X6_250";
  std::string corner_refinement = "subpix";  // none, subpix, contour, apriltag
  int adaptive_thresh_win_size_min = 3;
  int adaptive_thresh_win_size_max = 23;
  int adaptive_thresh_win_size_step = 10;
  double adaptive_thresh_constant = 7.0;
  double min_marker_perimeter_rate = 0.03;
  double max_marker_perimeter_rate = 4.0;
  double polygonal_approx_accuracy_rate = 0.03;
  int corner_refinement_win_size = 5;
  int corner_refinement_max_iterations = 30;
  double corner_refinement_min_accuracy = 0.1;
  double error_correction_rate = 0.6;

  bool IsValid(std::string* error) const;
  static ArucoOptions FromYaml(const YamlMap& map);
};

std::unique_ptr<Tracker> MakeArucoTracker(const ArucoOptions& options);

}  // namespace markerbench
