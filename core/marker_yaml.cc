#include "core/marker_yaml.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/codes/runetag_cyclic_code.h"
#include "core/marker_bits.h"
#include "core/marker_scaling.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

constexpr double kGeometryTol = 1e-9;  // metres; "on the axis", "at the origin"
constexpr double kPi = 3.14159265358979323846;

Disk ReadDisk(const YamlMap& map) {
  Disk disk;
  disk.center = map.GetPoint("center");
  disk.radius_m = map.GetLength("radius");
  disk.color = map.GetColor("color");
  map.RejectUnknownKeys();
  return disk;
}

Disk ReadDiskKey(const YamlMap& root, const std::string& key) { return ReadDisk(root.GetMap(key)); }

std::vector<Disk> ReadDisks(const YamlMap& root, size_t count) {
  const std::vector<YamlMap> maps = root.GetMapList("disks");
  if (maps.size() != count) {
    root.Fail(
        "disks",
        "a list of " + std::to_string(count) + " disks for kind " + root.Get<std::string>("kind"));
  }
  std::vector<Disk> disks;
  for (const YamlMap& m : maps) disks.push_back(ReadDisk(m));
  return disks;
}

void PaintDisk(MarkerSpec* spec, const Disk& disk) {
  spec->layers.push_back({DiskShape{disk.center, disk.radius_m}, disk.color});
}

bool OnPositiveXAxis(const Eigen::Vector2d& p) {
  return std::abs(p.y()) <= kGeometryTol && p.x() > kGeometryTol;
}

void RequireOrigin(const YamlMap& root, const std::string& key, const Eigen::Vector2d& p) {
  if (p.norm() > kGeometryTol) root.Fail(key, "a centre at the origin [0, 0] (m0)");
}

void RequireOnXAxis(const YamlMap& root, const std::string& key, const Eigen::Vector2d& p) {
  if (!OnPositiveXAxis(p)) root.Fail(key, "a centre on the +x axis [x > 0, 0] (m1)");
}

