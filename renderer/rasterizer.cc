#include "renderer/rasterizer.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace markerbench {
namespace {

constexpr int kMaxDepth = 5;  // cells down to 1/32 px
// Largest h²·κ·anisotropy for which one line per cell stays below 1/255 per pixel.
constexpr double kCurvatureBudget = 0.006;
// A boundary farther than kReach·h (> √2/2·h) from the cell centre misses the cell.
constexpr double kReach = 0.75;
constexpr int kMaxGridCellsPerFootprint = 64;
// Layer tests a render may make (about half a second) before the rest of its pixels are
// point-sampled. Renders of the paper sweeps make about 250 000; a grazing close-up of
// RUNETag's 129 dots, where every cell is curved and crossed, would take minutes without it.
constexpr int64_t kLayerTestsPerRender = 10'000'000;

struct Color {
  std::array<float, 3> v{};
};

Color ToColor(const Rgb& rgb, int channels) {
  Color c;
  if (channels == 1) {
    c.v[0] = static_cast<float>(Luma(rgb));
  } else {
    for (int i = 0; i < 3; ++i) c.v[i] = static_cast<float>(rgb[i]);
  }
  return c;
}

// The marker-plane point under a pixel and the local derivative dX/dp (metres per pixel),
// and the pixel's signed distance to the horizon (the image of the plane's line at infinity,
// a curve under distortion), linearised at the pixel: positive beyond it (rays that miss the
// plane), +-inf when the view has no horizon.
struct PlanePoint {
  bool on_plane = false;
  Eigen::Vector2d X;
  Eigen::Matrix2d dX_dp;
  double horizon_px = -INFINITY;
  Eigen::Vector2d horizon_normal = Eigen::Vector2d::UnitX();  // towards beyond the horizon
};

// Singular values of dX_dp (largest, smallest).
std::pair<double, double> SingularValues(const Eigen::Matrix2d& m) {
  const double frob2 = m.squaredNorm();
  const double det = std::abs(m.determinant());
  const double disc = std::sqrt(std::max(0.0, frob2 * frob2 - 4.0 * det * det));
  const double sigma_max = std::sqrt(0.5 * (frob2 + disc));
  return {sigma_max, det / std::max(sigma_max, 1e-300)};
}

class PlaneMapper {
 public:
  PlaneMapper(const Camera& camera, const Rigid3& cam_from_marker) : camera_(camera) {
    plane_from_ray_ = RayFromPlane(cam_from_marker).inverse();
    distorted_ = camera.HasDistortion();
  }

  PlanePoint Map(double u, double v) const {
    PlanePoint p;
    Eigen::Vector2d n((u - camera_.cx) / camera_.fx, (v - camera_.cy) / camera_.fy);
    Eigen::Matrix2d dn_dp = Eigen::Vector2d(1.0 / camera_.fx, 1.0 / camera_.fy).asDiagonal();
    if (distorted_) {
      n = camera_.Undistort(n);
      dn_dp = camera_.DistortJacobian(n).inverse() * dn_dp;
    }
    const Eigen::Vector3d w = plane_from_ray_ * Eigen::Vector3d(n.x(), n.y(), 1.0);
    // w.z() is linear in the undistorted ray n and zero on the horizon.
    const Eigen::Vector2d grad = dn_dp.transpose() * plane_from_ray_.row(2).head<2>().transpose();
    if (grad.norm() > 0.0) {
      p.horizon_px = -w.z() / grad.norm();
      p.horizon_normal = -grad / grad.norm();
    } else {
      p.horizon_px = w.z() > 0.0 ? -INFINITY : INFINITY;
    }
    if (!(w.z() > 0.0)) return p;  // the ray meets the plane behind the camera, or never
    p.on_plane = true;
    p.X = w.head<2>() / w.z();
    Eigen::Matrix2d dX_dn;
    for (int c = 0; c < 2; ++c) {
      dX_dn.col(c) = (plane_from_ray_.col(c).head<2>() - p.X * plane_from_ray_(2, c)) / w.z();
    }
    p.dX_dp = dX_dn * dn_dp;
    return p;
  }

