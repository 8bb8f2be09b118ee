// The blurred printed design of markers e and f against closed forms and against a brute-force
// convolution of the sharp design.
#include "trackers/circle/blurred_design.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/marker_yaml.h"

namespace markerbench {
namespace {

TEST(BivariateNormalCdf, MatchesClosedForms) {
  for (double h : {-1.3, 0.0, 0.7}) {
    for (double k : {-0.4, 0.0, 1.9}) {
      EXPECT_NEAR(BivariateNormalCdf(h, k, 0.0), NormalCdf(h) * NormalCdf(k), 1e-12);
      for (double rho : {-0.95, -0.5, 0.3, 0.9}) {
        EXPECT_NEAR(BivariateNormalCdf(h, k, rho), BivariateNormalCdf(k, h, rho), 1e-12);
        // P(X < h, Y < k) + P(X < h, -Y < -k) = P(X < h), and -Y has correlation -ρ.
        EXPECT_NEAR(
            BivariateNormalCdf(h, k, rho) + BivariateNormalCdf(h, -k, -rho), NormalCdf(h), 1e-6)
            << h << " " << k << " " << rho;
      }
    }
  }
  for (double rho : {-0.9, -0.5, 0.0, 0.5, 0.9}) {
    EXPECT_NEAR(BivariateNormalCdf(0.0, 0.0, rho), 0.25 + std::asin(rho) / (2.0 * M_PI), 1e-9);
  }
}

// The design's luma convolved with the image Gaussian and averaged over the pixel, through the
// local map, by brute force: a (2 half + 1)² grid of the sharp design over the kernel's ±(4 σ +
// 1/2) px, weighted by the kernel (separable in the pixel's axes: Φ((x + 1/2)/σ) - Φ((x - 1/2)/σ)
// along each).
double PixelLuma(const MarkerSpec& marker,
                 const Eigen::Vector2d& p,
                 const Eigen::Matrix2d& marker_from_px,
                 double sigma_px,
                 int half = 80) {
  const double step = (4.0 * sigma_px + 0.5) / half;
  std::vector<double> kernel;
  for (int i = -half; i <= half; ++i) {
    kernel.push_back(NormalCdf((i * step + 0.5) / sigma_px) -
                     NormalCdf((i * step - 0.5) / sigma_px));
  }
  double sum = 0.0, weights = 0.0;
  for (int i = -half; i <= half; ++i) {
    for (int j = -half; j <= half; ++j) {
      const double w = kernel[i + half] * kernel[j + half];
      const Eigen::Vector2d offset_px(i * step, j * step);
      sum += w * Luma(*marker.ColorAt(p + marker_from_px * offset_px).color);
      weights += w;
    }
  }
  return sum / weights;
}

// A straight edge's blurred step averaged over a pixel, in closed form: z the pixel centre's
// distance inside the edge and a, b the pixel's half-widths along its normal, all in σ; H =
// ∫∫Φ = ((x² + 1) Φ(x) + x φ(x)) / 2.
double StraightEdgeOverPixel(double z, double a, double b) {
  const auto H = [](double x) {
    return 0.5 * ((x * x + 1.0) * NormalCdf(x) + x * NormalDensity(x));
  };
  return (H(z + a + b) - H(z + a - b) - H(z - a + b) + H(z - a - b)) / (4.0 * a * b);
}

// A 30° tilt and a turn: 1 px is 1.5 mm one way and 1.3 mm the other.
Eigen::Matrix2d TiltedMap() {
  Eigen::Matrix2d m;
  m << 0.0013, 0.0004, -0.0003, 0.0015;
  return m;
}

// f's wedge: its sides are straight and its apex the corner of two half-planes, which the
// model takes exactly; where the wedge meets the rim, the corner of a line and a circle. Along
// its arc the wedge and the disk share the rim, grey to white: their steps add (a cover of
// the wedge over the blurred disk would be 0.2 too dark there).
TEST(BlurredDesign, MatchesTheConvolvedWedge) {
  const MarkerSpec f = LoadMarkerYaml("scenarios/markers/circle_f.yaml");
  const double sigma = 2.0;
  double largest = 0.0;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.0, 0.0),
                                   Eigen::Vector2d(0.002, 0.001),
                                   Eigen::Vector2d(-0.002, 0.0005),
                                   Eigen::Vector2d(0.02, 0.0015),
                                   Eigen::Vector2d(0.01, 0.012),
                                   Eigen::Vector2d(0.03, 0.02),
                                   Eigen::Vector2d(-0.01, -0.01),
                                   Eigen::Vector2d(0.0433, 0.025),
                                   Eigen::Vector2d(0.0448, 0.0258),
                                   Eigen::Vector2d(0.0413, 0.0239)}) {
    const double model = BlurredDesign(f).At(p, TiltedMap(), sigma).luma;
    const double truth = PixelLuma(f, p, TiltedMap(), sigma);
    largest = std::max(largest, std::abs(model - truth));
    EXPECT_NEAR(model, truth, 2e-3) << p.transpose();
  }
  EXPECT_GT(largest, 0.0);
}

