// The exact blurred ellipse: its chords against the conic, its value against the definition
// (a fine sum of the Gaussian over the ellipse) and against the blurred disk's tabulated exact
// profile, its gradient against finite differences, and the row's factors kept.
#include "trackers/circle/blurred_ellipse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/circle/conic.h"

namespace markerbench {
namespace {

// G with the nodes an ellipse of `semi_major` needs.
BlurredEllipseValue BlurredAt(const EllipseChords<double>& e,
                              double semi_major,
                              double sigma,
                              const Eigen::Vector2d& x) {
  return BlurredEllipse(e, sigma, BlurredEllipse::NodesFor(semi_major / sigma)).At(x);
}

Ellipse TiltedEllipse() {
  Ellipse e;
  e.center = {40.0, 25.0};
  e.semi_major = 9.0;
  e.semi_minor = 4.0;
  e.angle_rad = 0.6;
  return e;
}

TEST(BlurredEllipse, ChordsLieOnTheConic) {
  const Eigen::Matrix3d conic = ConicFromEllipse(TiltedEllipse());
  for (const double scale : {1.0, -3.0}) {
    const std::optional<EllipseChords<double>> e = ChordsOfConic<double>(scale * conic);
    ASSERT_TRUE(e);
    EXPECT_NEAR(e->x0, 40.0, 1e-9);
    EXPECT_NEAR(e->y0, 25.0, 1e-9);
    for (const double v : {-0.99, -0.5, 0.0, 0.3, 0.9}) {
      const double y = e->y0 + v * e->half_height;
      const double half = e->half_width * std::sqrt(1.0 - v * v);
      for (const double x : {e->x0 + e->slope * v * e->half_height - half,
                             e->x0 + e->slope * v * e->half_height + half}) {
        EXPECT_NEAR(
            Eigen::Vector3d(x, y, 1.0).dot(conic * Eigen::Vector3d(x, y, 1.0)) / conic.norm(),
            0.0,
            1e-12);
      }
    }
  }
  EXPECT_FALSE(
      ChordsOfConic<double>(Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal().toDenseMatrix()));
  EXPECT_FALSE(ChordsOfConic<double>(Eigen::Vector3d(1.0, 1.0, 1.0).asDiagonal().toDenseMatrix()));
}

// P(x + n ∈ E) summed over a 0.02 px grid of the ellipse (midpoints).
double BlurredByGrid(const Ellipse& ellipse, double sigma, const Eigen::Vector2d& x) {
  const Eigen::Matrix3d conic = ConicFromEllipse(ellipse);
  constexpr double kStep = 0.02;
  const Eigen::Vector3d center(ellipse.center.x(), ellipse.center.y(), 1.0);
  const double inside_sign = center.dot(conic * center);
  const double reach = ellipse.semi_major + 0.5;
  double sum = 0.0;
  for (double u = -reach; u < reach; u += kStep) {
    for (double v = -reach; v < reach; v += kStep) {
      const Eigen::Vector3d p(
          ellipse.center.x() + u + 0.5 * kStep, ellipse.center.y() + v + 0.5 * kStep, 1.0);
      if (p.dot(conic * p) * inside_sign <= 0.0) continue;  // outside: not the centre's sign
      const double r2 = (p.head<2>() - x).squaredNorm();
      sum += std::exp(-0.5 * r2 / (sigma * sigma));
    }
  }
  return sum * kStep * kStep / (2.0 * M_PI * sigma * sigma);
}

TEST(BlurredEllipse, IsTheGaussiansMassOverTheEllipse) {
  const Ellipse ellipse = TiltedEllipse();
  const EllipseChords<double> e = *ChordsOfConic<double>(ConicFromEllipse(ellipse));
  for (const double sigma : {1.5, 4.0, 10.0}) {
    for (const Eigen::Vector2d& x : {Eigen::Vector2d(40.0, 25.0),
                                     Eigen::Vector2d(47.0, 30.0),
                                     Eigen::Vector2d(36.0, 29.0),
                                     Eigen::Vector2d(52.0, 20.0)}) {
      EXPECT_NEAR(
          BlurredAt(e, ellipse.semi_major, sigma, x).value, BlurredByGrid(ellipse, sigma, x), 2e-4)
          << "σ " << sigma << " at " << x.transpose();
    }
  }
}

TEST(BlurredEllipse, IsTheBlurredDisksProfileForACircle) {
  Ellipse circle;
  circle.center = {0.0, 0.0};
  circle.semi_major = circle.semi_minor = 6.0;
  const EllipseChords<double> e = *ChordsOfConic<double>(ConicFromEllipse(circle));
  for (const double sigma : {1.0, 3.0, 6.0, 12.0}) {
    const BlurredDiskProfile profile(6.0 / sigma);
    for (const double r : {0.0, 3.0, 5.5, 6.0, 7.0, 10.0, 20.0}) {
      const Eigen::Vector2d x(r * std::cos(1.0), r * std::sin(1.0));
      // The profile's z: the distance inside the edge, in σ.
      EXPECT_NEAR(BlurredAt(e, 6.0, sigma, x).value, profile.At((6.0 - r) / sigma).value, 1e-3)
          << "σ " << sigma << " r " << r;
    }
  }
}

TEST(BlurredEllipse, GradientIsTheFiniteDifferences) {
  const Ellipse ellipse = TiltedEllipse();
  const EllipseChords<double> e = *ChordsOfConic<double>(ConicFromEllipse(ellipse));
  for (const double sigma : {2.0, 8.0}) {
    for (const Eigen::Vector2d& x : {Eigen::Vector2d(45.0, 27.0), Eigen::Vector2d(33.0, 22.0)}) {
      const BlurredEllipseValue at = BlurredAt(e, ellipse.semi_major, sigma, x);
      constexpr double kStep = 1e-6;
      for (int i = 0; i < 6; ++i) {
        EllipseChords<double> up = e, down = e;
        double* const up_params[] = {&up.x0, &up.y0, &up.slope, &up.half_width, &up.half_height};
        double* const down_params[] = {
            &down.x0, &down.y0, &down.slope, &down.half_width, &down.half_height};
        double sigma_up = sigma, sigma_down = sigma;
        if (i < 5) {
          *up_params[i] += kStep;
          *down_params[i] -= kStep;
        } else {
          sigma_up += kStep;
          sigma_down -= kStep;
        }
        const double numeric = (BlurredAt(up, ellipse.semi_major, sigma_up, x).value -
                                BlurredAt(down, ellipse.semi_major, sigma_down, x).value) /
                               (2.0 * kStep);
        EXPECT_NEAR(at.gradient[i], numeric, 1e-7 + 1e-5 * std::abs(numeric))
            << "parameter " << i << " σ " << sigma;
      }
    }
  }
}

// Each size's nodes take G within 1e-7 of 64 nodes (themselves within 1.3e-12 at 8 σ), for
// ellipses of its range: long ones, sheared chords, round ones at the range's end.
TEST(BlurredEllipse, TakesEachSizeWithEnoughNodes) {
  for (const double semi_major_per_sigma : {1.2, 1.9, 3.4, 5.2, 8.0}) {
    for (const double ratio : {1.0, 1.6, 2.5}) {
      for (const double angle : {0.0, 0.5, 1.2}) {
        Ellipse ellipse;
        ellipse.center = {0.0, 0.0};
        ellipse.semi_major = 10.0;
        ellipse.semi_minor = 10.0 / ratio;
        ellipse.angle_rad = angle;
        const EllipseChords<double> e = *ChordsOfConic<double>(ConicFromEllipse(ellipse));
        const double sigma = 10.0 / semi_major_per_sigma;
        const int nodes = BlurredEllipse::NodesFor(semi_major_per_sigma);
        BlurredEllipse chosen(e, sigma, nodes), finest(e, sigma, BlurredEllipse::kMaxNodes);
        for (double y = -14.0 - 3 * sigma; y <= 14.0 + 3 * sigma; y += 0.7) {
          for (double x = -14.0 - 3 * sigma; x <= 14.0 + 3 * sigma; x += 0.9) {
            ASSERT_NEAR(chosen.At({x, y}).value, finest.At({x, y}).value, 1e-7)
                << semi_major_per_sigma << " σ, " << nodes << " nodes, ratio " << ratio << " angle "
                << angle << " at " << x << ", " << y;
          }
        }
      }
    }
  }
  EXPECT_EQ(BlurredEllipse::NodesFor(0.5), 12);
  EXPECT_EQ(BlurredEllipse::NodesFor(20.0), BlurredEllipse::kMaxNodes);
}

// The factors kept from a row give what a fresh evaluation gives, whatever the order of the
// rows asked for.
TEST(BlurredEllipse, KeepsTheRowsFactorsForItsPixels) {
  const EllipseChords<double> e = *ChordsOfConic<double>(ConicFromEllipse(TiltedEllipse()));
  BlurredEllipse kept(e, 3.0, 32);
  for (const Eigen::Vector2d& x : {Eigen::Vector2d(33.0, 22.0),
                                   Eigen::Vector2d(34.0, 22.0),
                                   Eigen::Vector2d(45.0, 27.0),
                                   Eigen::Vector2d(46.0, 27.0),
                                   Eigen::Vector2d(35.0, 22.0)}) {
    const BlurredEllipseValue at = kept.At(x), fresh = BlurredEllipse(e, 3.0, 32).At(x);
    EXPECT_EQ(at.value, fresh.value) << x.transpose();
    EXPECT_EQ(at.gradient, fresh.gradient) << x.transpose();
  }
}

// The value alone is At's, to the bit, with the rows asked for in turn by both (a fit's costs
// and its normal equations must agree on what they fit), inside, on and beyond the edge.
TEST(BlurredEllipse, ValueAloneIsAtsValue) {
  const EllipseChords<double> e = *ChordsOfConic<double>(ConicFromEllipse(TiltedEllipse()));
  for (const double sigma : {0.7, 3.0, 9.0}) {
    BlurredEllipse values(e, sigma, 24), with_gradients(e, sigma, 24);
    for (double y = 0.0; y <= 60.0; y += 1.0) {
      for (double x = 0.0; x <= 80.0; x += 1.0) {
        ASSERT_EQ(values.ValueAt({x, y}), with_gradients.At({x, y}).value)
            << "σ " << sigma << " at " << x << ", " << y;
      }
    }
  }
}

// The nodes read four at a time in AVX2 lanes give the bits of reading them one by one, for
// every rule, blurs from a fraction of a pixel to far beyond the ellipse (where rows' factors
// vanish and chord ends leave the tables), at pixels inside, on, beyond and far from the edge,
// and at NaN and infinite pixels.
TEST(BlurredEllipse, NodesInLanesGiveTheSameBitsAsOneByOne) {
  if (!kCpuHasAvx2) GTEST_SKIP() << "no AVX2 on this CPU";
  const EllipseChords<double> e = *ChordsOfConic<double>(ConicFromEllipse(TiltedEllipse()));
  std::vector<Eigen::Vector2d> pixels = {{std::nan(""), 25.0},
                                         {40.0, std::nan("")},
                                         {HUGE_VAL, 25.0},
                                         {-HUGE_VAL, 30.0},
                                         {40.0, HUGE_VAL},
                                         {1e9, -1e9}};
  for (double y = -40.0; y <= 90.0; y += 2.5) {
    for (double x = -60.0; x <= 140.0; x += 3.7) pixels.emplace_back(x, y);
  }
  using Lanes = BlurredEllipse::NodeLanes;
  int compared = 0;
  for (const int nodes : {12, 16, 24, 32, 48, 64}) {
    for (const double sigma : {0.3, 0.7, 3.0, 9.0, 40.0}) {
      BlurredEllipse one_by_one(e, sigma, nodes), in_lanes(e, sigma, nodes);
      for (const Eigen::Vector2d& x : pixels) {
        const BlurredEllipseValue a = one_by_one.At(x, Lanes::kOneByOne);
        const BlurredEllipseValue b = in_lanes.At(x, Lanes::kAvx2);
        ASSERT_EQ(std::memcmp(&a.value, &b.value, sizeof(double)), 0)
            << nodes << " nodes, σ " << sigma << " at " << x.transpose() << ": " << a.value
            << " against " << b.value;
        ASSERT_EQ(std::memcmp(a.gradient.data(), b.gradient.data(), sizeof(double) * 6), 0)
            << nodes << " nodes, σ " << sigma << " at " << x.transpose();
        const double value_a = one_by_one.ValueAt(x, Lanes::kOneByOne);
        const double value_b = in_lanes.ValueAt(x, Lanes::kAvx2);
        ASSERT_EQ(std::memcmp(&value_a, &value_b, sizeof(double)), 0)
            << nodes << " nodes, σ " << sigma << " at " << x.transpose();
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 6 * 5 * static_cast<int>(pixels.size()));
}

// The distance from a curved edge near its point: on a circle through that point, with its
// normal and radius, within a⁴/8ρ³ at a along it (the leading terms, with a tenth to spare),
// where the tangent's is a²/2ρ off; off the circle a² |d|/2ρ(ρ + d) more; its derivative in
// the edge point is -(n + (a/ρ) t); with no curvature, the tangent's.
TEST(OffsetFromCurvedEdge, IsTheDistanceFromACircleToSecondOrder) {
  const Eigen::Vector2d center(3.0, -2.0);
  const double radius = 7.0, angle = 0.4;
  const Eigen::Vector2d normal(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d tangent(-normal.y(), normal.x());
  const Eigen::Vector2d edge_point = center + radius * normal;
  for (const double turn : {-0.15, -0.05, 0.0, 0.05, 0.15}) {
    for (const double from_center : {5.0, 7.0, 9.5}) {
      const Eigen::Vector2d point =
          center + from_center * Eigen::Vector2d(std::cos(angle + turn), std::sin(angle + turn));
      const EdgeOffset offset = OffsetFromCurvedEdge(point, edge_point, normal, 1.0 / radius);
      const double a = offset.along, d = from_center - radius;
      EXPECT_NEAR(offset.along, from_center * std::sin(turn), 1e-12);
      EXPECT_NEAR(offset.distance,
                  d,
                  1.1 * (std::pow(a, 4) / (8 * std::pow(radius, 3)) +
                         a * a * std::abs(d) / (2 * radius * from_center)) +
                      1e-12)
          << turn << " " << from_center;
      const double h = 1e-6;
      for (const Eigen::Vector2d& move : {Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0.0, 1.0)}) {
        const double moved =
            OffsetFromCurvedEdge(point, edge_point + h * move, normal, 1.0 / radius).distance;
        EXPECT_NEAR(
            (moved - offset.distance) / h, -(normal + a / radius * tangent).dot(move), 1e-5);
      }
    }
  }
  // A point on the circle a pixel along: the tangent's distance is 1/14 px off, this 1/2744.
  const Eigen::Vector2d on_circle =
      center +
      radius * Eigen::Vector2d(std::cos(angle + 1.0 / radius), std::sin(angle + 1.0 / radius));
  EXPECT_LT(std::abs(OffsetFromCurvedEdge(on_circle, edge_point, normal, 1.0 / radius).distance),
            1e-3);
  EXPECT_GT(std::abs(normal.dot(on_circle - edge_point)), 0.07);
  const Eigen::Vector2d point = edge_point + 0.5 * normal + 2.0 * tangent;
  const EdgeOffset flat = OffsetFromCurvedEdge(point, edge_point, normal, 0.0);
  EXPECT_DOUBLE_EQ(flat.distance, 0.5);
}

}  // namespace
}  // namespace markerbench
