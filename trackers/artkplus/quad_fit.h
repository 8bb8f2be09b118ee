// Steps 4-5 of the ARToolKitPlus pipeline (baselines.md): split a region's outer contour at
// its four vertices, fit a line to each side by PCA after dropping 5% of the side at each end,
// and intersect neighbouring lines. Lines are fitted in undistorted pixels.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "core/camera.h"
#include "trackers/artkplus/dark_regions.h"

namespace markerbench {

struct QuadFitOptions {
  // A contour point is a vertex when its squared distance from the chord exceeds
  // vertex_area_fraction * region area (the original's check_square: 0.01 / 0.75).
  double vertex_area_fraction = 0.01 / 0.75;
  double side_trim = 0.05;  // fraction of each side dropped at each end before the line fit
  // Our addition (artkplus-improved): refit each side on the sub-pixel crossings of
  // edge_level along each boundary pixel's outward 4-neighbour steps. The original fits the
  // dark boundary pixels' centres, which lie about 0.5 px inside the edge.
  bool subpixel_edges = false;
};

// The contour indices of its four vertices, in contour order (clockwise on screen) from the
// vertex farthest from region.first_px (indices may exceed the contour's size by one turn);
// nullopt unless the contour has exactly 4 vertices.
std::optional<std::array<size_t, 4>> FindQuadVertices(const std::vector<Eigen::Vector2i>& contour,
                                                      const DarkRegion& region,
                                                      const QuadFitOptions& options);

// Corners in distorted pixels, corner k at vertices[k]: the intersections of the sides' lines.
// edge_level (0..255): the grey level of the edge for subpixel_edges, best halfway between
// the ink and the paper (the labelling threshold is only a first guess of it).
std::optional<std::array<Eigen::Vector2d, 4>> FitQuadCorners(
    const std::vector<Eigen::Vector2i>& contour,
    const std::array<size_t, 4>& vertices,
    const uint8_t* grey,
    double edge_level,
    const DarkRegions& regions,
    const Camera& camera,
    const QuadFitOptions& options);

}  // namespace markerbench
