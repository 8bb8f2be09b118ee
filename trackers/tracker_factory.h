// Builds trackers by name (the names used in scenarios and on the command line).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "trackers/tracker.h"

namespace markerbench {

class YamlMap;

// Names of every available tracker.
std::vector<std::string> TrackerNames();

// Whether the tracker's work is done by third-party C code (libapriltag), which can crash
// the process on an input it does not expect: sweeps run such trackers in a worker process.
bool RunsThirdPartyCCode(const std::string& name);

// `options` (may be null: all defaults) is read strictly; bad options and unknown names throw
// ConfigError naming the file and key.
std::unique_ptr<Tracker> MakeTracker(const std::string& name, const YamlMap* options);

}  // namespace markerbench
