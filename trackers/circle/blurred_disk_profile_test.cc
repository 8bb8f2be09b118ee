// The blurred disk's profile averaged over a pixel (BlurredDiskProfile::OverPixel): it is the
// profile's average over the pixel's offsets along the edge's normal (two uniforms), to the
// tables' interpolation, and its derivatives are its own; a wide disk's profile is a straight
// edge moved by its curvature.
#include "trackers/circle/blurred_disk_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <tuple>
#include <vector>

#include "trackers/circle/avx2_lanes.h"
#include "trackers/pixel_area_blur.h"

namespace markerbench {
namespace {

// E[G(s, z + u1 + u2)], u1 and u2 uniform on [-a, a] and [-b, b], by the midpoint rule.
double AverageOverPixel(const BlurredDiskProfile& profile, double z, double a, double b) {
  constexpr int kSteps = 200;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double u1 = a * (2.0 * (i + 0.5) / kSteps - 1.0);
    for (int j = 0; j < kSteps; ++j) {
      const double u2 = b * (2.0 * (j + 0.5) / kSteps - 1.0);
      sum += profile.At(z + u1 + u2).value;
    }
  }
  return sum / (kSteps * kSteps);
}

struct HalfWidths {
  double a, b;  // in σ
};

// Axis-aligned (b at its floor), diagonal and in between at σ = 1 px (half-widths up to ½ px),
// and a sharp edge (σ = 0.1 px: the profile a step beside the pixel).
constexpr HalfWidths kPixels[] = {{0.5, 0.0}, {0.354, 0.354}, {0.45, 0.22}, {4.5, 2.2}};

TEST(BlurredDiskProfile, OverAPixelIsTheAverageOverItsOffsets) {
  for (const double s : {40.0, 3.0, 0.8}) {
    const BlurredDiskProfile profile(s);
    for (const HalfWidths& w : kPixels) {
      for (const double z : {-8.0, -3.0, -1.0, -0.3, 0.0, 0.4, 1.5, 3.0, 8.0}) {
        // Measured: within 5e-5 (the tables' bilinear and Hermite interpolations).
        EXPECT_NEAR(profile.OverPixel(z, w.a, w.b).value,
                    AverageOverPixel(profile, z, w.a, std::max(w.b, 1e-3)),
                    2e-4)
            << "s " << s << " z " << z << " a " << w.a << " b " << w.b;
      }
    }
  }
}

// H₀, the straight edge's Φ integrated twice: ((x² + 1) Φ(x) + x φ(x)) / 2.
double StraightEdgeSecondIntegral(double x) {
  const double cdf = 0.5 * std::erfc(-x / std::sqrt(2.0));
  const double density = std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI);
  return 0.5 * ((x * x + 1.0) * cdf + x * density);
}

// A disk many σ across is a straight edge moved by its curvature, G → Φ(z - 1/2s), up to any
// radius: a sharp image's disks are hundreds to thousands of σ across. Over a pixel that is
// the second difference of H₀ in closed form; its derivative in s, that of the edge's move.
// (The table's radius was clamped at 40, which put such edges 1/80 - 1/2s σ off: 0.005 in G
// at z = 0 and s = 1000.)
TEST(BlurredDiskProfile, AWideDiskIsAStraightEdgeMovedByItsCurvature) {
  for (const double s : {100.0, 1000.0, 1e6}) {
    const BlurredDiskProfile profile(s);
    const double step = 0.01 * s;
    const BlurredDiskProfile larger(s + step), smaller(s - step);
    for (const HalfWidths& w : kPixels) {
      const double b = std::max(w.b, 1e-3);  // the floor, as OverPixel takes it
      for (const double z : {-2.0, -0.5, 0.0, 0.3, 1.5}) {
        SCOPED_TRACE("s " + std::to_string(s) + " z " + std::to_string(z) + " a " +
                     std::to_string(w.a) + " b " + std::to_string(w.b));
        const double moved = z - 0.5 / s;
        const double exact = (StraightEdgeSecondIntegral(moved + w.a + b) -
                              StraightEdgeSecondIntegral(moved + w.a - b) -
                              StraightEdgeSecondIntegral(moved - w.a + b) +
                              StraightEdgeSecondIntegral(moved - w.a - b)) /
                             (4.0 * w.a * b);
        const PixelProfileValue v = profile.OverPixel(z, w.a, w.b);
        // Measured: within 8e-5 (the tables' integrals, as above).
        EXPECT_NEAR(v.value, exact, 2e-4);
        const double d_ds =
            (larger.OverPixel(z, w.a, w.b).value - smaller.OverPixel(z, w.a, w.b).value) /
            (2.0 * step);
        EXPECT_NEAR(v.d_ds, d_ds, 1e-3 * std::abs(d_ds) + 1e-12);
      }
    }
  }
}

