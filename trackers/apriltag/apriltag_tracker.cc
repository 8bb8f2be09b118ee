#include "trackers/apriltag/apriltag_tracker.h"

#include <apriltag/apriltag.h>
#include <apriltag/apriltag_pose.h>
#include <apriltag/common/matd.h>

#include <cstdlib>
#include <memory>
#include <sstream>
#include <vector>

#include "core/marker_bits.h"
#include "core/number_text.h"
#include "core/option_fields.h"
#include "core/yaml_reader.h"
#include "trackers/grey_image.h"
#include "trackers/square_pose.h"

namespace markerbench {
namespace {

// libapriltag puts pixel centres at +0.5 (baselines.md): its corners sit 0.5 px right and
// down of ours.
constexpr double kAprilTagPixelOffset = 0.5;

// AprilTag's tag frame has y down and z into the tag; ours has y up and z out.
const Eigen::Matrix3d kTagFromMarker = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();

// AprilTagOptions' keys, read and written (core/option_fields.h).
template <typename Options, typename Fields>
void VisitAprilTagFields(Options& o, Fields&& fields) {
  fields("family", o.family);
  fields("quad_decimate", o.quad_decimate);
  fields("quad_sigma", o.quad_sigma);
  fields("refine_edges", o.refine_edges);
  fields("decode_sharpening", o.decode_sharpening);
  fields("nthreads", o.nthreads);
  fields("max_hamming", o.max_hamming);
}

struct DetectionsDeleter {
  void operator()(zarray_t* detections) const { apriltag_detections_destroy(detections); }
};

class AprilTagTracker final : public Tracker {
 public:
  AprilTagTracker(const AprilTagOptions& options, AprilTagPose pose)
      : options_(options),
        pose_(pose),
        family_(CreateAprilTagFamily(options.family)),
        detector_(apriltag_detector_create(), apriltag_detector_destroy) {
    apriltag_detector_add_family_bits(
        detector_.get(), static_cast<apriltag_family_t*>(family_.get()), options.max_hamming);
    detector_->quad_decimate = static_cast<float>(options.quad_decimate);
    detector_->quad_sigma = static_cast<float>(options.quad_sigma);
    detector_->refine_edges = options.refine_edges;
    detector_->decode_sharpening = options.decode_sharpening;
    detector_->nthreads = options.nthreads;
  }

  bool CanTrack(const MarkerSpec& marker) const override {
    return marker.kind == MarkerKind::kAprilTag && marker.family == options_.family;
  }

  TrackResult Track(const Observation& obs) override {
    if (auto unusable = UnusableImage(obs)) return *unusable;
    const MarkerSpec& marker = *obs.marker;
    if (!CanTrack(marker)) {
      return CannotTrack("the apriltag tracker (family " + options_.family + ")", marker);
    }
    TrackResult result;
    GreyImage grey(*obs.image);
    image_u8_t image{grey.width(), grey.height(), grey.width(), grey.data()};
    const std::unique_ptr<zarray_t, DetectionsDeleter> detections(
        apriltag_detector_detect(detector_.get(), &image));
    apriltag_detection_t* best = nullptr;
    for (int i = 0; i < zarray_size(detections.get()); ++i) {
      apriltag_detection_t* det;
      zarray_get(detections.get(), i, &det);
      if (det->id != marker.id) continue;
      if (!best || det->decision_margin > best->decision_margin) best = det;
    }
    if (!best) {
      result.status =
          zarray_size(detections.get()) > 0 ? TrackStatus::kWrongId : TrackStatus::kNotDetected;
      return result;
    }
    ShiftToOurPixels(best);
    // p[0..3] are the tag-frame corners (-s,+s), (+s,+s), (+s,-s), (-s,-s) with y down, i.e.
    // bottom-left, bottom-right, top-right, top-left in ours: reverse them.
    std::array<Eigen::Vector2d, 4> corners;
    for (int i = 0; i < 4; ++i)
      corners[static_cast<size_t>(i)] = {best->p[3 - i][0], best->p[3 - i][1]};
    result.keypoints_px.assign(corners.begin(), corners.end());

    if (pose_ == AprilTagPose::kIppe) {
      result.hypotheses = SquarePoseHypotheses(corners, marker.size_m, *obs.camera);
    } else if (obs.camera->HasDistortion()) {
      result.status = TrackStatus::kPoseFailed;
      result.message = "estimate_tag_pose assumes no lens distortion; use apriltag-ippe";
      return result;
    } else {
      result.hypotheses.push_back(NativePose(best, marker.size_m, *obs.camera));
    }
    result.status = result.hypotheses.empty() ? TrackStatus::kPoseFailed : TrackStatus::kOk;
    return result;
  }

