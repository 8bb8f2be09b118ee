#include "core/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/random.h"

namespace markerbench {
namespace {

constexpr double kTol = 1e-12;

TEST(Shapes, BoxOutlineIsCounterClockwiseFromBottomLeft) {
  const Eigen::AlignedBox2d box(Eigen::Vector2d(-1.0, -2.0), Eigen::Vector2d(3.0, 4.0));
  const std::vector<Eigen::Vector2d> corners = BoxOutline(box, 1);
  ASSERT_EQ(corners.size(), 4u);
  EXPECT_EQ(corners[0], Eigen::Vector2d(-1.0, -2.0));
  EXPECT_EQ(corners[1], Eigen::Vector2d(3.0, -2.0));
  EXPECT_EQ(corners[2], Eigen::Vector2d(3.0, 4.0));
  EXPECT_EQ(corners[3], Eigen::Vector2d(-1.0, 4.0));
  const std::vector<Eigen::Vector2d> outline = BoxOutline(box, 2);
  ASSERT_EQ(outline.size(), 8u);
  EXPECT_EQ(outline[1], Eigen::Vector2d(1.0, -2.0));  // midpoint of the bottom side
}

TEST(Shapes, CrescentArcsPassThroughTheTipsWithTheirSagittas) {
  const Eigen::Vector2d tip0(0.03, 0.0), tip1(0.0, -0.03);
  const CrescentShape c = CrescentFromTips(tip0, tip1, 0.012, 0.005);
  for (const DiskShape& circle : {c.outer, c.inner}) {
    EXPECT_NEAR((tip0 - circle.center).norm(), circle.radius, kTol);
    EXPECT_NEAR((tip1 - circle.center).norm(), circle.radius, kTol);
  }
  // The arcs bulge to the left of tip0 → tip1, i.e. away from the origin here.
  const Eigen::Vector2d mid = 0.5 * (tip0 + tip1);
  const Eigen::Vector2d left = Eigen::Vector2d(1.0, -1.0).normalized();
  EXPECT_NEAR((mid + 0.012 * left - c.outer.center).norm(), c.outer.radius, kTol);
  EXPECT_NEAR((mid + 0.005 * left - c.inner.center).norm(), c.inner.radius, kTol);
}

// PaintAt: inside tests from each shape's own definition, and the clearance as a promise: the
// colour is the same everywhere within it (checked on a circle just inside it), and a disk's
// is its exact distance to the edge.
TEST(Shapes, PaintAtKnowsInsideAndKeepsItsColourWithinTheClearance) {
  GridShape grid;
  grid.rows = 2;
  grid.cols = 3;
  grid.cell_m = 0.02;
  grid.top_left = Eigen::Vector2d(-0.03, 0.02);
  grid.ink = {1, 0, 1, 0, 1, 1};
  grid.paper_color = Rgb::Constant(0.9);
  const Rgb ink(0.1, 0.2, 0.3);
  const std::vector<PaintedShape> shapes = {
      {DiskShape{{0.01, -0.01}, 0.03}, ink},
      {CrescentFromTips({0.03, 0.0}, {0.0, -0.03}, 0.012, 0.005), ink},
      {SectorShape{{0.0, 0.01}, 0.04, 0.3, 0.3 + 2.0}, ink},
      {grid, ink}};
  auto inside_by_definition = [&](size_t k, const Eigen::Vector2d& p) -> std::optional<Rgb> {
    if (k == 0)
      return (p - Eigen::Vector2d(0.01, -0.01)).norm() < 0.03 ? std::optional(ink) : std::nullopt;
    if (k == 1) {
      const auto& c = std::get<CrescentShape>(shapes[1].shape);
      const bool in = (p - c.outer.center).norm() < c.outer.radius &&
                      (p - c.inner.center).norm() > c.inner.radius;
      return in ? std::optional(ink) : std::nullopt;
    }
    if (k == 2) {
      const Eigen::Vector2d d = p - Eigen::Vector2d(0.0, 0.01);
      double angle = std::atan2(d.y(), d.x()) - 0.3;
      while (angle < 0.0) angle += 2.0 * M_PI;
      return d.norm() < 0.04 && angle < 2.0 ? std::optional(ink) : std::nullopt;
    }
    const int col = static_cast<int>(std::floor((p.x() + 0.03) / 0.02));
    const int row = static_cast<int>(std::floor((0.02 - p.y()) / 0.02));
    if (col < 0 || row < 0 || col >= 3 || row >= 2) return std::nullopt;
    return grid.Ink(row, col) ? ink : grid.paper_color;
  };
  uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  for (size_t k = 0; k < shapes.size(); ++k) {
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Vector2d p(0.1 * uniform() - 0.05, 0.1 * uniform() - 0.05);
      const PaintSample sample = PaintAt(shapes[k], p);
      ASSERT_EQ(sample.color, inside_by_definition(k, p)) << k << " " << p.transpose();
      for (int j = 0; j < 16; ++j) {
        const double a = j * M_PI / 8.0;
        const Eigen::Vector2d q =
            p + 0.999 * sample.clearance_m * Eigen::Vector2d(std::cos(a), std::sin(a));
        ASSERT_EQ(inside_by_definition(k, q), sample.color) << k << " " << p.transpose();
      }
      if (k == 0) {
        EXPECT_NEAR(
            sample.clearance_m, std::abs((p - Eigen::Vector2d(0.01, -0.01)).norm() - 0.03), kTol);
      }
    }
  }
}

// DistancesTo: a point is inside (PaintAt) where every distance is negative; stepping back
// along a term's gradient by its distance lands on that term's circle or line, where the
// gradient turns along the boundary at the term's curvature; grids have none.
TEST(Shapes, DistancesToLeadToEachBoundary) {
  const std::vector<Shape> shapes = {DiskShape{{0.01, -0.01}, 0.03},
                                     CrescentFromTips({0.03, 0.0}, {0.0, -0.03}, 0.012, 0.005),
                                     SectorShape{{0.0, 0.01}, 0.04, 0.3, 0.3 + 2.0}};
  const size_t counts[] = {1, 2, 3};
  Rng rng(7);
  for (size_t k = 0; k < shapes.size(); ++k) {
    for (int i = 0; i < 1000; ++i) {
      const double y = rng.Uniform(-0.05, 0.05);  // before x: g++'s order as arguments
      const Eigen::Vector2d p(rng.Uniform(-0.05, 0.05), y);
      const BoundaryDistances b = DistancesTo(shapes[k], p);
      ASSERT_EQ(b.count, counts[k]);
      bool inside = true;
      for (size_t t = 0; t < b.count; ++t) {
        inside &= b.terms[t].metres < 0.0;
        EXPECT_NEAR(b.terms[t].gradient.norm(), 1.0, 1e-12);
        const Eigen::Vector2d foot = p - b.terms[t].metres * b.terms[t].gradient;
        EXPECT_NEAR(DistancesTo(shapes[k], foot).terms[t].metres, 0.0, 1e-12) << k << " " << t;
        const Eigen::Vector2d tangent(-b.terms[t].gradient.y(), b.terms[t].gradient.x());
        const double h = 1e-6;
        const Eigen::Vector2d turned = DistancesTo(shapes[k], foot + h * tangent).terms[t].gradient;
        EXPECT_NEAR((turned - b.terms[t].gradient).dot(tangent) / h,
                    b.terms[t].curvature_per_m,
                    1e-3 * (1.0 + std::abs(b.terms[t].curvature_per_m)))
            << k << " " << t;
      }
      EXPECT_EQ(inside, PaintAt({shapes[k], Rgb::Zero()}, p).color.has_value()) << k;
    }
  }
  EXPECT_EQ(DistancesTo(GridShape{}, Eigen::Vector2d::Zero()).count, 0u);
}

// DistanceToOutline against the outline found by brute force: the points of a 0.1 mm grid
// inside the shape with a neighbour outside. Near a sector's line past its centre, or a
// crescent's circle past its tips, the nearest edge term (DistancesTo) is much nearer than
// the outline.
TEST(Shapes, DistanceToOutlineIsTheDistanceToTheDrawnEdges) {
  const std::vector<Shape> shapes = {DiskShape{{0.01, -0.01}, 0.03},
                                     CrescentFromTips({0.03, 0.0}, {0.0, -0.03}, 0.012, 0.005),
                                     SectorShape{{0.0, 0.01}, 0.04, 0.3, 0.3 + 1.0}};
  constexpr double kStep = 1e-4;
  constexpr int kCells = 1200;  // [-0.06, 0.06]²
  Rng rng(8);
  for (size_t k = 0; k < shapes.size(); ++k) {
    const auto inside = [&](int i, int j) {
      const Eigen::Vector2d q(-0.06 + i * kStep, -0.06 + j * kStep);
      return PaintAt({shapes[k], Rgb::Zero()}, q).color.has_value();
    };
    std::vector<Eigen::Vector2d> outline;
    for (int i = 1; i < kCells; ++i) {
      for (int j = 1; j < kCells; ++j) {
        if (inside(i, j) &&
            (!inside(i - 1, j) || !inside(i + 1, j) || !inside(i, j - 1) || !inside(i, j + 1))) {
          outline.emplace_back(-0.06 + i * kStep, -0.06 + j * kStep);
        }
      }
    }
    int nearer_terms = 0;
    for (int n = 0; n < 300; ++n) {
      const double y = rng.Uniform(-0.05, 0.05);  // before x: g++'s order as arguments
      const Eigen::Vector2d p(rng.Uniform(-0.05, 0.05), y);
      double brute = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& q : outline) brute = std::min(brute, (p - q).norm());
      const double exact = DistanceToOutline(shapes[k], p);
      EXPECT_NEAR(exact, brute, 1.5 * kStep) << k << " at " << p.transpose();
      for (const double reach : {0.002, 0.01, 0.03}) {
        EXPECT_EQ(IsNearOutline(shapes[k], p, reach), exact <= reach) << k << " " << reach;
      }
      const BoundaryDistances b = DistancesTo(shapes[k], p);
      for (size_t t = 0; t < b.count; ++t) {
        nearer_terms += std::abs(b.terms[t].metres) < 0.5 * exact;
      }
    }
    // The disk's one circle is its outline; the others' extended edges come nearer.
    if (k == 0) {
      EXPECT_EQ(nearer_terms, 0);
    } else {
      EXPECT_GT(nearer_terms, 10) << k;
    }
  }
  GridShape grid;
  grid.cell_m = 0.01;
  grid.rows = grid.cols = 2;
  grid.ink = {1, 0, 0, 1};
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.013, -0.004), Eigen::Vector2d(0.03, 0.01)}) {
    const double clearance = PaintAt({grid, Rgb::Zero()}, p).clearance_m;
    EXPECT_EQ(DistanceToOutline(grid, p), clearance);
    EXPECT_TRUE(IsNearOutline(grid, p, clearance));
    EXPECT_FALSE(IsNearOutline(grid, p, 0.99 * clearance));
  }
}

