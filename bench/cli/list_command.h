// markerbench list trackers|markers: what a user can put in a scenario. Each tracker with its
// options and their defaults, whether sweeps isolate it, and the marker files it reads; each
// marker file with its kind, size and the trackers that read it.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace markerbench {

// The *.yaml files of `dir`, sorted by name (the marker files of list and markers). Throws
// ConfigError when `dir` is not a folder.
std::vector<std::string> MarkerFilesIn(const std::string& dir);

// `what`: "trackers" or "markers"; `markers_dir`: the folder of marker YAML files to match
// trackers with. Throws ConfigError for another `what` or a bad marker file.
void ListCommand(const std::string& what, const std::string& markers_dir, std::ostream& out);

}  // namespace markerbench
