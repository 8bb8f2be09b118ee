// What the renderer knows about a frame and trackers never see (architecture.md, layering).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/rigid3.h"

namespace markerbench {

struct GroundTruth {
  Rigid3 cam_from_marker;
  // Projections of MarkerSpec::keypoints (true centres for m0/m1, never ellipse centres).
  std::vector<Eigen::Vector2d> keypoints_px;
  // sqrt of the image area of the projected ink bounding box, in pixels.
  double apparent_size_px = 0.0;
};

}  // namespace markerbench
