// Exact box-filtered rendering of a marker plane: every pixel is the area average of the
// scene over its footprint [u-½, u+½] × [v-½, v+½], with a coverage error below 1/255.
//
// Method (analytic coverage with adaptive subdivision): each layer's boundary is a set of
// circles and lines in the marker plane. At a (sub)pixel cell we map its centre to the plane,
// linearise each nearby boundary into an image-space line (signed distance s / |∇_p s|), and
//  - a cell no boundary reaches takes the top-most opaque colour (one evaluation);
//  - a cell crossed by exactly one straight-enough boundary takes the exact area fraction of
//    the square cut by that line (closed form);
//  - anything else (corners, two boundaries, curvature too high for the cell) splits into
//    four, down to 1/32 px, where the centre is sampled.
// The curvature rule keeps the chord error (≈ h²κ/12 per cell) well below 1/255 per pixel.
#pragma once

#include "core/image.h"
#include "renderer/scene.h"

namespace markerbench {

// Pixel rectangle [x0, x1) × [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool Empty() const { return x1 <= x0 || y1 <= y0; }
};

struct RasterResult {
  ImageF image;  // linear intensities, 1 (grey, Rec. 601 luma) or 3 (RGB) channels
  // Where the image is not constant; outside it every pixel has the same colour.
  PixelRect nonuniform;
};

// Renders `scene` into a channels-plane image of the camera's size.
RasterResult Rasterize(const Scene& scene, int channels);

}  // namespace markerbench
