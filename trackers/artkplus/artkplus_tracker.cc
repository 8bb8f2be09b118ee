#include "trackers/artkplus/artkplus_tracker.h"

#include <array>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/option_fields.h"
#include "core/random.h"
#include "core/yaml_reader.h"
#include "trackers/artkplus/contour_trace.h"
#include "trackers/artkplus/pattern_reader.h"
#include "trackers/grey_image.h"

namespace markerbench {
namespace {

struct Detection {
  std::array<Eigen::Vector2d, 4> corners_px;  // our order: top-left, top-right, ...
  PatternRead pattern;
};

struct Detections {
  std::vector<Detection> decoded;
  int squares = 0;  // regions whose contour has four vertices
};

// ArtkPlusOptions' keys, read and written (core/option_fields.h).
template <typename Options, typename Fields>
void VisitArtkPlusFields(Options& o, Fields&& fields) {
  fields.Choice("threshold_mode",
                o.threshold_mode,
                {{ArtkPlusThreshold::kAuto, "auto"}, {ArtkPlusThreshold::kFixed, "fixed"}});
  fields("threshold", o.threshold);
  fields("auto_threshold_retries", o.auto_threshold_retries);
  fields("auto_threshold_seed", o.auto_threshold_seed);
  fields("retry_only_without_squares", o.retry_only_without_squares);
  fields("min_area_px", o.regions.min_area_px);
  fields("max_area_px", o.regions.max_area_px);
  fields("side_trim", o.quad.side_trim);
  fields("subpixel_edges", o.quad.subpixel_edges);
  fields("truncated_samples", o.pattern.truncated_samples);
  fields("pattern_samples", o.pattern.samples_per_side);
  fields("bits_at_threshold", o.bits_at_threshold);
  fields("max_corrected_bits", o.pattern.max_corrected_bits);
  fields("min_code_contrast", o.pattern.min_code_contrast);
  fields("min_confidence", o.min_confidence);
  fields.Choice(
      "pose", o.pose, {{ArtkPlusPose::kRobustPlanar, "rpp"}, {ArtkPlusPose::kClassic, "classic"}});
}

class ArtkPlusTracker final : public Tracker {
 public:
  explicit ArtkPlusTracker(const ArtkPlusOptions& options) : options_(options) { Reset(); }

  bool CanTrack(const MarkerSpec& marker) const override {
    return marker.kind == MarkerKind::kArtkPlus;
  }

  void Reset() override {
    threshold_ = options_.threshold;
    retry_rng_ = Rng(static_cast<uint64_t>(options_.auto_threshold_seed));
  }

  TrackResult Track(const Observation& obs) override {
    if (auto unusable = UnusableImage(obs)) return *unusable;
    const MarkerSpec& marker = *obs.marker;
    if (!CanTrack(marker)) return CannotTrack("the artkplus tracker", marker);
    const std::optional<ArtkPlusIdMode> mode = ArtkPlusIdModeFromString(marker.family);
    if (!mode) return CannotTrack("the artkplus tracker", marker, "unknown id mode");
    GreyImage grey(*obs.image);

    Detections found_now = Detect(grey, threshold_, *mode, marker, *obs.camera);
    const bool automatic = options_.threshold_mode == ArtkPlusThreshold::kAuto;
    const auto missed = [&] {
      return options_.retry_only_without_squares ? found_now.squares == 0
                                                 : found_now.decoded.empty();
    };
    for (int retry = 0; automatic && missed() && retry < options_.auto_threshold_retries; ++retry) {
      const int threshold = 10 + static_cast<int>(retry_rng_.NextU64() % 230);
      found_now = Detect(grey, threshold, *mode, marker, *obs.camera);
    }
    const std::vector<Detection>& detections = found_now.decoded;

    TrackResult result;
    const Detection* found = nullptr;
    for (const Detection& d : detections) {
      if (d.pattern.id == marker.id &&
          (!found || d.pattern.confidence > found->pattern.confidence)) {
        found = &d;
      }
    }
    if (!found) {
      result.status = detections.empty() ? TrackStatus::kNotDetected : TrackStatus::kWrongId;
      return result;
    }
    if (automatic) {
      threshold_ = static_cast<int>(
          std::lround(0.5 * (found->pattern.min_level + found->pattern.max_level)));
    }
    result.keypoints_px.assign(found->corners_px.begin(), found->corners_px.end());
    result.hypotheses = Pose(found->corners_px, marker, *obs.camera);
    result.status = result.hypotheses.empty() ? TrackStatus::kPoseFailed : TrackStatus::kOk;
    return result;
  }

  std::vector<std::pair<std::string, std::string>> Parameters() const override {
    FieldWriter fields;
    VisitArtkPlusFields(options_, fields);
    return fields.parameters;
  }

