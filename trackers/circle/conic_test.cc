// PndReach: no point beyond it from an ellipse's centre is within its distance of the
// ellipse, whatever the ellipse's eccentricity, in every direction.
#include "trackers/circle/conic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/random.h"

namespace markerbench {
namespace {

TEST(PndReach, NoPointBeyondItIsWithinTheDistance) {
  Rng rng(17);
  for (int trial = 0; trial < 2000; ++trial) {
    Ellipse e;
    e.center = {rng.Uniform(-300.0, 900.0), rng.Uniform(-300.0, 700.0)};
    e.semi_major = std::exp(rng.Uniform(std::log(0.5), std::log(2000.0)));
    e.semi_minor = e.semi_major / std::exp(rng.Uniform(0.0, std::log(50.0)));
    e.angle_rad = rng.Uniform(-M_PI, M_PI);
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

}  // namespace
}  // namespace markerbench