TEST(BlurredDiskProfile, OverAPixelsDerivativesAreItsFiniteDifferences) {
  const double step = 1e-6;
  for (const double s : {3.0, 12.0}) {
    const BlurredDiskProfile profile(s);
    const BlurredDiskProfile larger(s + step), smaller(s - step);
    for (const HalfWidths& w : kPixels) {
      for (const double z : {-2.0, -0.3, 0.0, 0.7, 2.5}) {
        SCOPED_TRACE("s " + std::to_string(s) + " z " + std::to_string(z) + " a " +
                     std::to_string(w.a) + " b " + std::to_string(w.b));
        const PixelProfileValue v = profile.OverPixel(z, w.a, w.b);
        const double d_dz = (profile.OverPixel(z + step, w.a, w.b).value -
                             profile.OverPixel(z - step, w.a, w.b).value) /
                            (2.0 * step);
        const double d_ds =
            (larger.OverPixel(z, w.a, w.b).value - smaller.OverPixel(z, w.a, w.b).value) /
            (2.0 * step);
        const double b = std::max(w.b, 1e-3);  // the floor, as OverPixel takes it
        const double d_dlog_width =
            (profile.OverPixel(z, w.a * (1.0 + step), b * (1.0 + step)).value -
             profile.OverPixel(z, w.a * (1.0 - step), b * (1.0 - step)).value) /
            (2.0 * step);
        EXPECT_NEAR(v.d_dz, d_dz, 1e-6);
        EXPECT_NEAR(v.d_ds, d_ds, 1e-6);
        EXPECT_NEAR(v.d_dlog_width, d_dlog_width, 1e-6);
      }
    }
  }
}

// A NaN point (a pose step gone astray in a fit) gives NaN, which the fit rejects: never a
// crash or a number read outside the tables.
TEST(BlurredDiskProfile, ANanPointGivesNan) {
  const double nan = std::nan("");
  for (const double s : {2.0, 1e4}) {
    const BlurredDiskProfile profile(s);
    const ProfileValue at = profile.At(nan);
    EXPECT_TRUE(std::isnan(at.value) && std::isnan(at.d_dz) && std::isnan(at.d_ds));
    for (const auto& [z, a, b] : {std::tuple{nan, 0.3, 0.3}, {0.0, nan, 0.3}, {0.0, 0.3, nan}}) {
      const PixelProfileValue over = profile.OverPixel(z, a, b);
      EXPECT_TRUE(std::isnan(over.value) && std::isnan(over.d_dz) && std::isnan(over.d_ds) &&
                  std::isnan(over.d_dlog_width));
    }
  }
}

// The four corners read in one AVX2 vector give the bits of reading them one by one: across
// the table's rows (one row beyond s = 80, two below, s on a row and clamped below 0.5), inside
// and past both ends of z, at NaN and infinite points, and at half-widths from the floor up.
TEST(BlurredDiskProfile, CornersInAVectorGiveTheSameBitsAsOneByOne) {
  if (!kCpuHasAvx2) GTEST_SKIP() << "no AVX2 on this CPU";
  const double nan = std::nan(""), infinity = HUGE_VAL;
  const std::vector<double> radii = {0.1, 0.5, 0.8, 1.0, 2.0, 3.7, 12.0, 80.0, 81.0, 1e3, 1e6, nan};
  std::vector<double> points = {
      -infinity, -30.0, -7.0, -6.999, 6.999, 7.0, 7.3, 30.0, infinity, nan};
  for (int k = 0; k <= 400; ++k) points.push_back(-10.0 + 0.05 * k + 1e-3 * std::sin(k));
  int compared = 0;
  for (const double s : radii) {
    const BlurredDiskProfile profile(s);
    for (const double z : points) {
      for (const double a : {0.0, 1e-3, 0.02, 0.35, 0.5, 1.7, 6.0, nan}) {
        for (const double b : {0.0, 0.01, 0.354, 2.2}) {
          const PixelProfileValue one_by_one =
              profile.OverPixel(z, a, b, BlurredDiskProfile::Corners::kOneByOne);
          const PixelProfileValue vector =
              profile.OverPixel(z, a, b, BlurredDiskProfile::Corners::kAvx2);
          ASSERT_EQ(std::memcmp(&one_by_one, &vector, sizeof(PixelProfileValue)), 0)
              << "s " << s << " z " << z << " a " << a << " b " << b << ": " << one_by_one.value
              << " against " << vector.value;
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 12 * 411 * 8 * 4);
}

// The blur of a model over pixels and the σ of its image's edges convert both ways: the edges
// hold the pixel's area (variance 1/12) on top of the blur.
TEST(BlurredDiskProfile, BlurAndEdgeSigmaRoundTrip) {
  for (const double blur : {0.0, 0.02, 0.5, 3.0, 10.0}) {
    const double edge = EdgeSigmaOfBlur(blur);
    EXPECT_NEAR(edge * edge, blur * blur + 1.0 / 12.0, 1e-12) << blur;
    EXPECT_NEAR(BlurSigmaOfEdges(edge), blur, 1e-9) << blur;
  }
}

}  // namespace
}  // namespace markerbench
