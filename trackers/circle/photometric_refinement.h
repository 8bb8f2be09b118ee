// Direct ("photometric") refinement of a circle marker's pose on the pixels around its edges
// (issue 21). The printed design is the background plus one colour step per disk (its colour
// minus what lies under it), so the design blurred by a Gaussian of σ is, at a pixel u,
//   I_c(u) = offset_c + gain_c (base_c + Σ_k jump_kc G(ρ_k/σ, -d_k(u)/σ)),
// summed over the disks whose edge is within reach of u, with G the exact blurred-disk profile
// averaged over the pixel's area (blurred_disk_profile.h: σ is the blur alone, the pixel's area
// apart), d_k the pixel's signed distance to the disk's projected edge
// (from its edge point nearest the pixel, to second order along the edge, with the normal and
// curvature there at the start pose: OffsetFromCurvedEdge), ρ_k the edge's radius of
// curvature there (the osculating disk: a tilted disk's ellipse has the blurred edge of that
// disk to first order, its midpoint shifted by σ²/2ρ) and base the background plus the steps
// of the disks u lies deep inside. A disk blurred by a good part of its size (σ at
// least 0.25 of its semi-minor axis) is modelled whole instead, its exact blurred ellipse
// (blurred_ellipse.h) on every pixel of its image and within reach of it. Blur is linear, so
// the sum holds however far the blurred edges overlap. Each pixel is compared with the model
// as the noise leaves it, clipped to [0, 1] and rounded (clipped_noise.h: the paper is white,
// so about half its noisy pixels read 255), on its likelihood. Pose, σ and each channel's gain
// and offset are fitted by Levenberg-Marquardt on every channel of every pixel within 2σ + 1
// px of an edge. Under Gaussian pixel noise this is the maximum-likelihood pose; the edge
// points (one position per ray, kept from a whole profile) lose part of that information.
#pragma once

#include <optional>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"
#include "trackers/circle/pixel_fit.h"

