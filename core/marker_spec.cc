#include "core/marker_spec.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace markerbench {
namespace {

constexpr std::array<std::pair<MarkerKind, const char*>, 12> kKindNames = {{
    {MarkerKind::kCirclesA, "circles_a"},
    {MarkerKind::kCirclesB, "circles_b"},
    {MarkerKind::kCirclesC, "circles_c"},
    {MarkerKind::kCircleD, "circle_d"},
    {MarkerKind::kCircleE, "circle_e"},
    {MarkerKind::kCircleF, "circle_f"},
    {MarkerKind::kAprilTag, "apriltag"},
    {MarkerKind::kAruco, "aruco"},
    {MarkerKind::kBitGrid, "bit_grid"},
    {MarkerKind::kArtkPlus, "artkplus"},
    {MarkerKind::kDotRings, "dot_rings"},
    {MarkerKind::kRuneTag, "runetag"},
}};

bool IsGrey(const Rgb& c) { return c.maxCoeff() - c.minCoeff() < 1e-12; }

Eigen::AlignedBox2d InkCellBounds(const GridShape& grid) {
  Eigen::AlignedBox2d box;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      if (!grid.Ink(r, c)) continue;
      const Eigen::Vector2d corner = grid.top_left + grid.cell_m * Eigen::Vector2d(c, -r);
      box.extend(corner);
      box.extend(corner + grid.cell_m * Eigen::Vector2d(1.0, -1.0));
    }
  }
  return box;
}

}  // namespace

const char* ToString(MarkerKind kind) {
  for (const auto& [k, name] : kKindNames) {
    if (k == kind) return name;
  }
  return "unknown";
}

std::vector<std::string> MarkerKindNames() {
  std::vector<std::string> names;
  for (const auto& [kind, name] : kKindNames) names.emplace_back(name);
  return names;
}

std::optional<MarkerKind> MarkerKindFromString(const std::string& name) {
  for (const auto& [k, n] : kKindNames) {
    if (name == n) return k;
  }
  return std::nullopt;
}

bool IsCircleKind(MarkerKind kind) {
  switch (kind) {
    case MarkerKind::kCirclesA:
    case MarkerKind::kCirclesB:
    case MarkerKind::kCirclesC:
    case MarkerKind::kCircleD:
    case MarkerKind::kCircleE:
    case MarkerKind::kCircleF:
      return true;
    default:
      return false;
  }
}

bool IsSquareKind(MarkerKind kind) {
  return kind == MarkerKind::kAprilTag || kind == MarkerKind::kAruco ||
         kind == MarkerKind::kBitGrid || kind == MarkerKind::kArtkPlus;
}

Eigen::AlignedBox2d MarkerSpec::InkBounds() const {
  Eigen::AlignedBox2d box;
  for (const PaintedShape& layer : layers) {
    if (const auto* grid = std::get_if<GridShape>(&layer.shape)) {
      box.extend(InkCellBounds(*grid));
    } else if (layer.color != background) {
      box.extend(ShapeBounds(layer.shape));
    }
  }
  return box;
}

PaintSample MarkerSpec::ColorAt(const Eigen::Vector2d& p) const {
  PaintSample printed{background, std::numeric_limits<double>::infinity(), -1};
  for (size_t i = 0; i < layers.size(); ++i) {
    const PaintSample sample = PaintAt(layers[i], p);
    if (sample.color) {
      printed.color = sample.color;
      printed.layer = static_cast<int>(i);
    }
    printed.clearance_m = std::min(printed.clearance_m, sample.clearance_m);
  }
  return printed;
}

bool MarkerSpec::HasColor() const {
  if (!IsGrey(background)) return true;
  for (const PaintedShape& layer : layers) {
    if (!IsGrey(layer.color)) return true;
    if (const auto* grid = std::get_if<GridShape>(&layer.shape)) {
      if (!IsGrey(grid->paper_color)) return true;
    }
  }
  return false;
}

}  // namespace markerbench
