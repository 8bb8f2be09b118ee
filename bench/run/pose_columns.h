// The pose columns shared by every CSV file (architecture.md, "File formats"):
// r11..r33, tx, ty, tz of a cam_from_marker, row-major.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/config_error.h"
#include "core/number_text.h"
#include "core/rigid3.h"

namespace markerbench {

inline constexpr const char* kPoseColumns[12] = {
    "r11", "r12", "r13", "r21", "r22", "r23", "r31", "r32", "r33", "tx", "ty", "tz"};

// ",r11,...,tz" for `pose`: twelve exact numbers, each after a comma.
inline std::string PoseFields(const Rigid3& pose) {
  std::string out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out += ',' + NumberText(pose.rotation(r, c));
  }
  for (int i = 0; i < 3; ++i) out += ',' + NumberText(pose.translation[i]);
  return out;
}

// Where the twelve pose columns are in a row: `first` and the eleven after it.
inline std::array<size_t, 12> ConsecutiveColumns(size_t first) {
  std::array<size_t, 12> columns;
  for (size_t k = 0; k < 12; ++k) columns[k] = first + k;
  return columns;
}

enum class RotationCheck { kRequired, kNone };

// The pose in `fields[columns[0..11]]` (`prefix`r11..tz). Throws ConfigError starting with
// `where` ("file:line: ") and naming the column that is not a finite number, or, when the
// check is required, that r11..r33 are not a rotation.
inline Rigid3 PoseFromFields(const std::vector<std::string>& fields,
                             const std::array<size_t, 12>& columns,
                             const std::string& where,
                             RotationCheck check = RotationCheck::kRequired,
                             const std::string& prefix = "") {
  double v[12];
  for (size_t k = 0; k < 12; ++k) {
    const std::string& field = columns[k] < fields.size() ? fields[columns[k]] : std::string();
    const std::optional<double> number = ParseFiniteNumber(field);
    if (!number) {
      throw ConfigError(where + "column '" + prefix + kPoseColumns[k] +
                        "': expected a number, got '" + field + "'");
    }
    v[k] = *number;
  }
  Rigid3 pose;
  pose.rotation << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  pose.translation << v[9], v[10], v[11];
  if (check == RotationCheck::kRequired && !IsRotation(pose.rotation)) {
    throw ConfigError(where + "columns '" + prefix + "r11'..'" + prefix +
                      "r33': expected a rotation matrix (orthonormal, det +1)");
  }
  return pose;
}

}  // namespace markerbench
