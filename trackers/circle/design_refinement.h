// Direct refinement of a circle marker's whole pose on the pixels around every edge of its
// printed design, for the designs photometric_refinement.h does not model: (e)'s nose and
// mouth and (f)'s wedge inside the circle (paper Fig. 3). Each pixel u is modelled as
//   I(u) = offset + gain · D_σ(p(u)),
// with p(u) the marker-plane point u sees at the pose and D_σ the printed design blurred as
// the image is, through the local map from pixels to the plane (blurred_design.h), each colour
// beyond the paper's and the ink's (f's grey) at a fitted level. Pose, σ, gain, offset and
// those levels are fitted by Levenberg-Marquardt (pixel_fit.h) on every pixel within
// 3σ + 1.5 px of an edge: the maximum-likelihood pose under Gaussian noise, whose clipping
// at black and white (a sensor's saturation) is part of the model. For (f) the tilt
// then rests on the circle, the wedge's two sides and its apex at once; the edge points of
// the circle and one centre point (circle_tracker.cc) leave most of that out.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"
#include "trackers/circle/pixel_fit.h"

namespace markerbench {

struct DesignRefinementOptions {
  // Pixels within this many σ, plus band_px, of an edge take part (the circle tracker's
  // `design_band_sigmas` and `design_band_px`).
  double band_sigmas = 3.0;
  double band_px = 1.5;
  int max_iterations = 20;  // per solve
  // Solves, each on the pixels chosen at the last result, until the translation moves by less
  // than 1e-4 of its length.
  int max_rounds = 3;
  // RefineDesignFromStarts: a later start's fit ends after its first round where that round's
  // result is less likely than an earlier start's result by more than this, 2 ln Λ on their
  // shared pixels (the circle tracker's `design_max_other_tilt_log_ratio`). On the paper's
  // noise and blur sweeps of e and f (1,393 fits from the circle's other tilt) 746 ended so;
  // the 2 of them that would have won beat the earlier result by 0.08 and 0.09 in the end:
  // the same optimum (results/speed.md).
  double max_first_round_log_ratio = 100.0;
};

// `sigma_px`: the edges' σ at the start (the blur with the pixel's area, as edge points measure
// it; the fit's, PixelFit::sigma_px, is the blur alone, the model averaging over each pixel).
// `noise_sigma`: a first estimate of the image's, 0-1 units. nullopt when too few pixels near the
// design's edges are in front of the camera and in the image, or where `abandons` says so of
// the first round's result. On a grey image the fit's levels are (offset, gain) of the design's
// luma, 0-1, then each fitted colour's luma less the design's (BlurredDesign::FittedLevels).
std::optional<PixelRefinement> RefineDesign(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const Rigid3& cam_from_marker,
    double sigma_px,
    double noise_sigma,
    const DesignRefinementOptions& options = {},
    const std::function<bool(const PixelRefinement&)>& abandons = nullptr);

// The refinement from each start (RefineDesign), best first (DesignLogRatios), each with its
// 2 ln Λ against the first on the pixels all share; a start after the first is given up after
// its first round where that round's result is far less likely than an earlier start's
// (max_first_round_log_ratio). Empty when no start gives a refinement.
std::vector<RankedFit<PixelRefinement>> RefineDesignFromStarts(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const std::vector<Rigid3>& starts,
    double sigma_px,
    double noise_sigma,
    const DesignRefinementOptions& options = {});

// How much less likely each of several refinements explains the image than the best: its 2 ln Λ
// against the least cost (the clipped pixels' likelihood), 0 for the best, each fit judged on
// the same pixels (those near the design's edges at any of them) at the least noise any fit
// leaves. `fits` not empty.
std::vector<double> DesignLogRatios(const Image8& image,
                                    const Camera& camera,
                                    const MarkerSpec& marker,
                                    const std::vector<PixelRefinement>& fits,
                                    const DesignRefinementOptions& options = {});

}  // namespace markerbench
