#include "bench/cli/crlb_command.h"

#include <fstream>
#include <iostream>
#include <vector>

#include "bench/cli/render_command.h"
#include "bench/metrics/metrics.h"
#include "core/number_text.h"
#include "core/yaml_reader.h"
#include "renderer/pose_crlb.h"

namespace markerbench {

std::string RunCrlbCommand(const CrlbCommandOptions& o) {
  const Degradations& d = o.degradations;
  const ExplicitFrames frames =
      LoadExplicitFrames(o.marker_path, o.camera_path, o.poses_path, d, o.channels);
  const MarkerSpec& marker = frames.marker;
  std::ofstream file;
  if (!o.out_csv.empty()) {
    file.open(o.out_csv);
    if (!file) throw std::runtime_error(o.out_csv + ": cannot write");
  }
  std::ostream& out = o.out_csv.empty() ? std::cout : file;
  out << "pose,distance_m,apparent_size_px,noise_var,blur_sigma_px,gamma,channels,"
         "crlb_position_m,crlb_position_med_m,crlb_rotation_deg,crlb_rotation_med_deg\n";
  const Eigen::Vector2d center = marker.InkBounds().center();
  std::vector<double> position, rotation;
  for (size_t i = 0; i < frames.poses.size(); ++i) {
    const Rigid3& pose = frames.poses[i];
    const PoseBound bound = PoseCrlb(frames.Request(i));
    const GroundTruth truth = ComputeGroundTruth(marker, frames.camera, pose);
    out << i << ',' << NumberText((pose * Eigen::Vector3d(center.x(), center.y(), 0.0)).norm())
        << ',' << NumberText(truth.apparent_size_px) << ',' << NumberText(d.noise_var) << ','
        << NumberText(d.blur_sigma_px) << ',' << NumberText(d.gamma) << ',' << frames.channels
        << ',' << NumberText(bound.position_rms_m) << ',' << NumberText(bound.position_median_m)
        << ',' << NumberText(bound.rotation_rms_deg) << ',' << NumberText(bound.rotation_median_deg)
        << '\n';
    position.push_back(bound.position_median_m);
    rotation.push_back(bound.rotation_median_deg);
  }
  out.flush();
  if (!out) throw std::runtime_error((o.out_csv.empty() ? "stdout" : o.out_csv) + ": write failed");
  return marker.name + ": median over " + std::to_string(frames.poses.size()) +
         " poses of the median error at the physical limit: position " +
         FormattedOrDash(1e3 * Median(position), "%.4g") + " mm, rotation " +
         FormattedOrDash(Median(rotation), "%.4g") + " deg (noise_var " + NumberText(d.noise_var) +
         ", blur_sigma_px " + NumberText(d.blur_sigma_px) + ", gamma " + NumberText(d.gamma) + ")";
}

}  // namespace markerbench