// e's mouth: its arcs are taken as straight edges of their tangent, its tips as corners of
// those; near the tips and across its thin middle that is approximate.
TEST(BlurredDesign, ApproximatesTheConvolvedMouth) {
  const MarkerSpec e = LoadMarkerYaml("scenarios/markers/circle_e.yaml");
  const double sigma = 1.5;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.0, 0.0),
                                   Eigen::Vector2d(0.0235, -0.0235),
                                   Eigen::Vector2d(0.02, -0.02),
                                   Eigen::Vector2d(0.03, 0.0),
                                   Eigen::Vector2d(0.028, -0.004)}) {
    EXPECT_NEAR(
        BlurredDesign(e).At(p, TiltedMap(), sigma).luma, PixelLuma(e, p, TiltedMap(), sigma), 0.03)
        << p.transpose();
  }
}

// Far from an edge the blurred step is taken as sharp, but only where the blur leaves nothing
// in double precision: 5 σ outside f's rim (and far from its wedge) the black disk's tail (over
// the pixel, its curvature moving it by (σ² + 1/12)/2ρ = 0.011 σ) still darkens the white
// paper; 12 σ and 20 σ out the paper is white, with no gradient.
TEST(BlurredDesign, IsSharpOnlyWhereTheBlurLeavesNothing) {
  const MarkerSpec f = LoadMarkerYaml("scenarios/markers/circle_f.yaml");
  const BlurredDesign design(f);
  const Eigen::Matrix2d one_mm_per_px = 0.001 * Eigen::Matrix2d::Identity();
  const Eigen::Vector2d outward(std::cos(200.0 * M_PI / 180.0), std::sin(200.0 * M_PI / 180.0));
  const double paper = Luma(f.background);
  const BlurredLuma near = design.At((0.05 + 0.005) * outward, one_mm_per_px, 1.0);
  // The table's tail (blurred_disk_profile.h) is within 2 % of the closed form there.
  const double tail = StraightEdgeOverPixel(
      -5.0 - (1.0 + 1.0 / 12.0) / 100.0, 0.5 * std::abs(outward.x()), 0.5 * std::abs(outward.y()));
  EXPECT_NEAR(paper - near.luma, tail, 0.02 * tail);
  EXPECT_GT(near.gradient.norm(), 0.0);
  for (const double out_m : {0.012, 0.02}) {
    const BlurredLuma far = design.At((0.05 + out_m) * outward, one_mm_per_px, 1.0);
    EXPECT_EQ(far.luma, paper) << out_m;
    EXPECT_EQ(far.gradient, Eigen::Vector2d::Zero()) << out_m;
    EXPECT_EQ(far.d_sigma, 0.0) << out_m;
  }
}

// A sharp image (σ 0.1 px): what a pixel reads is the share of its square each layer covers,
// which no Gaussian of the pixel's variance gives (a straight edge 0.3 px from the centre of a
// pixel covers 0.8 of it, Φ(0.3/0.29) = 0.85). The model's straight edges over the pixel are
// exact; at the wedge's apex and where it meets the rim its corners take the pixel as Gaussian.
TEST(BlurredDesign, AveragesASharpDesignOverThePixel) {
  const MarkerSpec f = LoadMarkerYaml("scenarios/markers/circle_f.yaml");
  const BlurredDesign design(f);
  const double sigma = 0.1;
  double largest_straight = 0.0;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.02, 0.0003),
                                   Eigen::Vector2d(0.02, -0.0004),
                                   Eigen::Vector2d(0.01, 0.0174),
                                   Eigen::Vector2d(0.0353, -0.0353),
                                   Eigen::Vector2d(0.0433, 0.025),
                                   Eigen::Vector2d(-0.0502, 0.0)}) {
    const double error =
        design.At(p, TiltedMap(), sigma).luma - PixelLuma(f, p, TiltedMap(), sigma, 200);
    largest_straight = std::max(largest_straight, std::abs(error));
    EXPECT_NEAR(error, 0.0, 1e-3) << p.transpose();
  }
  EXPECT_GT(largest_straight, 0.0);
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.0, 0.0),
                                   Eigen::Vector2d(0.0008, 0.0004),
                                   Eigen::Vector2d(0.0499, 0.0006)}) {
    const double error =
        design.At(p, TiltedMap(), sigma).luma - PixelLuma(f, p, TiltedMap(), sigma, 200);
    EXPECT_NEAR(error, 0.0, 1e-2) << p.transpose();
  }
}

