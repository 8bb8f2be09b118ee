// The Ceres settings of the circle tracker's two least-squares problems (the conic fit and
// the pose refinement): Levenberg-Marquardt with a dense QR, on the calling thread, silent.
#pragma once

#include <ceres/solver.h>

namespace markerbench {

inline ceres::Solver::Options OneThreadLevenbergMarquardt(int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  return options;
}

}  // namespace markerbench
