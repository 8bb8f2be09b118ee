#include "trackers/artkplus/contour_trace.h"

#include <array>

namespace markerbench {
namespace {

// E, SE, S, SW, W, NW, N, NE: clockwise on screen (y down).
const std::array<Eigen::Vector2i, 8> kSteps = {
    {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};

}  // namespace

std::vector<Eigen::Vector2i> TraceOuterContour(const DarkRegions& regions,
                                               const DarkRegion& region) {
  const auto inside = [&](const Eigen::Vector2i& p) {
    return p.x() >= 0 && p.y() >= 0 && p.x() < regions.width && p.y() < regions.height &&
           regions.LabelAt(p.x(), p.y()) == region.label;
  };
  const Eigen::Vector2i start = region.first_px;
  std::vector<Eigen::Vector2i> contour = {start};
  // Nothing lies W, NW, N or NE of the first pixel, so the search starts at E.
  int first_direction = -1;
  int search_from = 0;
  Eigen::Vector2i current = start;
  const size_t limit = 4 * static_cast<size_t>(region.area_px) + 8;
  while (contour.size() <= limit) {
    int direction = -1;
    for (int k = 0; k < 8; ++k) {
      const int d = (search_from + k) % 8;
      if (inside(current + kSteps[d])) {
        direction = d;
        break;
      }
    }
    if (direction < 0) break;                                     // an isolated pixel
    if (current == start && direction == first_direction) break;  // Jacob's stopping rule
    if (first_direction < 0) first_direction = direction;
    current += kSteps[direction];
    contour.push_back(current);
    // Back up 90 degrees (45 after a diagonal step) to the last neighbour known empty.
    search_from = (direction + (direction % 2 == 0 ? 7 : 6)) % 8;
  }
  if (contour.size() > 1 && contour.back() == start) contour.pop_back();
  return contour;
}

}  // namespace markerbench