// Markers (a)-(d) may sit anywhere in the file's frame: m0 is the first circle's centre and
// m1 its partner point, and poses are reported in that frame. (e) and (f) use the paper's
// frame (m0 at the origin, m1 on +x).
void LoadCircleMarker(const YamlMap& root, MarkerSpec* spec) {
  const MarkerKind kind = spec->kind;
  const bool two_circles = kind == MarkerKind::kCirclesA || kind == MarkerKind::kCirclesB ||
                           kind == MarkerKind::kCirclesC;
  spec->circles = ReadDisks(root, two_circles ? 2 : 1);
  const Disk& c0 = spec->circles[0];
  if (kind == MarkerKind::kCircleE || kind == MarkerKind::kCircleF) {
    RequireOrigin(root, "disks", c0.center);
  }
  spec->keypoints.push_back(c0.center);  // m0

  switch (kind) {
    case MarkerKind::kCirclesA:
    case MarkerKind::kCirclesB: {
      const Disk& c1 = spec->circles[1];
      if ((c1.center - c0.center).norm() <= c0.radius_m + c1.radius_m) {
        root.Fail("disks", "two separate disks (centre distance > sum of radii)");
      }
      PaintDisk(spec, c0);
      PaintDisk(spec, c1);
      if (kind == MarkerKind::kCirclesA) {
        if (c0.color == c1.color) root.Fail("disks", "two disks of different colours");
        spec->keypoints.push_back(c1.center);
        break;
      }
      const Disk dot = ReadDiskKey(root, "feature_dot");
      if ((dot.center - c1.center).norm() + dot.radius_m >= c1.radius_m) {
        root.Fail("feature_dot", "a dot inside the second disk");
      }
      PaintDisk(spec, dot);
      spec->keypoints.push_back(dot.center);
      break;
    }
    case MarkerKind::kCirclesC: {
      const Disk& inner = spec->circles[1];
      if ((inner.center - c0.center).norm() > kGeometryTol) {
        root.Fail("disks", "an inner circle concentric with the outer one");
      }
      if (inner.radius_m >= c0.radius_m) {
        root.Fail("disks", "the outer circle first, then a smaller concentric inner circle");
      }
      PaintDisk(spec, c0);
      PaintDisk(spec, inner);
      const Disk dot = ReadDiskKey(root, "feature_dot");
      const double r = (dot.center - c0.center).norm();
      if (r - dot.radius_m <= inner.radius_m || r + dot.radius_m >= c0.radius_m) {
        root.Fail("feature_dot", "a dot between the inner and outer circles");
      }
      PaintDisk(spec, dot);
      spec->keypoints.push_back(dot.center);
      break;
    }
    case MarkerKind::kCircleD: {
      PaintDisk(spec, c0);
      const Disk center_dot = ReadDiskKey(root, "center_dot");
      if ((center_dot.center - c0.center).norm() > kGeometryTol) {
        root.Fail("center_dot", "a dot at the disk's centre (m0)");
      }
      if (center_dot.radius_m >= c0.radius_m)
        root.Fail("center_dot", "a dot smaller than the disk");
      PaintDisk(spec, center_dot);
      const Disk dot = ReadDiskKey(root, "feature_dot");
      if ((dot.center - c0.center).norm() - dot.radius_m <= c0.radius_m) {
        root.Fail("feature_dot", "a dot outside the disk");
      }
      PaintDisk(spec, dot);
      spec->keypoints.push_back(dot.center);
      break;
    }
    case MarkerKind::kCircleE: {
      PaintDisk(spec, c0);
      const Disk nose = ReadDiskKey(root, "center_dot");
      RequireOrigin(root, "center_dot", nose.center);
      if (nose.radius_m >= c0.radius_m) root.Fail("center_dot", "a dot smaller than the disk");
      PaintDisk(spec, nose);
      const YamlMap mouth = root.GetMap("mouth");
      const std::vector<double> tip_coords = mouth.Get<std::vector<double>>("tips");
      if (tip_coords.size() != 4) mouth.Fail("tips", "two tips as [x0, y0, x1, y1]");
      const Eigen::Vector2d tip0(tip_coords[0], tip_coords[1]);
      const Eigen::Vector2d tip1(tip_coords[2], tip_coords[3]);
      RequireOnXAxis(mouth, "tips", tip0);
      const double outer = mouth.GetLength("outer_sagitta");
      const double inner = mouth.GetLength("inner_sagitta");
      if (inner >= outer) mouth.Fail("inner_sagitta", "a sagitta smaller than outer_sagitta");
      const Rgb color = mouth.GetColor("color");
      mouth.RejectUnknownKeys();
      const Eigen::Vector2d along = (tip1 - tip0).normalized();
      const Eigen::Vector2d bulge =
          0.5 * (tip0 + tip1) + outer * Eigen::Vector2d(-along.y(), along.x());
      for (const Eigen::Vector2d& p : {tip0, tip1, bulge}) {
        if (p.norm() >= c0.radius_m) mouth.Fail("tips", "a mouth inside the disk");
      }
      const CrescentShape crescent = CrescentFromTips(tip0, tip1, outer, inner);
      spec->layers.push_back({crescent, color});
      spec->keypoints.push_back(tip0);
      spec->keypoints.push_back(tip1);
      break;
    }
    case MarkerKind::kCircleF: {
      PaintDisk(spec, c0);
      const YamlMap wedge = root.GetMap("wedge");
      const double angle_rad = wedge.GetDouble("angle_deg", 1.0, 180.0) * kPi / 180.0;
      const Rgb color = wedge.GetColor("color");
      wedge.RejectUnknownKeys();
      if (color == c0.color) wedge.Fail("color", "a colour that contrasts with the disk");
      const SectorShape wedge_shape({0.0, 0.0}, c0.radius_m, 0.0, angle_rad);
      spec->layers.push_back({wedge_shape, color});
      spec->keypoints.push_back({c0.radius_m, 0.0});
      spec->keypoints.push_back(c0.radius_m * wedge_shape.end_direction());
      break;
    }
    default:
      break;
  }
}

void AddSquareCorners(MarkerSpec* spec) {
  const double s = 0.5 * spec->size_m;
  spec->keypoints = {{-s, s}, {s, s}, {s, -s}, {-s, -s}};
}

