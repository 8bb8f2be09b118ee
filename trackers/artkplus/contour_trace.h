// Step 4 of the ARToolKitPlus pipeline: the outer boundary of a labelled region, traced
// through 8-neighbours (Moore tracing with Jacob's stopping rule), clockwise on screen.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "trackers/artkplus/dark_regions.h"

namespace markerbench {

// Boundary pixels from region.first_px, each once per visit (a pixel on a one-pixel-wide
// neck is visited twice). A single-pixel region gives one point.
std::vector<Eigen::Vector2i> TraceOuterContour(const DarkRegions& regions,
                                               const DarkRegion& region);

}  // namespace markerbench
