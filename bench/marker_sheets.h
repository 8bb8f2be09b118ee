// `markerbench markers`: print-ready A4 sheets of marker files at 300 dpi, with the physical
// size and a 50 mm check bar printed on the sheet, so a user can print one and track it.
#pragma once

#include <string>
#include <vector>

namespace markerbench {

// Writes <out_dir>/<marker name>.png for each marker file. Returns the written paths.
std::vector<std::string> WriteMarkerSheets(const std::vector<std::string>& marker_files,
                                           const std::string& out_dir);

}  // namespace markerbench
