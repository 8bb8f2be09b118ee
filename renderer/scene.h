// What one frame shows: a marker on its plane, seen by a camera at a pose (architecture.md,
// "Scene"). By default the marker is printed on an infinite plane of its background colour;
// rays that miss the plane (beyond the horizon) see the backdrop.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "core/camera.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"

namespace markerbench {

struct Scene {
  const MarkerSpec* marker = nullptr;
  Camera camera;
  Rigid3 cam_from_marker;
  // A finite sheet (width, height in metres, centred on the ink bounds' centre) instead of an
  // infinite plane; what lies beyond it is the backdrop.
  std::optional<Eigen::Vector2d> sheet_size_m;
  Rgb backdrop = Rgb::Constant(0.5);
  // Something covers the ink (a sequence's occlusions): only the paper is drawn.
  bool marker_hidden = false;
};

}  // namespace markerbench
