// libFuzzer target: the loaders of every file a user writes (camera, marker and scenario
// YAML, POSES.csv) and of the results other commands read (frames.csv with timing.csv,
// plain or zstd-compressed) on arbitrary bytes. The first byte picks the loader, the rest is
// the file. Bad input must be a ConfigError (exit status 2); any other exception, a crash, a
// leak or a slow input is a finding. Scenarios may name cameras/*.yaml and markers/*.yaml,
// copied from scenarios/ beside the fuzzed file.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "bench/cli/render_command.h"
#include "bench/plan/scenario.h"
#include "bench/run/run_results.h"
#include "core/camera_yaml.h"
#include "core/config_error.h"
#include "core/marker_yaml.h"

namespace fs = std::filesystem;

namespace {

std::string FuzzedFilePath() {
  static const std::string path = [] {
    const fs::path dir =
        fs::temp_directory_path() / ("markerbench_fuzz_" + std::to_string(getpid()));
    fs::create_directories(dir);
    for (const char* folder : {"cameras", "markers"}) {
      fs::copy(fs::path(MARKERBENCH_SOURCE_DIR) / "scenarios" / folder,
               dir / folder,
               fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    }
    return (dir / "input.yaml").string();
  }();
  return path;
}

// Reads every row of a run's scenario folder holding only `file`, as report does.
void ReadRows(const std::string& file, const uint8_t* data, size_t size) {
  const fs::path folder = fs::path(FuzzedFilePath()).parent_path() / "run";
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream(folder / file, std::ios::binary)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  markerbench::ScenarioRowReader reader(folder.string());
  markerbench::FrameRow row;
  double time_ms = 0.0;
  while (reader.Next(&row, &time_ms)) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace markerbench;
  if (size == 0) return 0;
  const std::string path = FuzzedFilePath();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  try {
    switch (data[0] % 6) {
      case 0:
        LoadCameraYaml(path);
        break;
      case 1:
        LoadMarkerYaml(path);
        break;
      case 2:
        LoadScenario(path);
        break;
      case 3:
        LoadPosesCsv(path);
        break;
      case 4:
        ReadRows("frames.csv", data + 1, size - 1);
        break;
      default:
        ReadRows("frames.csv.zst", data + 1, size - 1);
        break;
    }
  } catch (const ConfigError&) {
    // bad input, reported as such
  }
  return 0;
}