// OutlineBox holds every point of the outline, a sector's arc between ShapeBounds' samples too;
// so a point IsBeyondOutlineBox sets aside is never near the outline, even at the box's edge.
TEST(Shapes, APointBeyondTheOutlineBoxIsNotNearTheOutline) {
  GridShape grid;
  grid.cell_m = 0.01;
  grid.rows = grid.cols = 2;
  grid.ink = {1, 0, 0, 1};
  // The sector's arc from 0.05 to 0.05 + 3π/4 crosses π/2 between ShapeBounds' 64 samples,
  // where the arc rises above them.
  const std::vector<Shape> shapes = {DiskShape{{0.01, -0.01}, 0.03},
                                     CrescentFromTips({0.03, 0.0}, {0.0, -0.03}, 0.012, 0.005),
                                     SectorShape{{0.0, 0.01}, 0.04, 0.05, 0.05 + 0.75 * M_PI},
                                     grid};
  const SectorShape& sector = std::get<SectorShape>(shapes[2]);
  const Eigen::Vector2d top = sector.center() + Eigen::Vector2d(0.0, sector.radius());
  EXPECT_GT(top.y(), ShapeBounds(sector).max().y());
  EXPECT_TRUE(OutlineBox(sector).contains(top));
  EXPECT_FALSE(IsBeyondOutlineBox(OutlineBox(sector), top, 0.0));
  Rng rng(21);
  for (size_t k = 0; k < shapes.size(); ++k) {
    const Eigen::AlignedBox2d box = OutlineBox(shapes[k]);
    int beyond = 0;
    for (int n = 0; n < 4000; ++n) {
      const double y = rng.Uniform(-0.08, 0.08);  // before x: g++'s order as arguments
      const Eigen::Vector2d p(rng.Uniform(-0.08, 0.08), y);
      const double reach = rng.Uniform(0.0, 0.02);
      if (!IsBeyondOutlineBox(box, p, reach)) continue;
      ++beyond;
      ASSERT_FALSE(IsNearOutline(shapes[k], p, reach)) << k << " at " << p.transpose();
      ASSERT_GT(DistanceToOutline(shapes[k], p), reach) << k << " at " << p.transpose();
    }
    EXPECT_GT(beyond, 1000) << k;
    // On the box's edge, at reach 0, a point is not beyond it.
    EXPECT_FALSE(IsBeyondOutlineBox(box, box.min(), 0.0)) << k;
    EXPECT_TRUE(IsBeyondOutlineBox(box, box.max() + Eigen::Vector2d(0.011, 0.0), 0.01)) << k;
    EXPECT_FALSE(IsBeyondOutlineBox(box, box.max() + Eigen::Vector2d(0.01, 0.0), 0.01)) << k;
  }
}

// A point that is not a number (from a degenerate pose) is painted by no shape, and never read
// from outside a grid's cells.
TEST(Shapes, ANanPointIsPaintedByNoShape) {
  GridShape grid;
  grid.cell_m = 0.01;
  grid.rows = grid.cols = 2;
  grid.ink = {1, 0, 0, 1};
  const double nan = std::nan("");
  for (const Shape& shape :
       std::vector<Shape>{DiskShape{{0.0, 0.0}, 0.03},
                          CrescentFromTips({0.03, 0.0}, {0.0, -0.03}, 0.012, 0.005),
                          SectorShape{{0.0, 0.0}, 0.04, 0.3, 2.3},
                          grid}) {
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(nan, 0.005), Eigen::Vector2d(0.005, nan)}) {
      EXPECT_FALSE(PaintAt({shape, Rgb::Zero()}, p).color);
    }
  }
}

}  // namespace
}  // namespace markerbench
