// Step 6 of the ARToolKitPlus pipeline (baselines.md): sample the 6x6 interior through the
// homography of the four corners, threshold each cell at the mean of the cells' min and max,
// and decode the word in all four orientations.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>

#include "core/camera.h"
#include "core/codes/artkplus_id_code.h"

namespace markerbench {

struct PatternRead {
  int id = -1;
  int corrected_bits = 0;
  // 1 - corrected_bits / minimum distance: 1 for a clean read, above 0.5 whenever the
  // word decodes (BCH: >= 5/9, simple: >= 3/4).
  double confidence = 0.0;
  int top_left = 0;        // index into the corners of the marker's top-left corner
  double min_level = 0.0;  // darkest and brightest cell mean, 0..255
  double max_level = 0.0;
};

// corners_px: distorted pixels, clockwise on screen. border_cells: black border width in
// cells (3 for border_fraction 0.25, 1 for 0.125). samples_per_side: 1 reads the nearest
// pixel to each cell centre (as the original's id markers, whose noise breakdown this
// reproduces); n > 1 averages n x n bilinear samples over the cell's central 3/4. nullopt
// when no orientation decodes, or when two do equally well (an ambiguous orientation).
std::optional<PatternRead> ReadPattern(const uint8_t* grey,
                                       int width,
                                       int height,
                                       const std::array<Eigen::Vector2d, 4>& corners_px,
                                       int border_cells,
                                       int samples_per_side,
                                       ArtkPlusIdMode mode,
                                       const Camera& camera);

}  // namespace markerbench
