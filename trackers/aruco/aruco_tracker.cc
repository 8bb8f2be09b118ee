#include "trackers/aruco/aruco_tracker.h"

#include <algorithm>
#include <array>
#include <opencv2/aruco.hpp>
#include <sstream>
#include <vector>

#include "core/marker_bits.h"
#include "core/option_fields.h"
#include "core/yaml_reader.h"
#include "trackers/grey_image.h"
#include "trackers/square_pose.h"

namespace markerbench {
namespace {

const std::array<std::pair<const char*, cv::aruco::CornerRefineMethod>, 4> kRefinements = {{
    {"none", cv::aruco::CORNER_REFINE_NONE},
    {"subpix", cv::aruco::CORNER_REFINE_SUBPIX},
    {"contour", cv::aruco::CORNER_REFINE_CONTOUR},
    {"apriltag", cv::aruco::CORNER_REFINE_APRILTAG},
}};

bool RefinementFromName(const std::string& name, cv::aruco::CornerRefineMethod* method) {
  for (const auto& [n, m] : kRefinements) {
    if (name == n) {
      *method = m;
      return true;
    }
  }
  return false;
}

// ArucoOptions' keys, read and written (core/option_fields.h).
template <typename Options, typename Fields>
void VisitArucoFields(Options& o, Fields&& fields) {
  fields("dictionary", o.dictionary);
  fields("corner_refinement", o.corner_refinement);
  fields("adaptive_thresh_win_size_min", o.adaptive_thresh_win_size_min);
  fields("adaptive_thresh_win_size_max", o.adaptive_thresh_win_size_max);
  fields("adaptive_thresh_win_size_step", o.adaptive_thresh_win_size_step);
  fields("adaptive_thresh_constant", o.adaptive_thresh_constant);
  fields("min_marker_perimeter_rate", o.min_marker_perimeter_rate);
  fields("min_pixels_per_cell", o.min_pixels_per_cell);
  fields("max_marker_perimeter_rate", o.max_marker_perimeter_rate);
  fields("polygonal_approx_accuracy_rate", o.polygonal_approx_accuracy_rate);
  fields("corner_refinement_win_size", o.corner_refinement_win_size);
  fields("corner_refinement_max_iterations", o.corner_refinement_max_iterations);
  fields("corner_refinement_min_accuracy", o.corner_refinement_min_accuracy);
  fields("error_correction_rate", o.error_correction_rate);
}

class ArucoTracker final : public Tracker {
 public:
  explicit ArucoTracker(const ArucoOptions& o)
      : options_(o),
        dictionary_(cv::aruco::getPredefinedDictionary(
            static_cast<cv::aruco::PREDEFINED_DICTIONARY_NAME>(ArucoDictionaryId(o.dictionary)))),
        parameters_(cv::aruco::DetectorParameters::create()) {
    cv::aruco::CornerRefineMethod method = cv::aruco::CORNER_REFINE_SUBPIX;
    RefinementFromName(o.corner_refinement, &method);
    parameters_->cornerRefinementMethod = method;
    parameters_->adaptiveThreshWinSizeMin = o.adaptive_thresh_win_size_min;
    parameters_->adaptiveThreshWinSizeMax = o.adaptive_thresh_win_size_max;
    parameters_->adaptiveThreshWinSizeStep = o.adaptive_thresh_win_size_step;
    parameters_->adaptiveThreshConstant = o.adaptive_thresh_constant;
    parameters_->minMarkerPerimeterRate = o.min_marker_perimeter_rate;
    parameters_->maxMarkerPerimeterRate = o.max_marker_perimeter_rate;
    parameters_->polygonalApproxAccuracyRate = o.polygonal_approx_accuracy_rate;
    parameters_->cornerRefinementWinSize = o.corner_refinement_win_size;
    parameters_->cornerRefinementMaxIterations = o.corner_refinement_max_iterations;
    parameters_->cornerRefinementMinAccuracy = o.corner_refinement_min_accuracy;
    parameters_->errorCorrectionRate = o.error_correction_rate;
    const int cells_per_side = dictionary_->markerSize + 2 * parameters_->markerBorderBits;
    min_perimeter_px_ = 4.0 * cells_per_side * o.min_pixels_per_cell;
  }

  bool CanTrack(const MarkerSpec& marker) const override {
    return marker.kind == MarkerKind::kAruco && marker.family == options_.dictionary;
  }

