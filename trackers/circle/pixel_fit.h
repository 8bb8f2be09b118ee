// Levenberg-Marquardt for the photometric fits (photometric_refinement.h, design_refinement.h)
// on the normal equations, with Marquardt's diagonal scaling. A model of the pixels takes
// θ = (angle-axis (3), translation (3), blur σ in px, then its levels: an offset and a gain per
// channel, and any further levels) and provides Parameters(), StartLevels() (the levels of the
// print as specified), MinSigmaPx() (the least σ a step may take) and Evaluate(θ, JᵀJ*,
// Jᵀr*, modelled*): the cost at θ (the pixels' ClippedPixelTerm summed, Σ r² where none is
// clipped), when the pointers are given the normal equations, and when `modelled` is given each
// pixel's ModelledPixel appended to it. FitPixelsAtTheirNoise (clipped_noise.h) asks a model for
// more: its noise and the levels its pixels show at the start.
#pragma once

#include <ceres/rotation.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "core/rigid3.h"

namespace markerbench {

// A pixel (and channel) at a fit: its residual and its modelled mean.
struct ModelledPixel {
  double residual;
  double mean;
};

struct PixelFit {
  Rigid3 cam_from_marker;
  double sigma_px = 0.0;
  Eigen::VectorXd levels;  // offset and gain per channel
  int iterations = 0;
  double cost = 0.0;    // at the result (or a small step before it: FitPixels)
  Eigen::MatrixXd jtj;  // JᵀJ of the normal equations there
  // θ's rotation at the result, the chart jtj is in (cam_from_marker's angle-axis, or the
  // same rotation's other one past a half-turn)
  Eigen::Vector3d angle_axis = Eigen::Vector3d::Zero();
};

// A refinement on the pixels (photometric_refinement.h, design_refinement.h).
struct PixelRefinement {
  PixelFit fit;  // iterations over all rounds
  int pixels = 0;
  double noise_sigma = 0.0;  // the image's, 0-1, as its residuals show (the model's clipping)
};

// θ of a pose, σ and the levels (offset and gain per channel).
inline Eigen::VectorXd PixelFitParameters(const Rigid3& cam_from_marker,
                                          double sigma_px,
                                          const Eigen::VectorXd& levels) {
  Eigen::VectorXd theta(7 + levels.size());
  ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(cam_from_marker.rotation.data()),
                                   theta.data());
  theta.segment<3>(3) = cam_from_marker.translation;
  theta[6] = sigma_px;
  // Copied element by element: GCC 12 takes Eigen's packet copy of a tail for an overflow.
  std::copy(levels.data(), levels.data() + levels.size(), theta.data() + 7);
  return theta;
}

// Levels of offsets 0 and gains 1, for a model of `parameters` with an offset and a gain per
// channel.
inline Eigen::VectorXd UnitGainLevels(int parameters) {
  Eigen::VectorXd levels = Eigen::VectorXd::Zero(parameters - 7);
  for (int gain = 1; gain < levels.size(); gain += 2) levels[gain] = 1.0;
  return levels;
}

