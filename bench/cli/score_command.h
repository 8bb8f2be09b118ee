// `markerbench score DIR --poses ESTIMATES.csv --tracker NAME --out RUN_DIR`: a tracker's
// estimates for a rendered dataset (bench/run/dataset.h), scored into a run folder like a
// sweep's, so that `report` and `check` work on it (README, "Benchmark your own tracker").
#pragma once

#include <ostream>
#include <string>

namespace markerbench {

struct ScoreOptions {
  std::string dataset_dir;
  std::string estimates_path;
  std::string tracker;
  std::string out_dir;
};

// ESTIMATES.csv: the header frame,status,r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz (and
// optionally ,time_ms), then rows; a frame's further rows are further hypotheses, best first.
// Frames without a row are not_detected rows ("no estimate"), counted on `out`. Writes
// RUN_DIR/<scenario>/frames.csv (timing.csv when every frame has a time_ms) and
// RUN_DIR/manifest.json. Throws ConfigError naming the line of an unknown frame, a bad
// status or number, a rotation that is not one, or rows of a frame that disagree.
void RunScoreCommand(const ScoreOptions& options, std::ostream& out);

}  // namespace markerbench
