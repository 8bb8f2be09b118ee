// Small scenes shared by the renderer tests and benchmark.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

#include "core/marker_spec.h"
#include "core/random.h"
#include "core/rigid3.h"
#include "renderer/render_frame.h"

namespace markerbench {

// A black disk of `radius_m` centred at the origin, on white paper.
inline MarkerSpec BlackDiskMarker(double radius_m) {
  MarkerSpec spec;
  spec.kind = MarkerKind::kCircleD;
  spec.circles = {{Eigen::Vector2d::Zero(), radius_m, Rgb::Zero()}};
  spec.layers = {{DiskShape{Eigen::Vector2d::Zero(), radius_m}, Rgb::Zero()}};
  spec.keypoints = {Eigen::Vector2d::Zero()};
  return spec;
}

// A black axis-aligned square with corners (x0, y0) and (x0 + size, y0 + size).
inline MarkerSpec BlackSquareMarker(double x0, double y0, double size_m) {
  MarkerSpec spec;
  spec.kind = MarkerKind::kBitGrid;
  GridShape grid;
  grid.rows = grid.cols = 1;
  grid.cell_m = size_m;
  grid.top_left = Eigen::Vector2d(x0, y0 + size_m);
  grid.ink = {1};
  spec.layers = {{grid, Rgb::Zero()}};
  spec.size_m = size_m;
  return spec;
}

// The camera at `distance_m` looking at the marker origin, tilted by tilt_deg about the
// marker's x axis and rolled by roll_deg about the optical axis.
inline Rigid3 TiltedView(double distance_m, double tilt_deg, double roll_deg) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  // Fronto-parallel: marker x → camera x, marker y → camera -y, marker z → camera -z.
  const Eigen::Matrix3d frontal = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitZ()) * frontal *
                            Eigen::AngleAxisd(tilt_deg * kDeg, Eigen::Vector3d::UnitX());
  return {R, Eigen::Vector3d(0.0, 0.0, distance_m)};
}

// Random draws for test scenes, one statement each: the order of a call's arguments is
// unspecified (g++ evaluates them last to first, clang first to last), so draws made as
// arguments of one call gave each compiler other frames. These draw in g++'s order, which the
// tests' measured figures come from.

// A view from `distance_m`, tilted by a uniform angle in [min_tilt_deg, max_tilt_deg] and
// rolled by any angle (the roll drawn first).
inline Rigid3 RandomTiltedView(double distance_m,
                               double min_tilt_deg,
                               double max_tilt_deg,
                               Rng* rng) {
  const double roll_deg = rng->Uniform(0.0, 360.0);
  const double tilt_deg = rng->Uniform(min_tilt_deg, max_tilt_deg);
  return TiltedView(distance_m, tilt_deg, roll_deg);
}

// Three standard normal coordinates (z drawn first).
inline Eigen::Vector3d GaussianVector(Rng* rng) {
  Eigen::Vector3d v;
  for (int k = 2; k >= 0; --k) v[k] = rng->Gaussian();
  return v;
}

// `truth` moved by about 1 mm and 0.25°: a refinement's start a typical edge fit away.
inline Rigid3 SlightlyPerturbed(const Rigid3& truth, Rng* rng) {
  const Eigen::Vector3d axis = GaussianVector(rng);
  Rigid3 start = truth;
  start.rotation = Eigen::AngleAxisd(0.25 * M_PI / 180.0, axis.normalized()) * truth.rotation;
  start.translation += 0.0006 * GaussianVector(rng);
  return start;
}

// The request for `marker` at a pose from the default camera, with noise and blur (the noise
// seed left at its default).
inline FrameRequest MarkerFrameRequest(const MarkerSpec& marker,
                                       const Rigid3& cam_from_marker,
                                       double noise_var,
                                       double blur_sigma_px,
                                       int channels) {
  FrameRequest request;
  request.scene.marker = &marker;
  request.scene.cam_from_marker = cam_from_marker;
  request.degradations.noise_var = noise_var;
  request.degradations.blur_sigma_px = blur_sigma_px;
  request.channels = channels;
  return request;
}

// `request` seen by a camera moving during its exposure at constant rates: the pose at time t
// is motion(t - truth_time_s)·T0, T0 the request's pose and motion(s) a turn by
// s·angular_velocity (rad/s, camera frame) and a shift by s·velocity (m/s).
inline void MoveAtConstantRates(FrameRequest* request,
                                const Eigen::Vector3d& velocity,
                                const Eigen::Vector3d& angular_velocity,
                                double exposure_s,
                                double readout_s,
                                double truth_time_s) {
  request->exposure_s = exposure_s;
  request->readout_s = readout_s;
  const Rigid3 truth = request->scene.cam_from_marker;
  request->cam_from_marker_at = [=](double t) {
    return Rigid3(RotationFromVector((t - truth_time_s) * angular_velocity),
                  (t - truth_time_s) * velocity) *
           truth;
  };
}

}  // namespace markerbench
