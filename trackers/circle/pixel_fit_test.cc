// Levenberg-Marquardt on the normal equations (pixel_fit.h) on a model linear in θ with σ²
// for σ (what the fit steps along), whose cost is exactly quadratic in them: the first (lightly
// damped) step lands next to the least-squares solution, σ too, and the fit stops there without
// evaluating a second step, whose predicted decrease is below the tolerance; a step held at σ's
// bound is the best given that bound.
#include "trackers/circle/pixel_fit.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "testing/linear_pixel_model.h"
#include "testing/unevaluable_pixel_model.h"

namespace markerbench {
namespace {

// r = A θ - b over 12 pixels, b off the range of A (a cost at the minimum of 1, about 10×
// what the start adds to it).
const LinearPixelModel::Shape kTwelvePixels{};

TEST(FitPixels, StopsAtTheMinimumOfAQuadraticCostWithoutASecondStep) {
  const LinearPixelModel model(kTwelvePixels);
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  const PixelFit fit = FitPixels(model, start, 1.0, model.StartLevels(), 15);
  // The start and one step: the damped step (1e-3 of the diagonal) lands within about 1e-3
  // of the minimum, and the step after it is predicted to gain below 1e-5 of the cost (it
  // was evaluated, and then counted as converged, before the prediction).
  EXPECT_EQ(fit.iterations, 1);
  EXPECT_EQ(model.evaluations(), 2);
  const Eigen::VectorXd theta = PixelFitParameters(fit.cam_from_marker, fit.sigma_px, fit.levels);
  EXPECT_LT((theta - model.solution()).norm(), 1e-3 * model.solution().norm());
  // σ from 1 to the least squares' 1.05 along σ²: a step of σ by the same δσ would have ended at
  // 1 + (1.05² - 1)/2 = 1.05125.
  EXPECT_NEAR(fit.sigma_px, 1.05, 2e-4);
}

// After a taken step, a step predicted to lower the cost by less than
// kUnevaluatedLastStepCostShare of it is taken without evaluating the model there, and ends the fit
// (its cost and JᵀJ those of the point before it); one predicted above that is evaluated. The steps
// do not depend on the misfit off the model's range, which only adds its square to the cost: the
// misfit sets the share.
TEST(FitPixels, TakesASmallLastStepWithoutEvaluatingIt) {
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  const LinearPixelModel model(kTwelvePixels);
  // The first step alone (a tolerance it meets), then the next as the fit takes it: damped by a
  // tenth of the first's damping, with its predicted decrease.
  const PixelFit first = FitPixels(model, start, 1.0, model.StartLevels(), 15, 1.0);
  ASSERT_EQ(first.iterations, 1);
  const Eigen::VectorXd theta =
      PixelFitParameters(first.cam_from_marker, first.sigma_px, first.levels);
  Eigen::MatrixXd jtj;
  Eigen::VectorXd jtr;
  const double cost = model.Evaluate(theta, &jtj, &jtr, nullptr);
  Eigen::MatrixXd damped = jtj;
  damped.diagonal() *= 1.0 + 1e-4;
  const Eigen::VectorXd step = StepWithinSigmaBound(damped, jtr, theta[6], model.MinSigmaPx());
  const double predicted = -(2.0 * jtr.dot(step) + step.dot(jtj * step));
  ASSERT_GT(predicted, 0.0);
  Eigen::VectorXd stepped = theta + step;
  stepped[6] = SigmaAfterStep(theta[6], step[6], model.MinSigmaPx());
  // The model whose cost after the first step puts the prediction at `share` of it (the misfit's
  // square was part of `cost`).
  const auto predicted_at_share = [&](double share) {
    LinearPixelModel::Shape shape = kTwelvePixels;
    shape.misfit =
        std::sqrt(predicted / share - (cost - kTwelvePixels.misfit * kTwelvePixels.misfit));
    return shape;
  };
  // At 0.3 of the share: taken unevaluated, the start and the first step evaluated.
  const LinearPixelModel unevaluated(predicted_at_share(0.3 * kUnevaluatedLastStepCostShare));
  const PixelFit fit = FitPixels(unevaluated, start, 1.0, model.StartLevels(), 15);
  EXPECT_EQ(unevaluated.evaluations(), 2);
  EXPECT_EQ(fit.iterations, 1);
  const Eigen::VectorXd result = PixelFitParameters(fit.cam_from_marker, fit.sigma_px, fit.levels);
  EXPECT_LT((result - stepped).norm(), 1e-9);
  EXPECT_LT((result - model.solution()).norm(), 0.1 * (theta - model.solution()).norm());
  EXPECT_NEAR(fit.cost, predicted / (0.3 * kUnevaluatedLastStepCostShare), 1e-9 * fit.cost);
  EXPECT_LT((fit.jtj - jtj).norm(), 1e-9 * jtj.norm());
  // At 3 times it: evaluated, under a first round's looser tolerance too (a share of the cost,
  // not a multiple of the tolerance).
  for (const double tolerance : {kFunctionTolerance, kFirstRoundFunctionTolerance}) {
    const LinearPixelModel evaluated(predicted_at_share(3.0 * kUnevaluatedLastStepCostShare));
    EXPECT_GE(FitPixels(evaluated, start, 1.0, model.StartLevels(), 15, tolerance).iterations, 2);
    EXPECT_GE(evaluated.evaluations(), 3);
  }
}

// A start the model cannot evaluate (a disk whose image there is no ellipse) is a failed fit
// at the start, with its infinite cost, and no step is taken from it (there were none to solve
// for: before, the step read JᵀJ of no size, and crashed on the negative set under heavy blur).
TEST(FitPixels, GivesAFailedFitWhereTheStartCannotBeEvaluated) {
  const UnevaluablePixelModel model;
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  const PixelFit fit = FitPixels(model, start, 1.0, UnitGainLevels(9), 15);
  EXPECT_EQ(model.evaluations, 1);
  EXPECT_EQ(fit.iterations, 0);
  EXPECT_FALSE(std::isfinite(fit.cost));
  EXPECT_EQ(fit.jtj.size(), 0);
  EXPECT_EQ(fit.cam_from_marker.translation, start.translation);
  EXPECT_EQ(fit.levels, UnitGainLevels(9));
}

// A step that would take σ (θ₆) below its bound takes it to the bound, and the other
// parameters take the step that minimises the quadratic model given that move: its gradient
// in them vanishes. A step that stays above the bound is the free one. σ moves along σ²
// (SigmaAfterStep): the equations' δσ moves σ² by 2σ δσ.
TEST(FitPixels, StepsWithinTheSigmaBound) {
  const LinearPixelModel model(kTwelvePixels);
  Eigen::MatrixXd jtj;
  Eigen::VectorXd jtr;
  Eigen::VectorXd theta = model.solution();
  theta[6] = 0.6;  // the least squares' σ is 1.05: the free step raises σ² by 1.05² - 0.6²
  model.Evaluate(theta, &jtj, &jtr, nullptr);
  const Eigen::VectorXd free = jtj.ldlt().solve(-jtr);
  EXPECT_NEAR(SigmaAfterStep(theta[6], free[6], 0.2), 1.05, 1e-9);
  EXPECT_LT((StepWithinSigmaBound(jtj, jtr, theta[6], 0.2) - free).norm(), 1e-12);
  // Now from σ = 1.5 with the bound at 1.2: the free step would end at 1.05.
  theta[6] = 1.5;
  model.Evaluate(theta, &jtj, &jtr, nullptr);
  const Eigen::VectorXd step = StepWithinSigmaBound(jtj, jtr, theta[6], 1.2);
  EXPECT_NEAR(SigmaAfterStep(theta[6], step[6], 1e-3), 1.2, 1e-12);
  Eigen::VectorXd gradient = jtj * step + jtr;  // the quadratic model's, halved
  gradient[6] = 0.0;
  EXPECT_LT(gradient.norm(), 1e-9 * jtr.norm());
}

// σ after a step: σ² moves by 2σ δσ, and σ stops at its bound.
TEST(FitPixels, MovesSigmaAlongItsSquare) {
  EXPECT_NEAR(SigmaAfterStep(0.4, -0.1, 0.02), std::sqrt(0.16 - 0.08), 1e-15);
  EXPECT_NEAR(SigmaAfterStep(2.0, 0.5, 0.02), std::sqrt(4.0 + 2.0), 1e-15);
  EXPECT_EQ(SigmaAfterStep(0.4, -0.3, 0.02), 0.02);
}

// The pixels listed at the result are those of the result (its step's evaluation), not the
// start's: the same as the model lists at the fit's θ. A list given non-empty is replaced.
TEST(FitPixels, ListsThePixelsAtItsResult) {
  const LinearPixelModel model(kTwelvePixels);
  Rigid3 start;
  start.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  std::vector<ModelledPixel> listed(3, ModelledPixel{1.0, 1.0});
  const PixelFit fit =
      FitPixels(model, start, 1.0, model.StartLevels(), 15, kFunctionTolerance, &listed);
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
  model.Evaluate(PixelFitParameters(start, 1.0, model.StartLevels()), nullptr, nullptr, &at_start);
  ASSERT_EQ(at_start.size(), listed.size());
  double largest_move = 0.0;
  for (size_t i = 0; i < listed.size(); ++i) {
    largest_move = std::max(largest_move, std::abs(listed[i].mean - at_start[i].mean));
  }
  EXPECT_GT(largest_move, 1e-3);
}

// What a round of the FitInRounds tests gives: its fit alone.
struct Solved {
  PixelFit fit;
};

// 0.5 m in front of the camera, facing it: the FitInRounds tests' start.
const Rigid3 kFacing(Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal(), Eigen::Vector3d(0.0, 0.0, 0.5));

// A round of the FitInRounds tests that moves the marker 1 mm sideways.
std::optional<Solved> MovedSideways(const Rigid3& start, double sigma_px) {
  Solved solved;
  solved.fit.cam_from_marker = start;
  solved.fit.cam_from_marker.translation.x() += 1e-3;
  solved.fit.sigma_px = sigma_px;
  return solved;
}

// Only the first of several rounds is solved as one (FitRound::first_of_several: to the looser
// tolerance, the next round fitting again from its result); every later round, and a fit of
// one round, to the fit's own tolerance. Every round but the first follows another.
TEST(FitInRounds, SolvesOnlyAFirstRoundThatAnotherFollowsToTheLooserTolerance) {
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
  const Rigid3 start = kFacing;
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

// With first_settles, the first round is solved whole (to the fit's own tolerance) and is the
// result where first_settles, given the start and that round's result, says so; where it does
// not, the rounds go on as without it.
TEST(FitInRounds, StopsAfterAWholeFirstRoundThatSettles) {
  std::vector<double> tolerances;
  const auto solve_once = [&](const Rigid3& start, double sigma_px, const FitRound& round) {
    tolerances.push_back(round.function_tolerance());
    return MovedSideways(start, sigma_px);
  };
  const Rigid3 start = kFacing;
  std::vector<Eigen::Vector3d> judged;  // the start's and the result's translations
  bool settles = true;
  const RoundSettles<Solved> first_settles = [&](const Rigid3& from, const Solved& first) {
    judged = {from.translation, first.fit.cam_from_marker.translation};
    return settles;
  };
  std::optional<Solved> result = FitInRounds<Solved>(start, 1.0, 3, solve_once, first_settles);
  ASSERT_TRUE(result);
  EXPECT_EQ(tolerances, std::vector<double>{kFunctionTolerance});
  EXPECT_NEAR(result->fit.cam_from_marker.translation.x(), 1e-3, 1e-15);
  ASSERT_EQ(judged.size(), 2u);
  EXPECT_EQ(judged[0], start.translation);
  EXPECT_EQ(judged[1], result->fit.cam_from_marker.translation);
  tolerances.clear();
  settles = false;
  result = FitInRounds<Solved>(start, 1.0, 3, solve_once, first_settles);
  ASSERT_TRUE(result);
  EXPECT_EQ(tolerances, std::vector<double>(3, kFunctionTolerance));
  EXPECT_NEAR(result->fit.cam_from_marker.translation.x(), 3e-3, 1e-15);
}

// With later_settles, a round after the first ends the fit where later_settles, given that
// round's start (the last result) and its result, says so, whatever the translation moved;
// and only there: a round that moved the translation by less than 1e-4 of its length goes on.
TEST(FitInRounds, StopsAfterALaterRoundThatSettles) {
  int solves = 0;
  // Each solve moves the marker 1 mm sideways in its first round, then 1 µm (2e-6 of 0.5 m).
  const auto solve_once = [&](const Rigid3& start, double sigma_px, const FitRound&) {
    Solved solved;
    solved.fit.cam_from_marker = start;
    solved.fit.cam_from_marker.translation.x() += ++solves == 1 ? 1e-3 : 1e-6;
    solved.fit.sigma_px = sigma_px;
    return std::optional<Solved>(solved);
  };
  const Rigid3 start = kFacing;
  std::vector<std::pair<double, double>> judged;  // each later round's start and result, x
  int settling_round = 2;                         // the round (0 the first) that settles
  const RoundSettles<Solved> later_settles = [&](const Rigid3& from, const Solved& round) {
    judged.emplace_back(from.translation.x(), round.fit.cam_from_marker.translation.x());
    return solves - 1 == settling_round;
  };
  std::optional<Solved> result =
      FitInRounds<Solved>(start, 1.0, 5, solve_once, nullptr, later_settles);
  ASSERT_TRUE(result);
  EXPECT_EQ(solves, 3);
  EXPECT_NEAR(result->fit.cam_from_marker.translation.x(), 1e-3 + 2e-6, 1e-15);
  ASSERT_EQ(judged.size(), 2u);
  EXPECT_NEAR(judged[0].first, 1e-3, 1e-15);
  EXPECT_NEAR(judged[0].second, 1e-3 + 1e-6, 1e-15);
  EXPECT_NEAR(judged[1].first, 1e-3 + 1e-6, 1e-15);
  // Without it, the translation's move of 2e-6 of its length ends the fit after the second.
  solves = 0;
  result = FitInRounds<Solved>(start, 1.0, 5, solve_once);
  ASSERT_TRUE(result);
  EXPECT_EQ(solves, 2);
  // A later round that never settles runs to max_rounds.
  solves = 0;
  settling_round = 10;
  result = FitInRounds<Solved>(start, 1.0, 5, solve_once, nullptr, later_settles);
  ASSERT_TRUE(result);
  EXPECT_EQ(solves, 5);
}

// With abandons, the fit ends with no result after its first round where abandons, given that
// round's result, says so; where it does not, the rounds go on as without it.
TEST(FitInRounds, GivesUpWhereTheFirstRoundSaysSo) {
  int solves = 0;
  const auto solve_once = [&](const Rigid3& start, double sigma_px, const FitRound&) {
    ++solves;
    return MovedSideways(start, sigma_px);
  };
  const Rigid3 start = kFacing;
  std::vector<double> judged;  // the x of each result abandons was given
  bool gives_up = true;
  const std::function<bool(const Solved&)> abandons = [&](const Solved& first) {
    judged.push_back(first.fit.cam_from_marker.translation.x());
    return gives_up;
  };
  EXPECT_FALSE(FitInRounds<Solved>(start, 1.0, 3, solve_once, nullptr, nullptr, abandons));
  EXPECT_EQ(solves, 1);
  ASSERT_EQ(judged.size(), 1u);
  EXPECT_NEAR(judged[0], 1e-3, 1e-15);
  solves = 0;
  judged.clear();
  gives_up = false;
  const std::optional<Solved> result =
      FitInRounds<Solved>(start, 1.0, 3, solve_once, nullptr, nullptr, abandons);
  ASSERT_TRUE(result);
  EXPECT_EQ(solves, 3);
  EXPECT_EQ(judged.size(), 1u);
  EXPECT_NEAR(result->fit.cam_from_marker.translation.x(), 3e-3, 1e-15);
}

// RankedFitsFromStarts refines each start in turn, handing it the fits of the earlier starts
// that gave one (a start that gives none is left out), and ranks them by the 2 ln Λ that
// log_ratios gives each, best first, the earlier start first among equals; a single fit is not
// judged.
TEST(RankedFitsFromStarts, RefinesEachStartWithTheEarlierFitsAndRanksThemBestFirst) {
  std::vector<Rigid3> starts(4, kFacing);
  for (size_t i = 0; i < starts.size(); ++i) starts[i].translation.y() = static_cast<double>(i);
  std::vector<size_t> earlier_counts;
  const auto refine = [&](const Rigid3& start, const std::vector<Solved>& earlier) {
    earlier_counts.push_back(earlier.size());
    // The second start gives no fit.
    return start.translation.y() == 1.0 ? std::nullopt : MovedSideways(start, 1.0);
  };
  std::vector<double> offered;  // the y of each fit log_ratios was offered
  const auto log_ratios = [&](const std::vector<Solved>& fits) {
    for (const Solved& fit : fits) offered.push_back(fit.fit.cam_from_marker.translation.y());
    return fits.size() == 3 ? std::vector<double>{2.5, 0.0, 2.5}
                            : std::vector<double>(fits.size(), 7.0);
  };
  const std::vector<RankedFit<Solved>> ranked =
      RankedFitsFromStarts<Solved>(starts, refine, log_ratios);
  EXPECT_EQ(earlier_counts, (std::vector<size_t>{0, 1, 1, 2}));
  EXPECT_EQ(offered, (std::vector<double>{0.0, 2.0, 3.0}));
  ASSERT_EQ(ranked.size(), 3u);
  // The fits of the starts at y 2, 0 and 3, each moved sideways by 1e-3.
  const std::vector<double> ys = {2.0, 0.0, 3.0}, ratios = {0.0, 2.5, 2.5};
  for (size_t i = 0; i < ranked.size(); ++i) {
    EXPECT_EQ(ranked[i].result.fit.cam_from_marker.translation.y(), ys[i]) << i;
    EXPECT_EQ(ranked[i].result.fit.cam_from_marker.translation.x(), 1e-3) << i;
    EXPECT_EQ(ranked[i].log_ratio, ratios[i]) << i;
  }
  // One start: its fit, with no judging; none gives a fit: none, and nothing judged.
  offered.clear();
  const std::vector<RankedFit<Solved>> one =
      RankedFitsFromStarts<Solved>({starts[3]}, refine, log_ratios);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].log_ratio, 0.0);
  const auto none = [](const Rigid3&, const std::vector<Solved>&) {
    return std::optional<Solved>();
  };
  EXPECT_TRUE(RankedFitsFromStarts<Solved>(starts, none, log_ratios).empty());
  EXPECT_TRUE(offered.empty());
}

// The pose's move in standard errors against closed forms: with the pose's normal equations
// apart from σ's and the levels', √(Σ JᵀJ_ii δ_i²)/σ_n; with a pose parameter tied to σ
// (JᵀJ [[a, b], [b, c]] on them), σ free, the parameter's information is a - b²/c.
TEST(PoseMoveInStandardErrors, MatchesClosedForms) {
  PixelFit fit;
  fit.cam_from_marker.rotation =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()).toRotationMatrix();
  fit.angle_axis = Eigen::Vector3d(0.5, 0.0, 0.0);
  fit.cam_from_marker.translation = Eigen::Vector3d(0.01, -0.02, 0.6);
  fit.sigma_px = 0.8;
  fit.levels = Eigen::Vector2d(0.1, 0.9);
  fit.jtj = Eigen::MatrixXd::Identity(9, 9);
  const Eigen::Matrix<double, 6, 1> information =
      (Eigen::Matrix<double, 6, 1>() << 4e6, 9e6, 1e6, 2.5e7, 1.6e7, 4e5).finished();
  fit.jtj.topLeftCorner<6, 6>() = information.asDiagonal();
  const double noise = 0.05;
  Rigid3 start = fit.cam_from_marker;
  start.translation += Eigen::Vector3d(2e-4, -1e-4, 3e-3);
  const double translation_only =
      std::sqrt(2.5e7 * 2e-4 * 2e-4 + 1.6e7 * 1e-4 * 1e-4 + 4e5 * 3e-3 * 3e-3) / noise;
  EXPECT_NEAR(PoseMoveInStandardErrors(fit, start, noise), translation_only, 1e-9);
  // A rotation of 1e-4 rad about the x axis: the angle-axis's first component.
  start = fit.cam_from_marker;
  start.rotation = Eigen::AngleAxisd(0.5 - 1e-4, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_NEAR(PoseMoveInStandardErrors(fit, start, noise), std::sqrt(4e6) * 1e-4 / noise, 1e-6);
  // t_z tied to σ.
  fit.jtj(5, 6) = fit.jtj(6, 5) = 600.0;  // c = 1
  start = fit.cam_from_marker;
  start.translation.z() += 3e-3;
  EXPECT_NEAR(PoseMoveInStandardErrors(fit, start, noise),
              std::sqrt((4e5 - 600.0 * 600.0 / 1.0) * 3e-3 * 3e-3) / noise,
              1e-9);
}

// A marker facing the camera is turned by about π: a fit may cross it (its angle-axis then
// longer than π) or start beyond it (the start's, at most π, pointing the other way), and the
// move is still the small rotation between them.
TEST(PoseMoveInStandardErrors, TakesTheStartInTheResultsChartAcrossAHalfTurn) {
  PixelFit fit;
  fit.cam_from_marker.translation = Eigen::Vector3d(0.01, -0.02, 0.6);
  fit.sigma_px = 0.8;
  fit.levels = Eigen::Vector2d(0.1, 0.9);
  fit.jtj = Eigen::MatrixXd::Identity(9, 9);
  fit.jtj(0, 0) = 4e6;
  const double noise = 0.05;
  const auto half_turn_and = [](double angle) {
    return Eigen::AngleAxisd(M_PI + angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
  };
  Rigid3 start = fit.cam_from_marker;
  for (const double start_past_half_turn : {-1e-4, 1e-4}) {
    for (const double result_past_half_turn : {-1e-4, 1e-4}) {
      fit.angle_axis = Eigen::Vector3d(M_PI + result_past_half_turn, 0.0, 0.0);
      fit.cam_from_marker.rotation = half_turn_and(result_past_half_turn);
      start.rotation = half_turn_and(start_past_half_turn);
      EXPECT_NEAR(PoseMoveInStandardErrors(fit, start, noise),
                  std::sqrt(4e6) * std::abs(result_past_half_turn - start_past_half_turn) / noise,
                  1e-6)
          << start_past_half_turn << " " << result_past_half_turn;
    }
  }
}

}  // namespace
}  // namespace markerbench
