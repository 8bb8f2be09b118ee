#include "trackers/circle/roll_feature.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/shapes.h"
#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/circle/plane_view.h"
#include "trackers/pixel_area_blur.h"
#include "trackers/printed_appearance.h"
#include "trackers/upper_median.h"

namespace markerbench {
namespace {

// Cells start at 1/16 of the window's width and split where a colour edge or the window's
// taper may cross them, down to 1/1024 of it (about 80 µm on the paper's markers).
constexpr int kTopCells = 16;
constexpr int kSplits = 6;

// The window's weight at distance r from the centre: 1 out to window - taper, then falling
// linearly to 0 at the window's edge, so that pixels cut by it count smoothly.
struct Window {
  double outer_m;
  double taper_m;
  double At(double r) const { return std::clamp((outer_m - r) / taper_m, 0.0, 1.0); }
};

struct DesignIntegral {
  const MarkerSpec& marker;
  const Rigid3& marker_from_paper;
  Window window;
  double disk_luma;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  // The first colour met in the window other than the disk's.
  std::optional<Rgb> design_color = std::nullopt;

  // Adds ∫ w(|q|) (luma - disk_luma) q dq over the square cell of centre q and half width
  // `half`.
  void Add(const Eigen::Vector2d& q, double half, int splits_left) {
    const double reach = half * std::sqrt(2.0);
    if (q.norm() - reach >= window.outer_m) return;
    const Eigen::Vector3d p = marker_from_paper * Eigen::Vector3d(q.x(), q.y(), 0.0);
    const PaintSample sample = marker.ColorAt(p.head<2>());
    const double ink = Luma(*sample.color) - disk_luma;
    if (ink != 0.0 && !design_color) design_color = *sample.color;
    const bool one_colour = sample.clearance_m >= reach;
    if (one_colour && ink == 0.0) return;
    const bool full_weight = q.norm() + reach <= window.outer_m - window.taper_m;
    if ((one_colour && full_weight) || splits_left == 0) {
      moment += window.At(q.norm()) * ink * 4.0 * half * half * q;
      return;
    }
    const double quarter = 0.5 * half;
    for (double dx : {-quarter, quarter}) {
      for (double dy : {-quarter, quarter})
        Add(q + Eigen::Vector2d(dx, dy), quarter, splits_left - 1);
    }
  }
};

// A pixel of the window: its luma, its point q in the paper frame, the plane area it covers
// (times the window's weight) and d(q)/d(pixel).
struct WindowPixel {
  int x, y;
  double value;
  Eigen::Vector2d q;
  double area;
  Eigen::Matrix2d plane_from_px;
};

// The pixels whose plane points fall in the window, and their box in the image.
struct WindowPixels {
  std::vector<WindowPixel> pixels;
  int x_begin = 0, y_begin = 0, columns = 0, rows = 0;
};

// nullopt when the window is not wholly in front of the camera and in the image.
std::optional<WindowPixels> ReadWindow(const Image8& image,
                                       const Camera& camera,
                                       const Rigid3& cam_from_paper,
                                       const Window& window) {
  // The window's image: its bounding box from points on its rim.
  const Eigen::Matrix3d ray_from_plane = RayFromPlane(cam_from_paper);
  double x0 = image.width, y0 = image.height, x1 = -1.0, y1 = -1.0;
  for (int k = 0; k < 32; ++k) {
    const double a = 2.0 * M_PI * k / 32;
    const double r = window.outer_m;
    const Eigen::Vector3d ray =
        ray_from_plane * Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 1.0);
    if (!(ray.z() > 0.0)) return std::nullopt;
    const Eigen::Vector2d px = camera.ImgFromCam(ray);
    x0 = std::min(x0, px.x()), y0 = std::min(y0, px.y());
    x1 = std::max(x1, px.x()), y1 = std::max(y1, px.y());
  }
  if (!(x0 >= 0.0 && y0 >= 0.0 && x1 <= image.width - 1 && y1 <= image.height - 1)) {
    return std::nullopt;
  }
  WindowPixels out;
  out.x_begin = static_cast<int>(std::floor(x0));
  out.y_begin = static_cast<int>(std::floor(y0));
  out.columns = static_cast<int>(std::ceil(x1)) - out.x_begin + 1;
  out.rows = static_cast<int>(std::ceil(y1)) - out.y_begin + 1;
  // Each pixel, at its plane point q, covers |det H⁻¹| / q̃_z³ of the plane per unit of the
  // normalized image's area (H = [r1 r2 t], q̃ = H⁻¹ ray): 1/(fx fy) of that per ideal pixel,
  // times the ideal pixels it spans through the lens.
  const PlaneView view(camera, cam_from_paper);
  const double pixel_area = std::abs(view.plane_from_ray().determinant()) / (camera.fx * camera.fy);
  for (int y = out.y_begin; y < out.y_begin + out.rows; ++y) {
    for (int x = out.x_begin; x < out.x_begin + out.columns; ++x) {
      const PlaneLook look = view.Look(x, y);
      const double weight = window.At(look.point.norm());
      if (!(weight > 0.0)) continue;
      const double h = look.homogeneous;
      const double area = weight * pixel_area * look.ideal_area_per_px / std::abs(h * h * h);
      out.pixels.push_back({x, y, LumaAt(image, x, y), look.point, area, look.plane_from_px});
    }
  }
  return out;
}

// The printed design seen through a pixel, with the design turned by `turn` and its centre
// moved to `center` in the paper frame (blurred_design.h); its gradient in the marker point.
struct DesignModel {
  const BlurredDesign& design;
  Eigen::Matrix2d marker_rotation;  // marker_from_paper's
  Eigen::Vector2d marker_shift;
  double sigma_px;  // the blur alone: the design is averaged over each pixel

