// AprilTag through Debian's libapriltag 3.3 (baselines.md): `apriltag` (the library's pose,
// estimate_tag_pose) and `apriltag-ippe` (the same detections, IPPE_SQUARE pose, both
// hypotheses). libapriltag types stay in the .cc.
#pragma once

#include <memory>
#include <string>

#include "trackers/tracker.h"

namespace markerbench {

class YamlMap;

// Detector fields mirror apriltag_detector_t; defaults are apriltag_detector_create()'s,
// except nthreads (1: the harness parallelises over frames).
struct AprilTagOptions {
  std::string family = "tag36h11";  // any libapriltag family
  double quad_decimate = 2.0;       // library default 2.0; > 1 speeds up, loses small tags
  double quad_sigma = 0.0;          // Gaussian blur before quads (px); library default 0
  bool refine_edges = true;         // library default true
  double decode_sharpening = 0.25;  // library default 0.25
  int nthreads = 1;                 // library default 1
  int max_hamming = 2;              // bits corrected by apriltag_detector_add_family (default 2)

  bool IsValid(std::string* error) const;
  // Reads the keys above from `map` (all optional); throws ConfigError.
  static AprilTagOptions FromYaml(const YamlMap& map);
};

enum class AprilTagPose { kNative, kIppe };

std::unique_ptr<Tracker> MakeAprilTagTracker(const AprilTagOptions& options, AprilTagPose pose);

}  // namespace markerbench
