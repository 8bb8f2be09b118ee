// Loads a marker file (architecture.md, "File formats"; every kind is documented in README.md
// with its default geometry in scenarios/markers/).
#pragma once

#include <string>

#include "core/marker_spec.h"

namespace markerbench {

// Throws ConfigError naming the file, line and key on bad, missing or unknown keys, and on
// geometry that breaks the kind's rules (e.g. m1 not on +x, overlapping disks).
MarkerSpec LoadMarkerYaml(const std::string& path);

}  // namespace markerbench
