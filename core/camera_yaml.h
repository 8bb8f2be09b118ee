// Loads the ROS camera_info YAML that ROS and OpenCV calibration tools write
// (architecture.md, "File formats"). plumb_bob distortion only; skew must be 0.
#pragma once

#include <cstdint>
#include <string>

#include "core/camera.h"

namespace markerbench {

// What a camera file may describe: images up to 64 Mpx (a side up to 100 000 px), focal
// lengths in [1e-3, 1e7] px, the principal point inside the image, and plumb_bob distortion
// with |k1|, |k2|, |k3| <= 100 and |p1|, |p2| <= 1 that maps the image one to one.
constexpr int kMaxImageSide = 100000;
constexpr int64_t kMaxImagePixels = 64LL * 1024 * 1024;
constexpr double kMinFocalPx = 1e-3;
constexpr double kMaxFocalPx = 1e7;
constexpr double kMaxRadialCoefficient = 100.0;
constexpr double kMaxTangentialCoefficient = 1.0;

// Throws ConfigError naming the file, line and key on any bad or unknown input.
Camera LoadCameraYaml(const std::string& path);

}  // namespace markerbench
