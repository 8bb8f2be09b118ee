// PndResidual on Jets: a point given as plain numbers gives the value and derivatives of the
// same point as Jets with no derivatives (the products with their zeros add nothing).
// PndReach: no point beyond it from an ellipse's centre is within its distance of the
// ellipse, whatever the ellipse's eccentricity, in every direction. PndBandScales: no point of
// the ellipse scaled beyond its scales is.
#include "trackers/circle/conic.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>

#include "core/random.h"

namespace markerbench {
namespace {

// An ellipse of random size, eccentricity up to 50, angle and place, as the scans meet them.
Ellipse RandomEllipse(Rng* rng) {
  Ellipse e;
  e.center = {rng->Uniform(-300.0, 900.0), rng->Uniform(-300.0, 700.0)};
  e.semi_major = std::exp(rng->Uniform(std::log(0.5), std::log(2000.0)));
  e.semi_minor = e.semi_major / std::exp(rng->Uniform(0.0, std::log(50.0)));
  e.angle_rad = rng->Uniform(-M_PI, M_PI);
  return e;
}

TEST(PndResidual, APointOfPlainNumbersGivesTheSameJetAsAPointOfConstantJets) {
  using Jet = ceres::Jet<double, 6>;
  Rng rng(29);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Matrix3d C = ConicFromEllipse(RandomEllipse(&rng));
    Eigen::Matrix<Jet, 3, 3> C_jet;
    for (int k = 0; k < 9; ++k) {
      C_jet(k) = Jet(C(k));
      for (int i = 0; i < 6; ++i) C_jet(k).v[i] = rng.Uniform(-1.0, 1.0) * std::abs(C(k));
    }
    const double x = rng.Uniform(-500.0, 1500.0), y = rng.Uniform(-500.0, 1200.0);
    const Jet plain = PndResidual(C_jet, x, y);
    const Jet constant = PndResidual(C_jet, Jet(x), Jet(y));
    ASSERT_EQ(plain.a, constant.a) << "trial " << trial;
    for (int i = 0; i < 6; ++i) ASSERT_EQ(plain.v[i], constant.v[i]) << "trial " << trial;
  }
}

TEST(PndReach, NoPointBeyondItIsWithinTheDistance) {
  Rng rng(17);
  for (int trial = 0; trial < 2000; ++trial) {
    const Ellipse e = RandomEllipse(&rng);
    const double distance = std::exp(rng.Uniform(std::log(0.05), std::log(5.0)));
    const Eigen::Matrix3d C = ConicFromEllipse(e);
    const double reach = PndReach(e, distance);
    for (int k = 0; k < 200; ++k) {
      // Just beyond the reach, and along the axes, where the PND is smallest.
      const double angle = k < 4 ? e.angle_rad + k * M_PI / 2 : rng.Uniform(-M_PI, M_PI);
      const double radius = reach * (k % 2 ? 1.0 + 1e-12 : rng.Uniform(1.0, 1.5));
      const Eigen::Vector2d p =
          e.center + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      ASSERT_GT(std::abs(PndResidual<double>(C, p.x(), p.y())), distance)
          << "trial " << trial << ", a " << e.semi_major << ", b " << e.semi_minor;
    }
  }
}

// An ellipse whose axes rounding lost (EllipseFromConic of a near-degenerate conic) has no
// point that a scan may skip.
TEST(PndReach, IsInfiniteWhereTheAxesAreNaN) {
  Ellipse e;
  e.semi_major = 10.0;
  e.semi_minor = std::nan("");
  EXPECT_EQ(PndReach(e, 1.0), INFINITY);
}

// EllipseForm: 1 on the ellipse about its centre, below inside, above outside.
TEST(EllipseForm, IsOneOnTheEllipse) {
  Rng rng(29);
  for (int trial = 0; trial < 200; ++trial) {
    const Ellipse e = RandomEllipse(&rng);
    const Eigen::Matrix2d form = EllipseForm(e);
    const Eigen::Vector2d major(std::cos(e.angle_rad), std::sin(e.angle_rad));
    const Eigen::Vector2d minor(-major.y(), major.x());
    const double t = rng.Uniform(-M_PI, M_PI);
    const Eigen::Vector2d on_ellipse =
        e.semi_major * std::cos(t) * major + e.semi_minor * std::sin(t) * minor;
    EXPECT_NEAR(on_ellipse.dot(form * on_ellipse), 1.0, 1e-12) << "trial " << trial;
    EXPECT_LT((0.9 * on_ellipse).dot(form * (0.9 * on_ellipse)), 1.0);
    EXPECT_GT((1.1 * on_ellipse).dot(form * (1.1 * on_ellipse)), 1.0);
  }
}

TEST(PndBandScales, NoPointBeyondThemIsWithinTheDistance) {
  Rng rng(23);
  int deep_inside = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Ellipse e = RandomEllipse(&rng);
    const double distance = std::exp(rng.Uniform(std::log(0.05), std::log(5.0)));
    const Eigen::Matrix3d C = ConicFromEllipse(e);
    const PndBand band = PndBandScales(e, distance);
    const Eigen::Vector2d major(std::cos(e.angle_rad), std::sin(e.angle_rad));
    const Eigen::Vector2d minor(-major.y(), major.x());
    deep_inside += band.inner > 0.0;
    for (int k = 0; k < 200; ++k) {
      // Points of the ellipse, first the ends of its axes (the minor's is where both bounds
      // are tight), scaled just beyond each scale and farther.
      const double t = k < 8 ? (k % 4) * M_PI / 2 : rng.Uniform(-M_PI, M_PI);
      const Eigen::Vector2d on_ellipse =
          e.semi_major * std::cos(t) * major + e.semi_minor * std::sin(t) * minor;
      const bool just_beyond = k % 2 == 0;
      const double outside = band.outer * (just_beyond ? 1.0 + 1e-12 : rng.Uniform(1.0, 1.5));
      Eigen::Vector2d p = e.center + outside * on_ellipse;
      ASSERT_GT(std::abs(PndResidual<double>(C, p.x(), p.y())), distance)
          << "outside: trial " << trial << ", a " << e.semi_major << ", b " << e.semi_minor;
      if (band.inner == 0.0) continue;
      const double inside = band.inner * (just_beyond ? 1.0 - 1e-12 : rng.Uniform(0.0, 1.0));
      p = e.center + inside * on_ellipse;
      ASSERT_GT(std::abs(PndResidual<double>(C, p.x(), p.y())), distance)
          << "inside: trial " << trial << ", a " << e.semi_major << ", b " << e.semi_minor;
    }
  }
  EXPECT_GT(deep_inside, 1000);  // the inner scale was tested
}

// The scales are tight where the PND is the distance: a circle's band is within a few percent
// of the distance on either side.
TEST(PndBandScales, HoldACircleWithinAFewPercentOfTheDistance) {
  Ellipse circle;
  circle.semi_major = circle.semi_minor = 40.0;
  for (const double distance : {0.1, 1.0, 4.0}) {
    const PndBand band = PndBandScales(circle, distance);
    EXPECT_GE((band.outer - 1.0) * 40.0, distance);
    EXPECT_LE((band.outer - 1.0) * 40.0, 1.07 * distance);
    EXPECT_GE((1.0 - band.inner) * 40.0, distance);
    EXPECT_LE((1.0 - band.inner) * 40.0, 1.02 * distance);
  }
}

TEST(PndBandScales, SkipNothingWhereTheAxesAreNaN) {
  Ellipse e;
  e.semi_major = 10.0;
  e.semi_minor = std::nan("");
  const PndBand band = PndBandScales(e, 1.0);
  EXPECT_EQ(band.inner, 0.0);
  EXPECT_EQ(band.outer, INFINITY);
}

}  // namespace
}  // namespace markerbench