  Eigen::Matrix2d ToMarker(double turn) const {
    return marker_rotation * Eigen::Rotation2Dd(-turn).matrix();
  }
  BlurredLuma At(const WindowPixel& pixel,
                 const Eigen::Matrix2d& to_marker,
                 const Eigen::Vector2d& center) const {
    return design.At(
        to_marker * (pixel.q - center) + marker_shift, to_marker * pixel.plane_from_px, sigma_px);
  }
};

// pixel = offset + gain * printed, with the design turned and moved.
struct DesignFit {
  double offset = 0.0;
  double gain = 0.0;
  double turn = 0.0;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double gain_variance = 0.0;  // per unit noise variance, at the last linearisation

  double Residual(const DesignModel& model, const WindowPixel& pixel) const {
    return offset + gain * model.At(pixel, model.ToMarker(turn), center).luma - pixel.value;
  }
};

// Gauss-Newton on (offset, gain, turn, centre), or without the centre; steps of the turn and
// centre are bounded (0.05 rad, 0.05 of the window), and it stops once they move the design
// by less than 1e-4 px.
DesignFit FitDesign(const DesignModel& model,
                    const std::vector<const WindowPixel*>& pixels,
                    DesignFit fit,
                    bool fit_center,
                    int max_iterations,
                    double window_m,
                    double metres_per_px) {
  constexpr int kParameters = 5;
  using Vector = Eigen::Matrix<double, kParameters, 1>;
  using Matrix = Eigen::Matrix<double, kParameters, kParameters>;
  const Eigen::Matrix2d quarter_turn = Eigen::Rotation2Dd(M_PI / 2).matrix();
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    const Eigen::Matrix2d to_marker = model.ToMarker(fit.turn);
    Matrix JtJ = Matrix::Zero();
    Vector Jtr = Vector::Zero();
    for (const WindowPixel* pixel : pixels) {
      const BlurredLuma printed = model.At(*pixel, to_marker, fit.center);
      // p = R_m Rz(-turn) (q - centre) + t_m.
      const double d_turn =
          -printed.gradient.dot(to_marker * quarter_turn * (pixel->q - fit.center));
      const Eigen::Vector2d d_center = -to_marker.transpose() * printed.gradient;
      Vector J;
      J << 1.0, printed.luma, fit.gain * d_turn, fit.gain * d_center;
      JtJ += J * J.transpose();
      Jtr += J * (fit.offset + fit.gain * printed.luma - pixel->value);
    }
    if (!fit_center) {
      JtJ.bottomRows<2>().setZero();
      JtJ.rightCols<2>().setZero();
      JtJ.bottomRightCorner<2, 2>().setIdentity();
      Jtr.tail<2>().setZero();
    }
    const Eigen::LDLT<Matrix> normal_equations(JtJ);
    fit.gain_variance = normal_equations.solve(Vector::Unit(1))(1);
    Vector step = -normal_equations.solve(Jtr);
    if (!step.allFinite()) break;
    step(2) = std::clamp(step(2), -0.05, 0.05);
    const double center_step = step.tail<2>().norm();
    if (center_step > 0.05 * window_m) step.tail<2>() *= 0.05 * window_m / center_step;
    fit.offset += step(0);
    fit.gain += step(1);
    fit.turn += step(2);
    fit.center += step.tail<2>();
    if (std::abs(step(2)) * window_m + center_step < 1e-4 * metres_per_px) break;
  }
  return fit;
}

