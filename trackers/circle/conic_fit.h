// Ellipse fitting to edge points (circle-method.md §3): Hartley normalization, Fitzgibbon's
// direct least squares in the Halir-Flusser form, then Levenberg-Marquardt on the signed
// polar-n-direction distance (paper eqs. 15-18) with the conic on the unit sphere.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace markerbench {

struct ConicFitOptions {
  bool refine_pnd = true;   // LM on the PND distance after the direct fit (§3.3)
  int max_iterations = 20;  // LM iterations; from a direct start 3-6 are typical
};

struct ConicFit {
  Eigen::Matrix3d conic = Eigen::Matrix3d::Zero();  // pixels, canonical (§0)
  double rms_px = 0.0;                              // RMS PND distance of the points
  int iterations = 0;                               // LM iterations (0 without refinement)
};

// Direct fit (§3.2), then (optionally) PND LM (§3.3). Needs at least 5 points; nullopt if no
// ellipse results.
std::optional<ConicFit> FitEllipse(const std::vector<Eigen::Vector2d>& points_px,
                                   const ConicFitOptions& options = {});

// RMS of PndResidual over the points.
double RmsPndDistance(const Eigen::Matrix3d& conic, const std::vector<Eigen::Vector2d>& points);

}  // namespace markerbench
