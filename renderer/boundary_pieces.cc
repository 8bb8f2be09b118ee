#include "renderer/boundary_pieces.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <variant>

namespace markerbench {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;
// Points per curve for estimating its image length (distortion bends even segments).
constexpr int kCircleLengthSamples = 64;
constexpr int kSegmentLengthSamples = 8;
// Bounds the work for edges that pass next to the camera, where the image length explodes.
constexpr int kMaxPiecesPerCurve = 1 << 18;
// The sides of an edge are probed this far from it, relative to the curve's size.
constexpr double kSideProbe = 1e-7;
// Points closer than this to the camera plane (metres) have no usable image.
constexpr double kMinDepthM = 1e-9;

// A printed edge in the marker plane: a circle (centre, radius) or a segment (a to b).
struct Curve {
  bool is_circle = false;
  Eigen::Vector2d a;
  Eigen::Vector2d b;
  double radius = 0.0;
  size_t layer = 0;  // the painted layer whose edge it is
  // The layer's colours on either side are the same all along (a disk's circle, a grid cell's
  // side): unless another layer reaches it, one probe decides the whole curve.
  bool uniform = false;

  Eigen::Vector2d At(double s) const {
    if (!is_circle) return a + s * (b - a);
    return a + radius * Eigen::Vector2d(std::cos(kTwoPi * s), std::sin(kTwoPi * s));
  }
  // A unit normal at s (outwards for circles, left of a → b for segments).
  Eigen::Vector2d NormalAt(double s) const {
    if (is_circle) return {std::cos(kTwoPi * s), std::sin(kTwoPi * s)};
    const Eigen::Vector2d d = (b - a).normalized();
    return {-d.y(), d.x()};
  }
  double Size() const { return is_circle ? radius : (b - a).norm(); }
  Eigen::AlignedBox2d Bounds() const {
    if (!is_circle) return Eigen::AlignedBox2d(a.cwiseMin(b), a.cwiseMax(b));
    return Eigen::AlignedBox2d(a - Eigen::Vector2d::Constant(radius),
                               a + Eigen::Vector2d::Constant(radius));
  }
};

bool InCircle(const DiskShape& disk, const Eigen::Vector2d& x) {
  return (x - disk.center).squaredNorm() <= disk.radius * disk.radius;
}

// The layer's colour at x, or nothing where it is transparent; the rasteriser's rules.
std::optional<Rgb> LayerColor(const PaintedShape& layer, const Eigen::Vector2d& x) {
  if (const auto* disk = std::get_if<DiskShape>(&layer.shape)) {
    if (InCircle(*disk, x)) return layer.color;
    return std::nullopt;
  }
  if (const auto* crescent = std::get_if<CrescentShape>(&layer.shape)) {
    if (InCircle(crescent->outer, x) && !InCircle(crescent->inner, x)) return layer.color;
    return std::nullopt;
  }
  if (const auto* sector = std::get_if<SectorShape>(&layer.shape)) {
    const Eigen::Vector2d d = x - sector->center();
    const Eigen::Vector2d& start = sector->start_direction();
    const Eigen::Vector2d& end = sector->end_direction();
    // Inside the circle, left of the start ray and right of the end ray (span <= π).
    if (d.squaredNorm() <= sector->radius() * sector->radius() &&
        start.y() * d.x() - start.x() * d.y() <= 0.0 && -end.y() * d.x() + end.x() * d.y() <= 0.0) {
      return layer.color;
    }
    return std::nullopt;
  }
  const auto& grid = std::get<GridShape>(layer.shape);
  const double gx = (x.x() - grid.top_left.x()) / grid.cell_m;
  const double gy = (grid.top_left.y() - x.y()) / grid.cell_m;
  if (!(gx >= 0.0 && gy >= 0.0 && gx < grid.cols && gy < grid.rows)) return std::nullopt;
  return grid.Ink(static_cast<int>(gy), static_cast<int>(gx)) ? layer.color : grid.paper_color;
}

std::vector<Curve> CurvesOf(const PaintedShape& layer, size_t index) {
  auto circle = [index](const DiskShape& disk, bool uniform) {
    return Curve{true, disk.center, disk.center, disk.radius, index, uniform};
  };
  auto segment = [index](const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool uniform) {
    return Curve{false, a, b, 0.0, index, uniform};
  };
  if (const auto* disk = std::get_if<DiskShape>(&layer.shape)) return {circle(*disk, true)};
  if (const auto* crescent = std::get_if<CrescentShape>(&layer.shape)) {
    return {circle(crescent->outer, false), circle(crescent->inner, false)};
  }
  if (const auto* sector = std::get_if<SectorShape>(&layer.shape)) {
    const Eigen::Vector2d& c = sector->center();
    const double r = sector->radius();
    const Eigen::Vector2d& start = sector->start_direction();
    const Eigen::Vector2d& end = sector->end_direction();
    return {
        circle({c, r}, false), segment(c, c + r * start, false), segment(c, c + r * end, false)};
  }
  // Grid: every cell side once, so the layer's colours are constant along each curve.
  const auto& grid = std::get<GridShape>(layer.shape);
  const Eigen::Vector2d& tl = grid.top_left;
  const double h = grid.cell_m;
  std::vector<Curve> curves;
  for (int r = 0; r <= grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const double y = tl.y() - r * h;
      curves.push_back(segment({tl.x() + c * h, y}, {tl.x() + (c + 1) * h, y}, true));
    }
  }
  for (int c = 0; c <= grid.cols; ++c) {
    for (int r = 0; r < grid.rows; ++r) {
      const double x = tl.x() + c * h;
      curves.push_back(segment({x, tl.y() - r * h}, {x, tl.y() - (r + 1) * h}, true));
    }
  }
  return curves;
}

