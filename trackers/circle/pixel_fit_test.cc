// Levenberg-Marquardt on the normal equations (pixel_fit.h) on a model linear in θ, whose
// cost is exactly quadratic: the first (lightly damped) step lands next to the least-squares
// solution, and the fit stops there without evaluating a second step, whose predicted
// decrease is below the tolerance.
#include "trackers/circle/pixel_fit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "testing/linear_pixel_model.h"

namespace markerbench {
namespace {

// r = A θ - b over 12 pixels, b off the range of A (a cost at the minimum of 1, about 10×
// what the start adds to it).
const LinearPixelModel::Shape kTwelvePixels{};

TEST(FitPixels, StopsAtTheMinimumOfAQuadraticCostWithoutASecondStep) {
  const LinearPixelModel model(kTwelvePixels);
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  const PixelFit fit = FitPixels(model, start, 1.0, 15);
  // The start and one step: the damped step (1e-3 of the diagonal) lands within about 1e-3
  // of the minimum, and the step after it is predicted to gain below 1e-5 of the cost (it
  // was evaluated, and then counted as converged, before the prediction).
  EXPECT_EQ(fit.iterations, 1);
  EXPECT_EQ(model.evaluations(), 2);
  const Eigen::VectorXd theta = PixelFitParameters(fit.cam_from_marker, fit.sigma_px, fit.levels);
  EXPECT_LT((theta - model.solution()).norm(), 1e-3 * model.solution().norm());
}

// The pixels listed at the result are those of the result (its step's evaluation), not the
// start's: the same as the model lists at the fit's θ. A list given non-empty is replaced.
TEST(FitPixels, ListsThePixelsAtItsResult) {
  const LinearPixelModel model(kTwelvePixels);
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  std::vector<ModelledPixel> listed(3, ModelledPixel{1.0, 1.0});
  const PixelFit fit = FitPixels(model, start, 1.0, 15, kFunctionTolerance, &listed);
  std::vector<ModelledPixel> at_result;
  model.Evaluate(PixelFitParameters(fit.cam_from_marker, fit.sigma_px, fit.levels),
                 nullptr,
                 nullptr,
                 &at_result);
  ASSERT_EQ(listed.size(), at_result.size());
  for (size_t i = 0; i < listed.size(); ++i) {
    EXPECT_NEAR(listed[i].residual, at_result[i].residual, 1e-12) << "pixel " << i;
    EXPECT_NEAR(listed[i].mean, at_result[i].mean, 1e-12) << "pixel " << i;
  }
  // The start's differ: the fit moved the means by more than 1e-3.
  std::vector<ModelledPixel> at_start;
  model.Evaluate(
      PixelFitParameters(start, 1.0, StartLevels(model.Parameters())), nullptr, nullptr, &at_start);
  ASSERT_EQ(at_start.size(), listed.size());
  double largest_move = 0.0;
  for (size_t i = 0; i < listed.size(); ++i) {
    largest_move = std::max(largest_move, std::abs(listed[i].mean - at_start[i].mean));
  }
  EXPECT_GT(largest_move, 1e-3);
}

// Only the first of several rounds is solved as one (FitRound::first_of_several: to the looser
// tolerance, the next round fitting again from its result); every later round, and a fit of
// one round, to the fit's own tolerance. Every round but the first follows another.
TEST(FitInRounds, SolvesOnlyAFirstRoundThatAnotherFollowsToTheLooserTolerance) {
  struct Solved {
    PixelFit fit;
  };
  std::vector<bool> firsts, follows;
  std::vector<double> tolerances;
  // Each solve moves the marker 1 mm sideways in its first two rounds, then not at all.
  const auto solve_once = [&](const Rigid3& start, double sigma_px, const FitRound& round) {
    firsts.push_back(round.first_of_several);
    follows.push_back(round.follows_another);
    tolerances.push_back(round.function_tolerance());
    Solved solved;
    solved.fit.cam_from_marker = start;
    if (tolerances.size() <= 2) solved.fit.cam_from_marker.translation.x() += 1e-3;
    solved.fit.sigma_px = sigma_px;
    return std::optional<Solved>(solved);
  };
  Rigid3 start;  // 0.5 m in front of the camera, facing it
  start.rotation = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  ASSERT_TRUE(FitInRounds<Solved>(start, 1.0, 5, solve_once));
  EXPECT_EQ(firsts, (std::vector<bool>{true, false, false}));
  EXPECT_EQ(follows, (std::vector<bool>{false, true, true}));
  EXPECT_EQ(
      tolerances,
      (std::vector<double>{kFirstRoundFunctionTolerance, kFunctionTolerance, kFunctionTolerance}));
  firsts.clear();
  follows.clear();
  tolerances.clear();
  ASSERT_TRUE(FitInRounds<Solved>(start, 1.0, 1, solve_once));
  EXPECT_EQ(firsts, std::vector<bool>{false});
  EXPECT_EQ(follows, std::vector<bool>{false});
  EXPECT_EQ(tolerances, std::vector<double>{kFunctionTolerance});
}

}  // namespace
}  // namespace markerbench