// A fit stops where a step lowers the cost by less than this fraction of it. The cost is
// about N σ_n² for N residuals, so on a fit's thousands of them this is a change of
// χ² = cost/σ_n² under one (one standard error of the pose; 0.05 on the 5,400 of the speed
// benchmark's frames). 1e-6 (Ceres's function tolerance) took 5-8 % more time, and paired
// frame by frame on the circle markers' paper sweeps it was better in none of the 144 cells
// and worse in four (sign tests, Holm; results/speed.md).
constexpr double kFunctionTolerance = 1e-5;
// The same for a first round that another follows (FitInRounds): its result only places the
// next round's pixels, and that round fits the levels and the pose again on them from there.
// On the speed benchmark's frames 0.8 evaluations with the normal equations less a frame
// (6.1 -> 5.3), full detection and tracking mode about 5 % faster; paired frame by frame on the
// circle markers' paper sweeps no cell worse (sign tests, Holm), one better (circle_f without
// noise), 4 of 14,400 frames' success changed (results/speed.md).
constexpr double kFirstRoundFunctionTolerance = 1e-4;
// A step after a taken one (damped no more than the first) predicted to lower the cost by less
// than this share of it (a χ² of 54 on 5,400 residuals) is taken without evaluating the model
// there, and ends the fit. Near the minimum the normal equations predict such a step's decrease
// well: on the speed benchmark's frames, evaluated, the steps of 1e-4 to 1e-2 of the cost gained
// 0.72-1.34 of their prediction (median 1.00), none lost. At 1e-4 it took the steady glide's
// second steps; at 1e-2 it takes full detection's second step too (the first took σ from the edge
// points' to its bound): against 1e-4, full detection 0.93× its time, tracking mode 0.89×, the
// hand-held shake 0.88×, and paired frame by frame on the circle markers' paper sweeps no cell
// worse (sign tests, Holm), one better (results/speed.md).
// A share, not a multiple of the fit's tolerance: a first round's looser one would take steps of
// a tenth of the cost so, and that (1,000× the tolerance) cost the paper's noise sweep 0.3 % in
// error and e's design fits at 3.5 m a frame's tilt (DesignRefinement's far-away tilt test).
constexpr double kUnevaluatedLastStepCostShare = 1e-2;

// σ after a step δσ of the normal equations, taken along σ²: σ² moves by 2σ δσ, its tangent's
// move at σ, and σ is held at `min_sigma` at least. A pixel averages a sharp edge over its area;
// blur adds its variance σ² to that average's, so near a sharp image the pixels change with σ²
// (∂/∂σ vanishes at σ = 0), and steps taken along σ halved σ at each evaluation from the start's
// (0.40 -> 0.16 -> 0.07 -> 0.04 on the speed benchmark's frames, whose σ's bound is 0.02); along
// σ², one step takes it there.
inline double SquaredSigmaAfterStep(double sigma, double sigma_step) {
  return sigma * sigma + 2.0 * sigma * sigma_step;
}
inline double SigmaAfterStep(double sigma, double sigma_step, double min_sigma) {
  return std::sqrt(std::max(SquaredSigmaAfterStep(sigma, sigma_step), min_sigma * min_sigma));
}

// The step δ of the damped normal equations (damped δ = -Jᵀr) for θ, σ (θ₆, now `sigma`) held
// at `min_sigma` or above after the step (SigmaAfterStep): where the free step would take σ
// below, it goes to `min_sigma` and the other parameters take their step given that move (a
// bound's active set). Clipping σ's step alone leaves them a step made for another σ: a sharp
// image's fit, whose σ goes to its bound, took 8.7 evaluations a solve so on the speed
// benchmark's frames, against 6.0.
inline Eigen::VectorXd StepWithinSigmaBound(const Eigen::MatrixXd& damped,
                                            const Eigen::VectorXd& jtr,
                                            double sigma,
                                            double min_sigma) {
  Eigen::VectorXd step = damped.ldlt().solve(-jtr);
  if (SquaredSigmaAfterStep(sigma, step[6]) >= min_sigma * min_sigma) return step;
  // The equations without σ's row and column (an index list for Eigen's indexed views takes
  // GCC 12 to a false -Wfree-nonheap-object where this is inlined).
  const int others = static_cast<int>(jtr.size()) - 1;
  const auto other = [](int i) { return i < 6 ? i : i + 1; };
  const double sigma_step = (min_sigma * min_sigma - sigma * sigma) / (2.0 * sigma);
  Eigen::MatrixXd reduced(others, others);
  Eigen::VectorXd rhs(others);
  for (int i = 0; i < others; ++i) {
    for (int j = 0; j < others; ++j) reduced(i, j) = damped(other(i), other(j));
    rhs[i] = -(jtr[other(i)] + damped(other(i), 6) * sigma_step);
  }
  const Eigen::VectorXd rest = reduced.ldlt().solve(rhs);
  for (int i = 0; i < others; ++i) step[other(i)] = rest[i];
  step[6] = sigma_step;
  return step;
}

