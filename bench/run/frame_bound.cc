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

const std::vector<std::string>& FrameBoundColumns() {
  static const std::vector<std::string> kColumns = {"crlb_position_m",
                                                    "crlb_position_med_m",
                                                    "crlb_rotation_deg",
                                                    "crlb_rotation_med_deg",
                                                    "crlb_position_var1_m2",
                                                    "crlb_position_var2_m2",
                                                    "crlb_position_var3_m2"};
  return kColumns;
}

std::string FrameBoundFields(const FrameBound& bound) {
  std::string fields;
  for (const double value : {bound.position_m,
                             bound.position_med_m,
                             bound.rotation_deg,
                             bound.rotation_med_deg,
                             bound.position_variances_m2[0],
                             bound.position_variances_m2[1],
                             bound.position_variances_m2[2]}) {
    fields += ',' + NumberTextOrEmpty(value);
  }
  return fields;
}

void SetFrameBound(const FrameBound& bound, FrameRow* row) {
  row->crlb_position_m = bound.position_m;
  row->crlb_position_med_m = bound.position_med_m;
  row->crlb_rotation_deg = bound.rotation_deg;
  row->crlb_rotation_med_deg = bound.rotation_med_deg;
  row->crlb_position_variances_m2 = bound.position_variances_m2;
}

}  // namespace markerbench
