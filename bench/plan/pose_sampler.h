// The paper-protocol pose sampler (experiments.md, "Poses"), paired across markers: one
// cam_from_center per (cell, trial), where "center" is each marker's ink-bounds centre.
#pragma once

#include <vector>

#include "bench/plan/scenario.h"
#include "core/random.h"
#include "core/rigid3.h"

namespace markerbench {

// A look-at pose: camera centre at distance_m from the centre, at tilt θ from the normal and
// azimuth φ: C = d (sinθ cosφ, sinθ sinφ, cosθ); optical axis towards the centre, rolled by
// ρ about it; then turned so that the centre projects at image centre + the offset (polar,
// pixels). Angles in radians.
struct LookAt {
  double distance_m = 0.0;
  double tilt = 0.0;
  double azimuth = 0.0;
  double roll = 0.0;
  double offset_px = 0.0;
  double offset_angle = 0.0;
};
Rigid3 LookAtPose(const LookAt& look_at, const Camera& camera);

// One draw: tilt, azimuth and roll uniform in their ranges, the offset uniform in a disk of
// max_offset_px.
LookAt DrawLookAt(const PoseSamplerOptions& options, Rng* rng);
inline Rigid3 SampleCamFromCenter(const PoseSamplerOptions& options,
                                  const Camera& camera,
                                  Rng* rng) {
  return LookAtPose(DrawLookAt(options, rng), camera);
}

// cam_from_marker for a marker whose ink-bounds centre is placed by cam_from_center.
Rigid3 CamFromMarker(const Rigid3& cam_from_center, const MarkerSpec& marker);

// Whether the marker's ink bounds project inside the image with border_px to spare.
bool MarkerFitsInImage(const MarkerSpec& marker,
                       const Camera& camera,
                       const Rigid3& cam_from_marker,
                       double border_px);

// Whether every marker, its ink-bounds centre placed by cam_from_center, fits in the image.
bool MarkersFitInImage(const std::vector<MarkerSpec>& markers,
                       const Camera& camera,
                       const Rigid3& cam_from_center,
                       double border_px);

// The number of draws SamplePairedPose and SampleTrialTrajectory make before they give up.
inline constexpr int kMaxPoseDraws = 1000;

// Draws until every marker fits (deterministic: the same stream for the same seed).
// Throws std::runtime_error after 1000 draws.
Rigid3 SamplePairedPose(const PoseSamplerOptions& options,
                        const Camera& camera,
                        const std::vector<MarkerSpec>& markers,
                        uint64_t seed);

}  // namespace markerbench
