#include "trackers/circle/design_refinement.h"

#include <ceres/jet.h>
#include <ceres/rotation.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "trackers/circle/blurred_design.h"
#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/circle/clipped_noise.h"
#include "trackers/circle/plane_view.h"
#include "trackers/pixel_area_blur.h"

namespace markerbench {
namespace {

struct DesignPixel {
  int x = 0, y = 0;
  Eigen::Vector3d ray = Eigen::Vector3d::Zero();  // camera frame, z = 1
  double value = 0.0;                             // luma, 0-1
};

// Row-major order, in which the pixels are chosen (so selections merge).
bool RowMajorBefore(const DesignPixel& a, const DesignPixel& b) {
  return a.y != b.y ? a.y < b.y : a.x < b.x;
}

// The most metres a pixel spans on the plane: the largest singular value of the local map.
double LargestStretch(const Eigen::Matrix2d& m) {
  const double sum = m.squaredNorm();
  const double det = m.determinant();
  return std::sqrt(0.5 * (sum + std::sqrt(std::max(0.0, sum * sum - 4.0 * det * det))));
}

double ReachPx(double sigma_px, const DesignRefinementOptions& options) {
  return options.band_sigmas * std::max(sigma_px, 0.3) + options.band_px;
}

// The pixels whose plane points at the pose lie within `reach_px` of an edge drawn in the
// design, any layer's outline (not the lines of f's wedge past its centre and rim, nor the
// circles of e's mouth past its tips, on which nothing changes), in row-major order; none
// when the design's ink is not wholly in front of the camera.
std::vector<DesignPixel> PixelsNearDesignEdges(const Image8& image,
                                               const Camera& camera,
                                               const MarkerSpec& marker,
                                               const Rigid3& cam_from_marker,
                                               double reach_px) {
  const Eigen::AlignedBox2d ink = marker.InkBounds();
  double x0 = image.width, y0 = image.height, x1 = -1.0, y1 = -1.0;
  for (const auto corner : {Eigen::AlignedBox2d::BottomLeft,
                            Eigen::AlignedBox2d::BottomRight,
                            Eigen::AlignedBox2d::TopLeft,
                            Eigen::AlignedBox2d::TopRight}) {
    const Eigen::Vector2d p = ink.corner(corner);
    const Eigen::Vector3d in_camera = cam_from_marker * Eigen::Vector3d(p.x(), p.y(), 0.0);
    if (!(in_camera.z() > 0.0)) return {};
    const Eigen::Vector2d px = camera.ImgFromCam(in_camera);
    if (!px.allFinite()) return {};
    x0 = std::min(x0, px.x()), y0 = std::min(y0, px.y());
    x1 = std::max(x1, px.x()), y1 = std::max(y1, px.y());
  }
  const double pad = reach_px + 2.0;
  // Clamped as doubles first: a corner may project far off the image.
  const auto clamped = [](double v, int size) {
    return static_cast<int>(std::clamp(v, 0.0, size - 1.0));
  };
  const int u0 = clamped(std::floor(x0 - pad), image.width);
  const int u1 = clamped(std::ceil(x1 + pad), image.width);
  const int v0 = clamped(std::floor(y0 - pad), image.height);
  const int v1 = clamped(std::ceil(y1 + pad), image.height);
  const PlaneView view(camera, cam_from_marker);
  std::vector<Eigen::AlignedBox2d> outline_boxes;
  for (const PaintedShape& layer : marker.layers) outline_boxes.push_back(OutlineBox(layer.shape));
  const auto near_an_outline = [&](const Eigen::Vector2d& point, double reach_m) {
    for (size_t k = 0; k < marker.layers.size(); ++k) {
      if (!IsBeyondOutlineBox(outline_boxes[k], point, reach_m) &&
          IsNearOutline(marker.layers[k].shape, point, reach_m)) {
        return true;
      }
    }
    return false;
  };
  // Tiles of kTilePx × kTilePx pixels, each set aside whole where none of its pixels can be
  // near an outline. Their plane points lie within the hull of the tile's corner pixels' points
  // (a homography maps the tile to a convex quadrilateral; through a lens nearly so), so within
  // D of its centre's, D the farthest corner's distance; each pixel's reach is about its
  // corners' (the map's stretch is smooth); and an outline's distance moves no more than the
  // point does. So a centre beyond reach of every outline by D and the corners' largest reach,
  // both with the margin, settles the tile: the same pixels as testing each (results/speed.md).
  constexpr int kTilePx = 8;
  constexpr double kTileMargin = 1.25;
  const auto tile_may_be_near = [&](int ua, int va, int ub, int vb) {
    const PlaneLook center =
        view.LookAlong(camera.CamFromImg(0.5 * Eigen::Vector2d(ua + ub, va + vb)));
    if (!(center.homogeneous > 0.0)) return true;
    double farthest_m = 0.0, largest_reach_m = 0.0;
    for (const auto& [u, v] : {std::pair{ua, va}, {ub, va}, {ua, vb}, {ub, vb}}) {
      const PlaneLook corner = view.LookAlong(camera.CamFromImg(Eigen::Vector2d(u, v)));
      const double apart_m = (corner.point - center.point).norm();
      const double reach_m = reach_px * LargestStretch(corner.plane_from_px);
      // Near the horizon a point may overflow: such a tile is tested pixel by pixel.
      if (!(corner.homogeneous > 0.0) || !std::isfinite(apart_m) || !std::isfinite(reach_m)) {
        return true;
      }
      farthest_m = std::max(farthest_m, apart_m);
      largest_reach_m = std::max(largest_reach_m, reach_m);
    }
    return near_an_outline(center.point, kTileMargin * (farthest_m + largest_reach_m));
  };
  const int tiles_across = (u1 - u0) / kTilePx + 1;
  std::vector<bool> tile_near;
  for (int va = v0; va <= v1; va += kTilePx) {
    for (int ua = u0; ua <= u1; ua += kTilePx) {
      tile_near.push_back(
          tile_may_be_near(ua, va, std::min(ua + kTilePx - 1, u1), std::min(va + kTilePx - 1, v1)));
    }
  }
  std::vector<DesignPixel> pixels;
  for (int v = v0; v <= v1; ++v) {
    for (int u = u0; u <= u1; ++u) {
      if (!tile_near[(v - v0) / kTilePx * tiles_across + (u - u0) / kTilePx]) {
        u += kTilePx - 1 - (u - u0) % kTilePx;  // to the tile's last pixel
        continue;
      }
      const Eigen::Vector3d ray = camera.CamFromImg(Eigen::Vector2d(u, v));
      const PlaneLook look = view.LookAlong(ray);
      if (!(look.homogeneous > 0.0)) continue;
      if (near_an_outline(look.point, reach_px * LargestStretch(look.plane_from_px))) {
        pixels.push_back({u, v, ray, LumaAt(image, u, v) / 255.0});
      }
    }
  }
  return pixels;
}

// The cost of the design seen through the pose in θ (pixel_fit.h, one channel: luma; each
// pixel's ClippedPixelTerm), with its normal equations. The plane point of each pixel is
// differentiated by Jets in the pose; the design's luma by its gradient in that point and in σ
// (blurred_design.h).
class DesignModel {
 public:
  using Jet = ceres::Jet<double, 6>;

