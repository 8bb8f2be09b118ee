#include "bench/io/tum_trajectory.h"

#include <Eigen/Geometry>

#include "core/number_text.h"

namespace markerbench {

std::string TumLine(double time_s, const Rigid3& cam_from_marker) {
  const Rigid3 marker_from_cam = cam_from_marker.Inverse();
  const Eigen::Quaterniond q(marker_from_cam.rotation);
  std::string line = NumberText(time_s);
  for (const double v : {marker_from_cam.translation.x(),
                         marker_from_cam.translation.y(),
                         marker_from_cam.translation.z(),
                         q.x(),
                         q.y(),
                         q.z(),
                         q.w()}) {
    line += ' ' + NumberText(v);
  }
  return line + '\n';
}

}  // namespace markerbench