// From a pose, σ and levels; σ kept at the model's MinSigmaPx() at least.
// Stops where a step lowers the cost by less than `function_tolerance` of it, or where the normal
// equations predict that of the next step after a taken one, damped no more than the first
// (saving the evaluation of a step that would not count); where they predict below
// kUnevaluatedLastStepCostShare of the cost, the step is taken unevaluated and the fit stops.
// The fit's cost and JᵀJ are those of its last evaluation: at the result, or one such step
// before it. With `modelled_at_result`, the pixels are listed there from that evaluation (none
// is done for them). A start the model cannot evaluate (a cost not finite, without normal
// equations: a disk whose image there is no ellipse) gives a fit at the start with that cost and no
// JᵀJ: a failed fit (FitPixelsAtTheirNoise gives none for it).
template <class Model>
PixelFit FitPixels(const Model& model,
                   const Rigid3& cam_from_marker,
                   double sigma_px,
                   const Eigen::VectorXd& levels,
                   int max_iterations,
                   double function_tolerance = kFunctionTolerance,
                   std::vector<ModelledPixel>* modelled_at_result = nullptr) {
  Eigen::VectorXd theta = PixelFitParameters(cam_from_marker, sigma_px, levels);
  Eigen::MatrixXd jtj, trial_jtj;
  Eigen::VectorXd jtr, trial_jtr;
  std::vector<ModelledPixel> trial_modelled;
  // The list for an evaluation, emptied, if the result's is asked for.
  const auto listing = [&](std::vector<ModelledPixel>* list) {
    if (!modelled_at_result) return static_cast<std::vector<ModelledPixel>*>(nullptr);
    list->clear();
    return list;
  };
  double cost = model.Evaluate(theta, &jtj, &jtr, listing(modelled_at_result));
  PixelFit fit;
  if (!std::isfinite(cost)) {
    fit.cam_from_marker = cam_from_marker;
    fit.sigma_px = theta[6];
    fit.levels = levels;
    fit.cost = cost;
    return fit;
  }
  constexpr double kStartDamping = 1e-3;
  double damping = kStartDamping;
  bool after_a_step = false;  // the last trial was taken
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Eigen::MatrixXd damped = jtj;
    damped.diagonal() += damping * jtj.diagonal();
    const Eigen::VectorXd step = StepWithinSigmaBound(damped, jtr, theta[6], model.MinSigmaPx());
    // The cost Σ r² changes by 2 Jᵀr·δ + δᵀ JᵀJ δ to second order.
    const double predicted_decrease = -(2.0 * jtr.dot(step) + step.dot(jtj * step));
    // After a taken step, damped no more than the first, the prediction decides: below the
    // tolerance the fit stops, below kUnevaluatedLastStepCostShare of the cost the step ends it.
    const bool prediction_decides = after_a_step && damping <= kStartDamping;
    if (prediction_decides && predicted_decrease < function_tolerance * cost) break;
    Eigen::VectorXd trial = theta + step;
    trial[6] = SigmaAfterStep(theta[6], step[6], model.MinSigmaPx());
    if (prediction_decides && predicted_decrease < kUnevaluatedLastStepCostShare * cost) {
      theta = trial;
      break;
    }
    // With its normal equations: most steps are taken, and then they are the next ones.
    const double trial_cost =
        model.Evaluate(trial, &trial_jtj, &trial_jtr, listing(&trial_modelled));
    ++fit.iterations;
    after_a_step = trial_cost < cost;
    if (!after_a_step) {
      damping *= 10.0;
      if (damping > 1e6) break;
      continue;
    }
    const bool converged = cost - trial_cost < function_tolerance * cost;
    theta = trial;
    cost = trial_cost;
    jtj.swap(trial_jtj);
    jtr.swap(trial_jtr);
    if (modelled_at_result) modelled_at_result->swap(trial_modelled);
    damping = std::max(damping / 10.0, 1e-9);
    if (converged) break;
  }
  ceres::AngleAxisToRotationMatrix(
      theta.data(), ceres::ColumnMajorAdapter3x3(fit.cam_from_marker.rotation.data()));
  fit.cam_from_marker.translation = theta.template segment<3>(3);
  fit.sigma_px = theta[6];
  fit.levels = theta.tail(model.Parameters() - 7);
  fit.cost = cost;
  fit.jtj = std::move(jtj);
  fit.angle_axis = theta.template head<3>();
  return fit;
}

