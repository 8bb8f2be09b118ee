// Pixels after Gaussian noise, clipping to [0, 1] (as sensors saturate, and the renderer
// clips) and 8-bit rounding: each pixel's likelihood, on which the photometric fits
// (photometric_refinement.h, design_refinement.h) compare the model with the pixels, and how
// they find the noise.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <vector>

#include "trackers/circle/normal_tables.h"
#include "trackers/circle/pixel_fit.h"

namespace markerbench {

// One channel of a pixel in a photometric fit: its 8-bit value y (0-1) against the noise-free
// model value μ, under Gaussian noise of σ_n, clipping to [0, 1] and rounding (the renderer's
// and a sensor's: a pixel reads 255 for any μ + n ≥ 254.5/255, 0 below 0.5/255). The term is
// 2 σ_n² times its negative log-likelihood, up to a constant: (y - μ)² where y is neither 0
// nor 1 (rounding left out); -2 σ_n² log Q(z) where it is, z = (254.5/255 - μ)/σ_n at white
// or (μ - 0.5/255)/σ_n at black, the chance that the noise clips it. For the normal
// equations, the residual that stands in the gradient (y - μ; σ_n λ(z) at white, -σ_n λ(z)
// at black) and the weight of ∂μ/∂θ ∂μ/∂θᵀ (1; λ (λ - z), in (0, 1)): with these, least
// squares becomes the maximum-likelihood fit of the clipped pixels. A model that compared
// them with μ would see a blurred edge between white and black sharper than it is (about
// half the noisy pixels of white paper are clipped, their mean 0.4 σ_n below it).
struct PixelTerm {
  double cost;
  double residual;
  double weight;
};
inline PixelTerm ClippedPixelTerm(double y, double mu, double noise_sigma) {
  if (y > 0.0 && y < 1.0) return {(y - mu) * (y - mu), y - mu, 1.0};
  const bool white = y >= 1.0;
  const double z = white ? (254.5 / 255.0 - mu) / noise_sigma : (mu - 0.5 / 255.0) / noise_sigma;
  const NormalTailTable::Values tail = kNormalTailTable.At(z);
  const double residual = noise_sigma * tail.mills;
  return {2.0 * noise_sigma * noise_sigma * tail.minus_log_tail,
          white ? residual : -residual,
          tail.mills * tail.mills_excess};
}

// The mean of a pixel whose noise-free value is μ after noise of σ_n and clipping to [0, 1]
// (rounding left out), and its derivative in μ, P(0 < μ + n < 1):
//   E = μ (Φ(b) - Φ(a)) + σ_n (φ(a) - φ(b)) + 1 - Φ(b),  a = -μ/σ_n, b = (1 - μ)/σ_n.
// The matched filter of blurred dots (blurred_dot_search.h) compares pixels with it.
struct ClippedMeanValue {
  double mean;
  double d_mu;
};
inline ClippedMeanValue ClippedMean(double mu, double noise_sigma) {
  const NormalCdfTable::Values a = kNormalCdfTable.At(-mu / noise_sigma);
  const NormalCdfTable::Values b = kNormalCdfTable.At((1.0 - mu) / noise_sigma);
  return {mu * (b.cdf - a.cdf) + noise_sigma * (a.density - b.density) + 1.0 - b.cdf,
          b.cdf - a.cdf};
}

// The image's noise as a model takes it: at least 8-bit rounding's (0-1 units).
double ModelNoiseSigma(double noise_sigma);

// The noise the residuals show: their RMS over the pixels modelled between 0.2 and 0.8
// (where clipping takes little of it); nullopt with fewer than 50 of them.
std::optional<double> MidRangeNoise(const std::vector<ModelledPixel>& modelled);

// The offset and gain of each of `channels` channels (levels[2c], levels[2c + 1], as the
// photometric models order them) that fit pixels listed at offset 0 and gain 1 (`modelled`,
// channel-minor), by least squares on those modelled between 0.1 and 0.9: the edges, which noise
// rarely clips, not the paper or the ink (about half of a white paper's noisy pixels read 255).
// The list is rewritten at them. A channel without two distinct such values, or whose gain comes
// out not positive, keeps offset 0 and gain 1.
void FitOffsetsAndGains(int channels,
                        Eigen::VectorXd* levels,
                        std::vector<ModelledPixel>* modelled);

// How many times FitPixelsAtTheirNoise fits again at the noise its result shows. A start off by
// more than the noise shows its misalignment as noise: on noise-free frames (8-bit rounding,
// 0.29 levels) at 0.6 m, 20 levels from the edge points' start, 118 from one 4 mm off, and each
// fit at the noise it was given cut that 5-10× (the clipping at white paper modelled too wide
// biases σ and the pose). Fitted again once, circles_a's paper frames without noise ended 0.08 mm
// off (median, 14× the bound) at a few levels; until the noise agrees, 0.015 mm (2.5×, the
// model's: from the truth 0.015 mm); at most 3 or 6 times, 0.016 mm. Under noise a first fit
// again almost always agrees (the paper's noise sweeps: one cell of 44 moved, by 0.3 %).
constexpr int kMaxNoiseRefits = 4;

// FitPixels (to `round`'s tolerance) on a model whose clipping takes the noise it is given
// (noise_sigma(), set_noise_sigma(), and Evaluate(θ, JᵀJ*, Jᵀr*, modelled*) that also lists
// each pixel's ModelledPixel), at the noise its residuals show: the model takes the noise shown at
// the start (where the edges are near), at the levels the model's LevelsShownAtStart(listed)
// gives for the pixels listed at its StartLevels() (the list rewritten at them: for the disks'
// model each channel's offset and gain that fit the edges, FitOffsetsAndGains), and the fit is
// done again, from its result's pose and σ and the levels it started from, while its own
// residuals show one more than 10 % off (kMaxNoiseRefits). A global estimate on an image of
// clipped white paper puts the noise far too low (the detector's: 0.06 for a true 0.14). A round
// that follows another starts from the noise that one showed at its result, which the model has,
// and is not measured at the start; nor is a first round given `start_levels` (a tracked
// frame's last levels, the model at the noise that frame showed): it starts from them. nullopt
// where a fit fails (a start the model cannot evaluate: FitPixels' cost not finite).
//
// Measured at the levels of a white paper and a black ink (offset 0, gain 1), the noise at the
// start was 1.06-1.13× what the result showed on the first frames of the circle tracker's speed
// benchmark (circles_a; 0.99-1.03× at the levels fitted there), and 32 % of the fits were done
// again: none now, and a fit took 4.19 evaluations with the normal equations, from 4.71
// (results/speed.md; 3.0 since σ moves along σ², pixel_fit.h).
template <class Model>
std::optional<PixelFit> FitPixelsAtTheirNoise(Model& model,
                                              const Rigid3& cam_from_marker,
                                              double sigma_px,
                                              int max_iterations,
                                              const FitRound& round,
                                              const Eigen::VectorXd* start_levels = nullptr) {
  // Whether the noise the pixels show is more than 10 % off the model's; the model then
  // takes it.
  const auto takes_the_noise_shown = [&](const std::vector<ModelledPixel>& modelled) {
    const std::optional<double> measured = MidRangeNoise(modelled);
    if (!measured || !(std::abs(*measured / model.noise_sigma() - 1.0) > 0.1)) return false;
    model.set_noise_sigma(ModelNoiseSigma(*measured));
    return true;
  };
  const double function_tolerance = round.function_tolerance();
  std::vector<ModelledPixel> modelled;
  Eigen::VectorXd levels = model.StartLevels();
  if (!round.follows_another) {
    if (start_levels && start_levels->size() == levels.size()) {
      levels = *start_levels;
    } else {
      model.Evaluate(
          PixelFitParameters(cam_from_marker, sigma_px, levels), nullptr, nullptr, &modelled);
      levels = model.LevelsShownAtStart(&modelled);
      takes_the_noise_shown(modelled);
    }
  }
  PixelFit fit = FitPixels(
      model, cam_from_marker, sigma_px, levels, max_iterations, function_tolerance, &modelled);
  for (int refit = 0; refit < kMaxNoiseRefits && takes_the_noise_shown(modelled); ++refit) {
    const int iterations = fit.iterations;
    fit = FitPixels(model,
                    fit.cam_from_marker,
                    fit.sigma_px,
                    levels,
                    max_iterations,
                    function_tolerance,
                    &modelled);
    fit.iterations += iterations;
  }
  if (!std::isfinite(fit.cost)) return std::nullopt;
  return fit;
}

// FitInRounds (pixel_fit.h) with each round's solve at the noise the last one showed:
// solve_once(cam_from_marker, σ, noise, FitRound) gives an optional Result with a
// PixelFit `fit` and the noise it showed, `noise_sigma`; `first_settles`, `later_settles` and
// `abandons` as FitInRounds'.
template <class Result, class SolveOnce>
std::optional<Result> FitInRoundsAtTheirNoise(
    const Rigid3& cam_from_marker,
    double sigma_px,
    double noise_sigma,
    int max_rounds,
    const SolveOnce& solve_once,
    const RoundSettles<Result>& first_settles = nullptr,
    const RoundSettles<Result>& later_settles = nullptr,
    const std::function<bool(const Result&)>& abandons = nullptr) {
  double noise = noise_sigma;
  return FitInRounds<Result>(
      cam_from_marker,
      sigma_px,
      max_rounds,
      [&](const Rigid3& start, double sigma, const FitRound& round) {
        std::optional<Result> solved = solve_once(start, sigma, noise, round);
        if (solved) noise = solved->noise_sigma;
        return solved;
      },
      first_settles,
      later_settles,
      abandons);
}

}  // namespace markerbench
