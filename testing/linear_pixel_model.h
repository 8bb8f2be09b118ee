// A model for the pixel fits' own tests (pixel_fit_test, clipped_noise_test): linear in
// (angle-axis, translation, σ², offset, gain), θ with σ² for σ, the parameters the fits step
// along (SigmaAfterStep), so its cost is exactly quadratic in them, with a known least-squares θ
// and a misfit off the model's range that stays at it. It lists its pixels, takes a noise for
// its clipping as the photometric models do (unused: no pixel is clipped), and counts its
// evaluations.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "trackers/circle/pixel_fit.h"

namespace markerbench {

class LinearPixelModel {
 public:
  struct Shape {
    int pixels = 12;
    double scale = 1.0;     // of the rows of A: sin(1 + 9 row + 0.7 column), times this
    double diagonal = 3.0;  // added to A(row, row % 9)
    double level = 0.0;     // every pixel's mean at θ = 0
    double misfit = 1.0;    // the norm of the residuals at the least-squares θ
  };

  // The pixels' values b = level + A solution() + a misfit of cos(1.3 row) off A's range.
  explicit LinearPixelModel(const Shape& shape, double noise_sigma = 0.0)
      : a_(Eigen::MatrixXd::Zero(shape.pixels, 9)),
        b_(shape.pixels),
        level_(shape.level),
        noise_sigma_(noise_sigma) {
    for (int row = 0; row < shape.pixels; ++row) {
      for (int column = 0; column < 9; ++column) {
        a_(row, column) = shape.scale * std::sin(1.0 + row * 9 + column * 0.7) +
                          (row % 9 == column ? shape.diagonal : 0.0);
      }
    }
    solution_ << 0.002, -0.001, 0.001, 0.003, -0.002, 0.52, 1.05, 0.01, 0.98;
    Eigen::VectorXd misfit(shape.pixels);
    for (int row = 0; row < shape.pixels; ++row) misfit[row] = std::cos(1.3 * row);
    misfit -= a_ * (a_.transpose() * a_).ldlt().solve(a_.transpose() * misfit);
    b_ = Eigen::VectorXd::Constant(shape.pixels, level_) + a_ * AlongSigmaSquared(solution_) +
         shape.misfit * misfit / misfit.norm();
  }

  int Parameters() const { return 9; }
  Eigen::VectorXd StartLevels() const { return UnitGainLevels(Parameters()); }
  // Its levels are linear terms, not an offset and a gain: kept as they start.
  Eigen::VectorXd LevelsShownAtStart(std::vector<ModelledPixel>*) const { return StartLevels(); }
  double MinSigmaPx() const { return 0.2; }
  const Eigen::Matrix<double, 9, 1>& solution() const { return solution_; }
  double noise_sigma() const { return noise_sigma_; }
  void set_noise_sigma(double noise_sigma) { noise_sigma_ = noise_sigma; }
  int evaluations() const { return evaluations_; }
  int evaluations_without_normal_equations() const { return without_normal_equations_; }

  // Each row is a pixel whose value is b and whose modelled mean is level + A θ', θ' θ with σ²
  // for σ (its Jacobian A with σ's column times 2σ).
  double Evaluate(const Eigen::VectorXd& theta,
                  Eigen::MatrixXd* jtj,
                  Eigen::VectorXd* jtr,
                  std::vector<ModelledPixel>* modelled) const {
    ++evaluations_;
    if (!jtj) ++without_normal_equations_;
    const Eigen::VectorXd mean =
        Eigen::VectorXd::Constant(b_.size(), level_) + a_ * AlongSigmaSquared(theta);
    const Eigen::VectorXd r = mean - b_;
    if (jtj) {
      Eigen::MatrixXd jacobian = a_;
      jacobian.col(6) *= 2.0 * theta[6];
      *jtj = jacobian.transpose() * jacobian;
      *jtr = jacobian.transpose() * r;
    }
    for (int row = 0; modelled && row < r.size(); ++row) {
      modelled->push_back({b_[row] - mean[row], mean[row]});
    }
    return r.squaredNorm();
  }

 private:
  static Eigen::VectorXd AlongSigmaSquared(Eigen::VectorXd theta) {
    theta[6] *= theta[6];
    return theta;
  }

  Eigen::MatrixXd a_;
  Eigen::VectorXd b_;
  double level_;
  Eigen::Matrix<double, 9, 1> solution_;
  double noise_sigma_;
  mutable int evaluations_ = 0;
  mutable int without_normal_equations_ = 0;
};

}  // namespace markerbench
