// The results of a sweep's output folder, as `report` and `check` read them: every
// <scenario>/frames.csv (or frames.csv.zst) with the times of its timing.csv (or .zst).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bench/io/line_reader.h"
#include "bench/run/frames_csv.h"

namespace markerbench {

// The scenario folders of `dir` (those holding frames.csv or frames.csv.zst), in name order.
// Throws ConfigError when `dir` is not a folder or holds none.
std::vector<std::string> ScenarioFolders(const std::string& dir);

// One scenario folder's rows in file order, each with its time, in memory bounded by one row.
class ScenarioRowReader {
 public:
  explicit ScenarioRowReader(const std::string& folder);

  // The next row and its time_ms (NaN when timing.csv is missing or short); false at the end.
  // A malformed row throws ConfigError naming the file and line.
  bool Next(FrameRow* row, double* time_ms);
  // "frames.csv:LINE" of the row Next() returned last.
  std::string location() const;

 private:
  std::unique_ptr<LineReader> frames_;
  std::unique_ptr<LineReader> timing_;  // null without timing.csv
  std::string line_;
};

struct ScenarioResults {
  std::string name;  // the scenario folder's name
  std::vector<FrameRow> rows;
  std::vector<double> time_ms;  // per row; NaN when timing.csv is missing or short
};

// Every scenario folder, read whole. Throws as ScenarioFolders and ScenarioRowReader do.
std::vector<ScenarioResults> ReadRunResults(const std::string& dir);

}  // namespace markerbench
