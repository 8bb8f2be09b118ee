#include "trackers/circle/blurred_design.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace markerbench {
namespace {

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double NormalDensity(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI); }

// 10-point Gauss-Legendre rule on [-1, 1]: nodes (positive half) and weights.
constexpr std::array<double, 5> kNodes = {0.1488743389816312,
                                          0.4333953941292472,
                                          0.6794095682990244,
                                          0.8650633666889845,
                                          0.9739065285171717};
constexpr std::array<double, 5> kWeights = {0.2955242247147529,
                                            0.2692667193099963,
                                            0.2190863625159820,
                                            0.1494513491505806,
                                            0.0666713443086881};

// Edges nearer than this (in σ) to a point make a corner with its nearest edge.
constexpr double kCornerSigmas = 5.0;

// One edge of a layer at a point: its distance in σ (positive outside) and d(that)/dp.
struct Edge {
  double a = 0.0;
  Eigen::Vector2d da_dp = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal_px = Eigen::Vector2d::UnitX();  // unit, in pixels
};

}  // namespace

double BivariateNormalCdf(double h, double k, double rho) {
  rho = std::clamp(rho, -1.0, 1.0);
  // Φ2 = Φ(h) Φ(k) + 1/(2π) ∫_0^asin ρ exp(-(h² - 2hk sin θ + k²) / (2 cos² θ)) dθ.
  const double end = std::asin(rho);
  double integral = 0.0;
  for (size_t i = 0; i < kNodes.size(); ++i) {
    for (double sign : {-1.0, 1.0}) {
      const double theta = 0.5 * end * (1.0 + sign * kNodes[i]);
      const double s = std::sin(theta), c2 = 1.0 - s * s;
      integral += kWeights[i] * std::exp(-(h * h - 2.0 * h * k * s + k * k) / (2.0 * c2));
    }
  }
  return NormalCdf(h) * NormalCdf(k) + 0.5 * end * integral / (2.0 * M_PI);
}

BlurredLuma BlurredDesignLuma(const MarkerSpec& marker,
                              const Eigen::Vector2d& p,
                              const Eigen::Matrix2d& marker_from_px,
                              double sigma_px) {
  BlurredLuma out{Luma(marker.background), Eigen::Vector2d::Zero()};
  for (const PaintedShape& layer : marker.layers) {
    const BoundaryDistances b = DistancesTo(layer.shape, p);
    double cover = 1.0;
    Eigen::Vector2d cover_gradient = Eigen::Vector2d::Zero();
    if (b.count == 0) {
      cover = PaintAt(layer, p).color ? 1.0 : 0.0;
    } else {
      std::array<Edge, 3> edges;
      for (size_t i = 0; i < b.count; ++i) {
        const Eigen::Vector2d across = marker_from_px.transpose() * b.terms[i].gradient;
        const double per_metre = 1.0 / (across.norm() * sigma_px);
        edges[i] = {
            b.terms[i].metres * per_metre, per_metre * b.terms[i].gradient, across.normalized()};
      }
      // The two nearest edges as a corner, the others as straight edges (an insertion sort of
      // at most three that no NaN can lead astray).
      for (size_t i = 1; i < b.count; ++i) {
        for (size_t j = i; j > 0 && std::abs(edges[j].a) < std::abs(edges[j - 1].a); --j) {
          std::swap(edges[j], edges[j - 1]);
        }
      }
      // A factor of the cover, with its derivatives in the distances of the edges it uses.
      auto multiply = [&](double factor, double d_a1, const Edge& e1, double d_a2, const Edge& e2) {
        cover_gradient = cover_gradient * factor + cover * (d_a1 * e1.da_dp + d_a2 * e2.da_dp);
        cover *= factor;
      };
      auto multiply_edge = [&](const Edge& e) {
        multiply(NormalCdf(-e.a), -NormalDensity(e.a), e, 0.0, e);
      };
      // Beyond kCornerSigmas of the second edge its step is 0 or 1 within 3e-7, and so is
      // the corner's difference from the product of the two steps.
      size_t first_straight = 0;
      if (b.count >= 2 && std::abs(edges[1].a) < kCornerSigmas) {
        const Edge& e1 = edges[0];
        const Edge& e2 = edges[1];
        const double rho = std::clamp(e1.normal_px.dot(e2.normal_px), -0.999, 0.999);
        const double root = std::sqrt(1.0 - rho * rho);
        // d Φ2(h, k) / dh = φ(h) Φ((k - ρ h) / √(1 - ρ²)), with h = -a1, k = -a2.
        const double d_a1 = -NormalDensity(e1.a) * NormalCdf((-e2.a + rho * e1.a) / root);
        const double d_a2 = -NormalDensity(e2.a) * NormalCdf((-e1.a + rho * e2.a) / root);
        multiply(BivariateNormalCdf(-e1.a, -e2.a, rho), d_a1, e1, d_a2, e2);
        first_straight = 2;
      }
      for (size_t i = first_straight; i < b.count; ++i) multiply_edge(edges[i]);
    }
    const double contrast = Luma(layer.color) - out.luma;
    out.gradient = out.gradient * (1.0 - cover) + contrast * cover_gradient;
    out.luma += cover * contrast;
  }
  return out;
}

}  // namespace markerbench