  // With `fits_levels`, each fitted colour's level is a parameter (blurred_design.h);
  // otherwise those colours are the design's.
  DesignModel(const Camera& camera,
              const MarkerSpec& marker,
              const std::vector<DesignPixel>& pixels,
              double noise_sigma,
              bool fits_levels)
      : camera_(camera),
        px_from_ray_inverse_(camera.K().inverse()),
        through_lens_(camera.HasDistortion()),
        design_(marker),
        pixels_(pixels),
        noise_sigma_(noise_sigma),
        fitted_levels_(fits_levels ? design_.FittedLevels() : 0) {}

  // The pose, σ, the offset and gain, and the fitted colours' levels.
  int Parameters() const { return 9 + fitted_levels_; }
  // Offset 0 and gain 1, each fitted colour at its specified luma.
  Eigen::VectorXd StartLevels() const {
    Eigen::VectorXd levels = Eigen::VectorXd::Zero(Parameters() - 7);
    levels[1] = 1.0;
    return levels;
  }
  // Kept as they start: the design's start pose (the circle's edge points and one centre
  // point) is off by more than the noise, and the offset and gain that fit its edges there
  // (FitOffsetsAndGains) were far from the result's (on f's speed benchmark frames, gain 1.34
  // against 1.03), which cost f's full detection 5 % more time (results/speed.md).
  Eigen::VectorXd LevelsShownAtStart(std::vector<ModelledPixel>*) const { return StartLevels(); }
  // The optics' σ alone (the design is averaged over each pixel): sharp images fit near 0, and
  // the straight edge over a pixel is exact there.
  double MinSigmaPx() const { return kMinBlurSigmaPx; }
  double noise_sigma() const { return noise_sigma_; }
  void set_noise_sigma(double noise_sigma) { noise_sigma_ = noise_sigma; }

