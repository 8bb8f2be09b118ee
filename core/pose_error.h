// Pose error metrics (bop_toolkit style: small documented functions of an estimate and the
// ground truth). Both poses are cam_from_marker.
#pragma once

#include <cmath>

#include "core/rigid3.h"

namespace markerbench {

// The paper's localization error: distance between the estimated and the true camera centre
// in the marker frame (metres).
inline double PositionError(const Rigid3& estimate, const Rigid3& truth) {
  return (CameraCenterInMarker(estimate) - CameraCenterInMarker(truth)).norm();
}

// Angle of R_est R_trueᵀ (degrees, in [0, 180]).
inline double RotationErrorDeg(const Rigid3& estimate, const Rigid3& truth) {
  return RotationAngleBetween(estimate.rotation, truth.rotation) * 180.0 / M_PI;
}

}  // namespace markerbench
