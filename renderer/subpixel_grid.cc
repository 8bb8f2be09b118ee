#include "renderer/subpixel_grid.h"

namespace markerbench {

Eigen::Vector2d SubpixelGrid::FineFromCanvas(const Eigen::Vector2d& canvas_px) const {
  return scale * canvas_px + Eigen::Vector2d::Constant(0.5 * (scale - 1));
}

double SubpixelGrid::CanvasRow(double image_row) const {
  return region.y0 + (image_row - 0.5 * (scale - 1)) / scale;
}

Camera SubpixelGrid::FineCamera(const Camera& canvas_camera) const {
  Camera fine = canvas_camera;
  fine.width = scale * (region.x1 - region.x0);
  fine.height = scale * (region.y1 - region.y0);
  fine.fx *= scale;
  fine.fy *= scale;
  const Eigen::Vector2d principal = FineFromCanvas({canvas_camera.cx, canvas_camera.cy});
  fine.cx = principal.x() - scale * region.x0;
  fine.cy = principal.y() - scale * region.y0;
  return fine;
}

}  // namespace markerbench
