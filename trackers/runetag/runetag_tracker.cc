#include "trackers/runetag/runetag_tracker.h"

#include <limits>
#include <sstream>

#include "core/codes/runetag_cyclic_code.h"
#include "core/number_text.h"
#include "core/yaml_reader.h"
#include "trackers/grey_image.h"

namespace markerbench {

bool RuneTagTracker::CanTrack(const MarkerSpec& marker) const {
  return marker.kind == MarkerKind::kRuneTag;
}

TrackResult RuneTagTracker::Track(const Observation& obs) {
  if (auto unusable = UnusableImage(obs)) return *unusable;
  const MarkerSpec& marker = *obs.marker;
  if (!CanTrack(marker)) return CannotTrack("the runetag tracker", marker);
  diagnostics_ = {};
  GreyImage grey(*obs.image);
  const cv::Mat grey_mat(grey.height(), grey.width(), CV_8UC1, grey.data());
  // The original reads the image as it is; only our detector smooths it against the noise.
  const DotImage image =
      options_.original_dots ? DotImage{grey_mat, 0.0} : SmoothForDots(grey_mat, options_.dots);
  const std::vector<ImagedDot> dots = options_.original_dots
                                          ? DetectEllipsesAsOriginal(grey_mat, options_.ellipses)
                                          : DetectDots(image, options_.dots);
  diagnostics_.dots = static_cast<int>(dots.size());
  TrackResult result;
  const std::optional<RingMatch> match = MatchRings(dots,
                                                    image,
                                                    *obs.camera,
                                                    static_cast<uint64_t>(options_.ransac_seed),
                                                    marker.id,
                                                    options_.rings);
  if (!match) return result;  // not_detected
  diagnostics_.ring_dots = match->ring_dots;
  diagnostics_.matched = static_cast<int>(match->dot_slots.size());
  diagnostics_.mismatches = match->mismatches;
  diagnostics_.erasures = match->erasures;
  if (match->id != marker.id) {
    result.status = TrackStatus::kWrongId;
    return result;
  }
  // Keypoints are the printed dots in slot order: index them by slot.
  const RuneWord& codeword = RuneCodeword(marker.id);
  std::vector<int> keypoint_of_slot(3 * kRuneSectors, -1);
  int next = 0;
  for (int s = 0; s < kRuneSectors; ++s) {
    for (int r = 0; r < 3; ++r) {
      if (codeword[s] & (4 >> r)) keypoint_of_slot[3 * s + r] = next++;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  result.keypoints_px.assign(marker.keypoints.size(), Eigen::Vector2d(nan, nan));
  std::vector<Eigen::Vector2d> centers_px, dots_xy;
  std::vector<double> radii_m;
  for (const auto& [dot, slot] : match->dot_slots) {
    const int k = keypoint_of_slot[slot];
    centers_px.push_back(dots[dot].center_px);
    dots_xy.push_back(marker.keypoints[k]);
    radii_m.push_back(marker.keypoints[k].norm() / kRuneDotRadiusRatio);
    result.keypoints_px[k] = dots[dot].center_px;
  }
  DotPoseOptions pose_options = options_.pose;
  pose_options.ransac_seed = static_cast<uint64_t>(options_.ransac_seed);
  const std::optional<DotPose> pose =
      EstimateDotPose(centers_px, dots_xy, radii_m, *obs.camera, pose_options);
  if (!pose) {
    result.status = TrackStatus::kPoseFailed;
    return result;
  }
  diagnostics_.inliers = pose->inliers;
  diagnostics_.rms_px = pose->rms_px;
  result.hypotheses = {pose->cam_from_marker};
  result.status = TrackStatus::kOk;
  return result;
}

std::vector<std::pair<std::string, std::string>> RuneTagTracker::Parameters() const {
  const RuneTagOptions& o = options_;
  const OriginalEllipseOptions& e = o.ellipses;
  return {{"dot_detector", o.original_dots ? "original" : "ours"},
          {"ellipse_block_size_px", NumberText(e.block_size_px)},
          {"ellipse_threshold_offset", NumberText(e.threshold_offset)},
          {"ellipse_min_contour_points", NumberText(e.min_contour_points)},
          {"ellipse_max_contour_points", NumberText(e.max_contour_points)},
          {"ellipse_min_area_px", NumberText(e.min_area_px)},
          {"ellipse_max_area_px", NumberText(e.max_area_px)},
          {"ellipse_min_axis_ratio", NumberText(e.min_axis_ratio)},
          {"ellipse_max_fit_error", NumberText(e.max_fit_error)},
          {"ellipse_size_compensation_px", NumberText(e.size_compensation_px)},
          {"smoothing_per_noise", NumberText(o.dots.smoothing_per_noise)},
          {"max_smoothing_px", NumberText(o.dots.max_smoothing_px)},
          {"block_size_px", NumberText(o.dots.block_size_px)},
          {"threshold_offset", NumberText(o.dots.threshold_offset)},
          {"offset_per_noise", NumberText(o.dots.offset_per_noise)},
          {"min_area_px", NumberText(o.dots.min_area_px)},
          {"max_area_px", NumberText(o.dots.max_area_px)},
          {"min_axis_ratio", NumberText(o.dots.min_axis_ratio)},
          {"min_contrast", NumberText(o.dots.min_contrast)},
          {"contrast_per_noise", NumberText(o.dots.contrast_per_noise)},
          {"max_fit_error", NumberText(o.dots.max_fit_error)},
          {"ring_tolerance_px", NumberText(o.rings.ring_tolerance_px)},
          {"ring_tolerance_radii", NumberText(o.rings.ring_tolerance_radii)},
          {"neighbour_reach", NumberText(o.rings.neighbour_reach)},
          {"radius_tolerance", NumberText(o.rings.radius_tolerance)},
          {"angle_tolerance", NumberText(o.rings.angle_tolerance)},
          {"min_slot_contrast", NumberText(o.rings.min_slot_contrast)},
          {"slot_contrast_per_noise", NumberText(o.rings.slot_contrast_per_noise)},
          {"slot_margin", NumberText(o.rings.slot_margin)},
          {"max_dot_growth", NumberText(o.rings.max_dot_growth)},
          {"exclude_next_to_errors", BoolText(o.rings.exclude_next_to_errors)},
          {"read_slot_levels", BoolText(o.rings.read_slot_levels)},
          {"decode_missing_dots", BoolText(o.rings.decode_missing_dots)},
          {"undistort_dots", BoolText(o.rings.undistort_dots)},
          {"max_ransac_iterations", NumberText(o.rings.max_ransac_iterations)},
          {"ransac", BoolText(o.pose.ransac)},
          {"ransac_reprojection_px", NumberText(o.pose.ransac_reprojection_px)},
          {"refinement_passes", NumberText(o.pose.refinement_passes)},
          {"ransac_seed", NumberText(o.ransac_seed)}};
}

bool RuneTagOptions::IsValid(std::string* error) const {
  std::ostringstream msg;
  if (ellipses.block_size_px < 3 || ellipses.block_size_px % 2 == 0) {
    msg << "ellipse_block_size_px=" << ellipses.block_size_px << " must be odd and >= 3";
  } else if (ellipses.min_contour_points < 5 ||
             ellipses.max_contour_points < ellipses.min_contour_points) {
    msg << "ellipse_min_contour_points=" << ellipses.min_contour_points
        << " must be >= 5 (cv::fitEllipse) and <= ellipse_max_contour_points";
  } else if (!(ellipses.min_area_px >= 0.0 && ellipses.max_area_px > ellipses.min_area_px)) {
    msg << "ellipse_min_area_px=" << ellipses.min_area_px
        << " must be >= 0 and below ellipse_max_area_px";
  } else if (!(ellipses.min_axis_ratio > 0.0 && ellipses.min_axis_ratio <= 1.0)) {
    msg << "ellipse_min_axis_ratio=" << ellipses.min_axis_ratio << " must be in (0, 1]";
  } else if (!(ellipses.max_fit_error > 0.0)) {
    msg << "ellipse_max_fit_error=" << ellipses.max_fit_error << " must be > 0";
  } else if (!(dots.smoothing_per_noise >= 0.0 && dots.max_smoothing_px >= 0.0)) {
    msg << "smoothing_per_noise=" << dots.smoothing_per_noise
        << " and max_smoothing_px must be >= 0";
  } else if (!(dots.offset_per_noise >= 0.0)) {
    msg << "offset_per_noise=" << dots.offset_per_noise << " must be >= 0";
  } else if (dots.block_size_px < 3 || dots.block_size_px % 2 == 0) {
    msg << "block_size_px=" << dots.block_size_px << " must be odd and >= 3";
  } else if (!(dots.min_area_px > 0.0 && dots.max_area_px > dots.min_area_px)) {
    msg << "min_area_px=" << dots.min_area_px << " must be > 0 and below max_area_px";
  } else if (!(dots.min_axis_ratio > 0.0 && dots.min_axis_ratio <= 1.0)) {
    msg << "min_axis_ratio=" << dots.min_axis_ratio << " must be in (0, 1]";
  } else if (!(dots.max_fit_error > 0.0)) {
    msg << "max_fit_error=" << dots.max_fit_error << " must be > 0";
  } else if (!(rings.ring_tolerance_px > 0.0 && rings.radius_tolerance > 0.0 &&
               rings.angle_tolerance > 0.0 && rings.angle_tolerance <= 0.5)) {
    msg << "ring_tolerance_px=" << rings.ring_tolerance_px
        << " and radius_tolerance must be > 0, angle_tolerance in (0, 0.5]";
  } else if (!(rings.ring_tolerance_radii > 0.0 && rings.neighbour_reach > 0.0)) {
    msg << "ring_tolerance_radii=" << rings.ring_tolerance_radii
        << " and neighbour_reach must be > 0";
  } else if (!(rings.min_slot_contrast >= 0.0 && rings.slot_contrast_per_noise >= 0.0)) {
    msg << "min_slot_contrast=" << rings.min_slot_contrast
        << " and slot_contrast_per_noise must be >= 0";
  } else if (!(rings.slot_margin >= 0.0 && rings.slot_margin < 0.5)) {
    msg << "slot_margin=" << rings.slot_margin << " must be in [0, 0.5)";
  } else if (!(rings.max_dot_growth >= 1.0 || rings.max_dot_growth == 0.0)) {
    msg << "max_dot_growth=" << rings.max_dot_growth << " must be >= 1, or 0 (off)";
  } else if (rings.max_ransac_iterations < 1 || pose.ransac_iterations < 1 ||
             pose.refinement_passes < 0 || !(pose.ransac_reprojection_px > 0.0)) {
    msg << "max_ransac_iterations=" << rings.max_ransac_iterations
        << " must be >= 1, refinement_passes >= 0, ransac_reprojection_px > 0";
  } else if (ransac_seed < 0) {
    msg << "ransac_seed=" << ransac_seed << " must be >= 0";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

RuneTagOptions RuneTagOptions::Improved() {
  RuneTagOptions o;
  o.original_dots = false;
  o.rings.read_slot_levels = true;
  o.rings.decode_missing_dots = true;
  o.rings.radius_tolerance = 0.04;
  o.rings.angle_tolerance = 0.3;
  o.rings.max_dot_growth = 1.5;
  o.rings.exclude_next_to_errors = false;
  o.rings.undistort_dots = true;
  o.pose.ransac = true;
  o.pose.refinement_passes = 5;
  return o;
}

RuneTagOptions RuneTagOptions::FromYaml(const YamlMap& map, const RuneTagOptions& base) {
  RuneTagOptions o = base;
  const std::string detector =
      map.GetOr<std::string>("dot_detector", base.original_dots ? "original" : "ours");
  if (detector != "original" && detector != "ours") map.Fail("dot_detector", "original or ours");
  o.original_dots = detector == "original";
  OriginalEllipseOptions& e = o.ellipses;
  e.block_size_px = map.GetOr<int>("ellipse_block_size_px", e.block_size_px);
  e.threshold_offset = map.GetOr<double>("ellipse_threshold_offset", e.threshold_offset);
  e.min_contour_points = map.GetOr<int>("ellipse_min_contour_points", e.min_contour_points);
  e.max_contour_points = map.GetOr<int>("ellipse_max_contour_points", e.max_contour_points);
  e.min_area_px = map.GetOr<double>("ellipse_min_area_px", e.min_area_px);
  e.max_area_px = map.GetOr<double>("ellipse_max_area_px", e.max_area_px);
  e.min_axis_ratio = map.GetOr<double>("ellipse_min_axis_ratio", e.min_axis_ratio);
  e.max_fit_error = map.GetOr<double>("ellipse_max_fit_error", e.max_fit_error);
  e.size_compensation_px =
      map.GetOr<double>("ellipse_size_compensation_px", e.size_compensation_px);
  o.dots.smoothing_per_noise = map.GetOr<double>("smoothing_per_noise", o.dots.smoothing_per_noise);
  o.dots.max_smoothing_px = map.GetOr<double>("max_smoothing_px", o.dots.max_smoothing_px);
  o.dots.block_size_px = map.GetOr<int>("block_size_px", o.dots.block_size_px);
  o.dots.threshold_offset = map.GetOr<double>("threshold_offset", o.dots.threshold_offset);
  o.dots.offset_per_noise = map.GetOr<double>("offset_per_noise", o.dots.offset_per_noise);
  o.dots.min_area_px = map.GetOr<double>("min_area_px", o.dots.min_area_px);
  o.dots.max_area_px = map.GetOr<double>("max_area_px", o.dots.max_area_px);
  o.dots.min_axis_ratio = map.GetOr<double>("min_axis_ratio", o.dots.min_axis_ratio);
  o.dots.min_contrast = map.GetOr<double>("min_contrast", o.dots.min_contrast);
  o.dots.contrast_per_noise = map.GetOr<double>("contrast_per_noise", o.dots.contrast_per_noise);
  o.dots.max_fit_error = map.GetOr<double>("max_fit_error", o.dots.max_fit_error);
  o.rings.ring_tolerance_px = map.GetOr<double>("ring_tolerance_px", o.rings.ring_tolerance_px);
  o.rings.ring_tolerance_radii =
      map.GetOr<double>("ring_tolerance_radii", o.rings.ring_tolerance_radii);
  o.rings.neighbour_reach = map.GetOr<double>("neighbour_reach", o.rings.neighbour_reach);
  o.rings.radius_tolerance = map.GetOr<double>("radius_tolerance", o.rings.radius_tolerance);
  o.rings.angle_tolerance = map.GetOr<double>("angle_tolerance", o.rings.angle_tolerance);
  o.rings.min_slot_contrast = map.GetOr<double>("min_slot_contrast", o.rings.min_slot_contrast);
  o.rings.slot_contrast_per_noise =
      map.GetOr<double>("slot_contrast_per_noise", o.rings.slot_contrast_per_noise);
  o.rings.slot_margin = map.GetOr<double>("slot_margin", o.rings.slot_margin);
  o.rings.max_dot_growth = map.GetOr<double>("max_dot_growth", o.rings.max_dot_growth);
  o.rings.exclude_next_to_errors =
      map.GetOr<bool>("exclude_next_to_errors", o.rings.exclude_next_to_errors);
  o.rings.read_slot_levels = map.GetOr<bool>("read_slot_levels", o.rings.read_slot_levels);
  o.rings.decode_missing_dots = map.GetOr<bool>("decode_missing_dots", o.rings.decode_missing_dots);
  o.rings.undistort_dots = map.GetOr<bool>("undistort_dots", o.rings.undistort_dots);
  o.rings.max_ransac_iterations =
      map.GetOr<int>("max_ransac_iterations", o.rings.max_ransac_iterations);
  o.pose.ransac = map.GetOr<bool>("ransac", o.pose.ransac);
  o.pose.ransac_reprojection_px =
      map.GetOr<double>("ransac_reprojection_px", o.pose.ransac_reprojection_px);
  o.pose.refinement_passes = map.GetOr<int>("refinement_passes", o.pose.refinement_passes);
  o.ransac_seed = map.GetOr<int>("ransac_seed", o.ransac_seed);
  FinishOptions(map, o);
  return o;
}

std::unique_ptr<Tracker> MakeRuneTagTracker(const RuneTagOptions& options) {
  return std::make_unique<RuneTagTracker>(options);
}

}  // namespace markerbench