// Data bits inside a black border of border_cells, inside a white quiet zone.
GridShape BorderedGrid(const YamlMap& root, double size_m) {
  const std::vector<std::string> data = root.Get<std::vector<std::string>>("data");
  const int border = root.GetInt("border_cells", 1, 16);
  const int quiet = root.GetInt("quiet_zone_cells", 0, 16);
  const int n = static_cast<int>(data.size());
  if (n < 1) root.Fail("data", "at least one row of '#' (ink) and '.' (paper)");
  for (const std::string& row : data) {
    if (static_cast<int>(row.size()) != n || row.find_first_not_of("#.") != std::string::npos) {
      root.Fail("data", "a square of rows made of '#' (ink) and '.' (paper)");
    }
  }
  const int inked = n + 2 * border;
  const int total = inked + 2 * quiet;
  GridShape grid;
  grid.rows = grid.cols = total;
  grid.cell_m = size_m / inked;
  grid.top_left = Eigen::Vector2d(-0.5 * total * grid.cell_m, 0.5 * total * grid.cell_m);
  grid.ink.assign(static_cast<size_t>(total * total), 0);
  for (int r = 0; r < total; ++r) {
    for (int c = 0; c < total; ++c) {
      const int ri = r - quiet, ci = c - quiet;
      const bool in_black = ri >= 0 && ci >= 0 && ri < inked && ci < inked;
      const int rd = ri - border, cd = ci - border;
      const bool in_data = rd >= 0 && cd >= 0 && rd < n && cd < n;
      const bool ink = in_data ? data[rd][cd] == '#' : in_black;
      grid.ink[static_cast<size_t>(r * total + c)] = ink ? 1 : 0;
    }
  }
  return grid;
}

void LoadSquareMarker(const YamlMap& root, MarkerSpec* spec) {
  spec->size_m = root.GetLength("size_m");
  GridShape grid;
  if (spec->kind == MarkerKind::kBitGrid) {
    grid = BorderedGrid(root, spec->size_m);
  } else if (spec->kind == MarkerKind::kArtkPlus) {
    spec->family = root.Get<std::string>("mode");
    spec->id = root.Get<int>("id");
    spec->border_fraction = root.Get<double>("border_fraction");
    try {
      grid = ArtkPlusGrid(spec->family, spec->id, spec->border_fraction, spec->size_m);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      root.Fail(what.rfind("an id mode", 0) == 0 ? "mode"
                : what.rfind("an id", 0) == 0    ? "id"
                                                 : "border_fraction",
                what);
    }
  } else {
    const char* family_key = spec->kind == MarkerKind::kAprilTag ? "family" : "dictionary";
    spec->family = root.Get<std::string>(family_key);
    spec->id = root.Get<int>("id");
    try {
      grid = spec->kind == MarkerKind::kAprilTag
                 ? AprilTagGrid(spec->family, spec->id, spec->size_m)
                 : ArucoGrid(spec->family, spec->id, spec->size_m);
    } catch (const std::invalid_argument& e) {
      root.Fail(std::string(e.what()).rfind("an id", 0) == 0 ? "id" : family_key, e.what());
    }
  }
  grid.paper_color = root.Has("paper_color") ? root.GetColor("paper_color") : Rgb::Ones();
  const Rgb ink = root.Has("ink_color") ? root.GetColor("ink_color") : Rgb::Zero();
  spec->layers.push_back({grid, ink});
  AddSquareCorners(spec);
}

// Dots of radius ring / dot_radius_ratio on rings of radius ring_fractions[r] · radius_m, at
// the angles 2πs/sectors counter-clockwise from +x, where has_dot(ring, sector); keypoints
// in slot order (sectors outer loop, rings inner).
template <typename HasDot>
void PaintDotRings(double radius_m,
                   const std::vector<double>& ring_fractions,
                   int sectors,
                   double dot_radius_ratio,
                   const Rgb& color,
                   const HasDot& has_dot,
                   MarkerSpec* spec) {
  for (int s = 0; s < sectors; ++s) {
    const double angle = 2.0 * kPi * s / sectors;
    for (size_t r = 0; r < ring_fractions.size(); ++r) {
      if (!has_dot(static_cast<int>(r), s)) continue;
      const double ring_m = ring_fractions[r] * radius_m;
      const Eigen::Vector2d center = ring_m * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      spec->layers.push_back({DiskShape{center, ring_m / dot_radius_ratio}, color});
      spec->keypoints.push_back(center);
    }
  }
}

