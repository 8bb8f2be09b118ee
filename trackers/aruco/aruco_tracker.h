// ArUco through OpenCV 4.6 contrib (baselines.md): detectMarkers with explicit corner
// refinement, pose from IPPE_SQUARE with both hypotheses. OpenCV types stay in the .cc.
#pragma once

#include <memory>
#include <string>

#include "trackers/tracker.h"

namespace markerbench {

class YamlMap;

// Mirrors cv::aruco::DetectorParameters (4.6 defaults) except cornerRefinementMethod, which
// defaults to subpix here (NONE and CONTOUR bias corners 0.68 px inwards, baselines.md), and
// min_pixels_per_cell, which is ours.
struct ArucoOptions {
  std::string dictionary = "DICT_6X6_250";
  std::string corner_refinement = "subpix";  // none, subpix, contour, apriltag
  int adaptive_thresh_win_size_min = 3;
  int adaptive_thresh_win_size_max = 23;
  int adaptive_thresh_win_size_step = 10;
  double adaptive_thresh_constant = 7.0;
  double min_marker_perimeter_rate = 0.03;
  // A floor under min_marker_perimeter_rate in pixels: a candidate's perimeter must give each
  // of the marker's cells (border included) this many pixels a side. OpenCV reads the bits of
  // smaller ones anyway, and its filter of close candidates is quadratic in their number: a
  // fine texture of tiny quads in a small image took 1.6 s. At 0.5, half the one pixel per
  // cell that alternating cells need (Nyquist), the floor is below OpenCV's own from 534 px
  // (6x6 bits) or 400 px (4x4) on the image's larger side, where the detector is OpenCV's
  // unchanged; 0 turns the floor off.
  double min_pixels_per_cell = 0.5;
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
