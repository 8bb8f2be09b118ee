// `circle`: the method of Tang and Wu, "Efficient Circle-Based Camera Pose Tracking Free of
// PnP", as corrected in circle-method.md. Per frame: detect and fit the marker's ellipses
// (CircleDetector), l_inf and the analytic pose (SolveAnalytic), then Ceres LM (RefinePose);
// for markers e and f the roll (and f's centre) from the design inside the circle
// (RollFeature).
// In tracking mode (the paper's step 5) the previous poses predict this frame's: where the last
// pose came from the fit on the disks' pixels (a-d), that fit runs again without the detector,
// straight from this frame's prediction where the last prediction held (a smooth motion), and
// otherwise (a-c) from the prediction moved onto the circles' edges by their shifts
// (AlignByEdgeShifts) where the edges rule the circle's other tilt out; otherwise, or where its
// result fails the checks of a detection, the predicted ellipses are searched in a region around
// them; a miss there, or ellipses that are not the predicted ones, fall back to full detection
// of the whole image.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "trackers/circle/analytic_solver.h"
#include "trackers/circle/circle_detector.h"
#include "trackers/circle/design_refinement.h"
#include "trackers/circle/edge_shift_alignment.h"
#include "trackers/circle/photometric_refinement.h"
#include "trackers/circle/pose_refinement.h"
#include "trackers/printed_appearance.h"
#include "trackers/tracker.h"

namespace markerbench {

class YamlMap;

struct CircleTrackerOptions {
  CircleDetectorOptions detector;
  AnalyticOptions analytic;
  RefinementOptions refinement;
  bool refine = true;  // run the LM refinement (§6); off = analytic pose only
  // and then on the pixels (photometric_refinement.h; for (e) and (f) design_refinement.h)
  bool photometric = true;
  PhotometricOptions photometric_refinement;
  DesignRefinementOptions design_refinement;
  // Tracking mode: a prediction moved onto the frame by its edges' shifts before the fit on
  // the pixels runs from it (edge_shift_alignment.h).
  EdgeShiftOptions edge_shift;
  // The pixels are fitted from the circle's other tilt too when its normal is this far from
  // the chosen one's (nearer, the fit reaches it from either): for (e) and (f) always, and for
  // disks (a-d) where the edge points, refined from it, stay there and do not rule it out:
  // 2 ln Λ = N (rms_other² / rms² - 1) over the N edge points below this (far away and under
  // heavy blur the disks' images from both tilts nearly coincide; circles_a at 0.6 m: the
  // edges rule the other out, 2 ln Λ > 100, on all but 5 of 100 frames at σ² 0.3).
  double min_branch_angle_rad = 0.02;
  double max_other_tilt_log_ratio = 100.0;
  // (e, f) The circle's radius must be at least this many blur σ: below, the design (a 60°
  // wedge, a mouth) is too blurred to tell from clutter, which it then fits (on the negative
  // set, dark blobs as circles of 14.7-15.9 px at σ 2.2-3.7 px, 4.2-6.7 σ; on the paper sweeps
  // 6 % of the frames of e and f, at blur σ 4 and beyond, fall below).
  double min_design_radius_per_blur = 7.0;
  // The fit on the pixels from the circle's other tilt (above) is returned as a second
  // hypothesis where it explains them nearly as well as the first: 2 ln Λ against it at most
  // this (4: odds of at least e^-2, 1 to 7.4; on the paper's blur sweep 12 of 13 wrong choices
  // of e's and f's tilt at blur σ 4-5 were within 3.6 of the right one). In tracking mode the
  // fit straight from the prediction, which fits one tilt, runs only where the evidence carried
  // for it exceeds this.
  double max_second_hypothesis_log_ratio = 4.0;
  // Tracking mode weighs the circle's two tilts over the frames: each frame's 2 ln Λ between its
  // fits on the two is added to the evidence the frames before left for the tilt they tracked,
  // carried at most this far either way (2 ln odds; 10: a switch of the tracked tilt between
  // frames taken as about e^-5 likely, and a frame whose pixels favour the other by more
  // overrides the frames before).
  double max_carried_tilt_log_ratio = 10.0;
  bool tracking = true;  // search around the pose predicted from the last frames first (step 5)
  // Tracking mode predicts this frame's pose by moving the previous one on by the camera's
  // last frame-to-frame motion, where the two frames before both had a pose (constant
  // velocity; frames evenly spaced in time); otherwise, or with false, the previous pose.
  bool predict_motion = true;
  double roi_margin = 0.25;  // tracking region: predicted box grown by this fraction
  // A tracking-mode result stands only if each ellipse is within this fraction of its
  // prediction (centre shift per semi-minor axis, and each semi-axis); else full detection.
  double max_prediction_error = 0.5;
  double max_edge_rms_px = 2.0;  // accept the ellipses only if the edge fit's residual RMS is below
  // ... and only if the image shows the marker's whole design there (printed_appearance.h).
  AppearanceOptions appearance;