void LoadDotRings(const YamlMap& root, MarkerSpec* spec) {
  const double radius_m = root.GetLength("radius_m");
  const std::vector<double> rings = root.Get<std::vector<double>>("ring_radii");
  const int sectors = root.GetInt("sectors", 3, 1000);
  const double ratio = root.GetDouble("dot_radius_ratio", 2.0, 1000.0);
  const std::vector<std::string> pattern = root.Get<std::vector<std::string>>("pattern");
  const Rgb color = root.Has("dot_color") ? root.GetColor("dot_color") : Rgb::Zero();
  if (rings.empty()) root.Fail("ring_radii", "at least one ring radius (fraction of radius_m)");
  for (double r : rings) {
    if (!(r > 0.0 && r <= 1.0)) root.Fail("ring_radii", "fractions of radius_m in (0, 1]");
  }
  if (pattern.size() != rings.size()) root.Fail("pattern", "one string per ring");
  for (const std::string& row : pattern) {
    if (static_cast<int>(row.size()) != sectors ||
        row.find_first_not_of("01") != std::string::npos) {
      root.Fail("pattern", "strings of '0'/'1', one character per sector");
    }
  }
  PaintDotRings(
      radius_m,
      rings,
      sectors,
      ratio,
      color,
      [&](int r, int s) { return pattern[static_cast<size_t>(r)][static_cast<size_t>(s)] == '1'; },
      spec);
  if (spec->keypoints.empty()) root.Fail("pattern", "at least one dot ('1')");
}

// baselines.md: the rings and dots of kRuneRingFractions and kRuneDotRadiusRatio, sector s
// holding the symbol of RuneCodeword(id) with the inner ring as its most significant bit.
void LoadRuneTag(const YamlMap& root, MarkerSpec* spec) {
  const double radius_m = root.GetLength("radius_m");
  spec->id = root.Get<int>("id");
  if (!IsRuneId(spec->id)) {
    const std::vector<int>& ids = RuneIds();
    root.Fail("id",
              "an id of the original RUNETag code list (" + std::to_string(ids.size()) +
                  " ids from " + std::to_string(ids.front()) + " to " + std::to_string(ids.back()) +
                  ": 8, 10, 15, 23, ...)");
  }
  spec->size_m = 2.0 * radius_m;
  const RuneWord& word = RuneCodeword(spec->id);
  PaintDotRings(
      radius_m,
      {kRuneRingFractions.begin(), kRuneRingFractions.end()},
      kRuneSectors,
      kRuneDotRadiusRatio,
      Rgb::Zero(),
      [&](int r, int s) { return (word[static_cast<size_t>(s)] >> (2 - r) & 1) != 0; },
      spec);
}

}  // namespace

MarkerSpec LoadMarkerYaml(const std::string& path) {
  const YamlMap root = YamlMap::LoadFile(path);
  MarkerSpec spec;
  spec.name = std::filesystem::path(path).stem().string();
  const std::string kind_name = root.Get<std::string>("kind");
  const std::optional<MarkerKind> kind = MarkerKindFromString(kind_name);
  if (!kind) {
    root.Fail("kind",
              "one of circles_a, circles_b, circles_c, circle_d, circle_e, circle_f, apriltag, "
              "aruco, bit_grid, artkplus, dot_rings, runetag");
  }
  spec.kind = *kind;
  spec.background = root.Has("background") ? root.GetColor("background") : Rgb::Ones();
  if (IsCircleKind(spec.kind)) {
    LoadCircleMarker(root, &spec);
  } else if (IsSquareKind(spec.kind)) {
    LoadSquareMarker(root, &spec);
  } else if (spec.kind == MarkerKind::kRuneTag) {
    LoadRuneTag(root, &spec);
  } else {
    LoadDotRings(root, &spec);
  }
  // Written by sweeps for external trackers: the scenario's equal-area scaling.
  if (root.Has("scale")) spec = ScaledMarker(spec, root.GetDouble("scale", 1e-3, 1e3));
  root.RejectUnknownKeys();
  return spec;
}

}  // namespace markerbench
