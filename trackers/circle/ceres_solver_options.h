// The Ceres settings of the circle tracker's two least-squares problems (the conic fit and
// the pose refinement): Levenberg-Marquardt on the calling thread, silent, each step from the
// normal equations by Cholesky. Both have 6 parameters and up to a few hundred residuals: a
// dense QR of the Jacobian took full detection 3 % more time (results/speed.md).
#pragma once

#include <ceres/solver.h>

namespace markerbench {

inline ceres::Solver::Options OneThreadLevenbergMarquardt(int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  options.max_num_iterations = max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  return options;
}

}  // namespace markerbench
