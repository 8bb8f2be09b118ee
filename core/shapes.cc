#include "core/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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

// The part of a grid's box or cell under p: whether p is inside, and its distance to the box's
// or cell's edges (cells of one colour side by side still count their shared edge).
PaintSample GridPaint(const GridShape& grid, const Rgb& ink, const Eigen::Vector2d& p) {
  const double x = (p.x() - grid.top_left.x()) / grid.cell_m;
  const double y = (grid.top_left.y() - p.y()) / grid.cell_m;
  PaintSample sample;
  // Written so that NaN is outside: a NaN cast to int is undefined.
  if (!(x >= 0.0 && y >= 0.0 && x < grid.cols && y < grid.rows)) {
    const double dx = std::max({-x, x - grid.cols, 0.0});
    const double dy = std::max({-y, y - grid.rows, 0.0});
    sample.clearance_m = std::hypot(dx, dy) * grid.cell_m;
    return sample;
  }
  const int col = static_cast<int>(x), row = static_cast<int>(y);
  sample.color = grid.Ink(row, col) ? ink : grid.paper_color;
  sample.clearance_m = std::min({x - col, col + 1 - x, y - row, row + 1 - y}) * grid.cell_m;
  return sample;
}

// DistancesTo, each term's gradient and curvature only `with_gradients` (else left at their
// defaults): a point's paint takes the distances alone (MarkerSpec::ColorAt at each sample of
// the check of the printed design, whose instructions this cut by 13 %).
template <bool with_gradients>
BoundaryDistances DistancesOf(const Shape& shape, const Eigen::Vector2d& p) {
  BoundaryDistances b;
  auto circle = [&](const DiskShape& disk, double sign) {
    const Eigen::Vector2d d = p - disk.center;
    const double r = d.norm();
    // The signed distance to the circle's edge, negative inside.
    EdgeDistance& term = b.terms[b.count++];
    term.metres = sign * (r - disk.radius);
    if constexpr (with_gradients) {
      term.gradient = sign * (r > 0.0 ? Eigen::Vector2d(d / r) : Eigen::Vector2d::UnitX());
      term.curvature_per_m = sign / disk.radius;
    }
  };
  if (const auto* disk = std::get_if<DiskShape>(&shape)) {
    circle(*disk, 1.0);
  } else if (const auto* crescent = std::get_if<CrescentShape>(&shape)) {
    circle(crescent->outer, 1.0);
    circle(crescent->inner, -1.0);
  } else if (const auto* sector = std::get_if<SectorShape>(&shape)) {
    // Left of the start ray's line and right of the end ray's (span <= π).
    const Eigen::Vector2d d = p - sector->center();
    auto line = [&](const Eigen::Vector2d& direction, double sign) {
      const Eigen::Vector2d normal(-direction.y(), direction.x());  // left of the ray
      EdgeDistance& term = b.terms[b.count++];
      term.metres = sign * normal.dot(d);
      if constexpr (with_gradients) term.gradient = sign * normal;
    };
    circle({sector->center(), sector->radius()}, 1.0);
    line(sector->start_direction(), -1.0);
    line(sector->end_direction(), 1.0);
  }
  return b;
}

}  // namespace

BoundaryDistances DistancesTo(const Shape& shape, const Eigen::Vector2d& p) {
  return DistancesOf<true>(shape, p);
}

namespace {

// Where two of a shape's edges meet: a sector's centre and the ends of its arc, a crescent's
// tips; none for a disk.
std::vector<Eigen::Vector2d> OutlineCorners(const Shape& shape) {
  if (const auto* crescent = std::get_if<CrescentShape>(&shape)) {
    const DiskShape& a = crescent->outer;
    const DiskShape& b = crescent->inner;
    const Eigen::Vector2d between = b.center - a.center;
    const double d = between.norm();
    if (!(d > 0.0)) return {};  // concentric: a ring, no tips
    const double along = (a.radius * a.radius - b.radius * b.radius + d * d) / (2.0 * d);
    const double across_squared = a.radius * a.radius - along * along;
    if (!(across_squared >= 0.0)) return {};  // the circles do not cross
    const Eigen::Vector2d u = between / d, normal(-u.y(), u.x());
    const double across = std::sqrt(across_squared);
    return {a.center + along * u + across * normal, a.center + along * u - across * normal};
  }
  if (const auto* sector = std::get_if<SectorShape>(&shape)) {
    const auto rim = [&](const Eigen::Vector2d& direction) {
      return Eigen::Vector2d(sector->center() + sector->radius() * direction);
    };
    return {sector->center(), rim(sector->start_direction()), rim(sector->end_direction())};
  }
  return {};
}

// DistanceToOutline of a disk, crescent or sector from p's distances `b` to its edges.
double OutlineDistance(const Shape& shape, const Eigen::Vector2d& p, const BoundaryDistances& b) {
  // The outline is each edge where the others are not positive. The nearest point of an
  // edge's part is p's foot on the edge when the foot lies on the part, else an end of the
  // part, which is a corner; so the distance is the least of the feet on their parts and
  // the corners.
  double distance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < b.count; ++i) {
    const Eigen::Vector2d foot = p - b.terms[i].metres * b.terms[i].gradient;
    const BoundaryDistances at_foot = DistancesTo(shape, foot);
    bool on_outline = true;
    for (size_t j = 0; j < at_foot.count; ++j) {
      on_outline &= j == i || at_foot.terms[j].metres <= 1e-12;
    }
    if (on_outline) distance = std::min(distance, std::abs(b.terms[i].metres));
  }
  for (const Eigen::Vector2d& corner : OutlineCorners(shape)) {
    distance = std::min(distance, (p - corner).norm());
  }
  return distance;
}

}  // namespace

