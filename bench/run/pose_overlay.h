// A video of frames with tracked poses drawn on them, as in the paper's AR figures: the marker
// frame's axes (x red, y green, z blue, out of the marker) and a cube standing on the marker,
// projected through the camera (lens distortion included). `track --overlay OUT.mp4` draws
// one tracker's; a sweep's example sequence every tracker's, each cube in its own colour
// with the tracker's name in that colour in the corner.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/marker_spec.h"
#include "trackers/tracker.h"

namespace cv {
class VideoWriter;
}

namespace markerbench {

class PoseOverlay {
 public:
  // Nothing is written until the first frame.
  PoseOverlay(std::string path, const Camera& camera, const MarkerSpec& marker);
  ~PoseOverlay();

  // Appends `frame` (the camera's size) with the first hypothesis drawn when the status is ok.
  // The first frame opens the video at `fps` (FFmpeg, MPEG-4 Part 2); throws
  // std::runtime_error when it cannot.
  void Add(const Image8& frame, const TrackResult& result, double fps);
  // The same with several trackers' results, named (names are written only for two or more).
  void Add(const Image8& frame,
           const std::vector<std::pair<std::string, TrackResult>>& results,
           double fps);

  // The axes' length and the cube's edge: half the larger side of the marker's ink.
  double AxisLengthM() const { return axis_m_; }

 private:
  std::string path_;
  const Camera& camera_;
  Eigen::Vector2d center_;  // the ink centre, where the cube stands
  double axis_m_;
  std::unique_ptr<cv::VideoWriter> writer_;
};

}  // namespace markerbench