  bool IsValid(std::string* error) const;
  // Reads flat keys (cost, huber_px, point_weight, max_iterations, k_normal, depth, refine,
  // photometric, tracking, predict_motion, roi_margin, max_prediction_error, max_edge_rms_px,
  // max_appearance_misfit, max_appearance_block_misfit, appearance_blocks_per_side,
  // appearance_min_significance, appearance_design_image (the design check's max_misfit,
  // max_block_misfit, blocks_per_side, min_significance and design_image), min_contrast,
  // edge_passes, max_rays, max_blurred_dot_disks, max_blurred_dot_peak, min_dot_area_px,
  // min_blurred_dot_radius_px, min_dot_radius_px, blurred_dot_min_significance,
  // min_branch_angle_rad, max_other_tilt_log_ratio, min_design_radius_per_blur,
  // max_second_hypothesis_log_ratio, max_carried_tilt_log_ratio; pixel_band_sigmas and
  // pixel_band_px, the disks' fit's band_sigmas and band_px; design_band_sigmas, design_band_px and
  // design_max_other_tilt_log_ratio, e's and f's band_sigmas, band_px and
  // max_first_round_log_ratio; the edge_shift_ keys of tracking mode's alignment
  // (EdgeShiftOptions): the keys of Parameters()); throws ConfigError naming the file and key.
  static CircleTrackerOptions FromYaml(const YamlMap& map);
};

// Every stage of the last Track call, for tests and reports (style.md, item 4).
struct CircleDiagnostics {
  bool used_tracking_region = false;
  bool used_predicted_ellipses = false;  // the result is one edge pass from the predicted ellipses
  // The result is the fit on the pixels from the predicted pose (no detector; conics_px and m1_px
  // are the fitted pose's image, edges empty).
  bool tracked_on_pixels = false;
  // ... from the prediction moved by its edges' shifts (AlignByEdgeShifts), not the prediction
  // itself.
  bool aligned_by_edge_shifts = false;
  std::vector<Eigen::Matrix3d> conics_px;           // fitted, canonical
  std::vector<std::vector<Eigen::Vector2d>> edges;  // per circle, bias-corrected
  std::vector<int> edge_passes;                     // per circle, run
  std::optional<Eigen::Vector2d>
      m1_px;                   // detected feature point (b-d; e, f: by the design), undistorted
  double blur_sigma_px = 0.0;  // fitted edge σ (blur + pre-smoothing)
  double image_blur_sigma_px = 0.0;  // the image's own: without the smoothing
  double noise_sigma = 0.0;          // estimated image noise σ, 0-1 units
  Eigen::Vector3d l_inf_norm = Eigen::Vector3d::Zero();
  std::optional<Rigid3> analytic_cam_from_marker;
  std::optional<Rigid3> refined_cam_from_marker;
  int iterations = 0;
  double final_cost = 0.0;
  double edge_rms_px = 0.0;       // PND residual RMS of the edges to the final pose's conics
  bool photometric_used = false;  // the final pose is the photometric refinement's
  // 2 ln Λ of the fit on the pixels from the circle's other tilt against the final pose, where
  // that fit ended apart from it; a second hypothesis where at most
  // max_second_hypothesis_log_ratio. In tracking mode with the evidence of the frames before
  // (max_carried_tilt_log_ratio).
  std::optional<double> second_tilt_log_ratio;
  double appearance_misfit = 0.0;  // of the printed design at the final pose
  int appearance_grid = 0;         // the lattice that check decided on (AppearanceFit::grid)
};

class CircleTracker final : public Tracker {
 public:
  explicit CircleTracker(const CircleTrackerOptions& options = {});
  TrackResult Track(const Observation& observation) override;
  bool CanTrack(const MarkerSpec& marker) const override;
  void Reset() override {
    previous_cam_from_paper_.reset();
    previous_on_pixels_.reset();
    prediction_error_px_.reset();
    last_motion_.reset();
    tilt_log_ratio_ = 0.0;
  }
  std::vector<std::pair<std::string, std::string>> Parameters() const override;