// A solve of a fit in rounds (FitInRounds). The first of several only places the next
// round's pixels, and that round fits the levels and the pose again on them from its result:
// it stops at kFirstRoundFunctionTolerance, and a model may take fewer pixels for it; every
// later round, a fit of one round and a first round that may settle the fit (FitInRounds'
// first_settles) stop at kFunctionTolerance. A round that follows another starts from the
// noise that one's pixels showed at its result.
struct FitRound {
  bool first_of_several = false;
  bool follows_another = false;
  double function_tolerance() const {
    return first_of_several ? kFirstRoundFunctionTolerance : kFunctionTolerance;
  }
};

// How many standard errors a fit's pose lies from `start` at the image's noise σ_n (0-1): the
// Mahalanobis distance √(δᵀ C⁻¹ δ) of the move δ of θ's pose part (angle-axis, translation)
// under its covariance C = σ_n² ((JᵀJ)⁻¹)₆ₓ₆ at the fit's result (σ and the levels free):
// with JᵀJ = [[A, B], [Bᵀ, D]], A the pose's block, C⁻¹ = (A - B D⁻¹ Bᵀ)/σ_n², the Schur
// complement. The start's rotation is taken in the chart of the result's (the angle-axis
// vector of the same rotation nearest it): a marker facing the camera turns it by about π,
// where v and v (1 - 2π/|v|) are the same rotation, and a fit that crosses π ends on the other.
inline double PoseMoveInStandardErrors(const PixelFit& fit,
                                       const Rigid3& start,
                                       double noise_sigma) {
  const int parameters = static_cast<int>(fit.jtj.rows());
  Eigen::Matrix<double, 6, 1> start_pose =
      PixelFitParameters(start, fit.sigma_px, fit.levels).head<6>();
  const Eigen::Vector3d start_rotation = start_pose.head<3>();
  const double start_angle = start_rotation.norm();
  if (start_angle > 0.0) {
    const Eigen::Vector3d other = start_rotation * (1.0 - 2.0 * M_PI / start_angle);
    if ((other - fit.angle_axis).norm() < (start_rotation - fit.angle_axis).norm()) {
      start_pose.head<3>() = other;
    }
  }
  Eigen::Matrix<double, 6, 1> move;
  move << fit.angle_axis, fit.cam_from_marker.translation;
  move -= start_pose;
  const Eigen::MatrixXd& jtj = fit.jtj;
  const int others = parameters - 6;
  const Eigen::MatrixXd d_inverse_bt =
      jtj.bottomRightCorner(others, others).ldlt().solve(jtj.bottomLeftCorner(others, 6));
  const Eigen::Matrix<double, 6, 6> information =
      jtj.topLeftCorner<6, 6>() - jtj.topRightCorner(6, others) * d_inverse_bt;
  return std::sqrt(move.dot(information * move)) / noise_sigma;
}

// Whether a round settles a fit in rounds: settles(its start, its result).
template <class Result>
using RoundSettles = std::function<bool(const Rigid3&, const Result&)>;