 private:
  Camera camera_;
  Eigen::Matrix3d plane_from_ray_;
  bool distorted_ = false;
};

// One boundary piece of a shape: inside a circle (sign +1), outside it (sign -1), or the
// half-plane normal·X <= offset.
struct Constraint {
  bool is_circle = false;
  Eigen::Vector2d center_or_normal;
  double radius_or_offset = 0.0;
  double sign = 1.0;
};

enum class LayerType { kConstraints, kGrid, kPlane };

struct Layer {
  LayerType type = LayerType::kConstraints;
  std::vector<Constraint> constraints;
  const GridShape* grid = nullptr;
  Color color;  // ink / inside colour
  Color paper;  // grid paper cells, plane paper
  // kPlane without distortion: the horizon as an image line, |(a, b)| = 1, paper where < 0
  // (with distortion: PlanePoint::horizon_px).
  bool has_horizon = false;
  Eigen::Vector3d horizon;
  // Pixels outside this box see the layer as transparent (plane layers: whole canvas).
  double u_min = -1e300, u_max = 1e300, v_min = -1e300, v_max = 1e300;
};

// floor() as an int without a libm call (x86-64 baseline has no SSE4.1 roundsd).
int FloorInt(double x) {
  const int i = static_cast<int>(x);
  return i - (x < i);
}

enum class SampleType { kUniform, kEdge, kComplex };

// How a layer covers a cell: uniformly (colour or nullptr = transparent), split by one
// image-space line (neg side where normal·(p - centre) + dist < 0), or too complex.
struct Sample {
  SampleType type = SampleType::kUniform;
  const Color* neg = nullptr;
  const Color* pos = nullptr;
  Eigen::Vector2d normal;
  double dist = 0.0;
};

Sample Uniform(const Color* c) { return {SampleType::kUniform, c, c, {}, 0.0}; }
Sample Complex() { return {SampleType::kComplex, nullptr, nullptr, {}, 0.0}; }
Sample Edge(const Color* neg, const Color* pos, const Eigen::Vector2d& n, double d) {
  return {SampleType::kEdge, neg, pos, n, d};
}

// Image-space line from a marker-plane signed distance s with marker gradient g.
Sample EdgeFromPlane(
    const Color* neg, const Color* pos, const PlanePoint& p, double s, const Eigen::Vector2d& g) {
  const Eigen::Vector2d gi = p.dX_dp.transpose() * g;
  const double gn = gi.norm();
  return Edge(neg, pos, gi / gn, s / gn);
}

// A cell the horizon crosses: subdivided (its plane points are not all defined). The slack
// covers the bend of a distorted horizon across a block.
bool StraddlesHorizon(const PlanePoint& p, double h) {
  constexpr double kHorizonSlack = 1.5;
  return h > 0.0 && std::abs(p.horizon_px) <= kHorizonSlack * kReach * h;
}

Sample ClassifyConstraints(const Layer& layer, const PlanePoint& p, double h) {
  if (StraddlesHorizon(p, h)) return Complex();
  if (!p.on_plane) return Uniform(nullptr);
  int crossings = 0;
  bool too_curved = false;
  Sample edge;
  const auto [sigma_max, sigma_min] = SingularValues(p.dX_dp);
  const double anisotropy = sigma_max / sigma_min;
  for (const Constraint& c : layer.constraints) {
    double s;
    Eigen::Vector2d g;
    double reach = kReach * h;
    double curvature_term = 0.0;
    if (c.is_circle) {
      const Eigen::Vector2d dx = p.X - c.center_or_normal;
      const double rho = dx.norm();
      s = c.sign * (rho - c.radius_or_offset);
      g = rho > 0.0 ? Eigen::Vector2d(c.sign * dx / rho) : Eigen::Vector2d(1.0, 0.0);
      // Largest image curvature of the circle, σmax²/(σmin·r) px⁻¹, times h², anisotropy.
      const double kappa = sigma_max * sigma_max / (sigma_min * c.radius_or_offset);
      curvature_term = h * h * kappa * anisotropy;
      reach += curvature_term;  // slack for the linearised distance
    } else {
      s = c.center_or_normal.dot(p.X) - c.radius_or_offset;
      g = c.center_or_normal;
    }
    const Eigen::Vector2d gi = p.dX_dp.transpose() * g;
    const double gn = gi.norm();
    const double d = s / gn;
    if (d > reach) return Uniform(nullptr);
    if (d >= -reach) {
      ++crossings;
      edge = Edge(&layer.color, nullptr, gi / gn, d);
      too_curved |= curvature_term > kCurvatureBudget;
    }
  }
  if (crossings == 0) return Uniform(&layer.color);
  if (crossings == 1 && !too_curved) return edge;
  return Complex();
}

Sample ClassifyGrid(const Layer& layer, const PlanePoint& p, double h) {
  if (StraddlesHorizon(p, h)) return Complex();
  if (!p.on_plane) return Uniform(nullptr);
  const GridShape& grid = *layer.grid;
  const double gx = (p.X.x() - grid.top_left.x()) / grid.cell_m;
  const double gy = (grid.top_left.y() - p.X.y()) / grid.cell_m;
  constexpr double kFootprintSlack = 1.05;
  const double ex = kFootprintSlack * 0.5 * h * p.dX_dp.row(0).cwiseAbs().sum() / grid.cell_m;
  const double ey = kFootprintSlack * 0.5 * h * p.dX_dp.row(1).cwiseAbs().sum() / grid.cell_m;
  // Decide in floating point before any cell index exists: a footprint of more cells than
  // we count, or one wholly outside the grid (seen at grazing angles, from far away).
  if (!(ex <= kMaxGridCellsPerFootprint && ey <= kMaxGridCellsPerFootprint)) return Complex();
  if (gx + ex < 0.0 || gy + ey < 0.0 || gx - ex >= grid.cols || gy - ey >= grid.rows) {
    return Uniform(nullptr);
  }
  const int c0 = FloorInt(gx - ex), c1 = FloorInt(gx + ex);
  const int r0 = FloorInt(gy - ey), r1 = FloorInt(gy + ey);
  if ((c1 - c0 + 1) * (r1 - r0 + 1) > kMaxGridCellsPerFootprint) return Complex();
  // -1: outside the grid (transparent), 0: paper, 1: ink.
  auto value = [&](int r, int c) {
    if (r < 0 || c < 0 || r >= grid.rows || c >= grid.cols) return -1;
    return grid.Ink(r, c) ? 1 : 0;
  };
  auto color_of = [&](int v) -> const Color* {
    return v < 0 ? nullptr : (v == 1 ? &layer.color : &layer.paper);
  };
  bool rows_equal = true, cols_equal = true;  // value depends only on the column / row
  const int first = value(r0, c0);
  bool all_equal = true;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const int v = value(r, c);
      all_equal &= v == first;
      rows_equal &= v == value(r0, c);
      cols_equal &= v == value(r, c0);
    }
  }
  if (all_equal) return Uniform(color_of(first));
  if (rows_equal && c1 == c0 + 1) {  // one vertical boundary at column c1
    const double xb = grid.top_left.x() + c1 * grid.cell_m;
    return EdgeFromPlane(color_of(value(r0, c0)),
                         color_of(value(r0, c1)),
                         p,
                         p.X.x() - xb,
                         Eigen::Vector2d(1.0, 0.0));
  }
  if (cols_equal && r1 == r0 + 1) {  // one horizontal boundary below row r0
    const double yb = grid.top_left.y() - r1 * grid.cell_m;
    return EdgeFromPlane(color_of(value(r1, c0)),
                         color_of(value(r0, c0)),
                         p,
                         p.X.y() - yb,
                         Eigen::Vector2d(0.0, 1.0));
  }
  return Complex();
}

