// Test helpers for square-marker trackers: render a marker at a known pose, run a tracker,
// and measure corner and pose errors against the ground truth.
#pragma once

#include <cmath>
#include <string>

#include "core/marker_yaml.h"
#include "core/pose_error.h"
#include "core/random.h"
#include "core/test_files.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"
#include "trackers/tracker.h"

namespace markerbench {

struct TrackedFrame {
  RenderedFrame frame;
  TrackResult result;
};

// renderer/test_scenes.h's request with a noise seed from `seed`.
inline FrameRequest SeededFrameRequest(const MarkerSpec& marker,
                                       const Rigid3& cam_from_marker,
                                       double noise_var,
                                       double blur_sigma_px,
                                       uint64_t seed,
                                       int channels) {
  FrameRequest request =
      MarkerFrameRequest(marker, cam_from_marker, noise_var, blur_sigma_px, channels);
  request.noise_seed = SeedFor(seed, 0, 0, SeedPurpose::kNoise);
  return request;
}

// `marker` at a pose, with noise and blur, in RGB when it has colour, from the default camera.
inline RenderedFrame RenderMarker(const MarkerSpec& marker,
                                  const Rigid3& cam_from_marker,
                                  double noise_var,
                                  double blur_sigma_px,
                                  uint64_t seed) {
  return RenderFrame(SeededFrameRequest(
      marker, cam_from_marker, noise_var, blur_sigma_px, seed, marker.HasColor() ? 3 : 1));
}

// `rendered` at a pose (RGB when it or `expected` has colour), tracked as `expected`.
inline TrackedFrame RenderAndTrack(Tracker* tracker,
                                   const MarkerSpec& rendered,
                                   const MarkerSpec& expected,
                                   const Rigid3& cam_from_marker,
                                   double noise_var,
                                   uint64_t seed) {
  const FrameRequest request =
      SeededFrameRequest(rendered,
                         cam_from_marker,
                         noise_var,
                         0.0,
                         seed,
                         rendered.HasColor() || expected.HasColor() ? 3 : 1);
  TrackedFrame out;
  out.frame = RenderFrame(request);
  const Camera camera = request.scene.camera;
  out.result = tracker->Track({&out.frame.image, &camera, &expected});
  return out;
}

// Mean of (detected - true) corner offsets and mean inward offset (towards the centre).
struct CornerBias {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  double inward = 0.0;
  int count = 0;

  void Add(const std::vector<Eigen::Vector2d>& detected,
           const std::vector<Eigen::Vector2d>& truth) {
    Eigen::Vector2d center = Eigen::Vector2d::Zero();
    for (const auto& t : truth) center += t / truth.size();
    for (size_t i = 0; i < truth.size(); ++i) {
      const Eigen::Vector2d d = detected[i] - truth[i];
      mean += d;
      inward += -d.dot((truth[i] - center).normalized());
      ++count;
    }
  }
  Eigen::Vector2d Mean() const { return mean / count; }
  double Inward() const { return inward / count; }
};

// A tag36h11 marker file with another id.
inline std::string WriteTestTag(int id) {
  return WriteTestFile(
      "tag_" + std::to_string(id) + ".yaml",
      "kind: apriltag\nfamily: tag36h11\nid: " + std::to_string(id) + "\nsize_m: 0.1\n");
}

}  // namespace markerbench
