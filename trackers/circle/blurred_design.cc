#include "trackers/circle/blurred_design.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace markerbench {
namespace {

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
constexpr double kSharpSigmas = 9.0;

// One edge of a layer at a point: its distance in σ (positive outside), d(that)/dp and
// d(that)/dσ.
struct Edge {
  double a = 0.0;
  Eigen::Vector2d da_dp = Eigen::Vector2d::Zero();
  double da_dsigma = 0.0;
  Eigen::Vector2d normal_px = Eigen::Vector2d::UnitX();  // unit, in pixels
};

// A layer's blurred indicator at a point from its edges there, with its derivatives.
struct Cover {
  double value = 1.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  double d_sigma = 0.0;
};
Cover BlurredCover(const BoundaryDistances& b,
                   const Eigen::Matrix2d& marker_from_px,
                   double sigma_px) {
  Cover cover;
  std::array<Edge, 3> edges;
  const Eigen::Matrix2d px_from_marker = marker_from_px.inverse();
  const double area_px = std::abs(px_from_marker.determinant());
  for (size_t i = 0; i < b.count; ++i) {
    const EdgeDistance& term = b.terms[i];
    const Eigen::Vector2d across = marker_from_px.transpose() * term.gradient;
    const double per_metre = 1.0 / (across.norm() * sigma_px);
    // A circle's blurred edge has its midpoint σ²/2ρ towards its centre (ρ its radius of
    // curvature in the image, κ|det A|/|A t|³ for the map A and tangent t): to first order
    // in σ/ρ, a straight edge that much moved.
    const Eigen::Vector2d tangent_px =
        px_from_marker * Eigen::Vector2d(-term.gradient.y(), term.gradient.x());
    const double tangent_norm = tangent_px.norm();
    const double curvature_px =
        term.curvature_per_m * area_px / (tangent_norm * tangent_norm * tangent_norm);
    const double distance = term.metres * per_metre;
    edges[i] = {distance + 0.5 * sigma_px * curvature_px,
                per_metre * term.gradient,
                -distance / sigma_px + 0.5 * curvature_px,
                across.normalized()};
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
    cover.gradient = cover.gradient * factor + cover.value * (d_a1 * e1.da_dp + d_a2 * e2.da_dp);
    cover.d_sigma =
        cover.d_sigma * factor + cover.value * (d_a1 * e1.da_dsigma + d_a2 * e2.da_dsigma);
    cover.value *= factor;
  };
  // Beyond kSharpSigmas of an edge its step is 0 or 1 and its slope 0 in double precision
  // (Φ(-9) = 1e-19): most edges of a layer are that far from most of its pixels.
  auto multiply_edge = [&](const Edge& e) {
    if (e.a < -kSharpSigmas) return;
    if (e.a > kSharpSigmas) {
      cover = {0.0, Eigen::Vector2d::Zero(), 0.0};
      return;
    }
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
  return cover;
}

}  // namespace

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double NormalDensity(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI); }

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

BlurredDesign::BlurredDesign(const MarkerSpec& marker) : marker_(marker) {
  // What each layer is painted on: the layers below it at its deepest point on a grid.
  constexpr int kSteps = 32;
  for (size_t i = 0; i < marker.layers.size(); ++i) {
    const PaintedShape& layer = marker.layers[i];
    const Eigen::AlignedBox2d bounds = ShapeBounds(layer.shape);
    Eigen::Vector2d deepest = bounds.center();
    double clearance = -1.0;
    for (int x = 0; x <= kSteps; ++x) {
      for (int y = 0; y <= kSteps; ++y) {
        const Eigen::Vector2d q =
            bounds.min() + bounds.sizes().cwiseProduct(Eigen::Vector2d(x, y)) / kSteps;
        const PaintSample sample = PaintAt(layer, q);
        if (sample.color && sample.clearance_m > clearance) {
          clearance = sample.clearance_m;
          deepest = q;
        }
      }
    }
    Rgb under = marker.background;
    for (size_t j = 0; j < i; ++j) {
      const PaintSample below = PaintAt(marker.layers[j], deepest);
      if (below.color) under = *below.color;
    }
    steps_.push_back(Luma(layer.color) - Luma(under));
  }
}

BlurredLuma BlurredDesign::At(const Eigen::Vector2d& p,
                              const Eigen::Matrix2d& marker_from_px,
                              double sigma_px) const {
  BlurredLuma out{Luma(marker_.background), Eigen::Vector2d::Zero(), 0.0};
  // An edge farther than this from p is farther than kSharpSigmas + 1 σ in the image (the
  // map's Frobenius norm bounds the metres a pixel spans; the 1 σ covers the curvature's
  // shift of a circle's blurred edge, σ/2ρ σ for ρ ≥ σ).
  const double sharp_beyond_m = (kSharpSigmas + 1.0) * sigma_px * marker_from_px.norm();
  for (size_t l = 0; l < marker_.layers.size(); ++l) {
    const PaintedShape& layer = marker_.layers[l];
    const BoundaryDistances b = DistancesTo(layer.shape, p);
    if (b.count == 0) {
      // Sharp: where it paints, its colour replaces the layers below.
      if (PaintAt(layer, p).color) out = {Luma(layer.color), Eigen::Vector2d::Zero(), 0.0};
      continue;
    }
    bool inside = true, far = true;
    for (size_t i = 0; i < b.count; ++i) {
      inside &= b.terms[i].metres < 0.0;
      far &= std::abs(b.terms[i].metres) > sharp_beyond_m;
    }
    if (far) {  // what BlurredCover gives there, to double precision
      if (inside) out.luma += steps_[l];
      continue;
    }
    const Cover cover = BlurredCover(b, marker_from_px, sigma_px);
    out.luma += steps_[l] * cover.value;
    out.gradient += steps_[l] * cover.gradient;
    out.d_sigma += steps_[l] * cover.d_sigma;
  }
  return out;
}

}  // namespace markerbench