// The infinite plane: paper up to the horizon, an exact line without distortion, else the
// distorted curve linearised per cell (cells near it are subdivided down to pixels, where
// the curve is straight to well below 1/255 of a pixel's area).
Sample ClassifyPlane(const Layer& layer, const PlanePoint& p, double u, double v, double h) {
  if (layer.has_horizon) {
    const double d = layer.horizon.dot(Eigen::Vector3d(u, v, 1.0));
    if (d > kReach * h) return Uniform(nullptr);
    if (d < -kReach * h) return Uniform(&layer.paper);
    return Edge(&layer.paper, nullptr, layer.horizon.head<2>(), d);
  }
  if (h > 1.0 && StraddlesHorizon(p, h)) return Complex();
  if (p.horizon_px > kReach * h) return Uniform(nullptr);
  if (p.horizon_px < -kReach * h) return Uniform(&layer.paper);
  return Edge(&layer.paper, nullptr, p.horizon_normal, p.horizon_px);
}

// Area fraction of an h×h cell where normal·(p - centre) < t (Minkowski sum of two boxes: a
// trapezoidal distribution of normal·(p - centre)).
double HalfPlaneFraction(double t, const Eigen::Vector2d& normal, double h) {
  double a = h * std::abs(normal.x()), b = h * std::abs(normal.y());
  if (a < b) std::swap(a, b);
  const double half = 0.5 * (a + b), lo = 0.5 * (a - b);
  if (t <= -half) return 0.0;
  if (t >= half) return 1.0;
  if (t < -lo) return (t + half) * (t + half) / (2.0 * a * b);
  if (t <= lo) return 0.5 + t / a;
  return 1.0 - (half - t) * (half - t) / (2.0 * a * b);
}

