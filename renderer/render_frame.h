// One synthetic frame: exact rasterisation, then the degradations in physical order, plus
// the ground truth that trackers never see.
#pragma once

#include <cstdint>
#include <functional>

#include "core/ground_truth.h"
#include "core/image.h"
#include "renderer/degradations.h"
#include "renderer/scene.h"

namespace markerbench {

struct FrameRequest {
  Scene scene;
  Degradations degradations;
  int channels = 1;          // 1: grey (Rec. 601 luma of the colours), 3: RGB
  uint64_t noise_seed = 0;   // SeedFor(scenario seed, cell, trial, SeedPurpose::kNoise)
  bool keep_linear = false;  // also return the float image (after noise and clipping)
  // A moving camera: the pose t seconds after the first row's exposure starts (empty: a
  // still camera at scene.cam_from_marker, which stays the ground truth either way). Each
  // row integrates the scene over exposure_s (motion blur that matches the motion:
  // trapezoidal, the sub-frames doubled until the result changes by less than half an 8-bit
  // level); with a rolling shutter, row v starts readout_s × v / (height - 1) late (bands
  // of rows share a time, so that the motion within a band stays below 1/8 px).
  std::function<Rigid3(double t)> cam_from_marker_at;
  double exposure_s = 0.0;
  double readout_s = 0.0;
};

// Sub-frames the exposure integral starts with and may double to.
inline constexpr int kMinExposureSubframes = 8;
inline constexpr int kMaxExposureSubframes = 512;

struct RenderedFrame {
  Image8 image;
  ImageF linear;  // filled when FrameRequest::keep_linear
  GroundTruth truth;
};

RenderedFrame RenderFrame(const FrameRequest& request);

// The largest image motion (px) between times a and b of the outline of the marker's ink and
// of its finite sheet, if any (all else is uniform), for a camera at pose_at(t).
double ImageMotionPx(const Scene& scene,
                     const std::function<Rigid3(double)>& pose_at,
                     double a,
                     double b);

// Pose, projected keypoints (true centres, through the distortion) and apparent size.
GroundTruth ComputeGroundTruth(const MarkerSpec& marker,
                               const Camera& camera,
                               const Rigid3& cam_from_marker);

}  // namespace markerbench