// The gradient leaves out how each edge's direction turns along p (second order at the edge):
// within 5 % and 0.5 per metre (across the edges it reaches 150 per metre at σ 1.2 px). The
// derivative in σ is exact, at a blur and where the pixel's width dominates.
TEST(BlurredDesign, GradientIsTheDerivative) {
  for (const char* kind : {"circle_e", "circle_f"}) {
    const MarkerSpec marker = LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml");
    const BlurredDesign design(marker);
    for (const double sigma : {1.2, 0.1}) {
      for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.001, 0.002),
                                       Eigen::Vector2d(0.02, -0.018),
                                       Eigen::Vector2d(0.015, 0.004),
                                       Eigen::Vector2d(0.012, -0.0006)}) {
        const BlurredLuma at = design.At(p, TiltedMap(), sigma);
        for (int axis = 0; axis < 2; ++axis) {
          const Eigen::Vector2d h = 1e-7 * Eigen::Vector2d::Unit(axis);
          const double numeric = (design.At(p + h, TiltedMap(), sigma).luma -
                                  design.At(p - h, TiltedMap(), sigma).luma) /
                                 2e-7;
          EXPECT_NEAR(at.gradient(axis), numeric, 0.5 + 0.05 * std::abs(numeric))
              << kind << " " << p.transpose() << " axis " << axis << " sigma " << sigma;
        }
        // In σ nothing is held: the derivative is exact.
        const double numeric_sigma = (design.At(p, TiltedMap(), sigma + 1e-6).luma -
                                      design.At(p, TiltedMap(), sigma - 1e-6).luma) /
                                     2e-6;
        EXPECT_NEAR(at.d_sigma, numeric_sigma, 1e-6 + 1e-5 * std::abs(numeric_sigma))
            << kind << " " << p.transpose() << " sigma " << sigma;
      }
    }
  }
}

// The intermediate colours get a level each (f's grey wedge; e's white features on the black
// disk none, unless printed in greys), and the derivative in a level is the share of the pixel
// that colour covers: the luma's finite difference.
TEST(BlurredDesign, FittedColoursHaveLevelsWhoseDerivativeIsTheirShare) {
  const MarkerSpec f = LoadMarkerYaml("scenarios/markers/circle_f.yaml");
  MarkerSpec e = LoadMarkerYaml("scenarios/markers/circle_e.yaml");
  EXPECT_EQ(BlurredDesign(f).FittedLevels(), 1);
  EXPECT_EQ(BlurredDesign(e).FittedLevels(), 0);
  ASSERT_EQ(e.layers.size(), 3u);
  e.layers[1].color = Rgb(1.0, 0.0, 0.0);  // red: a third luma, but no level a response moves
  EXPECT_EQ(BlurredDesign(e).FittedLevels(), 0);
  e.layers[1].color = Rgb::Constant(0.7);
  EXPECT_EQ(BlurredDesign(e).FittedLevels(), 1);
  e.layers[2].color = Rgb::Constant(0.3);
  EXPECT_EQ(BlurredDesign(e).FittedLevels(), 2);
  for (const MarkerSpec* marker : {&f, static_cast<const MarkerSpec*>(&e)}) {
    const BlurredDesign design(*marker);
    const std::array<double, kMaxFittedLevels> shifts = {0.05, -0.03};
    int partly_covered = 0;  // pixels a fitted colour covers in part
    // Points 2.5 mm apart over the disk (a pixel is about 1.5 mm, the blur 0.8 px).
    for (int i = 0; i <= 1600; ++i) {
      const Eigen::Vector2d p(-0.05 + 0.0025 * (i % 41), -0.05 + 0.0025 * (i / 41));
      const BlurredLuma at = design.At(p, TiltedMap(), 0.8, shifts);
      for (int k = 0; k < kMaxFittedLevels; ++k) {
        std::array<double, kMaxFittedLevels> up = shifts, down = shifts;
        up[k] += 1e-6;
        down[k] -= 1e-6;
        const double numeric =
            (design.At(p, TiltedMap(), 0.8, up).luma - design.At(p, TiltedMap(), 0.8, down).luma) /
            2e-6;
        EXPECT_NEAR(at.d_levels[k], numeric, 1e-8) << p.transpose() << " level " << k;
        EXPECT_GE(at.d_levels[k], -2e-4);  // the tables' error (blurred_disk_profile.cc)
        EXPECT_LE(at.d_levels[k], 1.0 + 2e-4);
        partly_covered += at.d_levels[k] > 0.05 && at.d_levels[k] < 0.95;
      }
    }
    EXPECT_GE(partly_covered, 1);
    // Deep in the wedge the pixel is all grey: its luma the design's moved by the shift.
    if (marker == &f) {
      const Eigen::Vector2d in_wedge(0.025, 0.012);
      EXPECT_NEAR(design.At(in_wedge, TiltedMap(), 0.8, shifts).luma, 0.5 + 0.05, 1e-9);
      EXPECT_NEAR(design.At(in_wedge, TiltedMap(), 0.8, shifts).d_levels[0], 1.0, 1e-9);
    }
  }
}

}  // namespace
}  // namespace markerbench