class EdgeWalker {
 public:
  EdgeWalker(const Scene& scene, int channels, const Eigen::AlignedBox2d& window_px)
      : scene_(scene), marker_(*scene.marker), channels_(channels), window_(window_px) {
    for (const PaintedShape& layer : marker_.layers) bounds_.push_back(ShapeBounds(layer.shape));
  }

  void Walk(const Curve& curve, double max_piece_px, std::vector<BoundaryPiece>* pieces) const {
    if (curve.uniform && !Overlapped(curve)) {
      // One probe for the whole curve: most grid sides lie between cells of one colour.
      const Sides sides = Probe(curve, 0.5);
      if (!OwnsEdge(curve.layer, sides) || IsZero(Jump(sides))) return;
    }
    const int n = PieceCount(curve, max_piece_px);
    std::optional<Eigen::Vector2d> previous = Image(curve.At(0.0));
    for (int i = 0; i < n; ++i) {
      const std::optional<Eigen::Vector2d> next = Image(curve.At(static_cast<double>(i + 1) / n));
      if (previous && next && (window_.contains(*previous) || window_.contains(*next))) {
        AddPiece(curve, (i + 0.5) / n, *previous, *next, pieces);
      }
      previous = next;
    }
  }

 private:
  std::optional<Eigen::Vector2d> Image(const Eigen::Vector2d& x) const {
    const Eigen::Vector3d x_cam = scene_.cam_from_marker * Eigen::Vector3d(x.x(), x.y(), 0.0);
    if (!(x_cam.z() > kMinDepthM)) return std::nullopt;
    const Eigen::Vector2d p = scene_.camera.ImgFromCam(x_cam);
    if (!p.allFinite()) return std::nullopt;
    return p;
  }

  int PieceCount(const Curve& curve, double max_piece_px) const {
    const int samples = curve.is_circle ? kCircleLengthSamples : kSegmentLengthSamples;
    double length_px = 0.0;
    std::optional<Eigen::Vector2d> previous = Image(curve.At(0.0));
    for (int i = 1; i <= samples; ++i) {
      const std::optional<Eigen::Vector2d> next = Image(curve.At(static_cast<double>(i) / samples));
      if (previous && next) length_px += (*next - *previous).norm();
      previous = next;
    }
    // Chords under-estimate a curve's length (by 0.04 % for a circle's 64): a 1 % margin.
    const double pieces = std::ceil(1.01 * length_px / max_piece_px);
    return static_cast<int>(std::clamp(pieces, 1.0, static_cast<double>(kMaxPiecesPerCurve)));
  }

  // The colour the rasteriser paints at x: the top-most layer that is not transparent there.
  Rgb SceneColor(const Eigen::Vector2d& x) const {
    for (size_t i = marker_.layers.size(); i-- > 0;) {
      if (!bounds_[i].contains(x)) continue;
      if (std::optional<Rgb> c = LayerColor(marker_.layers[i], x)) return *c;
    }
    return marker_.background;
  }

  // Whether another layer reaches the curve's bounds: above it, it may hide the edge; below
  // it, it may show through where the curve's own layer is transparent.
  bool Overlapped(const Curve& curve) const {
    const Eigen::AlignedBox2d box = curve.Bounds();
    for (size_t i = 0; i < bounds_.size(); ++i) {
      if (i != curve.layer && bounds_[i].intersects(box)) return true;
    }
    return false;
  }

