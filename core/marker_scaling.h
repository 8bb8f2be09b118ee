// Equal-area scaling (experiments.md, "Equal image area"): every marker of a scenario is
// scaled about its origin so that its ink bounding box has the same area, like the red boxes
// of the paper's Fig. 5.
#pragma once

#include "core/marker_spec.h"

namespace markerbench {

// `marker` with every length (shapes, circles, size_m, keypoints) times `factor` > 0.
MarkerSpec ScaledMarker(const MarkerSpec& marker, double factor);

// The factor that gives `marker` an ink bounding box of `area_m2`.
double EqualAreaFactor(const MarkerSpec& marker, double area_m2);

}  // namespace markerbench
