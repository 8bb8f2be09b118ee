#include "bench/run/run_results.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/number_text.h"
#include "core/yaml_reader.h"

namespace fs = std::filesystem;

namespace markerbench {
std::vector<std::string> ScenarioFolders(const std::string& dir) {
  if (!fs::is_directory(dir)) throw ConfigError(dir + ": no such results folder");
  std::vector<std::string> folders;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_directory() && FindTextFile(entry.path().string(), "frames.csv")) {
      folders.push_back(entry.path().string());
    }
  }
  std::sort(folders.begin(), folders.end());
  if (folders.empty()) throw ConfigError(dir + ": no <scenario>/frames.csv");
  return folders;
}

ScenarioRowReader::ScenarioRowReader(const std::string& folder) {
  const std::optional<std::string> frames = FindTextFile(folder, "frames.csv");
  if (!frames) throw ConfigError(folder + ": no frames.csv");
  frames_ = std::make_unique<LineReader>(*frames);
  ExpectHeader(*frames_, FramesCsvHeader());
  if (const std::optional<std::string> timing = FindTextFile(folder, "timing.csv")) {
    timing_ = std::make_unique<LineReader>(*timing);
    ExpectHeader(*timing_, TimingCsvHeader());
  }
}

bool ScenarioRowReader::Next(FrameRow* row, double* time_ms) {
  if (!frames_->Next(&line_)) return false;
  try {
    *row = ParseFrameRow(line_);
  } catch (const std::exception& e) {
    throw ConfigError(location() + ": " + e.what());
  }
  *time_ms = NAN;
  // timing.csv rows follow frames.csv rows one for one; a short file leaves times unknown.
  if (timing_ && timing_->Next(&line_)) {
    const std::vector<std::string> f = SplitCsvLine(line_);
    const std::optional<double> time =
        f.size() == kTimingColumnCount ? ParseFiniteNumber(f[kTimingTimeColumn]) : std::nullopt;
    if (!time || f[kTimingFrameColumn] != std::to_string(row->frame) ||
        f[kTimingTrackerColumn] != row->tracker) {
      throw ConfigError(timing_->path() + ":" + std::to_string(timing_->line_number()) +
                        ": expected the timing of frames.csv's row " +
                        std::to_string(frames_->line_number()));
    }
    *time_ms = *time;
  }
  return true;
}

std::string ScenarioRowReader::location() const {
  return frames_->path() + ":" + std::to_string(frames_->line_number());
}

std::vector<ScenarioResults> ReadRunResults(const std::string& dir) {
  std::vector<ScenarioResults> results;
  for (const std::string& folder : ScenarioFolders(dir)) {
    ScenarioResults r;
    r.name = fs::path(folder).filename().string();
    ScenarioRowReader reader(folder);
    FrameRow row;
    double time_ms = NAN;
    while (reader.Next(&row, &time_ms)) {
      r.rows.push_back(row);
      r.time_ms.push_back(time_ms);
    }
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace markerbench
