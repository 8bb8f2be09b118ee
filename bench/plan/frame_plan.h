// Expands a scenario into its frames: for each cell (a value of the first sweep axis at one
// combination of a grid's other axes), trial and marker, the pose (paired: the same
// cam_from_center for every marker), degradations and seeds.
#pragma once

#include <functional>
#include <vector>

#include "bench/plan/scenario.h"
#include "core/rigid3.h"
#include "renderer/render_frame.h"

namespace markerbench {

struct PlannedFrame {
  int index = 0;
  int cell = 0;
  int trial = 0;
  int marker_index = 0;
  double sweep_value = 0.0;
  // The grid's other axes at this cell, "tilt_deg=30;noise_var=0.02" (GridText); empty for
  // a one-axis sweep.
  std::string grid;
  // Trial 0 at the example value (and the grid's first combination): the example image.
  bool example = false;
  Rigid3 cam_from_marker;
  Degradations degradations;
  int channels = 1;
  uint64_t noise_seed = 0;
  // Sequences (Scenario::trajectory): the frame's place in its sequence (-1: not a
  // sequence; its truth is at the trajectory's TruthTime), whether the marker is hidden, and
  // the moving camera's pose from the frame's start (FrameRequest::cam_from_marker_at; empty
  // without exposure_s or readout_s).
  int sequence_frame = -1;
  bool occluded = false;
  std::function<Rigid3(double)> cam_from_marker_at;
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

// "p1=v1;p2=v2" for the grid axes' values at `indices`.
std::string GridText(const std::vector<SweepAxis>& axes, const std::vector<size_t>& indices);

// Frames in (cell, trial, marker) order (and for sequences, the sequence's frames in order
// within each), cells with the first axis fastest and the grid's
// axes after it in file order; at most `limit` frames (0: all).
std::vector<PlannedFrame> PlanFrames(const Scenario& scenario, int limit = 0);

// What to render for `frame`; refers to the scenario's marker and camera.
FrameRequest RequestFor(const Scenario& scenario, const PlannedFrame& frame);

}  // namespace markerbench
