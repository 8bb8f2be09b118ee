// A circle marker's printed design (its disks, crescents and sectors; paper Fig. 3) as the
// image sees it under a Gaussian blur, as a smooth function of the marker-plane point: what
// the fits of roll_feature.h compare with the pixels. Each layer covers the ones below it by
// the blurred indicator of its shape: through the local map from pixels to the plane, each
// circle and line that bounds it is a straight edge at signed distance d (in σ across it),
// covered Φ(-d); where two of them are near (a crescent's tips, a sector's apex) the pair is
// the corner of two half-planes, covered Φ2(-d1, -d2; ρ) with ρ the cosine between their
// normals in pixels (exact for two straight edges; a product of steps would bias the apex).
#pragma once

#include <Eigen/Core>

#include "core/marker_spec.h"

namespace markerbench {

// The bivariate standard normal CDF P(X < h, Y < k) at correlation rho in [-1, 1].
double BivariateNormalCdf(double h, double k, double rho);

struct BlurredLuma {
  double luma = 0.0;
  // d luma / d marker point, the edges' directions held (what Gauss-Newton needs).
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
};

// The design's luma around marker point `p` under an image Gaussian of `sigma_px`, through
// the local map marker_from_px (metres per pixel). Layers other than disks, crescents and
// sectors (grids) are taken at their sharp colour.
BlurredLuma BlurredDesignLuma(const MarkerSpec& marker,
                              const Eigen::Vector2d& p,
                              const Eigen::Matrix2d& marker_from_px,
                              double sigma_px);

}  // namespace markerbench
