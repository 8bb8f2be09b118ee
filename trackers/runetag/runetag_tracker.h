// `runetag`: a faithful re-implementation of RUNETag (Bergamasco et al., TPAMI 2016;
// baselines.md), not a wrapper: the original is not in Debian and its code must not be
// copied. Per frame: the original's ellipse detector (DetectEllipsesAsOriginal), a ring
// found and rectified with K, the dots' sectors decoded (MatchRings), then the original's
// solvePnP on every matched dot (EstimateDotPose). RuneTagOptions::Improved() is
// `runetag-improved`, the same markers with our detector: DetectDots, slot levels and lost
// dots decoded, RANSAC PnP, LM and the perspective-bias refinement. The differences that
// remain in `runetag` are listed in the README.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "trackers/runetag/dot_detector.h"
#include "trackers/runetag/dot_pose.h"
#include "trackers/runetag/original_ellipse_detector.h"
#include "trackers/runetag/ring_decoder.h"
#include "trackers/tracker.h"

namespace markerbench {

class YamlMap;

struct RuneTagOptions {
  bool original_dots = true;  // DetectEllipsesAsOriginal; false: DetectDots
  OriginalEllipseOptions ellipses;
  DotDetectorOptions dots;
  RingDecoderOptions rings;
  DotPoseOptions pose;
  int ransac_seed = 1;  // both RANSACs restart from this seed every frame (reproducible)

  // `runetag-improved`: our dot detector, slot levels and lost dots decoded, RANSAC PnP with
  // the perspective-bias refinement.
  static RuneTagOptions Improved();

  bool IsValid(std::string* error) const;
  // Flat keys named as the fields of the options structs (the original detector's with an
  // `ellipse_` prefix; `dot_detector: original | ours`), the keys Parameters() lists, each
  // defaulting to `base`'s (the original's in the one-argument form). Throws ConfigError
  // naming the file and key.
  static RuneTagOptions FromYaml(const YamlMap& map, const RuneTagOptions& base);
  static RuneTagOptions FromYaml(const YamlMap& map) { return FromYaml(map, RuneTagOptions()); }
};

// Every stage of the last Track call (style.md, item 4).
struct RuneTagDiagnostics {
  int dots = 0;        // dot candidates found
  int ring_dots = 0;   // dots on the ring conic used to rectify
  int matched = 0;     // dots matched to a slot of the decoded codeword
  int mismatches = 0;  // sectors read with another symbol
  int erasures = 0;    // sectors with no dot seen
  int inliers = 0;     // RANSAC PnP inliers (the pose's support)
  double rms_px = 0.0;
};

class RuneTagTracker final : public Tracker {
 public:
  explicit RuneTagTracker(const RuneTagOptions& options = {}) : options_(options) {}
  TrackResult Track(const Observation& observation) override;
  bool CanTrack(const MarkerSpec& marker) const override;
  std::vector<std::pair<std::string, std::string>> Parameters() const override;

  const RuneTagDiagnostics& diagnostics() const { return diagnostics_; }

 private:
  RuneTagOptions options_;
  RuneTagDiagnostics diagnostics_;
};

std::unique_ptr<Tracker> MakeRuneTagTracker(const RuneTagOptions& options);

}  // namespace markerbench
