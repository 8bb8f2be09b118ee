#include "bench/run_results.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/number_text.h"
#include "core/regular_file.h"
#include "core/yaml_reader.h"

namespace fs = std::filesystem;

namespace markerbench {
namespace {

// timing.csv rows follow frames.csv rows one for one.
std::vector<double> ReadTimes(const std::string& path, const std::vector<FrameRow>& rows) {
  std::vector<double> times(rows.size(), NAN);
  if (!fs::exists(path)) return times;
  RequireRegularFile(path);
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line + '\n' != TimingCsvHeader()) {
    throw ConfigError(path + ":1: expected the header '" +
                      TimingCsvHeader().substr(0, TimingCsvHeader().size() - 1) + "'");
  }
  for (size_t i = 0; i < rows.size() && std::getline(in, line); ++i) {
    const std::vector<std::string> f = SplitCsvLine(line);
    const std::optional<double> time_ms = f.size() == 4 ? ParseFiniteNumber(f[2]) : std::nullopt;
    if (!time_ms || f[0] != std::to_string(rows[i].frame) || f[1] != rows[i].tracker) {
      throw ConfigError(path + ":" + std::to_string(i + 2) +
                        ": expected the timing of frames.csv's row " + std::to_string(i + 2));
    }
    times[i] = *time_ms;
  }
  return times;
}

}  // namespace

std::vector<ScenarioResults> ReadRunResults(const std::string& dir) {
  if (!fs::is_directory(dir)) throw ConfigError(dir + ": no such results folder");
  std::vector<std::string> folders;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_directory() && fs::exists(entry.path() / "frames.csv")) {
      folders.push_back(entry.path().string());
    }
  }
  std::sort(folders.begin(), folders.end());
  if (folders.empty()) throw ConfigError(dir + ": no <scenario>/frames.csv");
  std::vector<ScenarioResults> results;
  for (const std::string& folder : folders) {
    ScenarioResults r;
    r.name = fs::path(folder).filename().string();
    r.rows = ReadFramesCsv(folder + "/frames.csv");
    r.time_ms = ReadTimes(folder + "/timing.csv", r.rows);
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace markerbench