  std::vector<std::pair<std::string, std::string>> Parameters() const override {
    FieldWriter fields;
    VisitAprilTagFields(options_, fields);
    fields.parameters.push_back(
        {"pose", pose_ == AprilTagPose::kNative ? "estimate_tag_pose" : "ippe_square"});
    fields.parameters.push_back({"pixel_offset_corrected", NumberText(kAprilTagPixelOffset)});
    return fields.parameters;
  }

 private:
  // Moves the detection into our pixel convention: corners, centre and the homography.
  static void ShiftToOurPixels(apriltag_detection_t* det) {
    for (auto& p : det->p) {
      p[0] -= kAprilTagPixelOffset;
      p[1] -= kAprilTagPixelOffset;
    }
    det->c[0] -= kAprilTagPixelOffset;
    det->c[1] -= kAprilTagPixelOffset;
    for (int c = 0; c < 3; ++c) {
      MATD_EL(det->H, 0, c) -= kAprilTagPixelOffset * MATD_EL(det->H, 2, c);
      MATD_EL(det->H, 1, c) -= kAprilTagPixelOffset * MATD_EL(det->H, 2, c);
    }
  }

  static Rigid3 NativePose(apriltag_detection_t* det, double size_m, const Camera& camera) {
    apriltag_detection_info_t info{det, size_m, camera.fx, camera.fy, camera.cx, camera.cy};
    apriltag_pose_t pose{nullptr, nullptr};
    estimate_tag_pose(&info, &pose);
    Rigid3 cam_from_tag;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) cam_from_tag.rotation(r, c) = MATD_EL(pose.R, r, c);
      cam_from_tag.translation[r] = MATD_EL(pose.t, r, 0);
    }
    std::free(pose.R);  // each matd_t is one calloc block; matd_destroy is not exported
    std::free(pose.t);
    return cam_from_tag * Rigid3(kTagFromMarker, Eigen::Vector3d::Zero());
  }

  AprilTagOptions options_;
  AprilTagPose pose_;
  AprilTagFamilyPtr family_;  // outlives detector_, which refers to it
  std::unique_ptr<apriltag_detector_t, void (*)(apriltag_detector_t*)> detector_;
};

}  // namespace

bool AprilTagOptions::IsValid(std::string* error) const {
  std::ostringstream msg;
  if (!(quad_decimate >= 1.0)) {
    msg << "quad_decimate=" << quad_decimate << " must be >= 1";
  } else if (!(quad_sigma >= 0.0)) {
    msg << "quad_sigma=" << quad_sigma << " must be >= 0";
  } else if (!(decode_sharpening >= 0.0)) {
    msg << "decode_sharpening=" << decode_sharpening << " must be >= 0";
  } else if (nthreads < 1) {
    msg << "nthreads=" << nthreads << " must be >= 1";
  } else if (max_hamming < 0 || max_hamming > 3) {
    msg << "max_hamming=" << max_hamming << " must be in [0, 3]";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

AprilTagOptions AprilTagOptions::FromYaml(const YamlMap& map) {
  AprilTagOptions o;
  VisitAprilTagFields(o, FieldReader(map));
  FinishOptions(map, o);
  return o;
}

std::unique_ptr<Tracker> MakeAprilTagTracker(const AprilTagOptions& options, AprilTagPose pose) {
  return std::make_unique<AprilTagTracker>(options, pose);
}

}  // namespace markerbench