  TrackResult Track(const Observation& obs) override {
    if (auto unusable = UnusableImage(obs)) return *unusable;
    const MarkerSpec& marker = *obs.marker;
    if (!CanTrack(marker)) {
      return CannotTrack("the aruco tracker (" + options_.dictionary + ")", marker);
    }
    TrackResult result;
    GreyImage grey(*obs.image);
    const cv::Mat image(grey.height(), grey.width(), CV_8UC1, grey.data());
    // OpenCV scales the rate by the image's larger side.
    parameters_->minMarkerPerimeterRate =
        std::max(options_.min_marker_perimeter_rate,
                 min_perimeter_px_ / std::max(grey.width(), grey.height()));
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    cv::aruco::detectMarkers(image, dictionary_, corners, ids, parameters_);
    int found = -1;
    for (size_t i = 0; i < ids.size(); ++i) {
      if (ids[i] == marker.id) found = static_cast<int>(i);
    }
    if (found < 0) {
      result.status = ids.empty() ? TrackStatus::kNotDetected : TrackStatus::kWrongId;
      return result;
    }
    // detectMarkers returns corners clockwise from the top-left: our square order.
    std::array<Eigen::Vector2d, 4> px;
    for (size_t k = 0; k < 4; ++k) {
      px[k] = {corners[static_cast<size_t>(found)][k].x, corners[static_cast<size_t>(found)][k].y};
    }
    result.keypoints_px.assign(px.begin(), px.end());
    result.hypotheses = SquarePoseHypotheses(px, marker.size_m, *obs.camera);
    result.status = result.hypotheses.empty() ? TrackStatus::kPoseFailed : TrackStatus::kOk;
    return result;
  }

  std::vector<std::pair<std::string, std::string>> Parameters() const override {
    FieldWriter fields;
    VisitArucoFields(options_, fields);
    fields.parameters.push_back({"pose", "ippe_square"});
    return fields.parameters;
  }

 private:
  ArucoOptions options_;
  cv::Ptr<cv::aruco::Dictionary> dictionary_;
  cv::Ptr<cv::aruco::DetectorParameters> parameters_;
  double min_perimeter_px_ = 0.0;  // min_pixels_per_cell's floor
};

}  // namespace

bool ArucoOptions::IsValid(std::string* error) const {
  std::ostringstream msg;
  cv::aruco::CornerRefineMethod method;
  if (!RefinementFromName(corner_refinement, &method)) {
    msg << "corner_refinement=" << corner_refinement
        << " must be none, subpix, contour or apriltag";
  } else if (adaptive_thresh_win_size_min < 3 ||
             adaptive_thresh_win_size_max < adaptive_thresh_win_size_min ||
             adaptive_thresh_win_size_step < 1) {
    msg << "adaptive_thresh_win_size_min=" << adaptive_thresh_win_size_min
        << " must be >= 3, <= adaptive_thresh_win_size_max, with step >= 1";
  } else if (!(min_marker_perimeter_rate > 0.0 &&
               max_marker_perimeter_rate > min_marker_perimeter_rate)) {
    msg << "min_marker_perimeter_rate=" << min_marker_perimeter_rate
        << " must be > 0 and below max_marker_perimeter_rate";
  } else if (!(min_pixels_per_cell >= 0.0 && min_pixels_per_cell <= 1000.0)) {
    msg << "min_pixels_per_cell=" << min_pixels_per_cell << " must be in [0, 1000]";
  } else if (!(polygonal_approx_accuracy_rate > 0.0)) {
    msg << "polygonal_approx_accuracy_rate=" << polygonal_approx_accuracy_rate << " must be > 0";
  } else if (corner_refinement_win_size < 1 || corner_refinement_max_iterations < 1 ||
             !(corner_refinement_min_accuracy > 0.0)) {
    msg << "corner_refinement_win_size=" << corner_refinement_win_size
        << " and the iteration limits must be positive";
  } else if (!(error_correction_rate >= 0.0 && error_correction_rate <= 1.0)) {
    msg << "error_correction_rate=" << error_correction_rate << " must be in [0, 1]";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

ArucoOptions ArucoOptions::FromYaml(const YamlMap& map) {
  ArucoOptions o;
  VisitArucoFields(o, FieldReader(map));
  try {
    ArucoDictionaryId(o.dictionary);
  } catch (const std::invalid_argument& e) {
    map.Fail("dictionary", e.what());
  }
  FinishOptions(map, o);
  return o;
}

std::unique_ptr<Tracker> MakeArucoTracker(const ArucoOptions& options) {
  return std::make_unique<ArucoTracker>(options);
}

}  // namespace markerbench
