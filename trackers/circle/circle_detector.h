// Finds the circles of one circle marker (paper Fig. 3 a-f) in an image region and measures
// them: ink segmentation per channel on a noise-adapted smoothing, contour candidates with
// ellipse hypotheses, identification of each circle (colour for a, the feature dot for b,
// nesting for c, the centre dot for d and e, the largest ellipse for f; d's and e's dots by
// their blurred images where blur hides them from the threshold), then sub-pixel edges and a
// PND conic fit per circle.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/marker_spec.h"
#include "trackers/circle/blurred_dot_search.h"
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
  double min_area_px = 12.0;  // smallest blob (a disk of about 2 px radius)
  // d's feature dot, a blob of its own beside the disk, from this contour area on (px²; disks
  // still need min_area_px). From 2 m on the thresholded dot is below 12 px² (mostly below 5 at
  // 2.5 m): taken from min_area_px, d was found in no frame of the paper's distance sweep from
  // 2 m on, where its bound allows 96 %; from 2 px², on 100/100/74 % at 2/2.25/2.5 m (success
  // 92/88/62 %), and on one more of the 1,680 fresh negative frames (a RUNETag's dots;
  // results/circle_false_positives.md).
  double min_dot_area_px = 2.0;
  double max_outline_rms_px = 1.0;  // contour-to-ellipse RMS allowed, plus 8% of the minor axis
  int edge_passes = 2;              // edge search, fit, and again from the fitted ellipse
  // True where a fit on the pixels of disks follows (a-d; the circle tracker's choice), which
  // takes the pose from the image and needs the edges only for its start. Then:
  // - a pass after the first only where the last found the edges more blurred than it started
  //   from (its rays, 2.5σ + 3 px each way, then ended short of the blurred profile;
  //   EdgeSearchOptions::reach_sigmas). Paired against two passes always on the paper sweeps of
  //   circles_a and circle_d (7,200 frames): no cell differed (sign tests, Holm), the geometric
  //   mean of the error ratios 0.999-1.001 per sweep and marker, 7 frames' success changed (4
  //   found, 3 lost, all at 2.5 m or beyond); full detection 4 % less time (results/speed.md).
  //   Where the pose rests on the edge points themselves one pass is worse (photometric: false,
  //   circles_a with distance: errors 3 % larger, found at 3.5 m 67 -> 56 %).
  // - each conic is the direct fit of its edge points, without its PND refinement: the conics
  //   start the pose, whose refinement fits the edge points themselves (cost B), and whose fit
  //   on the pixels follows; full detection 3 % less time (results/speed.md).
  bool edges_start_a_pixel_fit = false;
  double min_edge_fraction = 0.7;  // of a circle's rays that must find its edge
  // d and e: when no disk shows its dots to the threshold, the dots are looked for by their
  // blurred images (blurred_dot_search.h) beside this many of the largest disks: dots of
  // min_blurred_dot_radius_px or more where the disk's edges (the image's blur and the
  // detector's smoothing) leave a dot's peak, 1 - exp(-ρ²/2σ²), below this fraction of its ink
  // (the threshold sits at 0.5); smaller ones where the image's own blur leaves it above, for
  // their thresholded blobs of a few pixels split or vanish under noise (d's dots from 2.5 m
  // on, 1.2-2 px: d was found on 74/27/0/0/0 % of the paper's distance sweep's frames at
  // 2.5-3.5 m without this, 96-100 % with it; success 62/15/0/0/0 -> 83/75/68/62/56 % where the
  // bound allows 95/91/89/87/81 %; e's nose alike). Small dots blurred in the image are not looked
  // for: on the negative set (circle_false_positives_test), blurred clutter passed as d's dots
  // at 2.2-2.6 px. Nor are dots under min_dot_radius_px: one covers about three pixels or
  // less, and texture of a pixel or two passes as it (on the negative set, beside a dark blob
  // of 3 px, at 0.98 px).
  int max_blurred_dot_disks = 3;
  double max_blurred_dot_peak = 0.75;
  double min_blurred_dot_radius_px = 3.0;
  double min_dot_radius_px = 1.0;
  BlurredDotOptions blurred_dots;
  EdgeSearchOptions edges;
  ConicFitOptions fit;

  bool IsValid(std::string* error) const;
};