class CellShader {
 public:
  CellShader(const PlaneMapper& mapper,
             const std::vector<Layer>& layers,
             const Color& backdrop,
             int channels)
      : mapper_(mapper), layers_(layers), backdrop_(backdrop), channels_(channels) {}

  // Area-average colour of the square cell of side h centred at (u, v).
  // Fills the size x size pixel block at (x0, y0) (clipped to `image`): one colour when the
  // whole block is provably uniform, else four sub-blocks, down to single pixels.
  void FillBlock(int x0, int y0, int size, ImageF* image) const {
    const int x1 = std::min(x0 + size, image->width), y1 = std::min(y0 + size, image->height);
    if (x0 >= x1 || y0 >= y1) return;
    if (size == 1) {
      float acc[3] = {0.0f, 0.0f, 0.0f};
      Shade(x0, y0, 1.0, 0, 1.0f, acc);
      for (int k = 0; k < channels_; ++k) {
        image->plane(k)[static_cast<size_t>(y0) * image->width + x0] = acc[k];
      }
      return;
    }
    Color c;
    // A block is tested as a cell 25 % larger than itself: slack for the perspective change of
    // the linearised distances across a block many pixels wide.
    constexpr double kBlockSlack = 1.25;
    const double center = 0.5 * (size - 1);
    if (ShadeCell(x0 + center, y0 + center, kBlockSlack * size, /*allow_edge=*/false, &c)) {
      for (int k = 0; k < channels_; ++k) {
        for (int y = y0; y < y1; ++y) {
          std::fill(image->plane(k) + static_cast<size_t>(y) * image->width + x0,
                    image->plane(k) + static_cast<size_t>(y) * image->width + x1,
                    c.v[k]);
        }
      }
      return;
    }
    const int half = size / 2;
    FillBlock(x0, y0, half, image);
    FillBlock(x0 + half, y0, half, image);
    FillBlock(x0, y0 + half, half, image);
    FillBlock(x0 + half, y0 + half, half, image);
  }