double DistanceToOutline(const Shape& shape, const Eigen::Vector2d& p) {
  if (const auto* grid = std::get_if<GridShape>(&shape)) {
    return GridPaint(*grid, Rgb::Zero(), p).clearance_m;
  }
  return OutlineDistance(shape, p, DistancesTo(shape, p));
}

bool IsNearOutline(const Shape& shape, const Eigen::Vector2d& p, double reach_m) {
  if (const auto* grid = std::get_if<GridShape>(&shape)) {
    return GridPaint(*grid, Rgb::Zero(), p).clearance_m <= reach_m;
  }
  // The outline lies on the edges' circles and lines: a point beyond reach of all of them is
  // beyond reach of the outline, which settles most points on the distances alone, without
  // their gradients or the feet.
  const BoundaryDistances b = DistancesOf<false>(shape, p);
  bool near_an_edge = false;
  for (size_t i = 0; i < b.count; ++i) near_an_edge |= std::abs(b.terms[i].metres) <= reach_m;
  return near_an_edge && OutlineDistance(shape, p, DistancesTo(shape, p)) <= reach_m;
}

PaintSample PaintAt(const PaintedShape& painted, const Eigen::Vector2d& p) {
  if (const auto* grid = std::get_if<GridShape>(&painted.shape)) {
    return GridPaint(*grid, painted.color, p);
  }
  const BoundaryDistances b = DistancesOf<false>(painted.shape, p);
  PaintSample sample;
  bool inside = true;
  sample.clearance_m = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < b.count; ++i) {
    inside &= b.terms[i].metres < 0.0;
    sample.clearance_m = std::min(sample.clearance_m, std::abs(b.terms[i].metres));
  }
  if (inside) sample.color = painted.color;
  return sample;
}

Eigen::AlignedBox2d ShapeBounds(const Shape& shape) {
  struct Visitor {
    Eigen::AlignedBox2d operator()(const DiskShape& s) const { return DiskBounds(s); }
    Eigen::AlignedBox2d operator()(const CrescentShape& s) const {
      // The crescent lies inside the outer circle and on the bulge side of the chord, which
      // the outer circle's bounds contain.
      return DiskBounds(s.outer);
    }
    Eigen::AlignedBox2d operator()(const SectorShape& s) const {
      Eigen::AlignedBox2d box(s.center());
      constexpr int kSteps = 64;
      for (int i = 0; i <= kSteps; ++i) {
        const double a = s.start_rad() + (s.end_rad() - s.start_rad()) * i / kSteps;
        box.extend(s.center() + s.radius() * Eigen::Vector2d(std::cos(a), std::sin(a)));
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

Eigen::AlignedBox2d OutlineBox(const Shape& shape) {
  // ShapeBounds samples a sector's arc, which bulges past the samples between them.
  if (const auto* sector = std::get_if<SectorShape>(&shape)) {
    return DiskBounds({sector->center(), sector->radius()});
  }
  return ShapeBounds(shape);
}

bool IsBeyondOutlineBox(const Eigen::AlignedBox2d& outline_box,
                        const Eigen::Vector2d& p,
                        double reach_m) {
  // By a millionth of the reach and a picometre more, far beyond the distances' rounding.
  const double margin = reach_m * (1.0 + 1e-6) + 1e-12;
  return outline_box.squaredExteriorDistance(p) > margin * margin;
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
