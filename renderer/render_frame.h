// One synthetic frame: exact rasterisation, then the degradations in physical order, plus
// the ground truth that trackers never see.
#pragma once

#include <cstdint>

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
};

struct RenderedFrame {
  Image8 image;
  ImageF linear;  // filled when FrameRequest::keep_linear
  GroundTruth truth;
};

RenderedFrame RenderFrame(const FrameRequest& request);

// Pose, projected keypoints (true centres, through the distortion) and apparent size.
GroundTruth ComputeGroundTruth(const MarkerSpec& marker,
                               const Camera& camera,
                               const Rigid3& cam_from_marker);

}  // namespace markerbench
