#include "renderer/subpixel_grid.h"

#include <algorithm>

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

void SubpixelGrid::AverageInto(const ImageF& fine,
                               const Eigen::Vector2i& image_origin,
                               ImageF* image) const {
  const float weight = 1.0f / static_cast<float>(scale * scale);
  const int x0 = region.x0 - image_origin.x(), x1 = region.x1 - image_origin.x();
  for (int c = 0; c < image->channels; ++c) {
    const float* src = fine.plane(c);
    for (int v = region.y0; v < region.y1; ++v) {
      float* row = image->plane(c) + static_cast<size_t>(v - image_origin.y()) * image->width;
      std::fill(row + x0, row + x1, 0.0f);
      for (int j = scale * (v - region.y0); j < scale * (v - region.y0 + 1); ++j) {
        const float* fine_row = src + static_cast<size_t>(j) * fine.width;
        for (int i = 0; i < fine.width; ++i) row[x0 + i / scale] += weight * fine_row[i];
      }
    }
  }
}

PixelRect SubpixelGrid::Coarsen(const PixelRect& fine_rect) const {
  return {fine_rect.x0 / scale,
          fine_rect.y0 / scale,
          (fine_rect.x1 + scale - 1) / scale,
          (fine_rect.y1 + scale - 1) / scale};
}

}  // namespace markerbench
