// The likelihood of a pixel clipped and rounded to 8 bits against the normal tail it is made
// of and against finite differences, and the noise read from a fit's mid-range residuals.
#include "trackers/circle/clipped_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/rigid3.h"
#include "testing/linear_pixel_model.h"
#include "testing/unevaluable_pixel_model.h"

namespace markerbench {
namespace {

// The term is 2σ² times the pixel's negative log-likelihood up to a constant per kind of
// pixel, its residual half its derivative in -μ, its weight within the Gauss-Newton
// approximation of its second derivative; for clipped pixels, against the probability of
// clipping by quadrature and against finite differences.
TEST(ClippedPixelTerm, IsTheLikelihoodOfTheClippedRoundedPixel) {
  for (double sigma : {0.003, 0.05, 0.14, 0.55}) {
    const double step = 1e-3 * sigma;
    for (double mu : {-0.3, -0.01, 0.0, 0.04, 0.3, 0.5, 0.93, 1.0, 1.02, 1.4}) {
      SCOPED_TRACE("sigma " + std::to_string(sigma) + " mu " + std::to_string(mu));
      // Neither black nor white: the squared residual.
      const PixelTerm grey = ClippedPixelTerm(0.6, mu, sigma);
      EXPECT_DOUBLE_EQ(grey.cost, (0.6 - mu) * (0.6 - mu));
      EXPECT_DOUBLE_EQ(grey.residual, 0.6 - mu);
      EXPECT_DOUBLE_EQ(grey.weight, 1.0);
      for (const double y : {0.0, 1.0}) {
        const double threshold = y == 1.0 ? 254.5 / 255.0 : 0.5 / 255.0;
        const double clipped = y == 1.0
                                   ? 0.5 * std::erfc((threshold - mu) / (sigma * std::sqrt(2.0)))
                                   : 0.5 * std::erfc((mu - threshold) / (sigma * std::sqrt(2.0)));
        const PixelTerm term = ClippedPixelTerm(y, mu, sigma);
        const double scale = 2.0 * sigma * sigma;
        if (clipped > 1e-300) {
          EXPECT_NEAR(term.cost, -scale * std::log(clipped), 1e-6 * std::max(scale, term.cost));
        }
        const auto cost_at = [&](double m) { return ClippedPixelTerm(y, m, sigma).cost; };
        const double derivative = (cost_at(mu + step) - cost_at(mu - step)) / (2.0 * step);
        EXPECT_NEAR(term.residual, -0.5 * derivative, 1e-4 * std::max(1.0, std::abs(derivative)));
        const double second =
            (cost_at(mu + step) - 2.0 * term.cost + cost_at(mu - step)) / (step * step);
        EXPECT_NEAR(term.weight, 0.5 * second, 2e-3);
        EXPECT_GE(term.weight, 0.0);
        EXPECT_LE(term.weight, 1.0);
      }
    }
  }
}

// The clipped mean against a quadrature of the clipped normal, and its derivative against
// finite differences.
TEST(ClippedMean, IsTheMeanOfTheClippedNormal) {
  for (double sigma : {0.003, 0.05, 0.14, 0.55}) {
    for (double mu : {-0.3, -0.01, 0.0, 0.04, 0.3, 0.5, 0.93, 1.0, 1.02, 1.4}) {
      SCOPED_TRACE("sigma " + std::to_string(sigma) + " mu " + std::to_string(mu));
      // ∫ clip(x) N(x; μ, σ²) dx by the midpoint rule over ±12 σ.
      const int steps = 200000;
      const double h = 24.0 * sigma / steps;
      double quadrature = 0.0;
      for (int i = 0; i < steps; ++i) {
        const double x = mu - 12.0 * sigma + (i + 0.5) * h;
        const double z = (x - mu) / sigma;
        quadrature += std::clamp(x, 0.0, 1.0) * std::exp(-0.5 * z * z) * h;
      }
      quadrature /= sigma * std::sqrt(2.0 * M_PI);
      const ClippedMeanValue value = ClippedMean(mu, sigma);
      EXPECT_NEAR(value.mean, quadrature, 1e-7);
      const double step = 1e-4 * sigma;
      const double derivative =
          (ClippedMean(mu + step, sigma).mean - ClippedMean(mu - step, sigma).mean) / (2.0 * step);
      EXPECT_NEAR(value.d_mu, derivative, 1e-5);
    }
  }
  EXPECT_NEAR(ClippedMean(0.5, 1e-3).mean, 0.5, 1e-12);  // far from the ends: μ itself
}

TEST(MidRangeNoise, IsTheResidualsRmsBetweenTwoTenthsAndEightTenths) {
  std::vector<ModelledPixel> modelled;
  for (int i = 0; i < 49; ++i) modelled.push_back({i % 2 ? 0.1 : -0.1, 0.5});
  EXPECT_FALSE(MidRangeNoise(modelled));  // fewer than 50 in the mid-range
  modelled.push_back({0.1, 0.2});
  for (int i = 0; i < 30; ++i) modelled.push_back({0.7, i % 2 ? 0.1 : 0.9});  // left out
  ASSERT_TRUE(MidRangeNoise(modelled));
  EXPECT_NEAR(*MidRangeNoise(modelled), 0.1, 1e-12);
}

// Two channels listed at offset 0 and gain 1 (channel-minor), the pixels' values an offset and a
// gain of the modelled ones plus a residual that averages out: each channel's are found, from the
// pixels modelled between 0.1 and 0.9 alone (those beyond read as clipped, far off the line), and
// the list is rewritten at them.
TEST(FitOffsetsAndGains, FindsEachChannelsLevelsOnTheEdgesAndRewritesTheList) {
  const double offsets[] = {0.08, -0.05}, gains[] = {0.85, 1.2};
  std::vector<ModelledPixel> listed;
  for (int i = 0; i <= 100; ++i) {
    const double x = i / 100.0;
    for (int c = 0; c < 2; ++c) {
      const bool edge = x > 0.1 && x < 0.9;
      const double value = edge ? offsets[c] + gains[c] * x + 0.01 * (i % 2 ? 1 : -1) : 1.0 - c;
      listed.push_back({value - x, x});
    }
  }
  const std::vector<ModelledPixel> at_unit = listed;
  Eigen::VectorXd levels = Eigen::VectorXd::Zero(5);
  levels << 0.0, 1.0, 0.0, 1.0, 0.7;  // and a further level, untouched
  FitOffsetsAndGains(2, &levels, &listed);
  for (int c = 0; c < 2; ++c) {
    EXPECT_NEAR(levels[2 * c], offsets[c], 2e-3) << c;
    EXPECT_NEAR(levels[2 * c + 1], gains[c], 3e-3) << c;
  }
  EXPECT_EQ(levels[4], 0.7);
  ASSERT_EQ(listed.size(), at_unit.size());
  for (size_t i = 0; i < listed.size(); ++i) {
    const int c = static_cast<int>(i % 2);
    const double value = at_unit[i].residual + at_unit[i].mean;
    EXPECT_NEAR(listed[i].mean, levels[2 * c] + levels[2 * c + 1] * at_unit[i].mean, 1e-15);
    EXPECT_NEAR(listed[i].residual, value - listed[i].mean, 1e-15);
  }
}

// A channel with no spread among its edge pixels, or whose gain would not be positive (an image
// that does not show the design's contrast), keeps offset 0 and gain 1, and its list its values.
TEST(FitOffsetsAndGains, KeepsUnitLevelsWhereTheEdgesGiveNoPositiveGain) {
  std::vector<ModelledPixel> listed;
  for (int i = 0; i < 50; ++i) {
    const double x = 0.2 + 0.6 * i / 49.0;
    listed.push_back({0.3 - x, 0.5});          // channel 0: one modelled value
    listed.push_back({0.9 - 0.5 * x - x, x});  // channel 1: the values fall as x rises
  }
  const std::vector<ModelledPixel> at_unit = listed;
  Eigen::VectorXd levels(4);
  levels << 0.0, 1.0, 0.0, 1.0;
  FitOffsetsAndGains(2, &levels, &listed);
  EXPECT_EQ(levels, Eigen::Vector4d(0.0, 1.0, 0.0, 1.0));
  for (size_t i = 0; i < listed.size(); ++i) {
    EXPECT_EQ(listed[i].mean, at_unit[i].mean);
    EXPECT_NEAR(listed[i].residual, at_unit[i].residual, 1e-15);
  }
}

// 100 mid-range pixels whose residuals at the least-squares θ show a noise of 0.05.
const LinearPixelModel::Shape kNoisyPixels{100, 0.01, 0.0, 0.5, 0.05 * std::sqrt(100.0)};

// A round of its own measures the noise at its start (one evaluation without the normal
// equations) and takes it; a round that follows another starts from the noise it is given,
// and takes the one its result shows only where that is more than 10 % off (fitting again).
TEST(FitPixelsAtTheirNoise, MeasuresTheNoiseAtTheStartUnlessARoundBeforeDid) {
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  LinearPixelModel alone(kNoisyPixels, 0.02);
  FitPixelsAtTheirNoise(alone, start, 1.0, 15, FitRound{});
  EXPECT_EQ(alone.evaluations_without_normal_equations(), 1);
  EXPECT_NEAR(alone.noise_sigma(), 0.05, 0.005);

  LinearPixelModel after_a_good_round(kNoisyPixels, 0.05);
  FitPixelsAtTheirNoise(after_a_good_round, start, 1.0, 15, FitRound{false, true});
  EXPECT_EQ(after_a_good_round.evaluations_without_normal_equations(), 0);
  EXPECT_EQ(after_a_good_round.noise_sigma(), 0.05);

  LinearPixelModel after_a_bad_round(kNoisyPixels, 0.02);
  FitPixelsAtTheirNoise(after_a_bad_round, start, 1.0, 15, FitRound{false, true});
  EXPECT_EQ(after_a_bad_round.evaluations_without_normal_equations(), 0);
  EXPECT_NEAR(after_a_bad_round.noise_sigma(), 0.05, 0.005);
}

// A first round given the levels to start from (a tracked frame's last) starts from them at the
// noise the model has, and lists no pixels at the start; levels of another size are not the
// model's, and it measures its own there.
TEST(FitPixelsAtTheirNoise, StartsFromTheLevelsGivenWithoutMeasuringThem) {
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  Eigen::VectorXd levels(2);
  levels << 0.01, 0.98;
  LinearPixelModel tracked(kNoisyPixels, 0.05);
  const std::optional<PixelFit> at_start =
      FitPixelsAtTheirNoise(tracked, start, 1.0, 0, FitRound{}, &levels);
  ASSERT_TRUE(at_start.has_value());
  EXPECT_EQ(at_start->levels, levels);
  EXPECT_EQ(tracked.evaluations_without_normal_equations(), 0);

  const Eigen::VectorXd other_size = Eigen::VectorXd::Zero(4);
  LinearPixelModel other(kNoisyPixels, 0.05);
  const std::optional<PixelFit> measured =
      FitPixelsAtTheirNoise(other, start, 1.0, 0, FitRound{}, &other_size);
  ASSERT_TRUE(measured.has_value());
  EXPECT_EQ(measured->levels, other.StartLevels());
  EXPECT_EQ(other.evaluations_without_normal_equations(), 1);
}

// A start the model cannot evaluate gives no fit, for its callers to drop.
TEST(FitPixelsAtTheirNoise, GivesNoFitWhereTheStartCannotBeEvaluated) {
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  UnevaluablePixelModel model;
  EXPECT_FALSE(FitPixelsAtTheirNoise(model, start, 1.0, 15, FitRound{}).has_value());
  EXPECT_FALSE(FitPixelsAtTheirNoise(model, start, 1.0, 15, FitRound{false, true}).has_value());
}

}  // namespace
}  // namespace markerbench
