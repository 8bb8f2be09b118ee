// A tracker's choice between the circle's two tilts (§4.7) against the best any tracker can make
// with the same pixels: the likelier of two fits, one started from the true pose and one from
// its mirror. Far away, or under blur, the pixels barely tell the two apart; where even that
// choice is often the mirror, a cell's errors are the mirror's frames, which the bound at the
// true pose does not count.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>

#include "core/binomial_tail.h"
#include "core/pose_error.h"
#include "core/random.h"
#include "renderer/test_scenes.h"
#include "testing/square_tracker_testing.h"
#include "trackers/circle/circle_geometry.h"
#include "trackers/circle/design_refinement.h"
#include "trackers/circle/photometric_refinement.h"
#include "trackers/tracker.h"

namespace markerbench {

struct TiltChoiceCounts {
  int from_truth_wrong = 0;                            // the fit from the truth and its mirror
  int ours_wrong = 0;                                  // the tracker's
  int only_ours_wrong = 0, only_from_truth_wrong = 0;  // the discordant frames
  int frames = 0;                                      // counted

  // McNemar's exact test on the discordant frames: the chance of the tracker being the wrong
  // one this often or more if both were wrong as often.
  double OursWrongMoreOftenP() const {
    return FairBinomialUpperTail(only_ours_wrong + only_from_truth_wrong, only_ours_wrong);
  }
};

// The views of the frames counted: `frames` of them at `distance_m`, tilted within
// [min_tilt_deg, max_tilt_deg] and rolled at random (Rng(pose_seed)), with noise of variance
// `noise_var` and blur `blur_sigma_px`, frame i's noise seeded by first_noise_seed + i.
struct TiltedFrames {
  double distance_m = 1.0;
  double min_tilt_deg = 0.0, max_tilt_deg = 40.0;
  double noise_var = 0.02, blur_sigma_px = 0.0;
  int frames = 30;
  uint64_t pose_seed = 1, first_noise_seed = 1;
};

// `fit_from_truth_and_mirror(image, truth)`: the kept fit's pose (nullopt counts as wrong).
using FitFromTruthAndMirror = std::function<std::optional<Rigid3>(const Image8&, const Rigid3&)>;

// That fit for the disks of a-d: the likelier of the fits on their pixels
// (RefinePhotometricFromStarts) from the truth and from OtherTilt(truth), started at the edges'
// σ `edge_sigma_px` and noise σ `noise_sigma` (0-1). `camera` and `marker` must outlive it.
inline FitFromTruthAndMirror PixelFitFromTruthAndMirror(const Camera& camera,
                                                        const MarkerSpec& marker,
                                                        double edge_sigma_px,
                                                        double noise_sigma) {
  return [&camera, &marker, edge_sigma_px, noise_sigma](
             const Image8& image, const Rigid3& truth) -> std::optional<Rigid3> {
    const std::vector<RankedFit<PixelRefinement>> fits = RefinePhotometricFromStarts(
        image, camera, marker, {truth, OtherTilt(truth)}, edge_sigma_px, noise_sigma);
    if (fits.empty()) return std::nullopt;
    return fits[0].result.fit.cam_from_marker;
  };
}

// That fit for the designs of e and f: the likelier of the fits on their design's pixels
// (RefineDesignFromStarts) from the truth and from OtherTilt(truth), each fit to its end, started
// at the edges' σ `edge_sigma_px` and noise σ `noise_sigma` (0-1). `camera` and `marker` must
// outlive it.
inline FitFromTruthAndMirror DesignFitFromTruthAndMirror(const Camera& camera,
                                                         const MarkerSpec& marker,
                                                         double edge_sigma_px,
                                                         double noise_sigma) {
  DesignRefinementOptions to_the_end;
  to_the_end.max_first_round_log_ratio = std::numeric_limits<double>::infinity();
  return [&camera, &marker, edge_sigma_px, noise_sigma, to_the_end](
             const Image8& image, const Rigid3& truth) -> std::optional<Rigid3> {
    const std::vector<RankedFit<PixelRefinement>> fits = RefineDesignFromStarts(
        image, camera, marker, {truth, OtherTilt(truth)}, edge_sigma_px, noise_sigma, to_the_end);
    if (fits.empty()) return std::nullopt;
    return fits[0].result.fit.cam_from_marker;
  };
}

// One frame counted, seen from `distance_m`: a pose is wrong beyond a tenth of it (the
// benchmark's success criterion), or where the tracker (Reset first) finds none; with
// `found_only`, a frame it finds none in is not counted (a cell's errors are those of the frames
// found).
inline void CountTiltChoice(const Image8& image,
                            const Camera& camera,
                            const MarkerSpec& marker,
                            const Rigid3& truth,
                            double distance_m,
                            Tracker& tracker,
                            const FitFromTruthAndMirror& fit_from_truth_and_mirror,
                            TiltChoiceCounts* counts,
                            bool found_only = false) {
  const double wrong_m = 0.1 * distance_m;
  tracker.Reset();
  const TrackResult ours = tracker.Track({&image, &camera, &marker});
  if (found_only && ours.status != TrackStatus::kOk) return;
  ++counts->frames;
  const bool ours_wrong = ours.status != TrackStatus::kOk ||
                          !(PositionError(ours.hypotheses.front(), truth) <= wrong_m);
  const std::optional<Rigid3> kept = fit_from_truth_and_mirror(image, truth);
  const bool truth_wrong = !kept || !(PositionError(*kept, truth) <= wrong_m);
  counts->from_truth_wrong += truth_wrong;
  counts->ours_wrong += ours_wrong;
  counts->only_ours_wrong += ours_wrong && !truth_wrong;
  counts->only_from_truth_wrong += truth_wrong && !ours_wrong;
}

// The frames of `views`, from the default camera.
inline TiltChoiceCounts CountTiltChoices(const MarkerSpec& marker,
                                         Tracker& tracker,
                                         const TiltedFrames& views,
                                         const FitFromTruthAndMirror& fit_from_truth_and_mirror) {
  const Camera camera;
  Rng rng(views.pose_seed);
  TiltChoiceCounts counts;
  for (int i = 0; i < views.frames; ++i) {
    const Rigid3 truth =
        RandomTiltedView(views.distance_m, views.min_tilt_deg, views.max_tilt_deg, &rng);
    const RenderedFrame frame = RenderMarker(
        marker, truth, views.noise_var, views.blur_sigma_px, views.first_noise_seed + i);
    CountTiltChoice(frame.image,
                    camera,
                    marker,
                    truth,
                    views.distance_m,
                    tracker,
                    fit_from_truth_and_mirror,
                    &counts);
  }
  return counts;
}

}  // namespace markerbench