  // Area average of the cell by recursive subdivision, down to kMaxDepth or until the
  // render's budget of layer tests is spent; then the centre point.
  void Shade(double u, double v, double h, int depth, float weight, float* acc) const {
    Color c;
    if (depth == kMaxDepth || layer_tests_ > kLayerTestsPerRender) {
      ShadeCell(u, v, 0.0, /*allow_edge=*/true, &c);
    } else if (!ShadeCell(u, v, h, /*allow_edge=*/true, &c)) {
      const double q = 0.25 * h;
      for (int i = 0; i < 4; ++i) {
        Shade(u + ((i & 1) ? q : -q),
              v + ((i & 2) ? q : -q),
              0.5 * h,
              depth + 1,
              0.25f * weight,
              acc);
      }
      return;
    }
    for (int k = 0; k < channels_; ++k) acc[k] += weight * c.v[k];
  }

 private:
  // Colour of the cell when at most one straight boundary crosses it; false otherwise.
  // h = 0 samples the centre point.
  bool ShadeCell(double u, double v, double h, bool allow_edge, Color* out) const {
    const PlanePoint p = mapper_.Map(u, v);
    const Color* stop = &backdrop_;
    bool have_edge = false;
    Sample edge;
    const double half = 0.5 * h;
    for (auto it = layers_.rbegin(); it != layers_.rend(); ++it) {
      const Layer& layer = *it;
      if (u + half < layer.u_min || u - half > layer.u_max || v + half < layer.v_min ||
          v - half > layer.v_max) {
        continue;
      }
      ++layer_tests_;
      Sample s = layer.type == LayerType::kConstraints ? ClassifyConstraints(layer, p, h)
                 : layer.type == LayerType::kGrid      ? ClassifyGrid(layer, p, h)
                                                       : ClassifyPlane(layer, p, u, v, h);
      if (s.type == SampleType::kComplex) return false;
      if (s.type == SampleType::kEdge && h == 0.0) s = Uniform(s.dist < 0.0 ? s.neg : s.pos);
      if (s.type == SampleType::kUniform) {
        if (s.neg == nullptr) continue;
        stop = s.neg;
        break;
      }
      if (have_edge || !allow_edge) return false;
      have_edge = true;
      edge = s;
      if (s.neg && s.pos) break;  // both sides opaque: nothing below shows
    }
    if (!have_edge) {
      *out = *stop;
      return true;
    }
    const Color& neg = edge.neg ? *edge.neg : *stop;
    const Color& pos = edge.pos ? *edge.pos : *stop;
    const float f = static_cast<float>(HalfPlaneFraction(-edge.dist, edge.normal, h));
    for (int k = 0; k < channels_; ++k) out->v[k] = f * neg.v[k] + (1.0f - f) * pos.v[k];
    return true;
  }

  const PlaneMapper& mapper_;
  const std::vector<Layer>& layers_;
  Color backdrop_;
  int channels_;
  mutable int64_t layer_tests_ = 0;  // so far in this render (one thread renders a frame)
};

Constraint Circle(const DiskShape& disk, double sign) {
  return {true, disk.center, disk.radius, sign};
}

// Half-plane normal·(X - point) <= 0.
Constraint HalfPlane(const Eigen::Vector2d& normal, const Eigen::Vector2d& point) {
  return {false, normal, normal.dot(point), 1.0};
}

std::vector<Constraint> ConstraintsOf(const Shape& shape) {
  if (const auto* disk = std::get_if<DiskShape>(&shape)) return {Circle(*disk, 1.0)};
  if (const auto* crescent = std::get_if<CrescentShape>(&shape)) {
    return {Circle(crescent->outer, 1.0), Circle(crescent->inner, -1.0)};
  }
  const auto& sector = std::get<SectorShape>(shape);
  const Eigen::Vector2d& start = sector.start_direction();
  const Eigen::Vector2d& end = sector.end_direction();
  // Left of the start ray and right of the end ray (span <= π).
  return {Circle({sector.center(), sector.radius()}, 1.0),
          HalfPlane(Eigen::Vector2d(start.y(), -start.x()), sector.center()),
          HalfPlane(Eigen::Vector2d(-end.y(), end.x()), sector.center())};
}

