// The marker files of a scenario as its frames show them: each source file with `scale` set
// to the scenario's equal-area factor, for programs outside markerbench (external trackers,
// a rendered dataset's users).
#pragma once

#include <map>
#include <string>

#include "bench/plan/scenario.h"

namespace markerbench {

// Writes `dir`/<name>.yaml: the marker file `source` with every length times `scale` (its
// own scale key included). Returns the absolute path.
std::string WriteScaledMarkerFile(const std::string& source,
                                  double scale,
                                  const std::string& dir,
                                  const std::string& name);

// Writes `dir`/<name>.yaml for every marker of `scenario`; returns their absolute paths by
// marker name.
std::map<std::string, std::string> WriteScaledMarkerFiles(const Scenario& scenario,
                                                          const std::string& dir);

}  // namespace markerbench
