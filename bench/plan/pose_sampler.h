// The paper-protocol pose sampler (experiments.md, "Poses"), paired across markers: one
// cam_from_center per (cell, trial), where "center" is each marker's ink-bounds centre.
#pragma once

#include <vector>

#include "bench/plan/scenario.h"
#include "core/random.h"
#include "core/rigid3.h"

namespace markerbench {

// One draw: camera centre at distance_m from the centre, at tilt θ from the normal and
// azimuth φ: C = d (sinθ cosφ, sinθ sinφ, cosθ); optical axis towards the centre, rolled by
// ρ about it; then turned so that the centre projects at image centre + an offset drawn
// uniformly in a disk of max_offset_px.
Rigid3 SampleCamFromCenter(const PoseSamplerOptions& options, const Camera& camera, Rng* rng);

// cam_from_marker for a marker whose ink-bounds centre is placed by cam_from_center.
Rigid3 CamFromMarker(const Rigid3& cam_from_center, const MarkerSpec& marker);

// Whether the marker's ink bounds project inside the image with border_px to spare.
bool MarkerFitsInImage(const MarkerSpec& marker,
                       const Camera& camera,
                       const Rigid3& cam_from_marker,
                       double border_px);

// Draws until every marker fits (deterministic: the same stream for the same seed).
// Throws std::runtime_error after 1000 draws.
Rigid3 SamplePairedPose(const PoseSamplerOptions& options,
                        const Camera& camera,
                        const std::vector<MarkerSpec>& markers,
                        uint64_t seed);

}  // namespace markerbench
