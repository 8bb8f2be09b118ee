// The physical limit of one frame: the Cramér-Rao lower bound on the camera pose that the
// rendered image allows (crlb.md).
//
// Model: the image is I(θ) + n, I the renderer's noise-free linear image (exact pixel-area
// average, Gaussian and motion blur, lighting gain), n Gaussian, independent from pixel to
// pixel, with the frame's noise variance plus the 8-bit quantisation variance 1/(12·255²) in
// each channel. A pixel's channels are independent but for their rounding: where the noise
// is below a level, channels of equal values round alike (EqualChannelsRoundingCovariance; a
// grey design rendered in RGB is one image three times, and without noise its rounding is one
// error, not three), and F takes each pixel's channels jointly. (Channels of unequal values
// are taken as rounding independently, though within a small fraction of a level they do
// not quite: the bound does not count the information such near coincidences would add.)
// The camera's response e = g(v) (Degradations::gamma) comes after the noise and before the
// rounding: being invertible it changes F only through the rounding, whose variance in v is
// 1/(12·255²·g'(v)²), so F is then summed pixel by pixel with the noise-free lit values v.
// Clipping and JPEG are left out. θ = (ω, t) with R = exp([ω]×)·R0: a rotation increment in the
// camera frame (radians) and the translation (metres).
//
// ∇θI is exact, not a finite difference: the colour jump across each printed edge times the
// edge's normal image velocity, integrated along the edge (boundary_pieces.h) and assigned to
// the pixels each piece crosses, then blurred like the image.
//
// A moving camera (FrameRequest::cam_from_marker_at): θ moves the truth pose T0 and the
// path with it, T(τ) = D(τ)·exp(θ)·T0 with D(τ) = T(τ)·T0⁻¹ the camera's own motion, taken as
// known. Each row is the mean over its exposure (its own, with a rolling shutter) of the
// still images along the path, and so is ∇θI. Knowing D can only lower the bound, so it
// bounds a tracker that does not know the motion too.
//
// Fisher information
// F = Σ_pixels ∇θIᵀ Σ⁻¹ ∇θI (the pixel's channels × θ; Σ their noise's covariance, σ² I
// where the noise is more than a level), cov(θ) ≥ F⁻¹, and the camera centre C = -Rᵀt has
// cov(C) ≥ J F⁻¹ Jᵀ.
#pragma once

#include <Eigen/Core>

#include "renderer/render_frame.h"

namespace markerbench {

// The variance of 8-bit rounding in [0, 1] units: the noise floor of a noise-free frame.
inline constexpr double kQuantisationVariance = 1.0 / (12.0 * 255.0 * 255.0);

// The covariance (8-bit levels²) of the rounding errors of two channels of a pixel with equal
// noise-free values, each with independent Gaussian noise of s = `noise_levels`, over values
// uniform within a level: from the sawtooth's Fourier series, Σ_k≥1 exp(-4π²k²s²) / 2π²k²;
// 1/12, the rounding's variance, without noise (the channels round alike), 2.6e-6 at s = ½.
double EqualChannelsRoundingCovariance(double noise_levels);

struct CrlbOptions {
  // Longest edge piece in the image (px). Pieces are split at pixel borders, so the bound
  // changes by less than 0.1 % when this is halved (tested).
  double max_piece_px = 0.25;
  // A moving camera's exposure is sampled at times this far apart in image motion (px); the
  // bound changes by less than 1 % when this is halved (tested).
  double max_motion_step_px = 0.25;
};

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct PoseBound {
  Matrix6d fisher = Matrix6d::Zero();  // θ = (ω, t)
  // False when F is singular (the marker is not in view, or a pose direction leaves the
  // image unchanged); every bound below is then +infinity.
  bool observable = false;
  Eigen::Matrix3d position_covariance = Eigen::Matrix3d::Zero();  // of C, m²
  Eigen::Matrix3d rotation_covariance = Eigen::Matrix3d::Zero();  // of ω, rad²
  double position_rms_m = 0.0;                                    // sqrt(trace cov(C))
  double position_median_m = 0.0;                                 // median |e| for e ~ N(0, cov(C))
  double rotation_rms_deg = 0.0;                                  // sqrt(trace cov(ω))
  double rotation_median_deg = 0.0;
  // The eigenvalues of cov(C), ascending (m²): with ProbabilityNormWithin, the chance that an
  // efficient estimator's camera-centre error is within a given distance.
  Eigen::Vector3d position_variances_m2 = Eigen::Vector3d::Zero();
};

// F for the frame `request` describes (its noise seed is not used).
Matrix6d PoseFisherInformation(const FrameRequest& request, const CrlbOptions& options = {});

PoseBound PoseCrlb(const FrameRequest& request, const CrlbOptions& options = {});

// The median of |e| for e ~ N(0, covariance) in 3-D (a quadrature, relative error < 1e-6):
// what an efficient estimator's median error is compared with (crlb.md).
double MedianGaussianNorm(const Eigen::Matrix3d& covariance);

// P(|e| <= r) for e ~ N(0, diag(variances)) in 3-D, variances >= 0 in any order (a
// quadrature, absolute error < 1e-6); 0 when a variance is +inf.
double ProbabilityNormWithin(double r, const Eigen::Vector3d& variances);

}  // namespace markerbench
