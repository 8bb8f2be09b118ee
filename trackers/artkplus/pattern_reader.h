// Step 6 of the ARToolKitPlus pipeline (baselines.md): sample the 6x6 interior through the
// homography of a quad, threshold each cell, and decode the word in all four orientations.
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

struct PatternReadOptions {
  // The original's arGetPatt (src/core/arGetCode.cpp, 6x6 samples for id markers): one
  // sample per cell at the truncated pixel coordinates of the homography of the quad, in
  // distorted pixels. Otherwise the quad is undistorted first and samples_per_side applies.
  bool truncated_samples = true;
  // 1 reads the nearest pixel to each cell centre; n > 1 averages n x n bilinear samples
  // over the cell's central 3/4.
  int samples_per_side = 1;
  // A cell is white above this grey level (the original: the labelling threshold); a
  // negative value thresholds at the mean of the darkest and brightest cells.
  double bit_threshold = -1.0;
  // Orientations that decode with more corrected bits are ignored. The original's BCH
  // confidence is 1 - bits / 4 and must reach 0.5, so it accepts at most 2.
  int max_corrected_bits = 4;
  // The cells' range (brightest - darkest) over the marker's own contrast (the quiet zone's
  // level - the black border's) must lie in [min_code_contrast, 1 / min_code_contrast]: a
  // quad whose border is not darker than its surround is not a marker, and blur shrinks the
  // cells' range long before the border's, leaving an interior that can lie near a wrong
  // codeword. 0: off (the original).
  double min_code_contrast = 0.0;
};

// quad_px: distorted pixels, clockwise on screen. border_cells: black border width in cells
// (3 for border_fraction 0.25, 1 for 0.125). nullopt when no orientation decodes within
// max_corrected_bits, or when two do equally well (an ambiguous orientation).
std::optional<PatternRead> ReadPattern(const uint8_t* grey,
                                       int width,
                                       int height,
                                       const std::array<Eigen::Vector2d, 4>& quad_px,
                                       int border_cells,
                                       ArtkPlusIdMode mode,
                                       const Camera& camera,
                                       const PatternReadOptions& options);

}  // namespace markerbench
