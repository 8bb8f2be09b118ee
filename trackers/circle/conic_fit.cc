#include "trackers/circle/conic_fit.h"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "trackers/circle/ceres_solver_options.h"
#include "trackers/circle/conic.h"

namespace markerbench {
namespace {

// q = T p with T = [[s, 0, -s mx], [0, s, -s my], [0, 0, 1]] and mean ‖q‖ = √2 (§3.1).
struct HartleyFrame {
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  double scale = 1.0;
  std::vector<Eigen::Vector2d> points;
};

HartleyFrame Normalize(const std::vector<Eigen::Vector2d>& points_px) {
  HartleyFrame frame;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points_px) mean += p;
  mean /= static_cast<double>(points_px.size());
  double spread = 0.0;
  for (const Eigen::Vector2d& p : points_px) spread += (p - mean).norm();
  spread /= static_cast<double>(points_px.size());
  frame.scale = spread > 0.0 ? std::sqrt(2.0) / spread : 1.0;
  frame.T << frame.scale, 0, -frame.scale * mean.x(), 0, frame.scale, -frame.scale * mean.y(), 0, 0,
      1;
  frame.points.reserve(points_px.size());
  for (const Eigen::Vector2d& p : points_px) frame.points.push_back(frame.scale * (p - mean));
  return frame;
}

// Halir-Flusser (§3.2) on already normalized points; returns the conic in their frame.
std::optional<Eigen::Matrix3d> HalirFlusser(const std::vector<Eigen::Vector2d>& q) {
  Eigen::Matrix3d S1 = Eigen::Matrix3d::Zero(), S2 = Eigen::Matrix3d::Zero(),
                  S3 = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector2d& p : q) {
    const Eigen::Vector3d d1(p.x() * p.x(), p.x() * p.y(), p.y() * p.y());
    const Eigen::Vector3d d2(p.x(), p.y(), 1.0);
    S1 += d1 * d1.transpose();
    S2 += d1 * d2.transpose();
    S3 += d2 * d2.transpose();
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> s3_lu(S3);
  if (!s3_lu.isInvertible()) return std::nullopt;
  const Eigen::Matrix3d Tm = -s3_lu.inverse() * S2.transpose();
  const Eigen::Matrix3d M = S1 + S2 * Tm;
  Eigen::Matrix3d Mc;
  Mc.row(0) = M.row(2) / 2.0;
  Mc.row(1) = -M.row(1);
  Mc.row(2) = M.row(0) / 2.0;
  const Eigen::EigenSolver<Eigen::Matrix3d> eig(Mc);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = eig.eigenvectors().col(k).real();
    if (4.0 * v(0) * v(2) - v(1) * v(1) <= 0.0) continue;
    const Eigen::Vector3d def = Tm * v;
    Eigen::Matrix3d C;
    C << v(0), v(1) / 2, def(0) / 2, v(1) / 2, v(2), def(1) / 2, def(0) / 2, def(1) / 2, def(2);
    return C;
  }
  return std::nullopt;
}

Eigen::Matrix3d ConicOf(const double* theta) {
  Eigen::Matrix3d C;
  C << theta[0], theta[1], theta[3], theta[1], theta[2], theta[4], theta[3], theta[4], theta[5];
  return C;
}

// Residuals of all Hartley-frame points, in pixels (§3.3): one block, so that Ceres
// differentiates the conic once per evaluation rather than once per point.
struct PndPointsCost {
  PndPointsCost(const std::vector<Eigen::Vector2d>& q, double inverse_scale)
      : q_(q), inverse_scale_(inverse_scale) {}
  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    const T* theta = parameters[0];
    Eigen::Matrix<T, 3, 3> C;
    C << theta[0], theta[1], theta[3], theta[1], theta[2], theta[4], theta[3], theta[4], theta[5];
    for (size_t j = 0; j < q_.size(); ++j) {
      residuals[j] = PndResidual(C, q_[j].x(), q_[j].y()) * inverse_scale_;
    }
    return true;
  }
  const std::vector<Eigen::Vector2d>& q_;
  double inverse_scale_;
};

}  // namespace

double RmsPndDistance(const Eigen::Matrix3d& conic, const std::vector<Eigen::Vector2d>& points) {
  if (points.empty()) return 0.0;
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const double r = PndResidual<double>(conic, p.x(), p.y());
    sum += r * r;
  }
  return std::sqrt(sum / static_cast<double>(points.size()));
}

std::optional<ConicFit> FitEllipse(const std::vector<Eigen::Vector2d>& points_px,
                                   const ConicFitOptions& options) {
  if (points_px.size() < 5) return std::nullopt;
  const HartleyFrame frame = Normalize(points_px);
  const std::optional<Eigen::Matrix3d> C0 = HalirFlusser(frame.points);
  if (!C0) return std::nullopt;
  Eigen::Matrix3d C = CanonicalConic(*C0);
  ConicFit fit;
  if (options.refine_pnd) {
    double theta[6] = {C(0, 0), C(0, 1), C(1, 1), C(0, 2), C(1, 2), C(2, 2)};
    const double norm = Eigen::Map<Eigen::Matrix<double, 6, 1>>(theta).norm();
    for (double& v : theta) v /= norm;
    ceres::Problem problem;
    auto* cost = new ceres::DynamicAutoDiffCostFunction<PndPointsCost, 6>(
        new PndPointsCost(frame.points, 1.0 / frame.scale));
    cost->AddParameterBlock(6);
    cost->SetNumResiduals(static_cast<int>(frame.points.size()));
    problem.AddResidualBlock(cost, nullptr, theta);
    problem.SetManifold(theta, new ceres::SphereManifold<6>());
    ceres::Solver::Summary summary;
    ceres::Solve(OneThreadLevenbergMarquardt(options.max_iterations), &problem, &summary);
    fit.iterations = static_cast<int>(summary.iterations.size()) - 1;
    C = ConicOf(theta);
  }
  fit.conic = CanonicalConic(frame.T.transpose() * C * frame.T);
  if (!IsRealEllipse(fit.conic)) return std::nullopt;
  fit.rms_px = RmsPndDistance(fit.conic, points_px);
  return fit;
}

}  // namespace markerbench
