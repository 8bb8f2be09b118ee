#include "trackers/artkplus/robust_planar_pose.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "trackers/artkplus/homography.h"

namespace markerbench {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

// The closest rotation to M (Frobenius), via SVD.
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

class OrthogonalIteration {
 public:
  OrthogonalIteration(const std::vector<Eigen::Vector2d>& marker_xy,
                      const std::vector<Eigen::Vector2d>& rays)
      : n_(marker_xy.size()) {
    Eigen::Matrix3d sum_F = Eigen::Matrix3d::Zero();
    for (size_t i = 0; i < n_; ++i) {
      p_.emplace_back(marker_xy[i].x(), marker_xy[i].y(), 0.0);
      const Eigen::Vector3d v = rays[i].homogeneous();
      F_.push_back(v * v.transpose() / v.squaredNorm());
      sum_F += F_.back();
      p_mean_ += p_.back() / static_cast<double>(n_);
    }
    // t(R) = T_factor * sum_i (F_i - I) R p_i   (LHM eq. 20)
    const double n = static_cast<double>(n_);
    t_factor_ = (Eigen::Matrix3d::Identity() - sum_F / n).inverse() / n;
  }

  Eigen::Vector3d OptimalTranslation(const Eigen::Matrix3d& R) const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < n_; ++i) sum += (F_[i] - Eigen::Matrix3d::Identity()) * (R * p_[i]);
    return t_factor_ * sum;
  }

  double ObjectSpaceError(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) const {
    double e = 0.0;
    for (size_t i = 0; i < n_; ++i) {
      e += ((Eigen::Matrix3d::Identity() - F_[i]) * (R * p_[i] + t)).squaredNorm();
    }
    return e;
  }

  PlanarPoseHypothesis Run(Eigen::Matrix3d R, const RobustPlanarPoseOptions& options) const {
    Eigen::Vector3d t = OptimalTranslation(R);
    double error = ObjectSpaceError(R, t);
    int iterations = 0;
    while (iterations < options.max_iterations) {
      // Absolute orientation between p_i and the projections q_i = F_i (R p_i + t).
      std::vector<Eigen::Vector3d> q(n_);
      Eigen::Vector3d q_mean = Eigen::Vector3d::Zero();
      for (size_t i = 0; i < n_; ++i) {
        q[i] = F_[i] * (R * p_[i] + t);
        q_mean += q[i] / static_cast<double>(n_);
      }
      Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
      for (size_t i = 0; i < n_; ++i) M += (q[i] - q_mean) * (p_[i] - p_mean_).transpose();
      R = NearestRotation(M);
      t = OptimalTranslation(R);
      const double previous = error;
      error = ObjectSpaceError(R, t);
      ++iterations;
      if (!(std::abs(previous - error) > options.relative_tolerance * previous)) break;
    }
    return Polish({Rigid3(R, t), error, iterations}, options);
  }

  // Gauss-Newton with Levenberg damping on E over (R exp([w]x), t), from an OI iterate:
  // r_i = (I - F_i)(R p_i + t), dr_i/dt = I - F_i, dr_i/dw = -(I - F_i) R [p_i]x.
  PlanarPoseHypothesis Polish(PlanarPoseHypothesis h,
                              const RobustPlanarPoseOptions& options) const {
    Rigid3& pose = h.cam_from_marker;
    double lambda = 1e-6;
    for (int step = 0; step < options.max_polish_steps; ++step) {
      Eigen::Matrix<double, 6, 6> JtJ = Eigen::Matrix<double, 6, 6>::Zero();
      Eigen::Matrix<double, 6, 1> Jtr = Eigen::Matrix<double, 6, 1>::Zero();
      for (size_t i = 0; i < n_; ++i) {
        const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - F_[i];
        Eigen::Matrix<double, 3, 6> J;
        J.leftCols<3>() = -P * pose.rotation * Skew(p_[i]);
        J.rightCols<3>() = P;
        const Eigen::Vector3d r = P * (pose * p_[i]);
        JtJ += J.transpose() * J;
        Jtr += J.transpose() * r;
      }
      Eigen::Matrix<double, 6, 6> A = JtJ;
      A.diagonal() *= 1.0 + lambda;
      const Eigen::Matrix<double, 6, 1> delta = -A.ldlt().solve(Jtr);
      const Rigid3 candidate(pose.rotation * RotationFromVector(delta.head<3>()),
                             pose.translation + delta.tail<3>());
      const double error = ObjectSpaceError(candidate.rotation, candidate.translation);
      if (error < h.object_space_error) {
        const double previous = h.object_space_error;
        pose = candidate;
        h.object_space_error = error;
        lambda *= 0.1;
        if (!(previous - error > options.relative_tolerance * previous)) break;
      } else {
        lambda *= 10.0;
      }
    }
    return h;
  }

  Eigen::Vector3d CentroidInCamera(const Rigid3& cam_from_marker) const {
    return cam_from_marker * p_mean_;
  }

 private:
  size_t n_;
  std::vector<Eigen::Vector3d> p_;
  std::vector<Eigen::Matrix3d> F_;
  Eigen::Vector3d p_mean_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d t_factor_;
};

// R from H ~ [r1 r2 t] (Zhang 2000). HomographyDlt scales H(2, 2) = t_z to 1, which puts
// the marker in front of the camera.
Eigen::Matrix3d RotationFromHomography(const Eigen::Matrix3d& H) {
  const Eigen::Vector3d r1 = H.col(0), r2 = H.col(1);
  Eigen::Matrix3d M;
  M << r1.normalized(), r2.normalized(), r1.normalized().cross(r2.normalized());
  return NearestRotation(M);
}

}  // namespace

std::vector<PlanarPoseHypothesis> RobustPlanarPose(const std::vector<Eigen::Vector2d>& marker_xy,
                                                   const std::vector<Eigen::Vector2d>& rays,
                                                   const RobustPlanarPoseOptions& options) {
  const OrthogonalIteration oi(marker_xy, rays);
  const PlanarPoseHypothesis first =
      oi.Run(RotationFromHomography(HomographyDlt(marker_xy, rays)), options);

  // The second minimum: mirror the plane normal about the line of sight to the points.
  const Eigen::Matrix3d& R1 = first.cam_from_marker.rotation;
  const Eigen::Vector3d sight = oi.CentroidInCamera(first.cam_from_marker).normalized();
  const Eigen::Vector3d normal = R1.col(2);
  const Eigen::Vector3d mirrored = 2.0 * sight.dot(normal) * sight - normal;
  const Eigen::Matrix3d flip =
      Eigen::Quaterniond::FromTwoVectors(normal, mirrored).toRotationMatrix();
  const PlanarPoseHypothesis second = oi.Run(flip * R1, options);

  std::vector<PlanarPoseHypothesis> minima = {first};
  const double kSameMinimumRad = 1e-6;
  if (RotationAngleBetween(second.cam_from_marker.rotation, R1) > kSameMinimumRad &&
      second.cam_from_marker.translation.z() > 0.0) {
    minima.push_back(second);
  }
  std::sort(minima.begin(), minima.end(), [](const auto& a, const auto& b) {
    return a.object_space_error < b.object_space_error;
  });
  return minima;
}

}  // namespace markerbench
