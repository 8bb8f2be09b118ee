#include "core/marker_scaling.h"

#include <cmath>
#include <type_traits>

namespace markerbench {
namespace {

DiskShape Scaled(const DiskShape& d, double f) { return {f * d.center, f * d.radius}; }

Shape Scaled(const Shape& shape, double f) {
  return std::visit(
      [f](const auto& s) -> Shape {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, DiskShape>) {
          return Scaled(s, f);
        } else if constexpr (std::is_same_v<S, CrescentShape>) {
          return CrescentShape{Scaled(s.outer, f), Scaled(s.inner, f)};
        } else if constexpr (std::is_same_v<S, SectorShape>) {
          return SectorShape(f * s.center(), f * s.radius(), s.start_rad(), s.end_rad());
        } else {
          GridShape grid = s;
          grid.top_left *= f;
          grid.cell_m *= f;
          return grid;
        }
      },
      shape);
}

}  // namespace

MarkerSpec ScaledMarker(const MarkerSpec& marker, double factor) {
  MarkerSpec out = marker;
  for (Disk& disk : out.circles) {
    disk.center *= factor;
    disk.radius_m *= factor;
  }
  out.size_m *= factor;
  for (PaintedShape& layer : out.layers) layer.shape = Scaled(layer.shape, factor);
  for (Eigen::Vector2d& k : out.keypoints) k *= factor;
  return out;
}

double EqualAreaFactor(const MarkerSpec& marker, double area_m2) {
  return std::sqrt(area_m2 / marker.InkBounds().volume());
}

}  // namespace markerbench
