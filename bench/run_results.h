// The results of a sweep's output folder, as `report` and `check` read them: every
// <scenario>/frames.csv with the times of its timing.csv.
#pragma once

#include <string>
#include <vector>

#include "bench/frames_csv.h"

namespace markerbench {

struct ScenarioResults {
  std::string name;  // the scenario folder's name
  std::vector<FrameRow> rows;
  std::vector<double> time_ms;  // per row; NaN when timing.csv is missing or short
};

// Scenario folders in name order. Throws ConfigError when `dir` is not a folder, holds no
// <scenario>/frames.csv, or a file is malformed (naming the file and line).
std::vector<ScenarioResults> ReadRunResults(const std::string& dir);

}  // namespace markerbench
