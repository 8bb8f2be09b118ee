#include "trackers/circle/circle_tracker.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/number_text.h"
#include "core/option_fields.h"
#include "core/yaml_reader.h"
#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/circle/conic.h"
#include "trackers/circle/conic_fit.h"
#include "trackers/circle/photometric_refinement.h"
#include "trackers/circle/roll_feature.h"
#include "trackers/pixel_area_blur.h"
#include "trackers/printed_appearance.h"

namespace markerbench {
namespace {

// Bounding box of an ellipse conic.
cv::Rect2d EllipseBox(const Eigen::Matrix3d& C) {
  const Ellipse e = EllipseFromConic(C);
  const double c = std::cos(e.angle_rad), s = std::sin(e.angle_rad);
  const double hw = std::hypot(e.semi_major * c, e.semi_minor * s);
  const double hh = std::hypot(e.semi_major * s, e.semi_minor * c);
  return {e.center.x() - hw, e.center.y() - hh, 2 * hw, 2 * hh};
}

// The marker's image at a pose: its circles (canonical conics) and its point m1, in px.
struct MarkerImage {
  std::vector<Eigen::Matrix3d> conics_px;
  Eigen::Vector2d m1_px;
};
MarkerImage MarkerImagedAt(const CircleGeometry& geometry,
                           const Camera& camera,
                           const Rigid3& cam_from_paper) {
  const Eigen::Matrix3d H = camera.K() * RayFromPlane(cam_from_paper);
  return {ConicsImagedThrough(geometry, H),
          (H * Eigen::Vector3d(geometry.Lx, 0.0, 1.0)).hnormalized()};
}

// The same as the image shows it through the lens: the pinhole's without distortion; with it,
// each circle the ellipse through 64 points of its image (the lens bends it off an ellipse by
// far less than the edge search's reach). nullopt where a circle gives no ellipse.
constexpr int kLensImagePoints = 64;
std::optional<MarkerImage> MarkerImageThroughLens(const CircleGeometry& geometry,
                                                  const Camera& camera,
                                                  const Rigid3& cam_from_paper,
                                                  const MarkerImage& pinhole) {
  if (!camera.HasDistortion()) return pinhole;
  MarkerImage image;
  for (size_t i = 0; i < geometry.centers.size(); ++i) {
    std::vector<Eigen::Vector2d> points_px;
    for (int k = 0; k < kLensImagePoints; ++k) {
      const double angle = 2.0 * M_PI * k / kLensImagePoints;
      const Eigen::Vector2d on_circle =
          geometry.centers[i] +
          geometry.radii_m[i] * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      points_px.push_back(
          camera.ImgFromCam(cam_from_paper * Eigen::Vector3d(on_circle.x(), on_circle.y(), 0.0)));
    }
    const std::optional<ConicFit> fit = FitEllipse(points_px);
    if (!fit) return std::nullopt;
    image.conics_px.push_back(fit->conic);
  }
  image.m1_px = camera.ImgFromCam(cam_from_paper * Eigen::Vector3d(geometry.Lx, 0.0, 0.0));
  return image;
}

// The marker's image at a predicted pose (the pinhole's, as the detector's undistorted
// ellipses are compared with it), through the lens (where the detector looks), and the region
// around the latter (the ellipses' and m1's box grown by `roi_margin` of its size and 10 px,
// within the image).
struct PredictedImage : MarkerImage {
  MarkerImage through_lens;
  cv::Rect region;
};

// nullopt where the pose puts a circle within its radius of the camera's plane or behind it (a
// motion carried on too far: no image to search), or the region outside the image.
std::optional<PredictedImage> PredictImage(const CircleGeometry& geometry,
                                           const Camera& camera,
                                           const Rigid3& cam_from_paper,
                                           double roi_margin,
                                           const cv::Rect& image) {
  for (size_t i = 0; i < geometry.centers.size(); ++i) {
    const Eigen::Vector2d& c = geometry.centers[i];
    if (!((cam_from_paper * Eigen::Vector3d(c.x(), c.y(), 0.0)).z() > geometry.radii_m[i])) {
      return std::nullopt;
    }
  }
  const MarkerImage pinhole = MarkerImagedAt(geometry, camera, cam_from_paper);
  const std::optional<MarkerImage> through_lens =
      MarkerImageThroughLens(geometry, camera, cam_from_paper, pinhole);
  if (!through_lens) return std::nullopt;
  PredictedImage predicted{pinhole, *through_lens, cv::Rect()};
  cv::Rect2d box;
  for (size_t i = 0; i < through_lens->conics_px.size(); ++i) {
    const cv::Rect2d b = EllipseBox(through_lens->conics_px[i]);
    box = i == 0 ? b : (box | b);
  }
  box |= cv::Rect2d(through_lens->m1_px.x(), through_lens->m1_px.y(), 1.0, 1.0);
  const double grow = roi_margin * std::max(box.width, box.height) + 10.0;
  // Far off the image (or not finite): nothing to search, and no int holds its corners.
  constexpr double kFar = 1e6;
  if (!(box.x - grow > -kFar && box.y - grow > -kFar && box.x + box.width + grow < kFar &&
        box.y + box.height + grow < kFar)) {
    return std::nullopt;
  }
  predicted.region =
      image & cv::Rect(cv::Point(static_cast<int>(std::floor(box.x - grow)),
                                 static_cast<int>(std::floor(box.y - grow))),
                       cv::Point(static_cast<int>(std::ceil(box.x + box.width + grow)),
                                 static_cast<int>(std::ceil(box.y + box.height + grow))));
  if (predicted.region.area() <= 0) return std::nullopt;
  return predicted;
}

// Whether the detection is the predicted image of the marker: each ellipse's centre within
// `max_error` of its predicted semi-minor axis and each semi-axis within that fraction, and
// a detected feature point m1 within that fraction of circle 0's predicted semi-minor axis
// (for c and d, whose circles alone do not fix the roll).
bool MatchPrediction(const CircleDiagnostics& detected,
                     const PredictedImage& predicted,
                     double max_error) {
  const std::vector<Eigen::Matrix3d>& predicted_conics_px = predicted.conics_px;
  if (detected.conics_px.size() != predicted_conics_px.size()) return false;
  for (size_t i = 0; i < predicted_conics_px.size(); ++i) {
    const Ellipse d = EllipseFromConic(detected.conics_px[i]);
    const Ellipse p = EllipseFromConic(predicted_conics_px[i]);
    if (!((d.center - p.center).norm() <= max_error * p.semi_minor &&
          std::abs(d.semi_major / p.semi_major - 1.0) <= max_error &&
          std::abs(d.semi_minor / p.semi_minor - 1.0) <= max_error)) {
      return false;
    }
  }
  return !detected.m1_px || (*detected.m1_px - predicted.m1_px).norm() <=
                                max_error * EllipseFromConic(predicted_conics_px[0]).semi_minor;
}

// Tracking on the pixels (CircleTracker::TrackOnPixels): the most the fit's residuals may show
// of noise against the last frame's fit (a fit that missed the marker's edges, moved beyond the
// pixels' band, leaves their steps in the residuals), and the factor by which each channel's
// gain may differ from the last frame's (a fit on paper without the marker, where it was, takes
// its gains to 0 and shows the paper's noise alone).
constexpr double kMaxNoiseGrowth = 1.5;
constexpr double kMaxContrastChange = 2.0;
// It starts from the prediction itself where the last frame's image lay within this many px of
// its prediction (PredictionErrorPx), and otherwise from the prediction moved onto the edges
// (AlignedByEdges): a fit from a prediction off by more than its pixels' band takes several
// rounds. Measured: on an orbit (scenarios/sequences/orbit.yaml, σ² 0.02) the motion's
// predictions were off by at most 0.16 px, and the fit took 2.7 evaluations; in the speed
// benchmark's hand-held shake by 1-10 px, and it took 12-28, where full detection's fit takes
// about 5 (results/speed.md).
constexpr double kMaxLastPredictionErrorPx = 0.5;

// Tracking mode (ChooseTilt): where a frame's fits from both of the circle's tilts end on one,
// on the tilt tracked, and the evidence carried stands against that tilt (a fit slid to it from
// the tilt the evidence favoured), the frame counts this 2 ln Λ for it. One fit measures nothing
// of the other tilt, and far away such fits are often on the wrong one: taken as ruling the other
// out (detection mode's reading), a fit that slid to circle_f's wrong tilt at 3.2 m and the merged
// fit after it settled that tilt, and 22 frames of a receding video were lost (where the slide's
// evidence stood, the next frame's two fits took the right tilt back). Near the camera's axis
// the fits merge on most frames: with nothing counted, a slide's evidence stood on every frame
// after it, each taking the search (an approach at 4-5° of tilt, from 1.9 m to 0.5 m). At 1 such
// evidence (at most max_carried_tilt_log_ratio, 10) is worked off in at most 10 merged frames;
// the next merged fit on that tilt, no longer disfavoured, rules the other out as any does.
constexpr double kMergedFitLogRatio = 1.0;

// How far the marker's image at a pose lies from a prediction of it: over its ellipses, the
// largest shift of a centre plus the largest change of a semi-axis (px), a bound on how far
// an edge point moved to first order.
double PredictionErrorPx(const CircleGeometry& geometry,
                         const Camera& camera,
                         const Rigid3& cam_from_paper,
                         const PredictedImage& predicted) {
  const std::vector<Eigen::Matrix3d> conics_px =
      ConicsImagedThrough(geometry, camera.K() * RayFromPlane(cam_from_paper));
  double error = 0.0;
  for (size_t i = 0; i < conics_px.size(); ++i) {
    const Ellipse at = EllipseFromConic(conics_px[i]);
    const Ellipse p = EllipseFromConic(predicted.conics_px[i]);
    error =
        std::max(error,
                 (at.center - p.center).norm() + std::max(std::abs(at.semi_major - p.semi_major),
                                                          std::abs(at.semi_minor - p.semi_minor)));
  }
  return error;
}

// RMS of the edge points' PND distances to the circles projected from a pose (px).
double EdgeRmsPx(const RefinementProblem& problem, const Rigid3& cam_from_paper) {
  const Eigen::Matrix3d H = problem.K * RayFromPlane(cam_from_paper);
  double sum = 0.0;
  size_t count = 0;
  for (const RefinementCircle& circle : problem.circles) {
    const Eigen::Matrix3d C = ImageOfCircle<double>(H, circle.center, circle.radius_m);
    for (const Eigen::Vector2d& p : circle.edge_points_px) {
      const double r = PndResidual<double>(C, p.x(), p.y());
      sum += r * r;
      ++count;
    }
  }
  return std::sqrt(sum / std::max<size_t>(1, count));
}

// CircleTrackerOptions' keys, read and written (core/option_fields.h).
template <typename Options, typename Fields>
void VisitCircleTrackerFields(Options& o, Fields&& fields) {
  fields.Choice("cost",
                o.refinement.cost,
                {{RefinementCost::kEdges, ToString(RefinementCost::kEdges)},
                 {RefinementCost::kConics, ToString(RefinementCost::kConics)}});
  fields("huber_px", o.refinement.huber_px);
  fields("point_weight", o.refinement.point_weight);
  fields("max_iterations", o.refinement.max_iterations);
  fields("k_normal", o.analytic.k_normal);
  fields.Choice("depth",
                o.analytic.depth,
                {{AnalyticDepth::kRadius, ToString(AnalyticDepth::kRadius)},
                 {AnalyticDepth::kLx, ToString(AnalyticDepth::kLx)}});
  fields("refine", o.refine);
  fields("photometric", o.photometric);
  fields("tracking", o.tracking);
  fields("predict_motion", o.predict_motion);
  fields("roi_margin", o.roi_margin);
  fields("max_prediction_error", o.max_prediction_error);
  fields("max_edge_rms_px", o.max_edge_rms_px);
  fields("max_appearance_misfit", o.appearance.max_misfit);
  fields("max_appearance_block_misfit", o.appearance.max_block_misfit);
  fields("appearance_blocks_per_side", o.appearance.blocks_per_side);
  fields("appearance_min_significance", o.appearance.min_significance);
  fields("appearance_design_image", o.appearance.design_image);
  fields("min_contrast", o.detector.min_contrast);
  fields("edge_passes", o.detector.edge_passes);
  fields("max_rays", o.detector.edges.max_rays);
  fields("max_blurred_dot_disks", o.detector.max_blurred_dot_disks);
  fields("max_blurred_dot_peak", o.detector.max_blurred_dot_peak);
  fields("min_dot_area_px", o.detector.min_dot_area_px);
  fields("min_blurred_dot_radius_px", o.detector.min_blurred_dot_radius_px);
  fields("min_dot_radius_px", o.detector.min_dot_radius_px);
  fields("blurred_dot_min_significance", o.detector.blurred_dots.min_significance);
  fields("min_branch_angle_rad", o.min_branch_angle_rad);
  fields("max_other_tilt_log_ratio", o.max_other_tilt_log_ratio);
  fields("min_design_radius_per_blur", o.min_design_radius_per_blur);
  fields("max_second_hypothesis_log_ratio", o.max_second_hypothesis_log_ratio);
  fields("max_carried_tilt_log_ratio", o.max_carried_tilt_log_ratio);
  fields("pixel_band_sigmas", o.photometric_refinement.band_sigmas);
  fields("pixel_band_px", o.photometric_refinement.band_px);
  fields("design_band_sigmas", o.design_refinement.band_sigmas);
  fields("design_band_px", o.design_refinement.band_px);
  fields("design_max_other_tilt_log_ratio", o.design_refinement.max_first_round_log_ratio);
  fields("edge_shift_alignment", o.edge_shift.enabled);
  fields("edge_shift_first_rays", o.edge_shift.first.rays_per_circle);
  fields("edge_shift_rays", o.edge_shift.second.rays_per_circle);
  fields("edge_shift_max_px", o.edge_shift.first.max_shift_px);
  fields("edge_shift_second_max_px", o.edge_shift.second.max_shift_px);
  fields("edge_shift_step_px", o.edge_shift.sample_step_px);
  fields("edge_shift_first_samples_across", o.edge_shift.first.samples_across);
  fields("edge_shift_samples_across", o.edge_shift.second.samples_across);
  fields("edge_shift_min_step_per_contrast", o.edge_shift.min_step_per_contrast);
  fields("edge_shift_first_min_found_fraction", o.edge_shift.first.min_found_fraction);
  fields("edge_shift_min_found_fraction", o.edge_shift.second.min_found_fraction);
  fields("edge_shift_max_rms_px", o.edge_shift.max_rms_px);
}

}  // namespace

bool CircleTrackerOptions::IsValid(std::string* error) const {
  if (!detector.IsValid(error) || !refinement.IsValid(error) || !edge_shift.IsValid(error)) {
    return false;
  }
  std::ostringstream msg;
  if (!(roi_margin >= 0.0)) {
    msg << "roi_margin=" << roi_margin << " must be >= 0";
  } else if (!(max_prediction_error > 0.0)) {
    msg << "max_prediction_error=" << max_prediction_error << " must be > 0";
  } else if (!(max_edge_rms_px > 0.0)) {
    msg << "max_edge_rms_px=" << max_edge_rms_px << " must be > 0";
  } else if (!(appearance.max_misfit > 0.0)) {
    msg << "max_appearance_misfit=" << appearance.max_misfit << " must be > 0";
  } else if (!(appearance.max_block_misfit > 0.0)) {
    msg << "max_appearance_block_misfit=" << appearance.max_block_misfit << " must be > 0";
  } else if (!(appearance.blocks_per_side >= 0)) {
    msg << "appearance_blocks_per_side=" << appearance.blocks_per_side << " must be >= 0";
  } else if (!(appearance.min_significance > 0.0)) {
    msg << "appearance_min_significance=" << appearance.min_significance << " must be > 0";
  } else if (!(min_branch_angle_rad >= 0.0 && min_branch_angle_rad < 0.5 * M_PI)) {
    msg << "min_branch_angle_rad=" << min_branch_angle_rad << " must be in [0, pi/2)";
  } else if (!(max_other_tilt_log_ratio >= 0.0)) {
    msg << "max_other_tilt_log_ratio=" << max_other_tilt_log_ratio << " must be >= 0";
  } else if (!(min_design_radius_per_blur >= 0.0)) {
    msg << "min_design_radius_per_blur=" << min_design_radius_per_blur << " must be >= 0";
  } else if (!(max_second_hypothesis_log_ratio >= 0.0)) {
    msg << "max_second_hypothesis_log_ratio=" << max_second_hypothesis_log_ratio << " must be >= 0";
  } else if (!(max_carried_tilt_log_ratio >= 0.0)) {
    msg << "max_carried_tilt_log_ratio=" << max_carried_tilt_log_ratio << " must be >= 0";
  } else if (!(photometric_refinement.band_sigmas > 0.0)) {
    msg << "pixel_band_sigmas=" << photometric_refinement.band_sigmas << " must be > 0";
  } else if (!(photometric_refinement.band_px >= 0.0)) {
    msg << "pixel_band_px=" << photometric_refinement.band_px << " must be >= 0";
  } else if (!(design_refinement.band_sigmas > 0.0)) {
    msg << "design_band_sigmas=" << design_refinement.band_sigmas << " must be > 0";
  } else if (!(design_refinement.band_px >= 0.0)) {
    msg << "design_band_px=" << design_refinement.band_px << " must be >= 0";
  } else if (!(design_refinement.max_first_round_log_ratio >= 0.0)) {
    msg << "design_max_other_tilt_log_ratio=" << design_refinement.max_first_round_log_ratio
        << " must be >= 0";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

CircleTrackerOptions CircleTrackerOptions::FromYaml(const YamlMap& map) {
  CircleTrackerOptions o;
  VisitCircleTrackerFields(o, FieldReader(map));
  FinishOptions(map, o);
  return o;
}

CircleTracker::CircleTracker(const CircleTrackerOptions& options) : options_(options) {
  PrepareBlurredDiskProfiles();
}

bool CircleTracker::CanTrack(const MarkerSpec& marker) const {
  return CircleGeometryOf(marker, nullptr).has_value();
}

std::vector<std::pair<std::string, std::string>> CircleTracker::Parameters() const {
  FieldWriter fields;
  VisitCircleTrackerFields(options_, fields);
  return fields.parameters;
}

TrackResult CircleTracker::Track(const Observation& observation) {
  const std::optional<Rigid3> before = previous_cam_from_paper_;
  TrackResult result = FindInFrame(observation);
  last_motion_.reset();
  if (before && previous_cam_from_paper_) {
    last_motion_ = *previous_cam_from_paper_ * before->Inverse();
  }
  return result;
}

TrackResult CircleTracker::FindInFrame(const Observation& observation) {
  if (auto unusable = UnusableImage(observation)) return *unusable;
  const MarkerSpec& marker = *observation.marker;
  std::string error;
  const std::optional<CircleGeometry> geometry = CircleGeometryOf(marker, &error);
  if (!geometry) return CannotTrack("the circle tracker", marker, error);
  const Image8& image = *observation.image;
  const cv::Rect whole(0, 0, image.width, image.height);
  const std::optional<double> last_prediction_error_px = prediction_error_px_;
  prediction_error_px_.reset();
  if (options_.tracking && previous_cam_from_paper_) {
    // The pose predicted for this frame, and the marker's image there.
    const Camera& camera = *observation.camera;
    const Rigid3 predicted_pose = options_.predict_motion && last_motion_
                                      ? *last_motion_ * *previous_cam_from_paper_
                                      : *previous_cam_from_paper_;
    const std::optional<PredictedImage> prediction =
        PredictImage(*geometry, camera, predicted_pose, options_.roi_margin, whole);
    if (prediction) {
      // The fit on the pixels from the prediction where the last pose came from one and the
      // last prediction was good (kMaxLastPredictionErrorPx), then the predicted ellipses, then
      // a search of the region, then the whole image. A result counts only where its ellipses
      // are the predicted ones: otherwise the prediction says nothing about this frame (a cut,
      // a jump, unrelated images), and the frame gets exactly the full detection a first frame
      // gets, never a lock on the old pose.
      const auto found_as_predicted = [&](const TrackResult& result) {
        if (result.status != TrackStatus::kOk ||
            !MatchPrediction(diagnostics_, *prediction, options_.max_prediction_error)) {
          return false;
        }
        prediction_error_px_ =
            PredictionErrorPx(*geometry, camera, *previous_cam_from_paper_, *prediction);
        return true;
      };
      const std::optional<PixelFitFound> last_on_pixels = previous_on_pixels_;
      const PredictedPose predicted{
          predicted_pose, previous_cam_from_paper_->rotation.col(2), tilt_log_ratio_};
      if (last_on_pixels) {
        const bool held =
            last_prediction_error_px && *last_prediction_error_px <= kMaxLastPredictionErrorPx;
        const std::optional<PredictedPose> start =
            held ? predicted : AlignedByEdges(observation, *geometry, predicted, *last_on_pixels);
        if (start) {
          const TrackResult result = TrackOnPixels(observation, *geometry, *start, *last_on_pixels);
          diagnostics_.used_tracking_region = true;
          diagnostics_.aligned_by_edge_shifts = !held;
          if (found_as_predicted(result)) return result;
        }
      }
      const std::vector<Eigen::Matrix3d>* const starts[] = {&prediction->through_lens.conics_px,
                                                            nullptr};
      for (const std::vector<Eigen::Matrix3d>* start : starts) {
        TrackResult result = TrackIn(observation,
                                     *geometry,
                                     prediction->region,
                                     start,
                                     &predicted,
                                     last_on_pixels ? &*last_on_pixels : nullptr);
        diagnostics_.used_tracking_region = true;
        diagnostics_.used_predicted_ellipses = start != nullptr;
        if (found_as_predicted(result)) return result;
      }
    }
  }
  TrackResult result = TrackIn(observation, *geometry, whole, nullptr, nullptr, nullptr);
  diagnostics_.used_tracking_region = false;
  return result;
}

TrackResult CircleTracker::TrackIn(const Observation& observation,
                                   const CircleGeometry& geometry,
                                   const cv::Rect& region,
                                   const std::vector<Eigen::Matrix3d>* predicted_conics_px,
                                   const PredictedPose* predicted,
                                   const PixelFitFound* last_on_pixels) {
  diagnostics_ = CircleDiagnostics{};
  previous_cam_from_paper_.reset();
  previous_on_pixels_.reset();
  TrackResult result;
  const Camera& camera = *observation.camera;
  const Eigen::Matrix3d K = camera.K();

  std::string why;
  // The fit on the pixels of disks (a-d) takes the pose from the image: the edges need only
  // start it.
  CircleDetectorOptions detector_options = options_.detector;
  detector_options.edges_start_a_pixel_fit =
      options_.refine && options_.photometric && !geometry.roll_from_design;
  const CircleDetector detector(*observation.marker, geometry, detector_options);
  std::optional<MarkerDetection> detection =
      detector.Detect(*observation.image, region, predicted_conics_px, &why);
  if (!detection) {
    result.status = TrackStatus::kNotDetected;
    result.message = why;
    return result;
  }
  diagnostics_.noise_sigma = detection->noise_sigma;

  // Lens distortion: move edges and points to the ideal pinhole image, refit the conics.
  CircleMeasurements measurements;
  RefinementProblem problem;
  problem.K = K;
  for (size_t i = 0; i < detection->circles.size(); ++i) {
    DetectedCircle& circle = detection->circles[i];
    if (camera.HasDistortion()) {
      for (Eigen::Vector2d& p : circle.edges.points_px) p = camera.IdealFromImg(p);
      const std::optional<ConicFit> fit = FitEllipse(circle.edges.points_px, options_.detector.fit);
      if (!fit) {
        result.status = TrackStatus::kPoseFailed;
        result.message = "undistorted edges give no ellipse";
        return result;
      }
      circle.conic_px = fit->conic;
    }
    measurements.conics_px.push_back(circle.conic_px);
    diagnostics_.conics_px.push_back(circle.conic_px);
    diagnostics_.edges.push_back(circle.edges.points_px);
    diagnostics_.edge_passes.push_back(circle.edge_passes);
    diagnostics_.blur_sigma_px = std::max(diagnostics_.blur_sigma_px, circle.edges.sigma_px);
    RefinementCircle rc;
    rc.center = geometry.centers[i];
    rc.radius_m = geometry.radii_m[i];
    rc.edge_points_px = circle.edges.points_px;
    rc.conic_px = circle.conic_px;
    problem.circles.push_back(std::move(rc));
  }
  // The fitted σ includes the detector's smoothing; the image's own is what remains.
  diagnostics_.image_blur_sigma_px = std::sqrt(std::max(
      0.1, std::pow(diagnostics_.blur_sigma_px, 2) - std::pow(detection->smoothing_sigma_px, 2)));
  if (detection->m0_px)
    measurements.m0_px =
        camera.HasDistortion() ? camera.IdealFromImg(*detection->m0_px) : *detection->m0_px;
  if (detection->m1_px)
    measurements.m1_px =
        camera.HasDistortion() ? camera.IdealFromImg(*detection->m1_px) : *detection->m1_px;
  diagnostics_.m1_px = measurements.m1_px;

  // Point terms (erratum 7): m0 where it is a detected dot, m1 where no circle gives it.
  if (measurements.m0_px && geometry.layout == CircleLayout::kCircleWithCenter) {
    problem.points.push_back({Eigen::Vector2d::Zero(), *measurements.m0_px});
  }
  if (measurements.m1_px && geometry.m1_circle < 0) {
    problem.points.push_back({Eigen::Vector2d(geometry.Lx, 0.0), *measurements.m1_px});
  }

  const std::optional<AnalyticSolution> analytic =
      SolveAnalytic(geometry, K, measurements, options_.analytic, &why);
  if (!analytic) {
    result.status = TrackStatus::kPoseFailed;
    result.message = why;
    return result;
  }
  diagnostics_.l_inf_norm = analytic->l_inf_norm;
  const Rigid3 paper_from_marker = geometry.marker_from_paper.Inverse();
  diagnostics_.analytic_cam_from_marker = analytic->pose.cam_from_paper * paper_from_marker;

  // The refinement starts from whichever start explains the image best: in tracking mode the
  // analytic pose or the predicted one; otherwise every analytic candidate, since with small
  // or blurred ellipses the chosen l_inf can land in the wrong basin.
  std::vector<Rigid3> starts;
  if (predicted) {
    starts.push_back(predicted->cam_from_paper);
  } else {
    for (const AnalyticSolution& candidate :
         AnalyticCandidates(geometry, K, measurements, options_.analytic.depth)) {
      starts.push_back(candidate.pose.cam_from_paper);
    }
  }
  auto refined_from_best = [&](Rigid3 start, const std::vector<Rigid3>& others) {
    if (!options_.refine) return start;
    double best_cost = RefinementCostAt(problem, start, options_.refinement);
    for (const Rigid3& other : others) {
      const double cost = RefinementCostAt(problem, other, options_.refinement);
      if (cost < best_cost) {
        best_cost = cost;
        start = other;
      }
    }
    const RefinementResult refined = RefinePose(problem, start, options_.refinement);
    diagnostics_.iterations = refined.iterations;
    diagnostics_.final_cost = refined.final_cost;
    return refined.cam_from_paper;
  };
  Rigid3 cam_from_paper = refined_from_best(analytic->pose.cam_from_paper, starts);

  // e, f: the circle (and e's nose) are blind to the roll, and f's circle alone to which of
  // its two tilts is seen (§4.7). The design inside the circle gives the roll and its centre
  // m0 (roll_feature.h), and whether it shows.
  std::optional<RollFeature> feature;
  if (geometry.roll_from_design) feature.emplace(*observation.marker, geometry);
  const double paper_level = detection->circles[0].edges.outside_level;
  auto align = [&](const Rigid3& pose, bool fit_center) {
    return feature->Align(*observation.image,
                          camera,
                          pose,
                          paper_level,
                          diagnostics_.image_blur_sigma_px,
                          255.0 * diagnostics_.noise_sigma,
                          fit_center);
  };
  if (geometry.roll_from_design) {
    const double radius_px = camera.fx * geometry.radii_m[0] / cam_from_paper.translation.norm();
    if (!(radius_px >= options_.min_design_radius_per_blur * diagnostics_.image_blur_sigma_px)) {
      result.status = TrackStatus::kNotDetected;
      result.message = "the design inside the circle is too blurred to read: radius " +
                       NumberText(radius_px) + " px < min_design_radius_per_blur x blur " +
                       NumberText(diagnostics_.image_blur_sigma_px) + " px";
      return result;
    }
    // m0 becomes the point term (for e in place of the nose's centroid), the pose is refined
    // again, and the roll fitted at that pose.
    std::optional<RollAlignment> aligned = align(cam_from_paper, true);
    if (aligned) {
      const Eigen::Vector3d center =
          aligned->cam_from_paper *
          Eigen::Vector3d(aligned->center_m.x(), aligned->center_m.y(), 0);
      problem.points = {{Eigen::Vector2d::Zero(), (K * center).hnormalized()}};
      cam_from_paper = refined_from_best(aligned->cam_from_paper, starts);
      aligned = align(cam_from_paper, false);
    }
    if (!aligned) {
      result.status = TrackStatus::kNotDetected;
      result.message = "the design inside the circle does not show";
      return result;
    }
    if (!aligned->shows_design) {
      result.status = TrackStatus::kNotDetected;
      result.message = "the design inside the circle does not fit the image: misfit " +
                       NumberText(aligned->misfit) + ", level " +
                       NumberText(aligned->design_level) + ", contrast ratio " +
                       NumberText(aligned->contrast_ratio) + " +- " +
                       NumberText(aligned->contrast_ratio_error);
      return result;
    }
    cam_from_paper = aligned->cam_from_paper;
  }
  // The ellipses are accepted on the edge fit (below); the pixels' fit runs only then: on
  // ellipses that do not fit (most of them clutter) it would cost its time for nothing.
  const double ellipses_rms_px = EdgeRmsPx(problem, cam_from_paper);
  diagnostics_.edge_rms_px = ellipses_rms_px;
  PixelFitFound on_pixels;
  std::optional<Rigid3> second_hypothesis;
  double tilt_evidence = 0.0;  // for the pose's tilt (ChooseTilt); 0 without the fit on the pixels
  if (options_.refine && options_.photometric && ellipses_rms_px <= options_.max_edge_rms_px) {
    const std::vector<Rigid3> starts =
        PixelFitStarts(problem, geometry.roll_from_design, cam_from_paper, ellipses_rms_px);
    const std::optional<FitOnPixels> direct = OnPixels(observation,
                                                       geometry.roll_from_design,
                                                       starts,
                                                       paper_from_marker,
                                                       predicted,
                                                       last_on_pixels,
                                                       &on_pixels);
    // Kept unless it leaves the edges (a fit gone astray: the pixels and the edge points
    // measure the same edges) by more than half a pixel RMS. For (e) and (f) the edge points
    // under blur are pulled by the design next to the rim (f's wedge meets it) by up to a
    // pixel or two, and the tilt they fit may be the circle's other one, so there anything
    // within the ellipses' acceptance goes too, and the design must still show there (a fit
    // of clutter can leave the design behind).
    if (direct) {
      const Rigid3 on_pixels = direct->cam_from_marker * geometry.marker_from_paper;
      const double rms = EdgeRmsPx(problem, on_pixels);
      const bool keeps_the_edges = rms <= ellipses_rms_px + 0.5;
      if (geometry.roll_from_design) {
        const std::optional<RollAlignment> at_pixels = align(on_pixels, false);
        diagnostics_.photometric_used = (keeps_the_edges || rms <= options_.max_edge_rms_px) &&
                                        at_pixels && at_pixels->shows_design;
      } else {
        diagnostics_.photometric_used = keeps_the_edges;
      }
      if (diagnostics_.photometric_used) {
        cam_from_paper = on_pixels;
        diagnostics_.edge_rms_px = rms;
        // The other tilt's fit, where it ended there, and where the pixels hardly tell the two
        // apart (far away, under blur, near the pixels' limit): a second hypothesis.
        tilt_evidence = direct->tilt_log_ratio;
        if (direct->other_tilt) {
          diagnostics_.second_tilt_log_ratio = direct->tilt_log_ratio;
          if (direct->tilt_log_ratio <= options_.max_second_hypothesis_log_ratio) {
            second_hypothesis = direct->other_tilt;
          }
        }
      }
    }
  }

  if (geometry.roll_from_design) {
    // m1 as the design places it, for the tracking mode's check of the prediction.
    diagnostics_.m1_px =
        (K * (cam_from_paper * Eigen::Vector3d(geometry.Lx, 0.0, 0.0))).hnormalized();
  }

  // Acceptance: the marker in front of the camera, and its projected circles on the edges.
  const Rigid3 cam_from_marker = cam_from_paper * paper_from_marker;
  diagnostics_.refined_cam_from_marker = cam_from_marker;
  if (!FacesTheCamera(cam_from_paper)) {
    result.status = TrackStatus::kPoseFailed;
    result.message = "the pose puts the marker behind the camera";
    return result;
  }
  if (!(ellipses_rms_px <= options_.max_edge_rms_px)) {
    result.status = TrackStatus::kNotDetected;
    result.message =
        "ellipses rejected: edge residual " + NumberText(ellipses_rms_px) + " px > max_edge_rms_px";
    return result;
  }
  result = Accept(observation, cam_from_paper, cam_from_marker, second_hypothesis);
  if (result.status == TrackStatus::kOk) tilt_log_ratio_ = tilt_evidence;
  if (result.status == TrackStatus::kOk && diagnostics_.photometric_used &&
      !geometry.roll_from_design) {
    KeepPixelFit(on_pixels);
  }
  return result;
}

std::optional<CircleTracker::PredictedPose> CircleTracker::AlignedByEdges(
    const Observation& observation,
    const CircleGeometry& geometry,
    const PredictedPose& predicted,
    const PixelFitFound& last) const {
  // None where the alignment is off, or for a single circle, whose edges fit both its tilts
  // alike (§4.7) and so never rule the other out.
  if (!options_.edge_shift.enabled || geometry.radii_m.size() < 2) return std::nullopt;
  const CircleDetector detector(*observation.marker, geometry, options_.detector);
  std::vector<CircleDetector::EdgeClearance> clearances;
  for (size_t i = 0; i < geometry.radii_m.size(); ++i) {
    clearances.push_back(detector.ClearanceOf(i));
  }
  const std::optional<EdgeShiftAlignment> aligned = AlignByEdgeShifts(*observation.image,
                                                                      *observation.camera,
                                                                      *observation.marker,
                                                                      geometry,
                                                                      clearances,
                                                                      predicted.cam_from_paper,
                                                                      last.levels,
                                                                      last.edge_sigma_px,
                                                                      options_.edge_shift,
                                                                      nullptr);
  // Where the edges leave the circle's other tilt open, the search fits both (PixelFitStarts);
  // the fit from this pose alone would keep the tilt predicted.
  if (!aligned || (TiltsApart(OtherTilt(aligned->cam_from_paper), aligned->cam_from_paper) &&
                   EdgesLeaveTheOtherTilt(aligned->cam_from_paper,
                                          aligned->other_tilt,
                                          aligned->points_kept,
                                          aligned->rms_px,
                                          aligned->other_tilt_rms_px))) {
    return std::nullopt;
  }
  PredictedPose moved = predicted;
  moved.cam_from_paper = aligned->cam_from_paper;
  return moved;
}

TrackResult CircleTracker::TrackOnPixels(const Observation& observation,
                                         const CircleGeometry& geometry,
                                         const PredictedPose& predicted,
                                         const PixelFitFound& last) {
  diagnostics_ = CircleDiagnostics{};
  diagnostics_.tracked_on_pixels = true;
  previous_cam_from_paper_.reset();
  previous_on_pixels_.reset();
  TrackResult result;
  result.status = TrackStatus::kNotDetected;
  // Where the frames before leave the tilt unsettled, both are fitted (the search): one fit says
  // nothing of its other tilt's likelihood. (Its distance in standard errors, squared, is no
  // measure of it: the other tilt is a minimum of its own, not the fit's quadratic bowl
  // extended. On receding videos at 2.5 m it was 150-1,300 where the two tilts' fits differed
  // by 2 ln Λ 0.1-6, and a fit that slid to the other tilt kept it for the rest of the video.)
  if (TiltsApart(OtherTilt(predicted.cam_from_paper), predicted.cam_from_paper) &&
      !(predicted.tilt_log_ratio > options_.max_second_hypothesis_log_ratio)) {
    result.message = "the frames before leave the tilt unsettled: 2 ln of its odds " +
                     NumberText(predicted.tilt_log_ratio);
    return result;
  }
  const Camera& camera = *observation.camera;
  const Rigid3 paper_from_marker = geometry.marker_from_paper.Inverse();
  const std::optional<PixelRefinement> fit =
      RefinePhotometric(*observation.image,
                        camera,
                        *observation.marker,
                        predicted.cam_from_paper * paper_from_marker,
                        last.edge_sigma_px,
                        last.noise_sigma,
                        options_.photometric_refinement,
                        last.levels);
  if (!fit) {
    result.message = "no fit on the pixels from the predicted pose";
    return result;
  }
  const Rigid3& cam_from_marker = fit->fit.cam_from_marker;
  const Rigid3 cam_from_paper = cam_from_marker * geometry.marker_from_paper;
  const PixelFitFound found{EdgeSigmaOfBlur(fit->fit.sigma_px), fit->noise_sigma, fit->fit.levels};
  diagnostics_.blur_sigma_px = diagnostics_.image_blur_sigma_px = found.edge_sigma_px;
  diagnostics_.noise_sigma = found.noise_sigma;
  diagnostics_.photometric_used = true;
  diagnostics_.refined_cam_from_marker = cam_from_marker;
  // The fitted pose's ellipses (for the check against the prediction), each whole in the frame
  // as the lens forms it: a marker leaving it has edges the fit does not see.
  const MarkerImage fitted_image = MarkerImagedAt(geometry, camera, cam_from_paper);
  diagnostics_.conics_px = fitted_image.conics_px;
  const std::optional<MarkerImage> seen =
      MarkerImageThroughLens(geometry, camera, cam_from_paper, fitted_image);
  const cv::Rect2d frame(0.0, 0.0, observation.image->width, observation.image->height);
  bool within_frame = seen.has_value();
  if (seen) {
    for (const Eigen::Matrix3d& conic_px : seen->conics_px) {
      const cv::Rect2d box = EllipseBox(conic_px);
      within_frame = within_frame && (box & frame) == box;
    }
  }
  diagnostics_.m1_px = fitted_image.m1_px;
  if (!within_frame) {
    result.message = "the marker's image at the fitted pose leaves the frame";
    return result;
  }
  for (int gain = 1; gain < found.levels.size(); gain += 2) {
    if (!(found.levels[gain] >= last.levels[gain] / kMaxContrastChange &&
          found.levels[gain] <= last.levels[gain] * kMaxContrastChange)) {
      result.message = "the fit's contrast " + NumberText(found.levels[gain]) + " in channel " +
                       std::to_string(gain / 2) + ", the last frame's " +
                       NumberText(last.levels[gain]);
      return result;
    }
  }
  if (!(found.noise_sigma <= kMaxNoiseGrowth * last.noise_sigma)) {
    result.message = "the fit's residuals show noise " + NumberText(255.0 * found.noise_sigma) +
                     " grey levels, the last frame's " + NumberText(255.0 * last.noise_sigma);
    return result;
  }
  // A fit that slid to the circle's other tilt needs both fitted too.
  const Rigid3 other = OtherTilt(cam_from_paper);
  if (TiltsApart(other, cam_from_paper) && !ContinuesTilt(cam_from_paper, other, predicted)) {
    result.message = "the fit from the prediction slid to the circle's other tilt";
    return result;
  }
  // The design's check starts at the lattice the last frame's decided on: where its noise left
  // the coarse one undecided, it would again (the orbit's tracked frames at σ² 0.1: each of
  // them, which took 0.89 of their time before; at σ² 0.02 the coarse one decides).
  result = Accept(observation, cam_from_paper, cam_from_marker, std::nullopt, last.appearance_grid);
  if (result.status == TrackStatus::kOk) KeepPixelFit(found);
  return result;
}

void CircleTracker::KeepPixelFit(PixelFitFound found) {
  found.appearance_grid = diagnostics_.appearance_grid;
  previous_on_pixels_ = std::move(found);
}

TrackResult CircleTracker::Accept(const Observation& observation,
                                  const Rigid3& cam_from_paper,
                                  const Rigid3& cam_from_marker,
                                  const std::optional<Rigid3>& second_hypothesis,
                                  int first_grid) {
  TrackResult result;
  const Camera& camera = *observation.camera;
  AppearanceOptions appearance_options = options_.appearance;
  appearance_options.coarse_grid = std::max(appearance_options.coarse_grid, first_grid);
  const AppearanceFit appearance = CheckPrintedAppearance(*observation.image,
                                                          camera,
                                                          *observation.marker,
                                                          cam_from_marker,
                                                          diagnostics_.image_blur_sigma_px,
                                                          appearance_options);
  diagnostics_.appearance_misfit = appearance.misfit;
  diagnostics_.appearance_grid = appearance.grid;
  if (!appearance.ShowsMarker()) {
    result.status = TrackStatus::kNotDetected;
    result.message = "the image does not show the marker's design there: misfit " +
                     NumberText(appearance.misfit) + " (" + NumberText(appearance.significance) +
                     " standard errors) > max_appearance_misfit";
    return result;
  }
  result.status = TrackStatus::kOk;
  result.hypotheses = {cam_from_marker};
  if (second_hypothesis) result.hypotheses.push_back(*second_hypothesis);
  for (const Eigen::Vector2d& k : observation.marker->keypoints) {
    result.keypoints_px.push_back(
        camera.ImgFromCam(cam_from_marker * Eigen::Vector3d(k.x(), k.y(), 0.0)));
  }
  previous_cam_from_paper_ = cam_from_paper;
  return result;
}

bool CircleTracker::TiltsApart(const Rigid3& cam_from_plane, const Rigid3& other) const {
  return cam_from_plane.rotation.col(2).dot(other.rotation.col(2)) <
         std::cos(options_.min_branch_angle_rad);
}

bool CircleTracker::ContinuesTilt(const Rigid3& cam_from_paper,
                                  const Rigid3& other,
                                  const PredictedPose& predicted) {
  return cam_from_paper.rotation.col(2).dot(predicted.tracked_normal) >=
         other.rotation.col(2).dot(predicted.tracked_normal);
}

std::vector<Rigid3> CircleTracker::PixelFitStarts(const RefinementProblem& problem,
                                                  bool whole_design,
                                                  const Rigid3& cam_from_paper,
                                                  double edge_rms_px) const {
  // The circle fixes its tilt only up to the other of its two (§4.7), and so, far away or
  // under heavy blur, do the edge points of two small disks, or (e, f) the centre point; the
  // pixels tell the two apart, so the fit on them starts from the other too, unless the two
  // nearly coincide (near fronto-parallel).
  const Rigid3 other = OtherTilt(cam_from_paper);
  if (!TiltsApart(other, cam_from_paper)) return {cam_from_paper};
  if (whole_design) return {cam_from_paper, other};
  // Disks: the other tilt's basin, where the edge points have one and do not rule it out.
  const Rigid3 refined = RefinePose(problem, other, options_.refinement).cam_from_paper;
  size_t edge_points = 0;
  for (const RefinementCircle& circle : problem.circles) {
    edge_points += circle.edge_points_px.size();
  }
  if (EdgesLeaveTheOtherTilt(
          cam_from_paper, refined, edge_points, edge_rms_px, EdgeRmsPx(problem, refined))) {
    return {cam_from_paper, refined};
  }
  return {cam_from_paper};
}

bool CircleTracker::EdgesLeaveTheOtherTilt(const Rigid3& cam_from_paper,
                                           const Rigid3& other_fitted,
                                           size_t edge_points,
                                           double edge_rms_px,
                                           double other_rms_px) const {
  const double log_ratio =
      edge_points * (other_rms_px * other_rms_px / (edge_rms_px * edge_rms_px) - 1.0);
  return TiltsApart(other_fitted, cam_from_paper) && log_ratio < options_.max_other_tilt_log_ratio;
}

CircleTracker::FitOnPixels CircleTracker::ChooseTilt(
    const Rigid3& marker_from_paper,
    const PredictedPose* predicted,
    std::vector<RankedFit<PixelRefinement>>* fits) const {
  const auto pose = [&](size_t i) -> const Rigid3& {
    return (*fits)[i].result.fit.cam_from_marker;
  };
  const Rigid3 first = pose(0) * marker_from_paper;
  const double limit = options_.max_carried_tilt_log_ratio;
  const auto carried_for = [&](const Rigid3& on_paper, const Rigid3& other_on_paper) {
    const bool continues = ContinuesTilt(on_paper, other_on_paper, *predicted);
    return (continues ? 1.0 : -1.0) * std::clamp(predicted->tilt_log_ratio, -limit, limit);
  };
  if (fits->size() < 2 || !TiltsApart(pose(1) * marker_from_paper, first)) {
    const Rigid3 other = OtherTilt(first);
    if (!TiltsApart(other, first)) return {pose(0), std::nullopt, 0.0};
    // The other tilt's fit was given up or ended on this one: ruled out, unless that is the
    // tilt tracked, whose evidence then stands against this fit (the fit from the tracked tilt
    // slid over, by an amount of likelihood unknown). Where that evidence stands against the tilt
    // tracked and this fit continues it, it moves by kMergedFitLogRatio toward this fit.
    const double carried = predicted ? carried_for(first, other) : 0.0;
    if (carried < 0.0 && ContinuesTilt(first, other, *predicted)) {
      return {pose(0), std::nullopt, carried + kMergedFitLogRatio};
    }
    if (carried < 0.0) return {pose(0), std::nullopt, carried};
    return {pose(0), std::nullopt, std::numeric_limits<double>::infinity()};
  }
  double evidence = (*fits)[1].log_ratio - (*fits)[0].log_ratio;
  if (predicted) {
    evidence += carried_for(first, pose(1) * marker_from_paper);
    if (evidence < 0.0) {
      std::swap((*fits)[0], (*fits)[1]);
      evidence = -evidence;
    }
  }
  return {pose(0), pose(1), evidence};
}

std::optional<CircleTracker::FitOnPixels> CircleTracker::OnPixels(
    const Observation& observation,
    bool whole_design,
    const std::vector<Rigid3>& cam_from_paper_starts,
    const Rigid3& paper_from_marker,
    const PredictedPose* predicted,
    const PixelFitFound* last,
    PixelFitFound* found) const {
  const Image8& image = *observation.image;
  const Camera& camera = *observation.camera;
  const MarkerSpec& marker = *observation.marker;
  const double sigma_px = diagnostics_.image_blur_sigma_px;
  const Rigid3 marker_from_paper = paper_from_marker.Inverse();
  std::vector<Rigid3> starts;
  for (const Rigid3& start : cam_from_paper_starts) starts.push_back(start * paper_from_marker);
  if (whole_design) {
    const DesignRefinementOptions& options = options_.design_refinement;
    std::vector<RankedFit<PixelRefinement>> fits = RefineDesignFromStarts(
        image, camera, marker, starts, sigma_px, diagnostics_.noise_sigma, options);
    if (fits.empty()) return std::nullopt;
    return ChooseTilt(marker_from_paper, predicted, &fits);
  }
  // A tracked frame's fit starts from the levels and noise the last one found.
  const double noise_sigma = last ? last->noise_sigma : diagnostics_.noise_sigma;
  std::optional<Eigen::VectorXd> levels;
  if (last) levels = last->levels;
  std::vector<RankedFit<PixelRefinement>> fits =
      RefinePhotometricFromStarts(image,
                                  camera,
                                  marker,
                                  starts,
                                  sigma_px,
                                  noise_sigma,
                                  options_.photometric_refinement,
                                  levels);
  if (fits.empty()) return std::nullopt;
  const FitOnPixels chosen = ChooseTilt(marker_from_paper, predicted, &fits);
  const PixelRefinement& fit = fits[0].result;
  *found = {EdgeSigmaOfBlur(fit.fit.sigma_px), fit.noise_sigma, fit.fit.levels};
  return chosen;
}

std::unique_ptr<Tracker> MakeCircleTracker(const CircleTrackerOptions& options) {
  return std::make_unique<CircleTracker>(options);
}

}  // namespace markerbench
