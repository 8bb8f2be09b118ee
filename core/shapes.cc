#include "core/shapes.h"

#include <cmath>

namespace markerbench {
namespace {

Eigen::AlignedBox2d DiskBounds(const DiskShape& disk) {
  const Eigen::Vector2d r(disk.radius, disk.radius);
  return {disk.center - r, disk.center + r};
}

// Circle through the chord's ends whose arc on the `normal` side has the given sagitta.
DiskShape ArcCircle(const Eigen::Vector2d& mid,
                    const Eigen::Vector2d& normal,
                    double half_chord,
                    double sagitta) {
  const double radius = (half_chord * half_chord + sagitta * sagitta) / (2.0 * sagitta);
  return {mid + normal * (sagitta - radius), radius};
}

}  // namespace

Eigen::AlignedBox2d ShapeBounds(const Shape& shape) {
  struct Visitor {
    Eigen::AlignedBox2d operator()(const DiskShape& s) const { return DiskBounds(s); }
    Eigen::AlignedBox2d operator()(const CrescentShape& s) const {
      // The crescent lies inside the outer circle and on the bulge side of the chord, which
      // the outer circle's bounds contain.
      return DiskBounds(s.outer);
    }
    Eigen::AlignedBox2d operator()(const SectorShape& s) const {
      Eigen::AlignedBox2d box(s.center);
      constexpr int kSteps = 64;
      for (int i = 0; i <= kSteps; ++i) {
        const double a = s.start_rad + (s.end_rad - s.start_rad) * i / kSteps;
        box.extend(s.center + s.radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
      }
      return box;
    }
    Eigen::AlignedBox2d operator()(const GridShape& s) const {
      const Eigen::Vector2d bottom_right =
          s.top_left + Eigen::Vector2d(s.cols * s.cell_m, -s.rows * s.cell_m);
      return {Eigen::Vector2d(s.top_left.x(), bottom_right.y()),
              Eigen::Vector2d(bottom_right.x(), s.top_left.y())};
    }
  };
  return std::visit(Visitor{}, shape);
}

std::vector<Eigen::Vector2d> BoxOutline(const Eigen::AlignedBox2d& box, int steps_per_side) {
  const Eigen::Vector2d corners[4] = {box.corner(Eigen::AlignedBox2d::BottomLeft),
                                      box.corner(Eigen::AlignedBox2d::BottomRight),
                                      box.corner(Eigen::AlignedBox2d::TopRight),
                                      box.corner(Eigen::AlignedBox2d::TopLeft)};
  std::vector<Eigen::Vector2d> points;
  points.reserve(static_cast<size_t>(4 * steps_per_side));
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d& a = corners[side];
    const Eigen::Vector2d& b = corners[(side + 1) % 4];
    for (int i = 0; i < steps_per_side; ++i) {
      points.push_back(a + (static_cast<double>(i) / steps_per_side) * (b - a));
    }
  }
  return points;
}

CrescentShape CrescentFromTips(const Eigen::Vector2d& tip0,
                               const Eigen::Vector2d& tip1,
                               double outer_sagitta_m,
                               double inner_sagitta_m) {
  const Eigen::Vector2d mid = 0.5 * (tip0 + tip1);
  const Eigen::Vector2d along = (tip1 - tip0).normalized();
  const Eigen::Vector2d left(-along.y(), along.x());
  const double half_chord = 0.5 * (tip1 - tip0).norm();
  return {ArcCircle(mid, left, half_chord, outer_sagitta_m),
          ArcCircle(mid, left, half_chord, inner_sagitta_m)};
}

}  // namespace markerbench
