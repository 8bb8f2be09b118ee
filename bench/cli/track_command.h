// `markerbench track`: runs one tracker on images or video files and writes one CSV row per
// frame (architecture.md, "CLI").
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
};

void RunTrackCommand(const TrackCommandOptions& options);

}  // namespace markerbench