  // The cost at θ (each pixel's ClippedPixelTerm); with jtj and jtr, also JᵀJ and Jᵀr; and each
  // pixel's residual and modelled mean if `modelled` is given. θ may hold fewer fitted levels
  // than Parameters() (a fit's without them, compared with others).
  double Evaluate(const Eigen::VectorXd& theta,
                  Eigen::MatrixXd* jtj,
                  Eigen::VectorXd* jtr,
                  std::vector<ModelledPixel>* modelled) const {
    Jet angle_axis[3];
    Eigen::Matrix<Jet, 3, 1> t;
    for (int k = 0; k < 3; ++k) {
      angle_axis[k] = Jet(theta[k], k);
      t[k] = Jet(theta[3 + k], 3 + k);
    }
    Eigen::Matrix<Jet, 3, 3> R;
    ceres::AngleAxisToRotationMatrix(angle_axis, ceres::ColumnMajorAdapter3x3(R.data()));
    Eigen::Matrix<Jet, 3, 3> ray_from_plane;
    ray_from_plane << R.col(0), R.col(1), t;
    const Eigen::Matrix<Jet, 3, 3> plane_from_ray = ray_from_plane.inverse();
    Eigen::Matrix3d plane_from_px;  // from ideal pixels, for the local map
    for (int i = 0; i < 9; ++i) plane_from_px(i) = plane_from_ray(i).a;
    plane_from_px = plane_from_px * px_from_ray_inverse_;
    const double sigma = theta[6], offset = theta[7], gain = theta[8];
    std::array<double, kMaxFittedLevels> level_shifts = {};
    const int parameters = static_cast<int>(theta.size());
    for (int k = 0; k + 9 < parameters; ++k) level_shifts[k] = theta[9 + k];

    // Summed in fixed-size matrices (kMaxFittedLevels levels at most), copied out at the end.
    constexpr int kMaxParameters = 9 + kMaxFittedLevels;
    Eigen::Matrix<double, kMaxParameters, kMaxParameters> normal =
        Eigen::Matrix<double, kMaxParameters, kMaxParameters>::Zero();
    Eigen::Matrix<double, kMaxParameters, 1> gradient =
        Eigen::Matrix<double, kMaxParameters, 1>::Zero();
    double cost = 0.0;
    for (const DesignPixel& pixel : pixels_) {
      const Eigen::Matrix<Jet, 3, 1> q = plane_from_ray.col(0) * pixel.ray.x() +
                                         plane_from_ray.col(1) * pixel.ray.y() +
                                         plane_from_ray.col(2) * pixel.ray.z();
      const Jet x = q.x() / q.z(), y = q.y() / q.z();
      const Eigen::Vector2d point(x.a, y.a);
      Eigen::Matrix2d marker_from_px;
      for (int j = 0; j < 2; ++j) {
        marker_from_px.col(j) =
            (plane_from_px.block<2, 1>(0, j) - point * plane_from_px(2, j)) / q.z().a;
      }
      if (through_lens_) marker_from_px *= camera_.IdealFromImgJacobian(pixel.ray);
      const BlurredLuma printed = design_.At(point, marker_from_px, sigma, level_shifts);
      // The pixel's term at μ, the pixel clipped and rounded (clipped_noise.h).
      const double mu = offset + gain * printed.luma;
      const PixelTerm term = ClippedPixelTerm(pixel.value, mu, noise_sigma_);
      cost += term.cost;
      if (modelled) modelled->push_back({pixel.value - mu, mu});
      if (!jtj) continue;
      Eigen::Matrix<double, kMaxParameters, 1> row;  // -∂μ/∂θ
      row.head<6>() = -gain * (printed.gradient.x() * x.v + printed.gradient.y() * y.v);
      row[6] = -gain * printed.d_sigma;
      row[7] = -1.0;
      row[8] = -printed.luma;
      for (int k = 0; k < kMaxFittedLevels; ++k) row[9 + k] = -gain * printed.d_levels[k];
      normal.selfadjointView<Eigen::Upper>().rankUpdate(row, term.weight);
      gradient += term.residual * row;
    }
    if (jtj) {
      *jtj = Eigen::MatrixXd(normal.selfadjointView<Eigen::Upper>())
                 .topLeftCorner(parameters, parameters);
      *jtr = gradient.head(parameters);
    }
    return cost;
  }

