// The Cramér-Rao bound of a frame (renderer/pose_crlb.h) as a run gives it: the same columns in
// frames.csv and in a rendered dataset's groundtruth.csv, so that a tracker scored offline
// (`markerbench score`) is compared with the bound of the very frames it saw.
#pragma once

#include <array>
#include <string>

#include "bench/plan/frame_plan.h"
#include "bench/run/frames_csv.h"
#include "renderer/pose_crlb.h"

namespace markerbench {

FrameBound BoundOf(const PoseBound& bound);

// A planned frame's: infinite where the marker is hidden, NaN where the scenario does not ask
// for the bound (crlb: false), else PoseCrlb of its request.
FrameBound PlannedFrameBound(const Scenario& scenario,
                             const PlannedFrame& frame,
                             const FrameRequest& request);

// The columns, as frames.csv names them, and the bound's values in their order.
constexpr size_t kFrameBoundColumns = 7;
const std::array<std::string, kFrameBoundColumns>& FrameBoundColumns();
std::array<double, kFrameBoundColumns> BoundValues(const FrameBound& bound);
FrameBound BoundFromValues(const std::array<double, kFrameBoundColumns>& values);
// Its fields in those columns, each after a comma.
std::string FrameBoundFields(const FrameBound& bound);

}  // namespace markerbench