  const CircleDiagnostics& diagnostics() const { return diagnostics_; }

 private:
  // What a fit on the disks' pixels found of the image: its blur, noise and levels.
  struct PixelFitFound {
    double edge_sigma_px = 0.0;  // the blur with the pixel's area, as edge points measure it
    double noise_sigma = 0.0;    // 0-1
    Eigen::VectorXd levels;      // offset and gain per channel (PixelFit::levels)
    int appearance_grid = 0;     // the lattice the check of the printed design decided on
  };
  // Tracking mode: the pose predicted for the frame, and the evidence the frames before left for
  // the tilt of the last pose, the plane's normal `tracked_normal` (2 ln of the odds against the
  // circle's other). The prediction's own normal may have crossed over: far away a frame's tilt
  // is uncertain by degrees, and the motion from the last two carries that on.
  struct PredictedPose {
    Rigid3 cam_from_paper;
    Eigen::Vector3d tracked_normal;
    double tilt_log_ratio = 0.0;
  };

  // Tracking mode around the predicted pose first, then the whole image.
  TrackResult FindInFrame(const Observation& observation);
  // The fit on the disks' pixels (a-d) from the predicted pose, at the last frame's blur, noise
  // and levels, with the checks of a detection that need no edge points: the marker's image within
  // the frame, its contrast (each channel's gain) within kMaxContrastChange of the last frame's,
  // the residuals' noise at most kMaxNoiseGrowth times the last frame's, the tilt the one tracked
  // (ContinuesTilt) and settled by the frames before (`predicted`'s evidence above
  // max_second_hypothesis_log_ratio), and the printed design. One fit does not measure its other
  // tilt's likelihood, so the evidence carried stands.
  TrackResult TrackOnPixels(const Observation& observation,
                            const CircleGeometry& geometry,
                            const PredictedPose& predicted,
                            const PixelFitFound& last);
  // The prediction moved onto this frame by its circles' edges (AlignByEdgeShifts, at the last
  // fit's levels and blur), for a frame whose last prediction was off by more than
  // kMaxLastPredictionErrorPx; nullopt where the edges do not show or leave the circle's other
  // tilt open (EdgesLeaveTheOtherTilt; always for d's single circle).
  std::optional<PredictedPose> AlignedByEdges(const Observation& observation,
                                              const CircleGeometry& geometry,
                                              const PredictedPose& predicted,
                                              const PixelFitFound& last) const;
  // The next frame's fit on the pixels starts from `found`, and its design check at the lattice
  // this frame's decided on.
  void KeepPixelFit(PixelFitFound found);
  // The check of the printed design at a pose (CheckPrintedAppearance), and the result: found,
  // with `second_hypothesis` after the pose where given, and the pose kept for the next frame's
  // prediction, or not detected. The check starts at `first_grid` where that is finer than the
  // options' coarse grid.
  TrackResult Accept(const Observation& observation,
                     const Rigid3& cam_from_paper,
                     const Rigid3& cam_from_marker,
                     const std::optional<Rigid3>& second_hypothesis = std::nullopt,
                     int first_grid = 0);
  // The detection in `region` (from the predicted ellipses where given; in tracking mode the
  // predicted pose starts the refinement and weighs the tilts); the fit on the disks' pixels
  // there starts from the levels and noise the last frame's found (`last_on_pixels`) where given.
  TrackResult TrackIn(const Observation& observation,
                      const CircleGeometry& geometry,
                      const cv::Rect& region,
                      const std::vector<Eigen::Matrix3d>* predicted_conics_px,
                      const PredictedPose* predicted,
                      const PixelFitFound* last_on_pixels);
  // Whether the normals of two poses' planes (the marker's, seen from the camera) lie more than
  // min_branch_angle_rad apart: the circle's two tilts told apart.
  bool TiltsApart(const Rigid3& cam_from_plane, const Rigid3& other) const;
  // Whether edge points fitted at a pose, and again from its other tilt (`other_fitted`, where
  // that fit ended), leave the other tilt open: it stayed apart, and 2 ln Λ of the two fits,
  // N (rms_other² / rms² - 1) over the N points (their RMS taken as their noise), is below
  // max_other_tilt_log_ratio.
  bool EdgesLeaveTheOtherTilt(const Rigid3& cam_from_paper,
                              const Rigid3& other_fitted,
                              size_t edge_points,
                              double edge_rms_px,
                              double other_rms_px) const;
  // Whether a pose continues the tilt tracked: its plane's normal is nearer the tracked one
  // (PredictedPose::tracked_normal) than the normal of its other tilt (`other`) is.
  static bool ContinuesTilt(const Rigid3& cam_from_paper,
                            const Rigid3& other,
                            const PredictedPose& predicted);
  // Where the fit on the pixels starts: the refined pose (`cam_from_paper`, whose edge
  // residual is `edge_rms_px`), and the circle's other tilt where it may be the one seen.
  std::vector<Rigid3> PixelFitStarts(const RefinementProblem& problem,
                                     bool whole_design,
                                     const Rigid3& cam_from_paper,
                                     double edge_rms_px) const;
  // The pose refined on the pixels from each start, the one that explains them best: around
  // the disks' edges (photometric_refinement.h), or (e, f) around every edge of the whole
  // design (design_refinement.h); nullopt where no start gives a fit.
  // With the disks' fit, what it found of the image (`found`); it starts from the levels and
  // noise of `last` where given.
  struct FitOnPixels {
    Rigid3 cam_from_marker;
    // The best fit on the circle's other tilt, where one ended apart from this one.
    std::optional<Rigid3> other_tilt;
    // 2 ln of the odds of this fit's tilt against the other's (ChooseTilt).
    double tilt_log_ratio = 0.0;
  };
  // The first of `fits` (ranked on the pixels) and the evidence for its tilt against the
  // circle's other: 2 ln Λ against the next fit where that one lies on the other tilt; else
  // infinite (the other ruled out), or 0 where the two tilts nearly coincide. In tracking mode
  // (`predicted`) the evidence carried (within max_carried_tilt_log_ratio) counts for the fit
  // that continues the tilt tracked (ContinuesTilt): where the first two fits lie on the two tilts
  // it is added, and the fit the sum favours goes first; where no fit lies on the tilt the evidence
  // favours, the one fit left keeps that evidence against it (a fit from the tracked tilt slid
  // to the other by a likelihood unknown), negative.
  FitOnPixels ChooseTilt(const Rigid3& marker_from_paper,
                         const PredictedPose* predicted,
                         std::vector<RankedFit<PixelRefinement>>* fits) const;
  std::optional<FitOnPixels> OnPixels(const Observation& observation,
                                      bool whole_design,
                                      const std::vector<Rigid3>& cam_from_paper_starts,
                                      const Rigid3& paper_from_marker,
                                      const PredictedPose* predicted,
                                      const PixelFitFound* last,
                                      PixelFitFound* found) const;

  CircleTrackerOptions options_;
  std::optional<Rigid3> previous_cam_from_paper_;
  // Where that pose is the disks' fit on the pixels: what it found of the image.
  std::optional<PixelFitFound> previous_on_pixels_;
  // Where that pose was found from a prediction: how far its image lay from it
  // (PredictionErrorPx).
  std::optional<double> prediction_error_px_;
  std::optional<Rigid3> last_motion_;  // cam_previous_from_cam_before, both frames with a pose
  // 2 ln of the odds of the previous pose's tilt against the circle's other (ChooseTilt).
  double tilt_log_ratio_ = 0.0;
  CircleDiagnostics diagnostics_;
};

std::unique_ptr<Tracker> MakeCircleTracker(const CircleTrackerOptions& options);

}  // namespace markerbench
