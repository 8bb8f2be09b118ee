// `markerbench crlb`: the Cramér-Rao bound alone (renderer/pose_crlb.h) for a marker, a camera
// and a list of poses, so that marker designs can be compared before one is printed.
#pragma once

#include <string>

#include "bench/plan/scenario.h"

namespace markerbench {

struct CrlbCommandOptions {
  std::string marker_path;
  std::string camera_path;
  std::string poses_path;  // POSES.csv, as for `render`
  std::string out_csv;     // empty: standard output
  // The options set noise_var (imnoise variance on [0, 1]; 0 leaves the 8-bit rounding),
  // blur_sigma_px and gamma.
  Degradations degradations;
  Channels channels = Channels::kAuto;
};

// Writes one CSV row per pose (pose, distance_m, apparent_size_px, noise_var, blur_sigma_px,
// gamma, channels and the four crlb_* columns of frames.csv) and returns a one-line summary: the
// median of each bound over the poses. Bad input: ConfigError naming the file.
std::string RunCrlbCommand(const CrlbCommandOptions& options);

}  // namespace markerbench
