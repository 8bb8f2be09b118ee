// Sub-pixel edge points of one imaged circle, taken along the normals of a hypothesised
// ellipse (circle-method.md §11). Each ray's profile is fitted with the blurred-disk model
//   f(d) = I_out + (I_in - I_out) G((1/κ + e)/σ, (e - d)/σ)
// (BlurredDiskProfile): d the offset along the outward normal, e the edge, κ the ellipse's
// curvature there, so the osculating disk stands in for the ellipse. This removes the
// curvature bias: a blurred disk's 50% level sits about σ²κ/2 inside the true edge (2.5 px
// at σ = 10, R = 20 px). σ and the two levels are shared by all rays; the rays' edges are
// solved jointly with them by Gauss-Newton (Schur complement on the levels).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace markerbench {

struct EdgeSearchOptions {
  int min_rays = 24;            // rays on small ellipses
  int max_rays = 96;            // rays on large ellipses
  double ray_spacing_px = 4.0;  // one ray per this much perimeter, between min and max
  double sample_step_px = 1.0;  // spacing of the profile samples along a ray
  double reach_sigmas = 2.5;    // a ray reaches reach_sigmas σ + 3 px past the edge, both ways
  int iterations = 6;           // Gauss-Newton iterations (stops earlier once converged)
};

struct CircleEdges {
  std::vector<Eigen::Vector2d> points_px;  // edge points, curvature bias removed
  double sigma_px = 0.0;                   // fitted edge blur (optics + pre-smoothing)
  double inside_level = 0.0;               // fitted intensity levels (image units)
  double outside_level = 0.0;
  int rays = 0;  // rays tried; points_px.size() kept
};

// How far a search's rays reach past the hypothesised edge, each way, from its start σ.
inline double EdgeSearchReachPx(double sigma_start_px, const EdgeSearchOptions& options) {
  return options.reach_sigmas * sigma_start_px + 3.0;
}

// `image` is one 8-bit channel (the pre-smoothed ink channel). `ellipse_px` the hypothesis;
// `max_inward_px` and `max_outward_px` bound how far rays look inside and outside (to stay
// clear of other edges of the marker). `sigma_start_px` is the initial σ. Coordinates are image
// pixels (architecture.md).
CircleEdges FindCircleEdges(const cv::Mat& image,
                            const Eigen::Matrix3d& ellipse_px,
                            double max_inward_px,
                            double max_outward_px,
                            double sigma_start_px,
                            const EdgeSearchOptions& options = {});

}  // namespace markerbench
