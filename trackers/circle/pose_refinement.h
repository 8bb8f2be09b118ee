// Levenberg-Marquardt refinement of the circle pose (circle-method.md §6) with Ceres:
// angle-axis + translation, from the analytic start.
// - Cost A (paper eq. 19): model points on each circle, projected, PND distance to the fitted
//   pixel conic.
// - Cost B (recommended): each edge point's PND distance to the conic projected from the pose,
//   adj(H)ᵀ C_w adj(H) with H = K [r1 r2 t]; all circles jointly under the rigid constraint.
// - Point terms (erratum 7): reprojection of m1 (and m0) fix the rotation about the circle axis,
//   which the conic costs cannot observe for concentric or single-circle markers.
// Residuals are in pixels; a Huber loss bounds outlier edges.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/rigid3.h"

namespace markerbench {

enum class RefinementCost {
  kConics,  // cost A, the paper's eq. 19
  kEdges,   // cost B
};
const char* ToString(RefinementCost cost);

struct RefinementOptions {
  RefinementCost cost = RefinementCost::kEdges;
  double huber_px = 1.5;      // Huber threshold on every residual (px); 0 = plain least squares
  double point_weight = 1.0;  // weight of the point terms: σ_edge / σ_point
  int model_points = 64;      // points per circle for cost A (N = 32-64 is enough, §6)
  int max_iterations = 20;    // LM iterations; 5-7 are typical from the analytic start

  bool IsValid(std::string* error) const;
};

// One circle of the marker in the paper frame and what the image says about it.
struct RefinementCircle {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // paper frame (m)
  double radius_m = 0.0;
  std::vector<Eigen::Vector2d> edge_points_px;         // cost B
  Eigen::Matrix3d conic_px = Eigen::Matrix3d::Zero();  // cost A: the fitted conic
};

// A marker point (paper frame, z = 0) and its observed pixel.
struct RefinementPoint {
  Eigen::Vector2d marker_xy = Eigen::Vector2d::Zero();
  Eigen::Vector2d observed_px = Eigen::Vector2d::Zero();
};

struct RefinementProblem {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  std::vector<RefinementCircle> circles;
  std::vector<RefinementPoint> points;
};

struct RefinementResult {
  Rigid3 cam_from_paper;
  int iterations = 0;
  double initial_cost = 0.0;  // Ceres cost, ½ Σ ρ(r²)
  double final_cost = 0.0;
  bool converged = false;
};

// The cost RefinePose starts from at `cam_from_paper` (½ Σ ρ(r²)), to rank starts.
double RefinementCostAt(const RefinementProblem& problem,
                        const Rigid3& cam_from_paper,
                        const RefinementOptions& options = {});

RefinementResult RefinePose(const RefinementProblem& problem,
                            const Rigid3& cam_from_paper,
                            const RefinementOptions& options = {});

}  // namespace markerbench
