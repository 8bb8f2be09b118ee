// The pose columns shared by every CSV file (architecture.md, "File formats"):
// r11..r33, tx, ty, tz of a cam_from_marker, row-major.
#pragma once

#include <string>

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

}  // namespace markerbench
