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

// `options` (may be null: all defaults) is read strictly; bad options and unknown names throw
// ConfigError naming the file and key.
std::unique_ptr<Tracker> MakeTracker(const std::string& name, const YamlMap* options);

}  // namespace markerbench
