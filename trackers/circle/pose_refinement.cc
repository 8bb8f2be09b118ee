#include "trackers/circle/pose_refinement.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <cmath>
#include <sstream>

#include "trackers/circle/ceres_solver_options.h"
#include "trackers/circle/conic.h"

namespace markerbench {
namespace {

// Huber's ρ applied inside the residual: r̃ = sign(r) sqrt(ρ(r²)), so ½ Σ r̃² is the Huber cost
// and every edge point can share one residual block per circle.
template <typename T>
T Robust(const T& r, double huber) {
  using std::abs;
  using std::sqrt;
  if (huber <= 0.0 || abs(r) <= T(huber)) return r;
  const T scaled = sqrt(T(2.0 * huber) * abs(r) - T(huber * huber));
  return r < T(0) ? -scaled : scaled;
}

template <typename T>
Eigen::Matrix<T, 3, 3> RotationOf(const T* angle_axis) {
  Eigen::Matrix<T, 3, 3> R;
  ceres::AngleAxisToRotationMatrix(angle_axis, ceres::ColumnMajorAdapter3x3(R.data()));
  return R;
}

// Cost B for one circle: PND distance of each edge point to the projected circle.
struct EdgeCost {
  EdgeCost(const Eigen::Matrix3d& K, const RefinementCircle& circle, double huber)
      : K_(K), circle_(circle), huber_(huber) {}
  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    const Eigen::Matrix<T, 3, 3> R = RotationOf(parameters[0]);
    Eigen::Matrix<T, 3, 3> Rt;
    Rt.col(0) = R.col(0);
    Rt.col(1) = R.col(1);
    Rt.col(2) << parameters[1][0], parameters[1][1], parameters[1][2];
    const Eigen::Matrix<T, 3, 3> H = K_.cast<T>() * Rt;
    Eigen::Matrix<T, 3, 3> C = ImageOfCircle<T>(H, circle_.center, circle_.radius_m);
    // Scale C to unit Frobenius norm: the PND distance ignores it, but Jets stay well scaled.
    C /= C.norm();
    for (size_t j = 0; j < circle_.edge_points_px.size(); ++j) {
      const Eigen::Vector2d& x = circle_.edge_points_px[j];
      residuals[j] = Robust(PndResidual(C, x.x(), x.y()), huber_);
    }
    return true;
  }
  Eigen::Matrix3d K_;
  const RefinementCircle& circle_;
  double huber_;
};

// Cost A for one circle (eq. 19): projected model points against the fitted conic.
struct ModelPointCost {
  ModelPointCost(const Eigen::Matrix3d& K, const RefinementCircle& circle, int n, double huber)
      : K_(K), conic_(CanonicalConic(circle.conic_px)), huber_(huber) {
    for (int k = 0; k < n; ++k) {
      const double theta = 2.0 * M_PI * k / n;
      points_.emplace_back(circle.center.x() + circle.radius_m * std::cos(theta),
                           circle.center.y() + circle.radius_m * std::sin(theta),
                           0.0);
    }
  }
  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    const Eigen::Matrix<T, 3, 3> R = RotationOf(parameters[0]);
    const Eigen::Matrix<T, 3, 1> t(parameters[1][0], parameters[1][1], parameters[1][2]);
    const Eigen::Matrix<T, 3, 3> C = conic_.cast<T>();
    for (size_t k = 0; k < points_.size(); ++k) {
      const Eigen::Matrix<T, 3, 1> p = K_.cast<T>() * (R * points_[k].cast<T>() + t);
      residuals[k] = Robust(PndResidual<T>(C, p.x() / p.z(), p.y() / p.z()), huber_);
    }
    return true;
  }
  Eigen::Matrix3d K_;
  Eigen::Matrix3d conic_;
  std::vector<Eigen::Vector3d> points_;
  double huber_;
};

