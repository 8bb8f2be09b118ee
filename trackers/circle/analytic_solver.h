// From fitted pixel conics (and detected points) to the analytic pose: l_inf (§4.3-4.5,
// optionally the K-normal variant of §5.5), imaged centres as poles (§4.6), the corrected
// eqs. 3-13 (§5.2) and the depth from the radii (§5.3).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "trackers/circle/analytic_pose.h"
#include "trackers/circle/circle_geometry.h"

namespace markerbench {

enum class AnalyticDepth {
  kLx,      // t = s0 m0 with s0 from Lx (eq. 9, least squares)
  kRadius,  // t from each circle's radius (§5.3), averaged; better for b, c, d in [V5]
};
const char* ToString(AnalyticDepth depth);

struct AnalyticOptions {
  // Replace the projective l_inf by the per-circle calibrated normals (§5.5): 3-9x better
  // rotation at tilt >= 20°, no gain near fronto-parallel.
  bool k_normal = true;
  AnalyticDepth depth = AnalyticDepth::kRadius;
};

// What the image gave: one pixel conic per circle of the geometry, in its order, and the
// detected points the layout needs (m0 for kCircleWithCenter; m1 unless a circle or the
// design gives it). With `roll_from_design` the pose's rotation about the circle's axis is
// arbitrary, and its depth always comes from the radius.
struct CircleMeasurements {
  std::vector<Eigen::Matrix3d> conics_px;
  std::optional<Eigen::Vector2d> m0_px;
  std::optional<Eigen::Vector2d> m1_px;
};

struct AnalyticSolution {
  Eigen::Vector3d l_inf_norm = Eigen::Vector3d::Zero();  // unit, = r3 (sign rule of §0)
  Eigen::Vector3d l_inf_px = Eigen::Vector3d::Zero();    // unit, same sign rule
  std::vector<Eigen::Vector2d> imaged_centers_px;        // poles of l_inf, per circle
  Eigen::Vector2d m0_px = Eigen::Vector2d::Zero();
  Eigen::Vector2d m1_px = Eigen::Vector2d::Zero();
  AnalyticPose pose;  // cam_from_paper
};

// nullopt (with `error` set) when the conics admit no consistent l_inf or pose.
std::optional<AnalyticSolution> SolveAnalytic(const CircleGeometry& geometry,
                                              const Eigen::Matrix3d& K,
                                              const CircleMeasurements& measurements,
                                              const AnalyticOptions& options,
                                              std::string* error);

// Every start worth refining, for frames where the choice of l_inf is ill-conditioned (small
// or blurred ellipses): the projective l_inf, its K-normal variant, and each circle's two
// calibrated normals (§4.7; one is r3 whatever the noise on the other circles). The caller
// ranks them by how well they explain the image.
std::vector<AnalyticSolution> AnalyticCandidates(const CircleGeometry& geometry,
                                                 const Eigen::Matrix3d& K,
                                                 const CircleMeasurements& measurements,
                                                 AnalyticDepth depth);

}  // namespace markerbench
