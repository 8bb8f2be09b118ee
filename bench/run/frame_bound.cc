#include "bench/run/frame_bound.h"

#include "core/number_text.h"

namespace markerbench {

FrameBound BoundOf(const PoseBound& bound) {
  return {bound.position_rms_m,
          bound.position_median_m,
          bound.rotation_rms_deg,
          bound.rotation_median_deg,
          bound.position_variances_m2};
}

FrameBound PlannedFrameBound(const Scenario& scenario,
                             const PlannedFrame& frame,
                             const FrameRequest& request) {
  if (frame.occluded) {
    return {INFINITY, INFINITY, INFINITY, INFINITY, Eigen::Vector3d::Constant(INFINITY)};
  }
  return scenario.crlb ? BoundOf(PoseCrlb(request)) : FrameBound{};
}

const std::array<std::string, kFrameBoundColumns>& FrameBoundColumns() {
  static const std::array<std::string, kFrameBoundColumns> kColumns = {"crlb_position_m",
                                                                       "crlb_position_med_m",
                                                                       "crlb_rotation_deg",
                                                                       "crlb_rotation_med_deg",
                                                                       "crlb_position_var1_m2",
                                                                       "crlb_position_var2_m2",
                                                                       "crlb_position_var3_m2"};
  return kColumns;
}

std::array<double, kFrameBoundColumns> BoundValues(const FrameBound& bound) {
  return {bound.position_m,
          bound.position_med_m,
          bound.rotation_deg,
          bound.rotation_med_deg,
          bound.position_variances_m2[0],
          bound.position_variances_m2[1],
          bound.position_variances_m2[2]};
}

FrameBound BoundFromValues(const std::array<double, kFrameBoundColumns>& values) {
  return {
      values[0], values[1], values[2], values[3], Eigen::Vector3d(values[4], values[5], values[6])};
}

std::string FrameBoundFields(const FrameBound& bound) {
  std::string fields;
  for (const double value : BoundValues(bound)) fields += ',' + NumberTextOrEmpty(value);
  return fields;
}

}  // namespace markerbench