// A fit in rounds, each on the pixels chosen at the last result (a solve ties its pixels to
// the start's edges), until the translation moves by less than 1e-4 of its length:
// solve_once(cam_from_marker, σ, FitRound) gives an optional Result with a PixelFit `fit` (a
// first round is the result only where the second fails). With `first_settles`, the first round
// is solved whole (as a last one, not FitRound::first_of_several) and is the result where it
// says so; with `later_settles`, a later round ends the fit where it says so instead; with
// `abandons`, the fit is given up (nullopt) where it says so of the first round's result. A solve
// that ends with the marker behind the camera (the plane's mirror image, FacesTheCamera) gives
// none: the rounds stop at the last result before it.
template <class Result, class SolveOnce>
std::optional<Result> FitInRounds(const Rigid3& cam_from_marker,
                                  double sigma_px,
                                  int max_rounds,
                                  const SolveOnce& solve_once,
                                  const RoundSettles<Result>& first_settles = nullptr,
                                  const RoundSettles<Result>& later_settles = nullptr,
                                  const std::function<bool(const Result&)>& abandons = nullptr) {
  const auto solve = [&](const Rigid3& start, double sigma, const FitRound& round) {
    std::optional<Result> solved = solve_once(start, sigma, round);
    if (solved && !FacesTheCamera(solved->fit.cam_from_marker)) solved.reset();
    return solved;
  };
  std::optional<Result> result =
      solve(cam_from_marker, sigma_px, FitRound{!first_settles && max_rounds > 1, false});
  if (result && first_settles && first_settles(cam_from_marker, *result)) {
    return result;
  }
  if (result && abandons && abandons(*result)) return std::nullopt;
  for (int round = 1; result && round < max_rounds; ++round) {
    std::optional<Result> next =
        solve(result->fit.cam_from_marker, result->fit.sigma_px, FitRound{false, true});
    if (!next) break;
    const Rigid3 last = result->fit.cam_from_marker;
    next->fit.iterations += result->fit.iterations;
    result = std::move(next);
    const Eigen::Vector3d& translation = result->fit.cam_from_marker.translation;
    if (later_settles ? later_settles(last, *result)
                      : (translation - last.translation).norm() < 1e-4 * translation.norm()) {
      break;
    }
  }
  return result;
}

// A fit and how much less likely it is than the best of those it was ranked with: 2 ln Λ against
// that best, on the pixels both were judged on; 0 for the best.
template <class Result>
struct RankedFit {
  Result result;
  double log_ratio = 0.0;
};

// The fit from each start by refine(start, the fits from earlier starts) (an optional Result),
// ranked best first by log_ratios(fits) (each one's 2 ln Λ against the best: 0 for it, and for a
// single fit); empty when no start gives one. The earlier fits let a refine give a start up
// early. Of fits equally likely the earlier start's comes first.
template <class Result, class Refine, class LogRatios>
std::vector<RankedFit<Result>> RankedFitsFromStarts(const std::vector<Rigid3>& starts,
                                                    const Refine& refine,
                                                    const LogRatios& log_ratios) {
  std::vector<Result> fits;
  for (const Rigid3& start : starts) {
    std::optional<Result> fit = refine(start, std::as_const(fits));
    if (fit) fits.push_back(std::move(*fit));
  }
  const std::vector<double> ratios =
      fits.size() > 1 ? log_ratios(std::as_const(fits)) : std::vector<double>(fits.size(), 0.0);
  std::vector<RankedFit<Result>> ranked;
  for (size_t i = 0; i < fits.size(); ++i) ranked.push_back({std::move(fits[i]), ratios[i]});
  std::stable_sort(
      ranked.begin(), ranked.end(), [](const RankedFit<Result>& a, const RankedFit<Result>& b) {
        return a.log_ratio < b.log_ratio;
      });
  return ranked;
}

}  // namespace markerbench
