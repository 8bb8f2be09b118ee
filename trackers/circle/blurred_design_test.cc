// The blurred printed design of markers e and f against closed forms and against a brute-force
// convolution of the sharp design.
#include "trackers/circle/blurred_design.h"

#include <gtest/gtest.h>

#include <cmath>

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

// The design's luma convolved with the image Gaussian through the local map, by brute force:
// a 161 x 161 grid of the sharp design over ±4 σ in pixels.
double ConvolvedLuma(const MarkerSpec& marker,
                     const Eigen::Vector2d& p,
                     const Eigen::Matrix2d& marker_from_px,
                     double sigma_px) {
  constexpr int kHalf = 80;
  const double step = 4.0 * sigma_px / kHalf;
  double sum = 0.0, weights = 0.0;
  for (int i = -kHalf; i <= kHalf; ++i) {
    for (int j = -kHalf; j <= kHalf; ++j) {
      const Eigen::Vector2d offset_px(i * step, j * step);
      const double w = std::exp(-0.5 * offset_px.squaredNorm() / (sigma_px * sigma_px));
      sum += w * Luma(*marker.ColorAt(p + marker_from_px * offset_px).color);
      weights += w;
    }
  }
  return sum / weights;
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
    const double truth = ConvolvedLuma(f, p, TiltedMap(), sigma);
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
    EXPECT_NEAR(BlurredDesign(e).At(p, TiltedMap(), sigma).luma,
                ConvolvedLuma(e, p, TiltedMap(), sigma),
                0.03)
        << p.transpose();
  }
}

// Far from an edge the blurred step is taken as sharp, but only where the blur leaves nothing
// in double precision: 5 σ outside f's rim (and far from its wedge) the black disk's tail,
// Φ(-5) (the circle's curvature moves it by σ/2ρ = 0.01 σ), still darkens the white paper;
// 12 σ and 20 σ out the paper is white, with no gradient.
TEST(BlurredDesign, IsSharpOnlyWhereTheBlurLeavesNothing) {
  const MarkerSpec f = LoadMarkerYaml("scenarios/markers/circle_f.yaml");
  const BlurredDesign design(f);
  const Eigen::Matrix2d one_mm_per_px = 0.001 * Eigen::Matrix2d::Identity();
  const Eigen::Vector2d outward(std::cos(200.0 * M_PI / 180.0), std::sin(200.0 * M_PI / 180.0));
  const double paper = Luma(f.background);
  const BlurredLuma near = design.At((0.05 + 0.005) * outward, one_mm_per_px, 1.0);
  EXPECT_NEAR(paper - near.luma, NormalCdf(-5.01), 1e-9);
  EXPECT_GT(near.gradient.norm(), 0.0);
  for (const double out_m : {0.012, 0.02}) {
    const BlurredLuma far = design.At((0.05 + out_m) * outward, one_mm_per_px, 1.0);
    EXPECT_EQ(far.luma, paper) << out_m;
    EXPECT_EQ(far.gradient, Eigen::Vector2d::Zero()) << out_m;
    EXPECT_EQ(far.d_sigma, 0.0) << out_m;
  }
}

// The gradient leaves out how each edge's direction turns along p (second order at the edge):
// within 5 % and 0.5 per metre (across the edges it reaches 150 per metre). The derivative in
// σ is exact.
TEST(BlurredDesign, GradientIsTheDerivative) {
  for (const char* kind : {"circle_e", "circle_f"}) {
    const MarkerSpec marker = LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml");
    const BlurredDesign design(marker);
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.001, 0.002),
                                     Eigen::Vector2d(0.02, -0.018),
                                     Eigen::Vector2d(0.015, 0.004)}) {
      const BlurredLuma at = design.At(p, TiltedMap(), 1.2);
      for (int axis = 0; axis < 2; ++axis) {
        const Eigen::Vector2d h = 1e-7 * Eigen::Vector2d::Unit(axis);
        const double numeric =
            (design.At(p + h, TiltedMap(), 1.2).luma - design.At(p - h, TiltedMap(), 1.2).luma) /
            2e-7;
        EXPECT_NEAR(at.gradient(axis), numeric, 0.5 + 0.05 * std::abs(numeric))
            << kind << " " << p.transpose() << " axis " << axis;
      }
      // In σ nothing is held: the derivative is exact.
      const double numeric_sigma = (design.At(p, TiltedMap(), 1.2 + 1e-6).luma -
                                    design.At(p, TiltedMap(), 1.2 - 1e-6).luma) /
                                   2e-6;
      EXPECT_NEAR(at.d_sigma, numeric_sigma, 1e-6 + 1e-5 * std::abs(numeric_sigma))
          << kind << " " << p.transpose();
    }
  }
}

}  // namespace
}  // namespace markerbench