 private:
  const Camera& camera_;
  Eigen::Matrix3d px_from_ray_inverse_;  // K⁻¹
  bool through_lens_;                    // the local map through the lens (IdealFromImgJacobian)
  BlurredDesign design_;
  const std::vector<DesignPixel>& pixels_;
  double noise_sigma_;
  int fitted_levels_;
};

// Each refinement's cost (the pixels' ClippedPixelTerm summed) on the same pixels: those near
// the design's edges at any of them, at the least noise any of them leaves (a fit's residuals
// hold the image's noise and its own misfit). At their mean, a wrong tilt's fit that leaves 88
// levels where the true one leaves 0.6 (a noise-free frame) set the noise for both: its gain of
// 2.8 puts the black ink far below 0 and the paper far above 1, where the clipped likelihood
// takes every such pixel as certain, and it won on 28 of 100 noise-free frames of e.
struct DesignCosts {
  std::vector<double> costs;
  double noise_sigma = 0.0;
};
DesignCosts CostsOnSharedPixels(const Image8& image,
                                const Camera& camera,
                                const MarkerSpec& marker,
                                const std::vector<PixelRefinement>& fits,
                                const DesignRefinementOptions& options) {
  std::vector<DesignPixel> pixels;
  for (const PixelRefinement& refinement : fits) {
    const std::vector<DesignPixel> near =
        PixelsNearDesignEdges(image,
                              camera,
                              marker,
                              refinement.fit.cam_from_marker,
                              ReachPx(refinement.fit.sigma_px, options));
    std::vector<DesignPixel> both;
    std::set_union(pixels.begin(),
                   pixels.end(),
                   near.begin(),
                   near.end(),
                   std::back_inserter(both),
                   RowMajorBefore);
    pixels = std::move(both);
  }
  DesignCosts costs;
  costs.noise_sigma = std::min_element(fits.begin(),
                                       fits.end(),
                                       [](const PixelRefinement& a, const PixelRefinement& b) {
                                         return a.noise_sigma < b.noise_sigma;
                                       })
                          ->noise_sigma;
  const DesignModel model(camera, marker, pixels, costs.noise_sigma, true);
  for (const PixelRefinement& refinement : fits) {
    const PixelFit& fit = refinement.fit;
    costs.costs.push_back(
        model.Evaluate(PixelFitParameters(fit.cam_from_marker, fit.sigma_px, fit.levels),
                       nullptr,
                       nullptr,
                       nullptr));
  }
  return costs;
}

std::optional<PixelRefinement> RefineOnce(const Image8& image,
                                          const Camera& camera,
                                          const MarkerSpec& marker,
                                          const Rigid3& cam_from_marker,
                                          double sigma_px,
                                          double noise_sigma,
                                          const FitRound& round,
                                          const DesignRefinementOptions& options) {
  const std::vector<DesignPixel> pixels =
      PixelsNearDesignEdges(image, camera, marker, cam_from_marker, ReachPx(sigma_px, options));
  if (pixels.size() < 20) return std::nullopt;
  // The fitted colours' levels from a round that follows another: free in the first round, on a
  // noise-free frame of f at 0.6 m the fit from the tracker's start on the true tilt (14 mm off)
  // ended on the other tilt, 66 mm off; held there, 0.1 mm. (From a worse start, 8.5 mm off,
  // both end 49-52 mm off with the grey moved below black.)
  DesignModel model(camera, marker, pixels, ModelNoiseSigma(noise_sigma), round.follows_another);
  // The noise is measured at every round's start here: from the last round's result instead,
  // circle_f without noise fitted 7 % worse (96 of 100 frames, paired on the paper's noise
  // sweep; on noise-free frames this fit's result depends on the noise it starts from).
  const FitRound measured_at_start{round.first_of_several, false};
  const std::optional<PixelFit> fit = FitPixelsAtTheirNoise(
      model, cam_from_marker, std::max(sigma_px, 0.3), options.max_iterations, measured_at_start);
  if (!fit) return std::nullopt;
  return PixelRefinement{*fit, static_cast<int>(pixels.size()), model.noise_sigma()};
}

}  // namespace

std::optional<PixelRefinement> RefineDesign(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const Rigid3& cam_from_marker,
    double sigma_px,
    double noise_sigma,
    const DesignRefinementOptions& options,
    const std::function<bool(const PixelRefinement&)>& abandons) {
  // A solve's pixels are those near the edges at its start; from a start a few pixels off,
  // some of the result's are missing.
  return FitInRoundsAtTheirNoise<PixelRefinement>(
      cam_from_marker,
      BlurSigmaOfEdges(sigma_px),
      noise_sigma,
      options.max_rounds,
      [&](const Rigid3& start, double sigma, double noise, const FitRound& round) {
        return RefineOnce(image, camera, marker, start, sigma, noise, round, options);
      },
      nullptr,
      nullptr,
      abandons);
}

std::vector<double> DesignLogRatios(const Image8& image,
                                    const Camera& camera,
                                    const MarkerSpec& marker,
                                    const std::vector<PixelRefinement>& fits,
                                    const DesignRefinementOptions& options) {
  const DesignCosts shared = CostsOnSharedPixels(image, camera, marker, fits, options);
  const double least = *std::min_element(shared.costs.begin(), shared.costs.end());
  std::vector<double> ratios;
  for (const double cost : shared.costs) {
    ratios.push_back((cost - least) / (shared.noise_sigma * shared.noise_sigma));
  }
  return ratios;
}

std::vector<RankedFit<PixelRefinement>> RefineDesignFromStarts(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const std::vector<Rigid3>& starts,
    double sigma_px,
    double noise_sigma,
    const DesignRefinementOptions& options) {
  const auto log_ratios = [&](const std::vector<PixelRefinement>& fits) {
    return DesignLogRatios(image, camera, marker, fits, options);
  };
  return RankedFitsFromStarts<PixelRefinement>(
      starts,
      [&](const Rigid3& start, const std::vector<PixelRefinement>& earlier) {
        const auto far_less_likely = [&](const PixelRefinement& first_round) {
          if (earlier.empty()) return false;
          std::vector<PixelRefinement> compared = earlier;
          compared.push_back(first_round);
          return log_ratios(compared).back() > options.max_first_round_log_ratio;
        };
        return RefineDesign(
            image, camera, marker, start, sigma_px, noise_sigma, options, far_less_likely);
      },
      log_ratios);
}

}  // namespace markerbench
