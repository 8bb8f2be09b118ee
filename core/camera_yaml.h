// Loads the ROS camera_info YAML that ROS and OpenCV calibration tools write
// (architecture.md, "File formats"). plumb_bob distortion only; skew must be 0.
#pragma once

#include <string>

#include "core/camera.h"

namespace markerbench {

// Throws ConfigError naming the file, line and key on any bad or unknown input.
Camera LoadCameraYaml(const std::string& path);

}  // namespace markerbench
