#include "bench/cli/list_command.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/config_error.h"
#include "core/joined.h"
#include "core/marker_yaml.h"
#include "core/number_text.h"
#include "trackers/tracker_factory.h"

namespace fs = std::filesystem;

namespace markerbench {
namespace {

std::string JoinedOrNone(const std::vector<std::string>& items) {
  return items.empty() ? "none" : Joined(items);
}

}  // namespace

std::vector<std::string> MarkerFilesIn(const std::string& dir) {
  if (!fs::is_directory(dir)) throw ConfigError(dir + ": no such folder of marker files");
  std::vector<std::string> paths;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".yaml") paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

void ListCommand(const std::string& what, const std::string& markers_dir, std::ostream& out) {
  if (what != "trackers" && what != "markers") {
    throw ConfigError("list: expected 'trackers' or 'markers', got '" + what + "'");
  }
  std::vector<MarkerSpec> markers;
  for (const std::string& path : MarkerFilesIn(markers_dir))
    markers.push_back(LoadMarkerYaml(path));
  const std::vector<std::string> names = TrackerNames();
  std::vector<std::unique_ptr<Tracker>> trackers;
  for (const std::string& name : names) trackers.push_back(MakeTracker(name, nullptr));
  if (what == "trackers") {
    for (size_t t = 0; t < trackers.size(); ++t) {
      const std::string& name = names[t];
      std::vector<std::string> reads;
      for (const MarkerSpec& m : markers) {
        if (trackers[t]->CanTrack(m)) reads.push_back(m.name + " (" + ToString(m.kind) + ")");
      }
      out << name << (RunsThirdPartyCCode(name) ? "  [isolated in sweeps by default]" : "")
          << "\n  reads: " << JoinedOrNone(reads) << "\n  options (defaults):\n";
      for (const auto& [key, value] : trackers[t]->Parameters()) {
        out << "    " << key << ": " << value << "\n";
      }
    }
    out << "An external tracker: {name, exec: [...], markers: [...]} in a scenario "
           "(README, \"Benchmark your own tracker\").\n";
    return;
  }
  out << "Marker files in " << markers_dir << ":\n";
  for (const MarkerSpec& m : markers) {
    std::vector<std::string> readers;
    for (size_t t = 0; t < trackers.size(); ++t) {
      if (trackers[t]->CanTrack(m)) readers.push_back(names[t]);
    }
    out << m.name << ": " << ToString(m.kind);
    if (!m.family.empty()) out << " " << m.family;
    if (m.id >= 0) out << " id " << m.id;
    if (m.size_m > 0.0) out << ", " << NumberText(1e3 * m.size_m) << " mm";
    if (!m.circles.empty()) {
      double radius_m = 0.0;
      for (const Disk& d : m.circles) radius_m = std::max(radius_m, d.radius_m);
      out << ", " << m.circles.size() << " circles of radius up to " << NumberText(1e3 * radius_m)
          << " mm";
    }
    out << "; read by " << JoinedOrNone(readers) << "\n";
  }
}

}  // namespace markerbench