namespace markerbench {

struct PhotometricOptions {
  // Pixels within this many σ, plus band_px, of an edge take part (`pixel_band_sigmas`). A
  // blurred step's pixels beyond 2σ hold erfc(2) = 0.5 % of its position's information (a few %
  // of σ's): at the truth of rendered frames the pose's standard errors are within 2.5 % of a
  // band twice as wide's (photometric_refinement_test.cc). Against 3: 6-9 % less time at 0.6 m,
  // 11-14 % at 1 m and blur σ 2, 26-29 % at σ 8; paired on the circle markers' paper sweeps no
  // cell's errors differed by a sign test after Holm, and over circles_a's blur sweep they grew
  // 0.9 % (geometric mean, 95 % interval -0.4..+2.1 %; results/speed.md).
  double band_sigmas = 2.0;
  // The band's margin (`pixel_band_px`). Half a pixel (its half-width, beyond which a pixel's
  // area meets the blurred edge only past band_sigmas) against 1: full detection 11 % less time
  // at 0.6 m, tracking mode 9 %, blur σ 2 5 %, but paired on circles_a's paper blur sweep the
  // errors at blur σ 0 and 1 grew 6 and 4 % (95 % intervals 1.6-10.8 and 0.1-8.3 %), elsewhere
  // within noise; at the truth the pose's standard errors were up to 4 % above a band twice as
  // wide's, from 2.5 % (results/speed.md). Without a margin the distance sweep's errors grew 3.5 %.
  double band_px = 1.0;
  // The same for the first of several rounds (FitRound, pixel_fit.h), whose result only places
  // the next round's pixels. Against 2: 8-9 % less time for full detection at 0.6 m, 3-5 % in
  // tracking mode, 6-9 % at blur σ 8; paired on the circle markers' paper sweeps no cell's
  // errors differed by a sign test after Holm, the geometric mean of the error ratios
  // 0.999-1.002 per sweep and marker, 1.005 on circles_a's blur sweep (95 % interval
  // 1.000-1.010; results/speed.md).
  double first_round_band_sigmas = 1.0;
  // A tilted disk's image is an ellipse, modelled at each pixel as the disk osculating its
  // edge at the pixel's foot point; deep inside, where the blur reaches the far edges, that
  // fails (on circles_a at 1 m and blur 10: the pose off by 130 mm from the truth without
  // noise, 23 mm at 0.3; 0.5 gives 63 mm). Pixels deeper inside a disk than this fraction of
  // its edge's radius of curvature are left out.
  double max_depth_per_curvature = 0.3;
  // Beyond a blur of the largest disk's radius in pixels the design is one blob, and the
  // pose stays the edge points' (the paper's blur sweep reaches σ ≈ 0.55 R). This also bounds
  // the pixels modelled, whose band grows with σ.
  double max_blur_per_radius = 1.0;
  // From a blur of this fraction of a disk's semi-minor axis in pixels on, the disk is
  // modelled whole and exactly (blurred_ellipse.h) on every pixel of its image and within the
  // band around it, instead of by its osculating disks (on circles_a at 1 m, paired on the
  // paper's frames: 0.35 against 0.5 better at blur σ 7-9, success 93/89/82 -> 95/94/89 %;
  // 0.25 against 0.35 better at σ 5-6, median error 18.1/17.0 -> 14.3/15.1 mm).
  double whole_disk_from_blur_per_axis = 0.25;
  int max_iterations = 15;  // per solve
  // Solves, each on the pixels chosen at the last result, until one moves the pose by less
  // than `later_round_settles_within_standard_errors` (FitInRounds, pixel_fit.h).
  int max_rounds = 3;
  // Below a start σ of this many px, the first round is solved whole and is the result where
  // it moved the pose by less than `settle_within_standard_errors` (PoseMoveInStandardErrors):
  // a second round, on the pixels chosen there, moved it by a median 0.2-0.3 standard errors
  // however far the first had moved below 10 (the new pixels' noise), by about 1 beyond (a
  // probe on circles_a's and circle_d's paper sweeps; 79-92 % of first rounds moved less). Under
  // more blur σ's own move changes which pixels take part and how they are modelled: settled
  // there too, circles_a's blur sweep was 2 % worse (σ 5-9). Against a first round on fewer
  // pixels always, paired on the circle markers' paper sweeps: no cell differed by a sign test
  // after Holm, the geometric mean of the error ratios 0.997-1.004 per sweep and marker, the
  // same successes; full detection 9 % less time, tracking mode 11 %, blur σ 2 24 %
  // (results/speed.md).
  double settle_below_sigma_px = 3.0;
  double settle_within_standard_errors = 10.0;
  // A round after the first ends the fit where it moved the pose by less than this many
  // standard errors: a third round, all three run, moved it by a median 0.04-0.24 standard
  // errors (p90 0.1-0.65) where the second had moved it by less than 3, 0.4-3 beyond (the same
  // probe); under blur σ ≥ 3 by 0.1-0.2 however far. The translation moving by less than 1e-4
  // of its length had stopped a quarter of the second rounds under noise, 1 % under blur.
  double later_round_settles_within_standard_errors = 3.0;
  // What a pixel's square adds to a curved edge's step beyond its mean shift (its chords,
  // pixel_chord_term.h) is modelled while the noise the fit works at is below this (0-1 units;
  // 2 grey levels). It is at most 0.1/2ρ of the step (ρ the edge's radius of curvature in px),
  // and fades as the blur widens past the pixel: on sharp noise-free frames it takes the
  // residuals from 0.32-0.34 grey levels to the rounding's 0.289, and circle_d's noise-free
  // paper cell from 1.54 to 1.20× the bound. At the paper's least noise, 25 grey levels, it is
  // below 2 % of the noise in any pixel; on its σ² = 0.02 frames it moved neither circles_a's
  // cell nor circle_d's (56 and 50 of 100 frames better), and cost 35 % more time.
  double chords_below_noise = 2.0 / 255.0;
};

// `sigma_px`: the edges' σ at the start (the blur with the pixel's area, as edge points measure
// it; the fit's, PixelFit::sigma_px, is the blur alone). `noise_sigma`: a first estimate of the
// image's, 0-1 units. `levels`: the offset and gain per channel to start from where they are
// known (a tracked frame's last, `noise_sigma` the noise that frame showed): the fit then lists
// no pixels at the start to fit them and measure the noise (one evaluation of the model less).
// nullopt for designs with layers other than disks, blur beyond max_blur_per_radius, or too few
// pixels.
std::optional<PixelRefinement> RefinePhotometric(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const Rigid3& cam_from_marker,
    double sigma_px,
    double noise_sigma,
    const PhotometricOptions& options = {},
    const std::optional<Eigen::VectorXd>& levels = std::nullopt);

// The refinement from each start (RefinePhotometric), best first by how well it explains the
// image (the cost, the clipped pixels' likelihood, over the pixels near the edges at each fit in
// turn, each fit judged on the same pixels with its own σ and levels: for the circle's two tilts,
// whose images nearly coincide far away or under heavy blur), each with its 2 ln Λ against the
// first (averaged over those sets of pixels); empty when no start gives one. Each from `levels`
// where given, as RefinePhotometric's.
std::vector<RankedFit<PixelRefinement>> RefinePhotometricFromStarts(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const std::vector<Rigid3>& starts,
    double sigma_px,
    double noise_sigma,
    const PhotometricOptions& options = {},
    const std::optional<Eigen::VectorXd>& levels = std::nullopt);

// The model's cost and normal equations (pixel_fit.h) at θ = (angle-axis, translation, σ,
// then offset and gain per channel), on the pixels chosen and tied at `cam_from_marker` for
// `sigma_px` (as a solve from there takes them), at noise `noise_sigma`: what each
// Levenberg-Marquardt step of RefinePhotometric works from, for checks of the model's
// derivatives. nullopt as for RefinePhotometric.
struct PhotometricNormalEquations {
  double cost = 0.0;
  Eigen::MatrixXd jtj;
  Eigen::VectorXd jtr;
};
std::optional<PhotometricNormalEquations> PhotometricNormalEquationsAt(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const Rigid3& cam_from_marker,
    double sigma_px,
    double noise_sigma,
    const Eigen::VectorXd& theta,
    const PhotometricOptions& options = {});

}  // namespace markerbench
