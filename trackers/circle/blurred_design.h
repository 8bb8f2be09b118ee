// A circle marker's printed design (its disks, crescents and sectors; paper Fig. 3) as a
// pixel sees it under a Gaussian blur, as a smooth function of the marker-plane point at the
// pixel's centre: what the fit of design_refinement.h compares with the pixels. Blur and the
// pixel's average are linear, so the blurred design is the background plus each layer's colour
// step (its colour minus the one it is painted on) times its blurred indicator; each layer of
// these markers lies on one colour (a wedge on the disk, a nose on the face), so the steps are
// constants, and edges that two layers share (the wedge's arc on the disk's rim) add up
// exactly. Through the local map from pixels to the plane, each circle and line that bounds a
// layer is a straight edge at signed distance d (in σ across it; a circle's moved by its
// curvature), whose step the pixel averages over its square (blurred_disk_profile.h's straight
// edge over a pixel); where two of them are near (a crescent's tips, a sector's apex) the pair
// is the corner of two half-planes: the product of their covers plus the corner's excess over
// that product under a Gaussian, Φ2(-d1, -d2; ρ) - Φ(-d1) Φ(-d2) with ρ the cosine between their
// normals in pixels (exact for two straight edges where the blur is much wider than the pixel;
// a product of steps alone would bias the apex).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/marker_spec.h"
#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/printed_appearance.h"

namespace markerbench {

// The standard normal CDF Φ and density φ.
double NormalCdf(double x);
double NormalDensity(double x);
// The bivariate standard normal CDF P(X < h, Y < k) at correlation rho in [-1, 1].
double BivariateNormalCdf(double h, double k, double rho);

struct BlurredLuma {
  double luma = 0.0;
  // d luma / d marker point, the edges' directions held (what Gauss-Newton needs).
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  double d_sigma = 0.0;  // d luma / d sigma_px
  // d luma / d each fitted colour's level (printed_appearance.h's FittedColors: f's grey
  // wedge, whose level a print or a camera's response moves): the share of the pixel it covers.
  std::array<double, kMaxFittedLevels> d_levels = {};
};

class BlurredDesign {
 public:
  // `marker` must outlive this.
  explicit BlurredDesign(const MarkerSpec& marker);

  // The fitted colours (FittedColors), in the order of At's `level_shifts`.
  int FittedLevels() const { return fitted_levels_; }

  // The design's luma averaged over the pixel whose centre sees marker point `p`, under an
  // image Gaussian of `sigma_px` (the optics' alone), through the local map marker_from_px
  // (metres per pixel), with each fitted colour's luma moved by its `level_shifts` entry (none:
  // the specified colours). Layers other than disks, crescents and sectors (grids) are taken at
  // their sharp colour.
  BlurredLuma At(const Eigen::Vector2d& p,
                 const Eigen::Matrix2d& marker_from_px,
                 double sigma_px,
                 const std::array<double, kMaxFittedLevels>& level_shifts = {}) const;

 private:
  const MarkerSpec& marker_;
  std::vector<double> steps_;  // per layer: its luma minus the luma it is painted on
  // Per layer, which fitted colour it paints and which it is painted on (-1: neither is one).
  std::vector<int> fitted_painted_, fitted_under_;
  int fitted_levels_ = 0;
  BlurredDiskProfile straight_edge_;  // s = ∞
};

}  // namespace markerbench
