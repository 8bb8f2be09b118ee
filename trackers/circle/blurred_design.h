// A circle marker's printed design (its disks, crescents and sectors; paper Fig. 3) as the
// image sees it under a Gaussian blur, as a smooth function of the marker-plane point: what
// the fits of roll_feature.h and design_refinement.h compare with the pixels. Blur is linear,
// so the blurred design is the background plus each layer's colour step (its colour minus the
// one it is painted on) times its blurred indicator; each layer of these markers lies on one
// colour (a wedge on the disk, a nose on the face), so the steps are constants, and edges
// that two layers share (the wedge's arc on the disk's rim) add up exactly. Through the local
// map from pixels to the plane, each circle and line that bounds a layer is a straight edge
// at signed distance d (in σ across it; a circle's moved by its curvature), covered Φ(-d);
// where two of them are near (a
// crescent's tips, a sector's apex) the pair is the corner of two half-planes, covered
// Φ2(-d1, -d2; ρ) with ρ the cosine between their normals in pixels (exact for two straight
// edges; a product of steps would bias the apex).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/marker_spec.h"

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
};

class BlurredDesign {
 public:
  // `marker` must outlive this.
  explicit BlurredDesign(const MarkerSpec& marker);

  // The design's luma around marker point `p` under an image Gaussian of `sigma_px`, through
  // the local map marker_from_px (metres per pixel). Layers other than disks, crescents and
  // sectors (grids) are taken at their sharp colour.
  BlurredLuma At(const Eigen::Vector2d& p,
                 const Eigen::Matrix2d& marker_from_px,
                 double sigma_px) const;

 private:
  const MarkerSpec& marker_;
  std::vector<double> steps_;  // per layer: its luma minus the luma it is painted on
};

}  // namespace markerbench
