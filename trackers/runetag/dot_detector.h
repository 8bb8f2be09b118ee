// Steps 1-2 of the RUNETag pipeline (baselines.md): an adaptive mean threshold, contours,
// and the dark blobs that look like imaged dots, with sub-pixel centres.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace markerbench {

struct DotDetectorOptions {
  // Deliberate difference: a Gaussian pre-smoothing of σ = smoothing_per_noise × the
  // estimated noise σ (0-1 units), at most max_smoothing_px, none on clean images. Without
  // it the mean threshold turns σ² = 0.02 noise into thousands of blobs.
  double smoothing_per_noise = 10.0;
  double max_smoothing_px = 1.5;
  int block_size_px = 127;  // adaptive mean threshold window (the original's)
  // A pixel is dark when below its window mean minus max(threshold_offset, offset_per_noise
  // × the noise left after smoothing). Deliberate difference: the original's fixed offset
  // lets σ² = 0.02 noise through as hundreds of blobs, which cost more time than the dots.
  double threshold_offset = 15;
  double offset_per_noise = 5.0;
  // Size filters at 640x480, scaled by the image area (so by sqrt(area) for lengths): the
  // original keeps 10-1000 px^2; we go down to 2 px^2 so that dots of radius 0.8 px are
  // still seen (1.5 px^2 lets too many σ² = 0.02 noise blobs through).
  double min_area_px = 2.0;
  double max_area_px = 1000.0;
  double min_axis_ratio = 0.3;  // minor / major axis (the original's)
  // A dot's darkness (paper level minus its darkest pixel, 0..255) must reach min_contrast
  // and contrast_per_noise times the noise left after smoothing (noise blobs stay near 3).
  double min_contrast = 30.0;
  double contrast_per_noise = 6.0;
  double max_fit_error = 0.24;  // RMS of (normalized radius - 1) over the contour
  // Levels tried to split a misshapen blob into dots, as fractions of the way from its
  // darkest pixel to the paper around it.
  std::vector<double> split_depths = {0.5, 0.3, 0.15};
};

struct ImagedDot {
  Eigen::Vector2d center_px;  // darkness-weighted centroid: the ellipse centre
  double area_px = 0.0;
  double semi_major_px = 0.0;
  double semi_minor_px = 0.0;
};

// The image the dots are found in, and the ring decoder samples: the grey image smoothed
// against its noise (DotDetectorOptions::smoothing_per_noise).
struct DotImage {
  cv::Mat smoothed;    // CV_8UC1
  double noise = 0.0;  // the noise σ left after smoothing, in grey levels
};

DotImage SmoothForDots(const cv::Mat& grey, const DotDetectorOptions& options);

std::vector<ImagedDot> DetectDots(const DotImage& image, const DotDetectorOptions& options);

}  // namespace markerbench
