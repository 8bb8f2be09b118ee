// A finer sampling of part of a canvas, for a Gaussian blur below kMinSampledBlurSigma
// (degradations.h). The grid of scale s divides each canvas pixel (u, v), the square
// [u - ½, u + ½] × [v - ½, v + ½], into s×s sub-pixels; sub-pixel (i, j) is centred at canvas
// point ((i + ½)/s - ½, (j + ½)/s - ½), so canvas pixel u holds i ∈ [su, su + s). Images on
// the grid cover `region` only: their pixel (0, 0) is sub-pixel (s·x0, s·y0). Scale 1 is the
// canvas.
#pragma once

#include <Eigen/Core>

#include "core/camera.h"
#include "renderer/rasterizer.h"

namespace markerbench {

struct SubpixelGrid {
  int scale = 1;
  PixelRect region;  // canvas pixels

  // Sub-pixel coordinates of a canvas point: s·p + (s - 1)/2 (the identity at scale 1).
  Eigen::Vector2d FineFromCanvas(const Eigen::Vector2d& canvas_px) const;
  // The canvas row of the centre of row j of an image on the grid.
  double CanvasRow(double image_row) const;
  // The camera whose image is the grid's image: focal lengths × s, the principal point
  // mapped as a point and shifted to the region (distortion acts on normalised coordinates,
  // before the intrinsics, and is unchanged).
  Camera FineCamera(const Camera& canvas_camera) const;
};

}  // namespace markerbench
