#include "trackers/runetag/runetag_tracker.h"

#include <limits>
#include <sstream>

#include "core/codes/runetag_cyclic_code.h"
#include "core/option_fields.h"
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

namespace {

// RuneTagOptions' keys, read and written (core/option_fields.h).
template <typename Options, typename Fields>
void VisitRuneTagFields(Options& o, Fields&& fields) {
  fields.Choice("dot_detector", o.original_dots, {{true, "original"}, {false, "ours"}});
  fields("ellipse_block_size_px", o.ellipses.block_size_px);
  fields("ellipse_threshold_offset", o.ellipses.threshold_offset);
  fields("ellipse_min_contour_points", o.ellipses.min_contour_points);
  fields("ellipse_max_contour_points", o.ellipses.max_contour_points);
  fields("ellipse_min_area_px", o.ellipses.min_area_px);
  fields("ellipse_max_area_px", o.ellipses.max_area_px);
  fields("ellipse_min_axis_ratio", o.ellipses.min_axis_ratio);
  fields("ellipse_max_fit_error", o.ellipses.max_fit_error);
  fields("ellipse_size_compensation_px", o.ellipses.size_compensation_px);
  fields("smoothing_per_noise", o.dots.smoothing_per_noise);
  fields("max_smoothing_px", o.dots.max_smoothing_px);
  fields("block_size_px", o.dots.block_size_px);
  fields("threshold_offset", o.dots.threshold_offset);
  fields("offset_per_noise", o.dots.offset_per_noise);
  fields("min_area_px", o.dots.min_area_px);
  fields("max_area_px", o.dots.max_area_px);
  fields("min_axis_ratio", o.dots.min_axis_ratio);
  fields("min_contrast", o.dots.min_contrast);
  fields("contrast_per_noise", o.dots.contrast_per_noise);
  fields("max_fit_error", o.dots.max_fit_error);
  fields("ring_tolerance_px", o.rings.ring_tolerance_px);
  fields("ring_tolerance_radii", o.rings.ring_tolerance_radii);
  fields("neighbour_reach", o.rings.neighbour_reach);
  fields("radius_tolerance", o.rings.radius_tolerance);
  fields("angle_tolerance", o.rings.angle_tolerance);
  fields("min_slot_contrast", o.rings.min_slot_contrast);
  fields("slot_contrast_per_noise", o.rings.slot_contrast_per_noise);
  fields("slot_margin", o.rings.slot_margin);
  fields("max_dot_growth", o.rings.max_dot_growth);
  fields("exclude_next_to_errors", o.rings.exclude_next_to_errors);
  fields("read_slot_levels", o.rings.read_slot_levels);
  fields("decode_missing_dots", o.rings.decode_missing_dots);
  fields("undistort_dots", o.rings.undistort_dots);
  fields("max_ransac_iterations", o.rings.max_ransac_iterations);
  fields("ransac", o.pose.ransac);
  fields("ransac_reprojection_px", o.pose.ransac_reprojection_px);
  fields("refinement_passes", o.pose.refinement_passes);
  fields("ransac_seed", o.ransac_seed);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> RuneTagTracker::Parameters() const {
  FieldWriter fields;
  VisitRuneTagFields(options_, fields);
  return fields.parameters;
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
  VisitRuneTagFields(o, FieldReader(map));
  FinishOptions(map, o);
  return o;
}

std::unique_ptr<Tracker> MakeRuneTagTracker(const RuneTagOptions& options) {
  return std::make_unique<RuneTagTracker>(options);
}

}  // namespace markerbench
