// Expands a scenario into its frames: for each sweep value (cell), trial and marker, the
// pose (paired: the same cam_from_center for every marker), degradations and seeds.
#pragma once

#include <vector>

#include "bench/scenario.h"
#include "core/rigid3.h"
#include "renderer/render_frame.h"

namespace markerbench {

struct PlannedFrame {
  int index = 0;
  int cell = 0;
  int trial = 0;
  int marker_index = 0;
  double sweep_value = 0.0;
  Rigid3 cam_from_marker;
  Degradations degradations;
  int channels = 1;
  uint64_t noise_seed = 0;
};

// The closed range of a sweep parameter's values, the same as its render or poses key's.
struct ValueRange {
  double lo;
  double hi;
};
ValueRange SweepRange(const std::string& parameter);

// Sets the sweep parameter to `value`; throws std::invalid_argument when out of range.
void ApplySweepValue(const std::string& parameter,
                     double value,
                     PoseSamplerOptions* poses,
                     Degradations* degradations);

// Frames in (cell, trial, marker) order; at most `limit` (0: all).
std::vector<PlannedFrame> PlanFrames(const Scenario& scenario, int limit = 0);

// What to render for `frame`; refers to the scenario's marker and camera.
FrameRequest RequestFor(const Scenario& scenario, const PlannedFrame& frame);

}  // namespace markerbench
