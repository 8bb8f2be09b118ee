// A marker as printed: its kind, what is drawn (vector layers in the marker frame) and the
// geometry that trackers and the harness query. Frames and units: architecture.md.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "core/shapes.h"

namespace markerbench {

enum class MarkerKind {
  kCirclesA,  // paper Fig. 3(a): two disks told apart by colour
  kCirclesB,  // Fig. 3(b): two disks, a feature dot inside the second
  kCirclesC,  // Fig. 3(c): concentric circles (a ring), a feature dot on the ring
  kCircleD,   // Fig. 3(d): one disk, a contrasting centre dot, a dot outside
  kCircleE,   // Fig. 3(e): a "face": disk, nose dot at the centre, a mouth with two tips
  kCircleF,   // Fig. 3(f): a disk with a wedge whose radii meet at the centre
  kAprilTag,  // libapriltag family bitmap
  kAruco,     // OpenCV 4.6 aruco dictionary bitmap
  kBitGrid,   // generic bordered bit-grid square
  kArtkPlus,  // ARToolKitPlus-style BCH-id or simple-id square (core/codes/artkplus_id_code.h)
  kDotRings,  // generic dots on concentric rings (building block for RUNETag style)
  kRuneTag,   // RUNETag-style: 43 sectors x 3 rings coded by core/codes/runetag_cyclic_code.h
};

const char* ToString(MarkerKind kind);
std::optional<MarkerKind> MarkerKindFromString(const std::string& name);
// Every kind's name, in the enum's order.
std::vector<std::string> MarkerKindNames();
bool IsCircleKind(MarkerKind kind);
bool IsSquareKind(MarkerKind kind);

struct Disk {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  Rgb color = Rgb::Zero();
};

struct MarkerSpec {
  MarkerKind kind = MarkerKind::kCirclesA;
  std::string name;              // the marker file's stem
  Rgb background = Rgb::Ones();  // the paper the marker is printed on

  // Circle markers: the circles whose edges carry the pose; circles[0] is centred at m0.
  std::vector<Disk> circles;
  // Square markers: family, dictionary or artkplus id mode ("bch", "simple"), id, and the
  // edge of the black square. runetag: id, and size_m = 2 R (R the outer ring's radius).
  std::string family;
  int id = -1;
  double size_m = 0.0;
  // artkplus: width of the black border as a fraction of size_m (0.25 or 0.125).
  double border_fraction = 0.0;

  // What is printed on the background, bottom layer first.
  std::vector<PaintedShape> layers;
  // Keypoints in the marker frame (z = 0):
  // - circle markers: m0 (the first circle's centre; the origin for (e) and (f)), m1 (its
  //   partner: circle 1's centre for (a), the feature dot for (b)-(d); on +x for (e) and (f)),
  //   and m2 for (e) (second mouth tip) and (f)
  //   (end of the second radius);
  // - square markers: corners of the black square, top-left, top-right, bottom-right,
  //   bottom-left as seen from the front: (-s,+s), (+s,+s), (+s,-s), (-s,-s), s = size_m/2;
  // - dot rings and runetag: the dot centres in slot order (slot = rings · sector + ring;
  //   runetag: 3 · sector + ring, ring 0 innermost).
  std::vector<Eigen::Vector2d> keypoints;

  // Bounds of everything inked, without the quiet zone (paper-coloured grid cells and the
  // background do not count). Used for equal-area scaling (experiments.md).
  Eigen::AlignedBox2d InkBounds() const;
  // The printed colour at a marker-plane point (the top-most layer painting it, and its index,
  // else the background) and a lower bound on its distance to every layer's colour edges.
  PaintSample ColorAt(const Eigen::Vector2d& p) const;
  // True when any colour has chroma, so the marker is best rendered in RGB.
  bool HasColor() const;
};

}  // namespace markerbench
