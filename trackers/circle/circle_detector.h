// Finds the circles of one circle marker (paper Fig. 3 a-f) in an image region and measures
// them: ink segmentation per channel on a noise-adapted smoothing, contour candidates with
// ellipse hypotheses, identification of each circle (colour for a, the feature dot for b,
// nesting for c, the centre dot for d and e, the largest ellipse for f), then sub-pixel
// edges and a PND conic fit per circle.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/marker_spec.h"
#include "trackers/circle/circle_geometry.h"
#include "trackers/circle/conic_fit.h"
#include "trackers/circle/subpixel_edges.h"

namespace markerbench {

struct CircleDetectorOptions {
  // Pre-smoothing σ = clamp(min + per_noise * noise σ (0-1 units), min, max) px.
  double smoothing_min_px = 0.7;
  double smoothing_per_noise = 5.0;
  double smoothing_max_px = 3.0;
  int half_resolution_min_px = 240;  // search candidates at half resolution in regions this big
  double min_contrast = 0.08;        // ink vs paper after smoothing, as a fraction of full scale
  // Edge contrast in units of the smoothed noise σ. Marker disks measure 16 or more at
  // σ² = 0.3; blobs of noise at most about 6.
  double min_contrast_snr = 10.0;
  double min_area_px = 12.0;        // smallest blob (a disk of about 2 px radius)
  double max_outline_rms_px = 1.0;  // contour-to-ellipse RMS allowed, plus 8% of the minor axis
  int edge_passes = 2;              // edge search, fit, and again from the fitted ellipse
  double min_edge_fraction = 0.7;   // of a circle's rays that must find its edge
  EdgeSearchOptions edges;
  ConicFitOptions fit;

  bool IsValid(std::string* error) const;
};

struct DetectedCircle {
  Eigen::Matrix3d conic_px = Eigen::Matrix3d::Zero();  // fitted to the edges, canonical
  CircleEdges edges;
};

struct MarkerDetection {
  std::vector<DetectedCircle> circles;   // in CircleGeometry order
  std::optional<Eigen::Vector2d> m0_px;  // detected centre dot (d, e)
  std::optional<Eigen::Vector2d> m1_px;  // detected feature point (b, c, d)
  double noise_sigma = 0.0;              // estimated image noise σ, 0-1 units
  double smoothing_sigma_px = 0.0;
};

class CircleDetector {
 public:
  CircleDetector(const MarkerSpec& marker,
                 const CircleGeometry& geometry,
                 const CircleDetectorOptions& options);

  // Searches `roi` (image pixels) of `image`; coordinates in the result are full-image
  // pixels. nullopt, with `why` set, when the marker is not found whole.
  // With `predicted_conics_px` (one per circle, from the previous pose), markers whose pose
  // needs no detected dot skip the candidate search and take one edge pass from the
  // prediction (the paper's step 5).
  std::optional<MarkerDetection> Detect(const Image8& image,
                                        const cv::Rect& roi,
                                        const std::vector<Eigen::Matrix3d>* predicted_conics_px,
                                        std::string* why) const;

 private:
  struct ChannelPlan {
    int channel = -1;  // RGB channel index, or -1 for luma
    bool ink_dark = true;
  };
  ChannelPlan PlanFor(const MarkerSpec& marker, size_t circle) const;

  MarkerKind kind_;
  CircleGeometry geometry_;
  CircleDetectorOptions options_;
  bool needs_color_ = false;
  std::vector<ChannelPlan> plans_;       // per circle
  std::vector<double> inward_clear_m_;   // per circle: ink-free margin inside its edge
  std::vector<double> outward_clear_m_;  // and outside it, in the circle's channel
  double dot_radius_m_ = 0.0;            // feature (and centre) dot radius
  double threshold_fraction_ = 0.5;      // of the way from the paper to the darkest ink
};

}  // namespace markerbench
