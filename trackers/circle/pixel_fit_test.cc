// Levenberg-Marquardt on the normal equations (pixel_fit.h) on a model linear in θ, whose
// cost is exactly quadratic: the first (lightly damped) step lands next to the least-squares
// solution, and the fit stops there without evaluating a second step, whose predicted
// decrease is below the tolerance.
#include "trackers/circle/pixel_fit.h"

#include <gtest/gtest.h>

#include <cmath>

namespace markerbench {
namespace {

// r = A θ - b over 12 rows, θ = (angle-axis, translation, σ, offset, gain), b off the range
// of A (a cost at the minimum of 1, about 10× what the start adds to it); counts its
// evaluations.
class LinearModel {
 public:
  LinearModel() : a_(Eigen::MatrixXd::Zero(12, 9)), b_(12) {
    for (int row = 0; row < 12; ++row) {
      for (int column = 0; column < 9; ++column) {
        a_(row, column) = std::sin(1.0 + row * 9 + column * 0.7) + (row % 9 == column ? 3.0 : 0.0);
      }
    }
    solution_ << 0.002, -0.001, 0.001, 0.003, -0.002, 0.52, 1.05, 0.01, 0.98;
    // A misfit off the range of A leaves the minimum at solution_ with a cost of about 1.
    Eigen::VectorXd misfit(12);
    for (int row = 0; row < 12; ++row) misfit[row] = 0.5 * std::cos(1.3 * row);
    misfit -= a_ * (a_.transpose() * a_).ldlt().solve(a_.transpose() * misfit);
    misfit /= misfit.norm();
    b_ = a_ * solution_ + misfit;
  }

  int Parameters() const { return 9; }
  const Eigen::Matrix<double, 9, 1>& solution() const { return solution_; }
  int evaluations() const { return evaluations_; }

  double Evaluate(const Eigen::VectorXd& theta, Eigen::MatrixXd* jtj, Eigen::VectorXd* jtr) const {
    ++evaluations_;
    const Eigen::VectorXd r = a_ * theta - b_;
    if (jtj) {
      *jtj = a_.transpose() * a_;
      *jtr = a_.transpose() * r;
    }
    return r.squaredNorm();
  }

 private:
  Eigen::MatrixXd a_;
  Eigen::VectorXd b_;
  Eigen::Matrix<double, 9, 1> solution_;
  mutable int evaluations_ = 0;
};

TEST(FitPixels, StopsAtTheMinimumOfAQuadraticCostWithoutASecondStep) {
  const LinearModel model;
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  const PixelFit fit = FitPixels(model, start, 1.0, 15);
  // The start and one step: the damped step (1e-3 of the diagonal) lands within about 1e-3
  // of the minimum, and the step after it is predicted to gain below 1e-6 of the cost (it
  // was evaluated, and then counted as converged, before the prediction).
  EXPECT_EQ(fit.iterations, 1);
  EXPECT_EQ(model.evaluations(), 2);
  const Eigen::VectorXd theta = PixelFitParameters(fit.cam_from_marker, fit.sigma_px, fit.levels);
  EXPECT_LT((theta - model.solution()).norm(), 1e-3 * model.solution().norm());
}

}  // namespace
}  // namespace markerbench
