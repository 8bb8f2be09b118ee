// Two trackers (or two settings of one) on the same rendered frames: the paired comparison
// of the refinements' tests.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "core/pose_error.h"
#include "core/random.h"
#include "renderer/test_scenes.h"
#include "testing/square_tracker_testing.h"
#include "trackers/tracker.h"

namespace markerbench {

// Camera-centre errors (m) frame by frame; a frame a tracker does not find counts as +infinity
// (it loses the comparison).
struct PairedErrors {
  std::vector<double> first, second;
  int first_better = 0;  // frames where the first's error is the smaller
  int first_missed = 0, second_missed = 0;
};

// `frames` frames of `marker` from the default camera at `distance_m`, tilted 10-40° and rolled
// at random (Rng(pose_seed)), with noise of variance `noise_var` and no blur, frame i's noise
// seeded by first_noise_seed + i; each tracker Reset before each frame.
inline PairedErrors TrackPaired(const MarkerSpec& marker,
                                Tracker& first,
                                Tracker& second,
                                double distance_m,
                                double noise_var,
                                int frames,
                                uint64_t pose_seed,
                                uint64_t first_noise_seed) {
  const Camera camera;
  Rng rng(pose_seed);
  PairedErrors errors;
  const auto error = [&](Tracker& tracker, const Image8& image, const Rigid3& truth, int* missed) {
    tracker.Reset();
    const TrackResult result = tracker.Track({&image, &camera, &marker});
    if (result.status == TrackStatus::kOk) return PositionError(result.hypotheses.front(), truth);
    ++*missed;
    return std::numeric_limits<double>::infinity();
  };
  for (int i = 0; i < frames; ++i) {
    const Rigid3 truth = RandomTiltedView(distance_m, 10.0, 40.0, &rng);
    const RenderedFrame frame = RenderMarker(marker, truth, noise_var, 0.0, first_noise_seed + i);
    errors.first.push_back(error(first, frame.image, truth, &errors.first_missed));
    errors.second.push_back(error(second, frame.image, truth, &errors.second_missed));
    errors.first_better += errors.first.back() < errors.second.back();
  }
  return errors;
}

}  // namespace markerbench
