// Vector shapes in the marker plane (metres, x right, y up; architecture.md). A marker's
// drawing is a stack of painted layers, bottom first. The renderer rasterises them with exact
// edges; the geometry queries of MarkerSpec are computed from them.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

namespace markerbench {

using Rgb = Eigen::Vector3d;  // linear intensities in [0, 1]

struct DiskShape {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
};

// Inside `outer` and outside `inner`: the crescent between two arcs through the same two tips
// (paper Fig. 3(e), the mouth).
struct CrescentShape {
  DiskShape outer;
  DiskShape inner;
};

// Pie sector of `radius` about `center`, counter-clockwise from start_rad to end_rad, with a
// span in (0, π] (paper Fig. 3(f)). Its rays' unit directions (cos, sin) are computed once, at
// construction: queries at many points (DistancesTo, the renderer's) took a sine and a cosine
// of each angle per point, a tenth of circle_f's full detection.
class SectorShape {
 public:
  SectorShape() = default;
  SectorShape(const Eigen::Vector2d& center, double radius, double start_rad, double end_rad)
      : center_(center),
        radius_(radius),
        start_rad_(start_rad),
        end_rad_(end_rad),
        start_direction_(std::cos(start_rad), std::sin(start_rad)),
        end_direction_(std::cos(end_rad), std::sin(end_rad)) {}

  const Eigen::Vector2d& center() const { return center_; }
  double radius() const { return radius_; }
  double start_rad() const { return start_rad_; }
  double end_rad() const { return end_rad_; }
  const Eigen::Vector2d& start_direction() const { return start_direction_; }
  const Eigen::Vector2d& end_direction() const { return end_direction_; }

 private:
  Eigen::Vector2d center_ = Eigen::Vector2d::Zero();
  double radius_ = 0.0;
  double start_rad_ = 0.0;
  double end_rad_ = 0.0;
  Eigen::Vector2d start_direction_ = Eigen::Vector2d::UnitX();
  Eigen::Vector2d end_direction_ = Eigen::Vector2d::UnitX();
};

// A rows x cols grid of square cells. Row 0 is the top row (largest y). Ink cells take the
// layer colour, the others `paper_color`; both are opaque.
struct GridShape {
  Eigen::Vector2d top_left = Eigen::Vector2d::Zero();
  double cell_m = 0.0;
  int rows = 0;
  int cols = 0;
  std::vector<uint8_t> ink;  // rows * cols, row-major, 1 = ink
  Rgb paper_color = Rgb::Ones();

  bool Ink(int row, int col) const { return ink[static_cast<size_t>(row * cols + col)] != 0; }
};

using Shape = std::variant<DiskShape, CrescentShape, SectorShape, GridShape>;

struct PaintedShape {
  Shape shape;
  Rgb color = Rgb::Zero();
};

// Rec. 601 luma: how a grey camera (and the grey renderer) sees a colour.
inline double Luma(const Rgb& c) { return 0.299 * c.x() + 0.587 * c.y() + 0.114 * c.z(); }

// What a painted layer puts at a marker-plane point: its colour, or nullopt where it leaves
// the layers below visible, and a lower bound on the point's distance to the layer's colour
// edges (exact for disks and grids' cells; for crescents and sectors the smallest distance to
// the circles and lines that bound them).
struct PaintSample {
  std::optional<Rgb> color;
  double clearance_m = 0.0;
  int layer = -1;  // MarkerSpec::ColorAt: the top-most layer painting the point; -1 none
};
PaintSample PaintAt(const PaintedShape& painted, const Eigen::Vector2d& p);

// A disk, crescent or sector as the signed distances from a point to the circles and lines
// that bound it (the shape is where all are negative), each with its unit gradient and how
// fast that turns along the boundary (1/radius for a circle the shape lies inside, -1/radius
// for one it lies outside, 0 for a line); none for grids.
struct EdgeDistance {
  double metres = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::UnitX();
  double curvature_per_m = 0.0;
};
struct BoundaryDistances {
  std::array<EdgeDistance, 3> terms;
  size_t count = 0;
};
BoundaryDistances DistancesTo(const Shape& shape, const Eigen::Vector2d& p);

// The distance from p to a shape's outline: to the arcs and segments that bound a disk,
// crescent or sector, not to the whole circles and lines of DistancesTo (a sector's lines go
// on past its centre and its rim, a crescent's circles past its tips); for a grid, to its
// box's and cells' edges (PaintAt's clearance).
double DistanceToOutline(const Shape& shape, const Eigen::Vector2d& p);

// Whether DistanceToOutline(shape, p) <= reach_m, found at the cost of DistancesTo for points
// beyond reach of every edge's whole circle or line.
bool IsNearOutline(const Shape& shape, const Eigen::Vector2d& p, double reach_m);

// Axis-aligned bounds of a shape in the marker plane.
Eigen::AlignedBox2d ShapeBounds(const Shape& shape);
// A box that holds a shape's outline: its bounds, but a sector's whole circle's. A point
// beyond reach of it (IsBeyondOutlineBox) is beyond reach of the outline, which sets most
// points aside before IsNearOutline where many are tested against a small shape.
Eigen::AlignedBox2d OutlineBox(const Shape& shape);
bool IsBeyondOutlineBox(const Eigen::AlignedBox2d& outline_box,
                        const Eigen::Vector2d& p,
                        double reach_m);

// Points along the outline of `box`, counter-clockwise from its bottom-left corner,
// steps_per_side per side (each corner once). steps_per_side = 1 gives the four corners.
std::vector<Eigen::Vector2d> BoxOutline(const Eigen::AlignedBox2d& box, int steps_per_side);

// The crescent whose two arcs pass through tip0 and tip1 and bulge to the left of
// tip0 → tip1 by the given sagittas (outer > inner > 0).
CrescentShape CrescentFromTips(const Eigen::Vector2d& tip0,
                               const Eigen::Vector2d& tip1,
                               double outer_sagitta_m,
                               double inner_sagitta_m);

}  // namespace markerbench