// Weighted reprojection of one marker point (§6, point terms).
struct PointCost {
  PointCost(const Eigen::Matrix3d& K, const RefinementPoint& point, double weight, double huber)
      : K_(K), point_(point), weight_(weight), huber_(huber) {}
  template <typename T>
  bool operator()(const T* angle_axis, const T* translation, T* residuals) const {
    const Eigen::Matrix<T, 3, 3> R = RotationOf(angle_axis);
    const Eigen::Matrix<T, 3, 1> X(T(point_.marker_xy.x()), T(point_.marker_xy.y()), T(0));
    const Eigen::Matrix<T, 3, 1> p =
        K_.cast<T>() *
        (R * X + Eigen::Matrix<T, 3, 1>(translation[0], translation[1], translation[2]));
    residuals[0] = Robust(T(weight_) * (p.x() / p.z() - T(point_.observed_px.x())), huber_);
    residuals[1] = Robust(T(weight_) * (p.y() / p.z() - T(point_.observed_px.y())), huber_);
    return true;
  }
  Eigen::Matrix3d K_;
  RefinementPoint point_;
  double weight_;
  double huber_;
};

template <typename Functor>
ceres::CostFunction* PerCircleCost(Functor* functor, int num_residuals) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<Functor, 6>(functor);
  cost->AddParameterBlock(3);
  cost->AddParameterBlock(3);
  cost->SetNumResiduals(num_residuals);
  return cost;
}

}  // namespace

const char* ToString(RefinementCost cost) {
  return cost == RefinementCost::kConics ? "conics" : "edges";
}

bool RefinementOptions::IsValid(std::string* error) const {
  std::ostringstream msg;
  if (!(huber_px >= 0.0)) {
    msg << "huber_px=" << huber_px << " must be >= 0";
  } else if (!(point_weight >= 0.0)) {
    msg << "point_weight=" << point_weight << " must be >= 0";
  } else if (model_points < 8) {
    msg << "model_points=" << model_points << " must be >= 8";
  } else if (max_iterations < 1) {
    msg << "max_iterations=" << max_iterations << " must be >= 1";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

namespace {

// The Ceres problem of RefinePose over the two parameter blocks.
void AddResiduals(const RefinementProblem& problem,
                  const RefinementOptions& options,
                  double* angle_axis,
                  double* translation,
                  ceres::Problem* ceres_problem) {
  for (const RefinementCircle& circle : problem.circles) {
    if (options.cost == RefinementCost::kEdges) {
      if (circle.edge_points_px.empty()) continue;
      ceres_problem->AddResidualBlock(
          PerCircleCost(new EdgeCost(problem.K, circle, options.huber_px),
                        static_cast<int>(circle.edge_points_px.size())),
          nullptr,
          angle_axis,
          translation);
    } else {
      ceres_problem->AddResidualBlock(
          PerCircleCost(
              new ModelPointCost(problem.K, circle, options.model_points, options.huber_px),
              options.model_points),
          nullptr,
          angle_axis,
          translation);
    }
  }
  for (const RefinementPoint& point : problem.points) {
    ceres_problem->AddResidualBlock(
        new ceres::AutoDiffCostFunction<PointCost, 2, 3, 3>(
            new PointCost(problem.K, point, options.point_weight, options.huber_px)),
        nullptr,
        angle_axis,
        translation);
  }
}

struct PoseParameters {
  explicit PoseParameters(const Rigid3& cam_from_paper) {
    ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(cam_from_paper.rotation.data()),
                                     angle_axis);
    for (int k = 0; k < 3; ++k) translation[k] = cam_from_paper.translation[k];
  }
  double angle_axis[3];
  double translation[3];
};

}  // namespace

double RefinementCostAt(const RefinementProblem& problem,
                        const Rigid3& cam_from_paper,
                        const RefinementOptions& options) {
  PoseParameters p(cam_from_paper);
  ceres::Problem ceres_problem;
  AddResiduals(problem, options, p.angle_axis, p.translation, &ceres_problem);
  double cost = 0.0;
  ceres_problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, nullptr);
  return cost;
}

RefinementResult RefinePose(const RefinementProblem& problem,
                            const Rigid3& cam_from_paper,
                            const RefinementOptions& options) {
  PoseParameters p(cam_from_paper);
  ceres::Problem ceres_problem;
  AddResiduals(problem, options, p.angle_axis, p.translation, &ceres_problem);

  ceres::Solver::Summary summary;
  ceres::Solve(OneThreadLevenbergMarquardt(options.max_iterations), &ceres_problem, &summary);

  RefinementResult result;
  ceres::AngleAxisToRotationMatrix(
      p.angle_axis, ceres::ColumnMajorAdapter3x3(result.cam_from_paper.rotation.data()));
  result.cam_from_paper.translation =
      Eigen::Vector3d(p.translation[0], p.translation[1], p.translation[2]);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  return result;
}

}  // namespace markerbench