// How far the design misses the pixels, without an estimate of the noise: residuals of
// pixels two apart in u share the misfit and not the noise, so their mean product estimates
// the squared misfit (as printed_appearance.h does over the marker).
struct SharedResidual {
  double mean_product = 0.0;
  int pairs = 0;
};
SharedResidual SharedResidualOf(const DesignModel& model,
                                const DesignFit& fit,
                                const WindowPixels& window,
                                const std::vector<const WindowPixel*>& pixels) {
  std::vector<double> residual(static_cast<size_t>(window.columns) * window.rows,
                               std::numeric_limits<double>::quiet_NaN());
  auto at = [&](int x, int y) -> double& {
    return residual[static_cast<size_t>(y - window.y_begin) * window.columns +
                    (x - window.x_begin)];
  };
  for (const WindowPixel* pixel : pixels) at(pixel->x, pixel->y) = fit.Residual(model, *pixel);
  SharedResidual out;
  double sum = 0.0;
  for (const WindowPixel* pixel : pixels) {
    if (pixel->x + 2 >= window.x_begin + window.columns) continue;
    const double product = at(pixel->x, pixel->y) * at(pixel->x + 2, pixel->y);
    if (std::isnan(product)) continue;
    sum += product;
    ++out.pairs;
  }
  out.mean_product = out.pairs > 0 ? sum / out.pairs : 0.0;
  return out;
}

}  // namespace

RollFeature::RollFeature(const MarkerSpec& marker,
                         const CircleGeometry& geometry,
                         const RollFeatureOptions& options)
    : marker_(marker),
      blurred_(marker),
      marker_from_paper_(geometry.marker_from_paper),
      window_m_(options.window_per_radius * geometry.radii_m[0]),
      taper_m_(options.taper_per_radius * geometry.radii_m[0]),
      disk_luma_(Luma(marker.circles[0].color)),
      background_luma_(Luma(marker.background)),
      options_(options) {
  DesignIntegral integral{marker, geometry.marker_from_paper, {window_m_, taper_m_}, disk_luma_};
  const double half_width = window_m_;
  const double cell = 2.0 * half_width / kTopCells;
  for (int i = 0; i < kTopCells; ++i) {
    for (int j = 0; j < kTopCells; ++j) {
      const Eigen::Vector2d q(-half_width + (i + 0.5) * cell, -half_width + (j + 0.5) * cell);
      integral.Add(q, 0.5 * cell, kSplits);
    }
  }
  design_moment_ = integral.moment;
  const Rgb design_color = integral.design_color.value_or(marker.circles[0].color);
  intermediate_design_ = IsIntermediateColor(marker, design_color);
  disk_level_ = PrintedLevel(marker, marker.circles[0].color);
  design_level_ = PrintedLevel(marker, design_color);
}