 private:
  Detections Detect(GreyImage& grey,
                    int threshold,
                    ArtkPlusIdMode mode,
                    const MarkerSpec& marker,
                    const Camera& camera) const {
    DarkRegionOptions region_options = options_.regions;
    region_options.threshold = threshold;
    const DarkRegions regions =
        FindDarkRegions(grey.data(), grey.width(), grey.height(), region_options);
    const int border_cells = marker.border_fraction == 0.125 ? 1 : 3;
    PatternReadOptions pattern_options = options_.pattern;
    if (options_.bits_at_threshold) pattern_options.bit_threshold = threshold;
    Detections detections;
    for (const DarkRegion& region : regions.regions) {
      const std::vector<Eigen::Vector2i> contour = TraceOuterContour(regions, region);
      const std::optional<std::array<size_t, 4>> vertices =
          FindQuadVertices(contour, region, options_.quad);
      if (!vertices) continue;
      ++detections.squares;
      const auto fit_corners = [&](double edge_level) {
        return FitQuadCorners(
            contour, *vertices, grey.data(), edge_level, regions, camera, options_.quad);
      };
      std::optional<std::array<Eigen::Vector2d, 4>> corners = fit_corners(threshold);
      if (!corners) continue;
      std::array<Eigen::Vector2d, 4> quad = *corners;
      if (pattern_options.truncated_samples) {
        for (size_t k = 0; k < 4; ++k) {
          quad[k] = contour[(*vertices)[k] % contour.size()].cast<double>();
        }
      }
      const std::optional<PatternRead> pattern = ReadPattern(grey.data(),
                                                             grey.width(),
                                                             grey.height(),
                                                             quad,
                                                             border_cells,
                                                             mode,
                                                             camera,
                                                             pattern_options);
      if (!pattern || pattern->confidence < options_.min_confidence) continue;
      if (options_.quad.subpixel_edges) {
        // Refit on the crossings of the level halfway between this marker's ink and paper.
        const double edge_level = 0.5 * (pattern->min_level + pattern->max_level);
        corners = fit_corners(edge_level);
        if (!corners) continue;
      }
      Detection detection{{}, *pattern};
      for (int k = 0; k < 4; ++k) {
        detection.corners_px[k] = (*corners)[(pattern->top_left + k) % 4];
      }
      detections.decoded.push_back(detection);
    }
    return detections;
  }

  std::vector<Rigid3> Pose(const std::array<Eigen::Vector2d, 4>& corners_px,
                           const MarkerSpec& marker,
                           const Camera& camera) const {
    std::array<Eigen::Vector2d, 4> rays;
    for (size_t k = 0; k < 4; ++k) rays[k] = camera.CamFromImg(corners_px[k]).hnormalized();
    if (options_.pose == ArtkPlusPose::kClassic) {
      const std::optional<Rigid3> pose = ClassicSquarePose(rays, marker.size_m, options_.classic);
      return pose ? std::vector<Rigid3>{*pose} : std::vector<Rigid3>{};
    }
    std::vector<Rigid3> hypotheses;
    for (const PlanarPoseHypothesis& h :
         RobustPlanarPose({marker.keypoints.begin(), marker.keypoints.end()},
                          {rays.begin(), rays.end()},
                          options_.robust_planar)) {
      hypotheses.push_back(h.cam_from_marker);
    }
    return hypotheses;
  }

  ArtkPlusOptions options_;
  int threshold_ = 100;
  Rng retry_rng_{1};
};

}  // namespace

bool ArtkPlusOptions::IsValid(std::string* error) const {
  std::ostringstream msg;
  if (threshold < 1 || threshold > 255) {
    msg << "threshold=" << threshold << " must be in [1, 255]";
  } else if (auto_threshold_retries < 0 || auto_threshold_seed < 0) {
    msg << "auto_threshold_retries=" << auto_threshold_retries
        << " and auto_threshold_seed=" << auto_threshold_seed << " must be >= 0";
  } else if (regions.min_area_px < 1 || regions.max_area_px < regions.min_area_px) {
    msg << "min_area_px=" << regions.min_area_px << " must be >= 1 and <= max_area_px";
  } else if (!(quad.side_trim >= 0.0 && quad.side_trim < 0.5)) {
    msg << "side_trim=" << quad.side_trim << " must be in [0, 0.5)";
  } else if (pattern.samples_per_side < 1 || pattern.samples_per_side > 8) {
    msg << "pattern_samples=" << pattern.samples_per_side << " must be in [1, 8]";
  } else if (pattern.max_corrected_bits < 0) {
    msg << "max_corrected_bits=" << pattern.max_corrected_bits << " must be >= 0";
  } else if (!(pattern.min_code_contrast >= 0.0 && pattern.min_code_contrast <= 1.0)) {
    msg << "min_code_contrast=" << pattern.min_code_contrast << " must be in [0, 1]";
  } else if (!(min_confidence >= 0.0 && min_confidence <= 1.0)) {
    msg << "min_confidence=" << min_confidence << " must be in [0, 1]";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

ArtkPlusOptions ArtkPlusOptions::Improved() {
  ArtkPlusOptions o;
  o.retry_only_without_squares = false;
  o.quad.subpixel_edges = true;
  o.pattern.truncated_samples = false;
  o.pattern.samples_per_side = 3;
  o.bits_at_threshold = false;
  o.pattern.max_corrected_bits = 2;
  o.pattern.min_code_contrast = 0.3;
  return o;
}

ArtkPlusOptions ArtkPlusOptions::FromYaml(const YamlMap& map, const ArtkPlusOptions& base) {
  ArtkPlusOptions o = base;
  VisitArtkPlusFields(o, FieldReader(map));
  FinishOptions(map, o);
  return o;
}

std::unique_ptr<Tracker> MakeArtkPlusTracker(const ArtkPlusOptions& options) {
  return std::make_unique<ArtkPlusTracker>(options);
}

}  // namespace markerbench