  // The marker-plane points just either side of the curve at s.
  struct Sides {
    Eigen::Vector2d plus, minus;
  };
  static Sides Probe(const Curve& curve, double s) {
    const Eigen::Vector2d step = kSideProbe * curve.Size() * curve.NormalAt(s);
    return {curve.At(s) + step, curve.At(s) - step};
  }

  // Whether `layer` is the top-most layer whose colour differs across the edge.
  bool OwnsEdge(size_t layer, const Sides& sides) const {
    for (size_t i = marker_.layers.size(); i-- > layer;) {
      const bool near = bounds_[i].contains(sides.plus) || bounds_[i].contains(sides.minus);
      if (!near) continue;
      const bool differs =
          LayerColor(marker_.layers[i], sides.plus) != LayerColor(marker_.layers[i], sides.minus);
      if (differs) return i == layer;
    }
    return false;
  }

  // Colour on the plus side minus the other, per channel (Rec. 601 luma for grey).
  std::array<double, 3> Jump(const Sides& sides) const {
    const Rgb jump = SceneColor(sides.plus) - SceneColor(sides.minus);
    if (channels_ == 1) return {Luma(jump), 0.0, 0.0};
    return {jump.x(), jump.y(), jump.z()};
  }
  static bool IsZero(const std::array<double, 3>& jump) {
    return jump[0] == 0.0 && jump[1] == 0.0 && jump[2] == 0.0;
  }

  void AddPiece(const Curve& curve,
                double s_mid,
                const Eigen::Vector2d& a_px,
                const Eigen::Vector2d& b_px,
                std::vector<BoundaryPiece>* pieces) const {
    const Sides sides = Probe(curve, s_mid);
    if (!OwnsEdge(curve.layer, sides)) return;
    BoundaryPiece piece;
    piece.jump = Jump(sides);
    if (IsZero(piece.jump)) return;
    const Eigen::Vector2d x = curve.At(s_mid);
    const Eigen::Vector2d normal = curve.NormalAt(s_mid);
    piece.a_px = a_px;
    piece.b_px = b_px;
    piece.mid_cam = scene_.cam_from_marker * Eigen::Vector3d(x.x(), x.y(), 0.0);
    // Image direction of the plus side: the marker-plane normal through the projection.
    const Eigen::Vector2d plus_px = ImgFromCamJacobian(scene_.camera, piece.mid_cam) *
                                    scene_.cam_from_marker.rotation.leftCols<2>() * normal;
    const Eigen::Vector2d d = b_px - a_px;
    piece.normal_px = Eigen::Vector2d(-d.y(), d.x());
    if (piece.normal_px.dot(plus_px) < 0.0) piece.normal_px = -piece.normal_px;
    pieces->push_back(piece);
  }

  const Scene& scene_;
  const MarkerSpec& marker_;
  int channels_;
  Eigen::AlignedBox2d window_;
  std::vector<Eigen::AlignedBox2d> bounds_;
};

}  // namespace

Eigen::Matrix<double, 2, 3> ImgFromCamJacobian(const Camera& camera, const Eigen::Vector3d& x_cam) {
  const double z = x_cam.z();
  const Eigen::Vector2d n = x_cam.head<2>() / z;
  Eigen::Matrix<double, 2, 3> dn_dx;
  dn_dx << 1.0 / z, 0.0, -n.x() / z, 0.0, 1.0 / z, -n.y() / z;
  Eigen::Matrix2d dp_dn = Eigen::Vector2d(camera.fx, camera.fy).asDiagonal();
  if (camera.HasDistortion()) dp_dn = dp_dn * camera.DistortJacobian(n);
  return dp_dn * dn_dx;
}

std::vector<BoundaryPiece> ImageBoundaryPieces(const Scene& scene,
                                               int channels,
                                               const Eigen::AlignedBox2d& window_px,
                                               double max_piece_px) {
  const EdgeWalker walker(scene, channels, window_px);
  std::vector<BoundaryPiece> pieces;
  const MarkerSpec& marker = *scene.marker;
  for (size_t i = 0; i < marker.layers.size(); ++i) {
    for (const Curve& curve : CurvesOf(marker.layers[i], i)) {
      walker.Walk(curve, max_piece_px, &pieces);
    }
  }
  return pieces;
}

}  // namespace markerbench