// Image bounds of a marker-plane box; unbounded when part of it is behind the camera.
void SetImageBounds(const Eigen::AlignedBox2d& box,
                    const Camera& camera,
                    const Rigid3& cam_from_marker,
                    Layer* layer) {
  constexpr int kStepsPerSide = 16;  // distortion bends the box's sides
  constexpr double kMarginPx = 2.0;
  // Depth is linear on the plane: a box whose corners are all behind the camera is unseen.
  bool seen = false;
  for (const Eigen::Vector2d& corner : {box.min(),
                                        box.max(),
                                        Eigen::Vector2d(box.min().x(), box.max().y()),
                                        Eigen::Vector2d(box.max().x(), box.min().y())}) {
    seen |= (cam_from_marker * Eigen::Vector3d(corner.x(), corner.y(), 0.0)).z() > 0.0;
  }
  if (!seen) {
    layer->u_min = layer->v_min = 1e300;
    layer->u_max = layer->v_max = -1e300;
    return;
  }
  Eigen::AlignedBox2d image_box;
  for (const Eigen::Vector2d& x : BoxOutline(box, kStepsPerSide)) {
    const Eigen::Vector3d x_cam = cam_from_marker * Eigen::Vector3d(x.x(), x.y(), 0.0);
    if (!(x_cam.z() > 1e-9)) return;  // leave unbounded
    image_box.extend(camera.ImgFromCam(x_cam));
  }
  layer->u_min = image_box.min().x() - kMarginPx;
  layer->v_min = image_box.min().y() - kMarginPx;
  layer->u_max = image_box.max().x() + kMarginPx;
  layer->v_max = image_box.max().y() + kMarginPx;
}

// A finite sheet: the rectangle of `size_m` centred on the ink bounds.
std::vector<Constraint> SheetConstraints(const MarkerSpec& marker, const Eigen::Vector2d& size_m) {
  const Eigen::Vector2d c = marker.InkBounds().center();
  const Eigen::Vector2d half = 0.5 * size_m;
  return {HalfPlane({1.0, 0.0}, c + half),
          HalfPlane({-1.0, 0.0}, c - half),
          HalfPlane({0.0, 1.0}, c + half),
          HalfPlane({0.0, -1.0}, c - half)};
}

// Is the infinite plane seen over the whole canvas (+1), nowhere (-1) or partly (0)?
int PlaneCoverage(const Layer& plane, const PlaneMapper& mapper, const Camera& camera) {
  constexpr int kSteps = 32;
  int on = 0, total = 0;
  for (int side = 0; side < 4; ++side) {
    for (int i = 0; i <= kSteps; ++i) {
      const double t = static_cast<double>(i) / kSteps;
      const double w = camera.width - 0.5, h = camera.height - 0.5;
      const double u = side < 2 ? -0.5 + t * (w + 0.5) : (side == 2 ? -0.5 : w);
      const double v = side < 2 ? (side == 0 ? -0.5 : h) : -0.5 + t * (h + 0.5);
      bool seen;
      if (plane.has_horizon) {
        const double d = plane.horizon.dot(Eigen::Vector3d(u, v, 1.0));
        if (std::abs(d) < 1.0) return 0;
        seen = d < 0.0;
      } else {
        seen = mapper.Map(u, v).on_plane;
      }
      on += seen;
      ++total;
    }
  }
  return on == total ? 1 : (on == 0 ? -1 : 0);
}

}  // namespace

