// The original RUNETag's dot detector (EllipseDetector::detectEllipses, RUNETag 2015, with
// its defaults), re-implemented from its description: an adaptive mean threshold (block 127,
// C = 15) that keeps paper white, the borders of every white region and hole (the dots are
// holes, outlined by the white pixels around them), cv::fitEllipse on each, and the size,
// roundness and fit checks below. `runetag` reads dots with it; `runetag-improved` uses
// DetectDots.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "trackers/runetag/dot_detector.h"

namespace markerbench {

struct OriginalEllipseOptions {
  int block_size_px = 127;
  double threshold_offset = 15;
  int min_contour_points = 10;
  int max_contour_points = 300;
  // The original's "area" is π × the fitted ellipse's full width × height: 4 × its area.
  double min_area_px = 10.0;
  double max_area_px = 1000.0;
  double min_axis_ratio = 0.3;  // width / height and height / width
  // sqrt(Σ d²) / n over the contour points, d = the sum of the distances to the two foci
  // minus the major axis (the original's "mse").
  double max_fit_error = 0.24;
  // Added to the fitted width and height: the thresholded holes are larger than the dots.
  double size_compensation_px = -1.5;
};

std::vector<ImagedDot> DetectEllipsesAsOriginal(const cv::Mat& grey,
                                                const OriginalEllipseOptions& options);

}  // namespace markerbench
