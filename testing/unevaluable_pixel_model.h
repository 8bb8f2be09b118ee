// A model for the pixel fits' own tests (pixel_fit_test, clipped_noise_test) that cannot be
// evaluated at any θ, as a disk whose image there is no ellipse: an infinite cost and no
// normal equations. It has what FitPixelsAtTheirNoise asks of a model too, and counts its
// evaluations.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "trackers/circle/pixel_fit.h"

namespace markerbench {

struct UnevaluablePixelModel {
  int Parameters() const { return 9; }
  double MinSigmaPx() const { return 0.2; }
  Eigen::VectorXd StartLevels() const { return UnitGainLevels(Parameters()); }
  Eigen::VectorXd LevelsShownAtStart(std::vector<ModelledPixel>*) const { return StartLevels(); }
  double noise_sigma() const { return 0.05; }
  void set_noise_sigma(double) {}
  double Evaluate(const Eigen::VectorXd&,
                  Eigen::MatrixXd*,
                  Eigen::VectorXd*,
                  std::vector<ModelledPixel>*) const {
    ++evaluations;
    return INFINITY;
  }
  mutable int evaluations = 0;
};

}  // namespace markerbench