RasterResult Rasterize(const Scene& scene, int channels) {
  const Camera& camera = scene.camera;
  const MarkerSpec& marker = *scene.marker;
  const PlaneMapper mapper(camera, scene.cam_from_marker);
  const Color paper = ToColor(marker.background, channels);
  const Color backdrop = ToColor(scene.backdrop, channels);

  std::vector<Layer> layers;
  Color base = backdrop;  // the colour outside every bounded layer
  bool base_uniform = true;
  if (scene.sheet_size_m) {
    Layer sheet;
    sheet.constraints = SheetConstraints(marker, *scene.sheet_size_m);
    sheet.color = paper;
    const Eigen::Vector2d c = marker.InkBounds().center();
    SetImageBounds({c - 0.5 * *scene.sheet_size_m, c + 0.5 * *scene.sheet_size_m},
                   camera,
                   scene.cam_from_marker,
                   &sheet);
    layers.push_back(sheet);
  } else {
    Layer plane;
    plane.type = LayerType::kPlane;
    plane.paper = paper;
    if (!camera.HasDistortion()) {
      // Rays through p meet the plane in front iff r3ᵀ K⁻¹ p < 0 (camera on the +z side).
      const Eigen::Vector3d l =
          camera.K().inverse().transpose() * scene.cam_from_marker.rotation.col(2);
      const double norm = l.head<2>().norm();
      if (norm > 1e-12 * std::abs(l.z())) {
        plane.has_horizon = true;
        plane.horizon = l / norm;
      }
    }
    const int coverage = PlaneCoverage(plane, mapper, camera);
    if (coverage == 1) base = paper;
    base_uniform = coverage != 0;
    layers.push_back(plane);
  }
  const std::vector<PaintedShape> no_ink;
  for (const PaintedShape& painted : scene.marker_hidden ? no_ink : marker.layers) {
    Layer layer;
    layer.color = ToColor(painted.color, channels);
    if (const auto* grid = std::get_if<GridShape>(&painted.shape)) {
      layer.type = LayerType::kGrid;
      layer.grid = grid;
      layer.paper = ToColor(grid->paper_color, channels);
    } else {
      layer.constraints = ConstraintsOf(painted.shape);
    }
    SetImageBounds(ShapeBounds(painted.shape), camera, scene.cam_from_marker, &layer);
    layers.push_back(layer);
  }

  // Pixels that some bounded layer may touch; the rest take the base colour.
  PixelRect roi{camera.width, camera.height, 0, 0};
  for (const Layer& layer : layers) {
    if (layer.type == LayerType::kPlane || layer.u_min > layer.u_max) continue;
    roi.x0 = std::min(roi.x0, static_cast<int>(std::floor(std::clamp(layer.u_min, -1.0, 1e9))));
    roi.y0 = std::min(roi.y0, static_cast<int>(std::floor(std::clamp(layer.v_min, -1.0, 1e9))));
    roi.x1 = std::max(roi.x1, static_cast<int>(std::ceil(std::clamp(layer.u_max, -1.0, 1e9))) + 1);
    roi.y1 = std::max(roi.y1, static_cast<int>(std::ceil(std::clamp(layer.v_max, -1.0, 1e9))) + 1);
  }
  if (!base_uniform) roi = {0, 0, camera.width, camera.height};
  roi.x0 = std::clamp(roi.x0, 0, camera.width);
  roi.y0 = std::clamp(roi.y0, 0, camera.height);
  roi.x1 = std::clamp(roi.x1, 0, camera.width);
  roi.y1 = std::clamp(roi.y1, 0, camera.height);

  RasterResult result;
  result.image = ImageF(camera.width, camera.height, channels);
  result.nonuniform = roi;
  for (int k = 0; k < channels; ++k) {
    std::fill_n(result.image.plane(k), result.image.plane_size(), base.v[k]);
  }
  const CellShader shader(mapper, layers, backdrop, channels);
  constexpr int kBlock = 16;
  for (int y = roi.y0; y < roi.y1; y += kBlock) {
    for (int x = roi.x0; x < roi.x1; x += kBlock) shader.FillBlock(x, y, kBlock, &result.image);
  }
  return result;
}

}  // namespace markerbench
