// `markerbench track`: runs one tracker on images or video files and writes one CSV row per
// frame. Images are independent frames (the tracker is Reset before each) unless `sequence`;
// a video is a sequence. Optionally a TUM trajectory of the tracked frames.
#pragma once

#include <string>
#include <vector>

namespace markerbench {

struct TrackCommandOptions {
  std::string tracker;
  std::string marker_path;
  std::string camera_path;
  std::string out_csv;  // empty: standard output
  std::vector<std::string> inputs;
  // Tracker options "key=value" (the value in YAML), as in a scenario's `options:`.
  std::vector<std::string> tracker_options;
  // The images are one sequence, in the order given: the tracker keeps its state (tracking
  // mode) from one to the next.
  bool sequence = false;
  // TUM trajectory (`timestamp tx ty tz qx qy qz qw`, the camera in the marker frame) of the
  // frames with a pose; a video frame's time is its index over the video's frame rate, an
  // image's its index in the inputs, in seconds. Empty: none.
  std::string tum_path;
  // A video of every frame of the camera's size with the pose drawn (bench/run/pose_overlay.h),
  // at the video's frame rate, or 1 frame/s for images. Empty: none.
  std::string overlay_path;
  // The frames' encoding gamma: each 8-bit value v becomes round(255 (v/255)^gamma) before the
  // tracker sees it (core/gamma_curve.h; the overlay draws the frame as read). The circle tracker
  // models intensities linear in the light, as the renderer makes them; a camera's sRGB-like
  // encoding (about 2.2) bends every blurred edge, and its poses go centimetres off or its design
  // checks reject the marker (circle_tracker_test.cc). 1: taken as linear.
  double gamma = 1.0;
};

// Checks the tracker, its options, the marker, the camera and the files before any frame
// (ConfigError); a frame that cannot be read or tracked is a row.
void RunTrackCommand(const TrackCommandOptions& options);

}  // namespace markerbench
