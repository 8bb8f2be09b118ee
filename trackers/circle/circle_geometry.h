// The geometry a circle tracker needs, read from a MarkerSpec (markers a-f of the paper's
// Fig. 3) and expressed in the paper's frame: origin at m0, +X towards m1, +Z towards the
// camera (circle-method.md §0). `marker_from_paper` maps it back to the marker file's frame,
// so poses are reported in the frame of the YAML even where the two differ.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/marker_spec.h"
#include "core/rigid3.h"

namespace markerbench {

// How l_inf and m0 are found (§4).
enum class CircleLayout {
  kTwoCircles,        // (a), (b): the pencil of two separate circles (§4.3)
  kConcentric,        // (c): two concentric circles (§4.4)
  kCircleWithCenter,  // (d), (e): one circle and its detected centre dot (§4.5)
  kSingleCircle,      // (f): one circle alone, its two calibrated normals (§4.7)
};

struct CircleGeometry {
  CircleLayout layout = CircleLayout::kTwoCircles;
  std::vector<Eigen::Vector2d> centers;  // paper frame; centers[0] = m0 = origin
  std::vector<double> radii_m;
  double Lx = 0.0;  // paper frame distance from m0 to m1 (§5.4)
  // Index of a circle centred at m1, whose imaged centre (a pole) then gives m1; -1 when m1 is
  // a detected feature point.
  int m1_circle = -1;
  // (e), (f): m1 is a point of a design painted inside the circle (a mouth tip, the end of a
  // radius), and the rotation about the circle's axis comes from that design (roll_feature.h)
  // rather than from a detected point.
  bool roll_from_design = false;
  Rigid3 marker_from_paper;
};

// nullopt (with `error` set) for markers other than circles_a/b/c and circle_d/e/f.
std::optional<CircleGeometry> CircleGeometryOf(const MarkerSpec& marker, std::string* error);

// Its circles' images through H = K [r1 r2 t] (a pose's plane-to-pixel map), as canonical
// conics (conic.h), in the order of `geometry.centers`.
std::vector<Eigen::Matrix3d> ConicsImagedThrough(const CircleGeometry& geometry,
                                                 const Eigen::Matrix3d& H);

// The start of the other of the two tilts (§4.7) from which a circle about the plane's origin
// looks nearly the same as from `cam_from_plane`: the plane's normal reflected about the ray
// to the circle's centre, R' = (2uuᵀ - I) R Rz(π) for the unit ray u, the centre kept; the
// Rz(π) keeps the plane's x axis where the image had it. From a centre on the optical axis
// the ellipse has the same shape, its centre mirrored through the principal point (a pixel
// or two); a fit from there finds the other tilt's pose. Its own inverse.
Rigid3 OtherTilt(const Rigid3& cam_from_plane);

}  // namespace markerbench