struct DetectedCircle {
  Eigen::Matrix3d conic_px = Eigen::Matrix3d::Zero();  // fitted to the edges, canonical
  CircleEdges edges;
  int edge_passes = 0;  // run
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

  // Where circle `i`'s edge is looked for: its channel (-1: luma) and how far the edge is clear
  // of other ink in it, inside and outside, in metres.
  struct EdgeClearance {
    int channel = -1;
    double inward_m = 0.0;
    double outward_m = 0.0;
  };
  EdgeClearance ClearanceOf(size_t i) const {
    return {plans_[i].channel, inward_clear_m_[i], outward_clear_m_[i]};
  }

 private:
  struct ChannelPlan {
    int channel = -1;  // RGB channel index, or -1 for luma
    bool ink_dark = true;
  };
  ChannelPlan PlanFor(const MarkerSpec& marker, size_t circle) const;
  // Edges of circle `i` along the normals of `hypothesis`, in its ink-free margins.
  CircleEdges EdgesOf(size_t i,
                      const cv::Mat& smoothed,
                      const Eigen::Matrix3d& hypothesis,
                      double sigma_start_px) const;
  struct FittedEdges {
    CircleEdges edges;
    Eigen::Matrix3d conic = Eigen::Matrix3d::Zero();
    int passes = 0;     // run
    std::string error;  // empty when found
  };
  // Circle `i`'s edges and conic in up to `passes` passes of EdgesOf, each from the last
  // pass's conic and blur (edges_start_a_pixel_fit); the conic's PND refinement in the
  // last when `refine_last`. Before a pass after the first, `smooth_the_rest` (if given)
  // completes `smoothed`, which the first pass needs only within its rays' reach of `start`.
  // An error where too few rays find an edge or the points give no ellipse.
  FittedEdges FitEdgesInPasses(size_t i,
                               const cv::Mat& smoothed,
                               const Eigen::Matrix3d& start,
                               double sigma_start_px,
                               int passes,
                               bool refine_last,
                               const std::function<void()>& smooth_the_rest = nullptr) const;
  struct DiskWithDots {
    Eigen::Matrix3d conic = Eigen::Matrix3d::Zero();
    Eigen::Vector2d m0_px = Eigen::Vector2d::Zero();
    std::optional<Eigen::Vector2d> m1_px;  // d's feature dot
  };
  // d and e: circle 0 at `conic` with its dots found by their blurred images; `raw` and
  // `smoothed` the ink channel of the search region, `noise_sigma` 0-1.
  std::optional<DiskWithDots> BlurredDots(const cv::Mat& raw,
                                          const cv::Mat& smoothed,
                                          const Eigen::Matrix3d& conic,
                                          double smoothing_sigma_px,
                                          double noise_sigma) const;

  MarkerKind kind_;
  CircleGeometry geometry_;
  CircleDetectorOptions options_;
  bool needs_color_ = false;
  std::vector<ChannelPlan> plans_;       // per circle
  std::vector<double> inward_clear_m_;   // per circle: ink-free margin inside its edge
  std::vector<double> outward_clear_m_;  // and outside it, in the circle's channel
  double dot_radius_m_ = 0.0;            // feature (and centre) dot radius
  // The dots' colour step over what lies under them, per unit of circle 0's ink step, in
  // circle 0's channel: -1 for a paper-coloured dot in the disk, +1 for an ink dot beside it.
  double center_dot_contrast_ = 0.0;
  double feature_dot_contrast_ = 0.0;
  double threshold_fraction_ = 0.5;  // of the way from the paper to the darkest ink
};

}  // namespace markerbench
