#include "trackers/artkplus/classic_square_pose.h"

#include <Eigen/Dense>
#include <cmath>

namespace markerbench {
namespace {

struct Square {
  std::array<Eigen::Vector3d, 4> corners_m;
  std::array<Eigen::Vector2d, 4> rays;

  // The least-squares translation for R: x_i ((R P_i)_z + t_z) = (R P_i)_x + t_x, same in y.
  Eigen::Vector3d Translation(const Eigen::Matrix3d& R) const {
    Eigen::Matrix<double, 8, 3> A;
    Eigen::Matrix<double, 8, 1> b;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d X = R * corners_m[i];
      const Eigen::Vector2d& x = rays[i];
      A.row(2 * i) << 1, 0, -x.x();
      A.row(2 * i + 1) << 0, 1, -x.y();
      b(2 * i) = x.x() * X.z() - X.x();
      b(2 * i + 1) = x.y() * X.z() - X.y();
    }
    return A.colPivHouseholderQr().solve(b);
  }

  // Sum of squared reprojection errors in normalized image units; infinite behind the camera.
  double Error(const Rigid3& cam_from_marker) const {
    double e = 0.0;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d X = cam_from_marker * corners_m[i];
      if (!(X.z() > 0.0)) return std::numeric_limits<double>::infinity();
      e += (X.hnormalized() - rays[i]).squaredNorm();
    }
    return e;
  }
};

// The 3D direction shared by two image lines of parallel edges: the intersection of the
// planes through the camera centre and each line.
Eigen::Vector3d VanishingDirection(const Eigen::Vector2d& a0,
                                   const Eigen::Vector2d& a1,
                                   const Eigen::Vector2d& b0,
                                   const Eigen::Vector2d& b1) {
  const Eigen::Vector3d line_a = a0.homogeneous().cross(a1.homogeneous());
  const Eigen::Vector3d line_b = b0.homogeneous().cross(b1.homogeneous());
  Eigen::Vector3d d = line_a.cross(line_b);
  // Orient it along a0 -> a1.
  if (d.dot(a1.homogeneous() - a0.homogeneous()) < 0.0) d = -d;
  return d;
}

Eigen::Matrix3d SmallRotation(const Eigen::Vector3d& angles_rad) {
  return (Eigen::AngleAxisd(angles_rad.x(), Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(angles_rad.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(angles_rad.z(), Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

}  // namespace

std::optional<Rigid3> ClassicSquarePose(const std::array<Eigen::Vector2d, 4>& rays,
                                        double size_m,
                                        const ClassicSquarePoseOptions& options) {
  const double s = 0.5 * size_m;
  const Square square{{{{-s, s, 0}, {s, s, 0}, {s, -s, 0}, {-s, -s, 0}}}, rays};

  // Marker x from the top and bottom sides, y (up) from the right and left sides.
  const Eigen::Vector3d x_dir = VanishingDirection(rays[0], rays[1], rays[3], rays[2]);
  const Eigen::Vector3d y_dir = VanishingDirection(rays[3], rays[0], rays[2], rays[1]);
  if (!(x_dir.norm() > 0.0 && y_dir.norm() > 0.0)) return std::nullopt;
  // Make them orthogonal by splitting their angle error evenly about their bisector.
  const Eigen::Vector3d u = x_dir.normalized(), v = y_dir.normalized();
  const Eigen::Vector3d sum = (u + v).normalized(), difference = (u - v).normalized();
  Eigen::Matrix3d R;
  R.col(0) = (sum + difference) / std::sqrt(2.0);
  R.col(1) = (sum - difference) / std::sqrt(2.0);
  R.col(2) = R.col(0).cross(R.col(1));
  if (!R.allFinite()) return std::nullopt;

  Rigid3 cam_from_marker(R, square.Translation(R));
  double error = square.Error(cam_from_marker);
  for (int loop = 0; loop < options.max_loops; ++loop) {
    const double start_error = error;
    for (double step = options.initial_step_deg * M_PI / 180.0;
         step >= options.min_step_deg * M_PI / 180.0;) {
      Rigid3 best = cam_from_marker;
      double best_error = error;
      for (int a = -1; a <= 1; ++a) {
        for (int b = -1; b <= 1; ++b) {
          for (int c = -1; c <= 1; ++c) {
            const Eigen::Matrix3d candidate_R =
                cam_from_marker.rotation * SmallRotation(step * Eigen::Vector3d(a, b, c));
            const Rigid3 candidate(candidate_R, square.Translation(candidate_R));
            const double e = square.Error(candidate);
            if (e < best_error) best_error = e, best = candidate;
          }
        }
      }
      if (best_error < error) {
        cam_from_marker = best;
        error = best_error;
      } else {
        step *= 0.5;
      }
    }
    if (!(error < start_error)) break;
  }
  if (!std::isfinite(error)) return std::nullopt;
  return cam_from_marker;
}

}  // namespace markerbench
