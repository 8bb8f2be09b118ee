// TUM RGB-D trajectory lines (`timestamp tx ty tz qx qy qz qw`, Sturm et al. 2012), as evo
// and the TUM tools read them: the camera's pose in the marker frame (marker_from_cam), so
// that `evo_ape tum truth.tum estimate.tum` compares a tracker with the ground truth.
#pragma once

#include <string>

#include "core/rigid3.h"

namespace markerbench {

// One line, ending in '\n'.
std::string TumLine(double time_s, const Rigid3& cam_from_marker);

}  // namespace markerbench