std::optional<RollAlignment> RollFeature::Align(const Image8& image,
                                                const Camera& camera,
                                                const Rigid3& cam_from_paper,
                                                double paper_level,
                                                double blur_sigma_px,
                                                double noise_sigma,
                                                bool fit_center) const {
  const std::optional<WindowPixels> window =
      ReadWindow(image, camera, cam_from_paper, {window_m_, taper_m_});
  if (!window || window->pixels.size() < 16) return std::nullopt;
  const std::vector<WindowPixel>& pixels = window->pixels;
  // The disk's level: most of the window is bare disk (the median ignores the weights).
  std::vector<double> sorted;
  for (const WindowPixel& p : pixels) sorted.push_back(p.value);
  const double disk_level = UpperMedian(sorted);
  const double gain = (paper_level - disk_level) / (background_luma_ - disk_luma_);

  // First the moment over the whole window, which finds the design at any roll: the
  // design's direction, turned by the pose's roll error, is where the image's points
  // (cam_from_paper_true = cam_from_paper * Rz(turn)).
  const Eigen::Vector2d design = gain * design_moment_;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (const WindowPixel& p : pixels) moment += (p.value - disk_level) * p.area * p.q;
  RollAlignment alignment;
  alignment.moment_ratio = design.norm() > 0.0 ? moment.norm() / design.norm() : 0.0;
  if (!(alignment.moment_ratio >= options_.min_moment_fraction)) return std::nullopt;
  const double coarse_turn =
      std::atan2(design.x() * moment.y() - design.y() * moment.x(), design.dot(moment));

  // Then the roll (and centre) that fit the printed design best, by Gauss-Newton on the
  // pixels within reach of its ink (the bare disk's carry noise and nothing of the roll):
  // the maximum-likelihood estimate under Gaussian noise. The reach covers the blur, two
  // pixels and a tenth of a radian of roll at the window's edge, so no ink the fit may turn
  // to falls outside it.
  const double depth = cam_from_paper.translation.norm();
  const double facing =
      std::abs(cam_from_paper.rotation.col(2).dot(cam_from_paper.translation)) / depth;
  const double metres_per_px = depth / (camera.fx * std::max(facing, 0.1));
  const double reach_m = (3.0 * blur_sigma_px + 2.0) * metres_per_px + 0.1 * window_m_;
  const DesignModel model{blurred_,
                          marker_from_paper_.rotation.topLeftCorner<2, 2>(),
                          marker_from_paper_.translation.head<2>(),
                          std::max(BlurSigmaOfEdges(blur_sigma_px), kMinBlurSigmaPx)};
  std::vector<const WindowPixel*> near_ink;
  for (const WindowPixel& pixel : pixels) {
    const PaintSample sample =
        marker_.ColorAt(model.ToMarker(coarse_turn) * pixel.q + model.marker_shift);
    if (Luma(*sample.color) != disk_luma_ || sample.clearance_m < reach_m) {
      near_ink.push_back(&pixel);
    }
  }
  DesignFit start;
  start.offset = disk_level - gain * disk_luma_;
  start.gain = gain;
  start.turn = coarse_turn;
  const DesignFit fit = FitDesign(
      model, near_ink, start, fit_center, options_.max_iterations, window_m_, metres_per_px);

  // Does the design show? Its misfit against the noise (a product of two residuals has
  // standard deviation σ² under the noise alone, σ at least the 8-bit quantisation's), and
  // its gain against the image's contrast.
  const SharedResidual shared = SharedResidualOf(model, fit, *window, near_ink);
  const double contrast2 = (paper_level - disk_level) * (paper_level - disk_level);
  if (shared.pairs < 16 || !(contrast2 > 0.0)) return std::nullopt;
  const double noise2 = std::max(noise_sigma * noise_sigma, 1.0 / 12.0);
  const double standard_error = noise2 / std::sqrt(static_cast<double>(shared.pairs));
  const double allowed = options_.max_misfit * options_.max_misfit * contrast2;
  alignment.misfit = std::sqrt(std::max(0.0, shared.mean_product) / contrast2);
  alignment.contrast_ratio = fit.gain / gain;
  alignment.contrast_ratio_error =
      std::sqrt(std::max(0.0, noise2 * fit.gain_variance)) / std::abs(gain);
  // The design's step from the disk, scaled by the contrast ratio.
  const double printed_step = design_level_ - disk_level_;
  alignment.design_level = disk_level_ + printed_step * alignment.contrast_ratio;
  const double level_error = std::abs(printed_step) * alignment.contrast_ratio_error;
  const double allowed_level_error = options_.min_significance * level_error;
  const bool shows_level =
      intermediate_design_
          ? alignment.design_level >= kMinIntermediateLevel - allowed_level_error &&
                alignment.design_level <= kMaxIntermediateLevel + allowed_level_error
          : std::abs(alignment.contrast_ratio - 1.0) <=
                options_.max_contrast_error +
                    options_.min_significance * alignment.contrast_ratio_error;
  alignment.shows_design =
      shared.mean_product - allowed <= options_.min_significance * standard_error && shows_level &&
      alignment.contrast_ratio_error <= options_.max_contrast_ratio_error;

  alignment.turn_rad = fit.turn;
  const Rigid3 turned(Eigen::AngleAxisd(fit.turn, Eigen::Vector3d::UnitZ()).matrix(),
                      Eigen::Vector3d::Zero());
  alignment.cam_from_paper = cam_from_paper * turned;
  alignment.center_m = Eigen::Rotation2Dd(-fit.turn) * fit.center;
  return alignment;
}

}  // namespace markerbench
