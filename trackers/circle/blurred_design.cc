#include "trackers/circle/blurred_design.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "trackers/pixel_area_blur.h"

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

// Φ2(h, k; ρ) - Φ(h) Φ(k) = 1/(2π) ∫_0^asin ρ exp(-(h² - 2hk sin θ + k²) / (2 cos² θ)) dθ, by
// Gauss-Legendre on both halves.
double CornerIntegral(double h, double k, double rho) {
  const double end = std::asin(std::clamp(rho, -1.0, 1.0));
  double integral = 0.0;
  for (size_t i = 0; i < kNodes.size(); ++i) {
    for (double sign : {-1.0, 1.0}) {
      const double theta = 0.5 * end * (1.0 + sign * kNodes[i]);
      const double s = std::sin(theta), c2 = 1.0 - s * s;
      integral += kWeights[i] * std::exp(-(h * h - 2.0 * h * k * s + k * k) / (2.0 * c2));
    }
  }
  return 0.5 * end * integral / (2.0 * M_PI);
}

// Edges nearer than this (in σc, below) to a point make a corner with its nearest edge.
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

// An edge's cover of a pixel: the straight edge's blurred step averaged over the pixel
// (blurred_disk_profile.h at s = ∞), with its derivatives in the edge's distance a and in σ
// through the pixel's width in σ.
struct PixelCover {
  double value = 0.0, d_a = 0.0, d_sigma = 0.0;
};
PixelCover CoverOfPixel(const BlurredDiskProfile& straight_edge, const Edge& e, double sigma_px) {
  const PixelProfileValue v = straight_edge.OverPixel(
      -e.a, 0.5 * std::abs(e.normal_px.x()) / sigma_px, 0.5 * std::abs(e.normal_px.y()) / sigma_px);
  return {v.value, -v.d_dz, -v.d_dlog_width / sigma_px};
}

// A layer's blurred indicator over a pixel from its edges there, with its derivatives.
struct Cover {
  double value = 1.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  double d_sigma = 0.0;
};
Cover BlurredCover(const BoundaryDistances& b,
                   const Eigen::Matrix2d& marker_from_px,
                   double sigma_px,
                   const BlurredDiskProfile& straight_edge) {
  Cover cover;
  std::array<Edge, 3> edges;
  const Eigen::Matrix2d px_from_marker = marker_from_px.inverse();
  const double area_px = std::abs(px_from_marker.determinant());
  for (size_t i = 0; i < b.count; ++i) {
    const EdgeDistance& term = b.terms[i];
    const Eigen::Vector2d across = marker_from_px.transpose() * term.gradient;
    const double per_metre = 1.0 / (across.norm() * sigma_px);
    // A circle's blurred edge has its midpoint v/2ρ towards its centre, v the variance of the
    // blur and the pixel along its tangent (σ² + 1/12; ρ its radius of curvature in the image,
    // κ|det A|/|A t|³ for the map A and tangent t): to first order in σ/ρ, a straight edge
    // that much moved.
    const Eigen::Vector2d tangent_px =
        px_from_marker * Eigen::Vector2d(-term.gradient.y(), term.gradient.x());
    const double tangent_norm = tangent_px.norm();
    const double curvature_px =
        term.curvature_per_m * area_px / (tangent_norm * tangent_norm * tangent_norm);
    const double distance = term.metres * per_metre;
    const double area_per_sigma = kPixelAreaVariance / sigma_px;
    edges[i] = {distance + 0.5 * (sigma_px + area_per_sigma) * curvature_px,
                per_metre * term.gradient,
                -distance / sigma_px + 0.5 * (1.0 - area_per_sigma / sigma_px) * curvature_px,
                across.normalized()};
  }
  // The two nearest edges as a corner, the others as straight edges (an insertion sort of
  // at most three that no NaN can lead astray).
  for (size_t i = 1; i < b.count; ++i) {
    for (size_t j = i; j > 0 && std::abs(edges[j].a) < std::abs(edges[j - 1].a); --j) {
      std::swap(edges[j], edges[j - 1]);
    }
  }
  // A factor of the cover, with its derivatives in the distances of the edges it uses and in
  // σ otherwise.
  auto multiply =
      [&](double factor, double d_a1, const Edge& e1, double d_a2, const Edge& e2, double d_sigma) {
        cover.gradient =
            cover.gradient * factor + cover.value * (d_a1 * e1.da_dp + d_a2 * e2.da_dp);
        cover.d_sigma = cover.d_sigma * factor +
                        cover.value * (d_a1 * e1.da_dsigma + d_a2 * e2.da_dsigma + d_sigma);
        cover.value *= factor;
      };
  // Beyond kSharpSigmas of an edge, with the pixel's reach, its step is 0 or 1 and its slope
  // 0 in double precision (Φ(-9) = 1e-19): most edges of a layer are that far from most of
  // its pixels.
  auto multiply_edge = [&](const Edge& e) {
    const double reach = (std::abs(e.normal_px.x()) + std::abs(e.normal_px.y())) / (2.0 * sigma_px);
    if (e.a < -kSharpSigmas - reach) return;
    if (e.a > kSharpSigmas + reach) {
      cover = {0.0, Eigen::Vector2d::Zero(), 0.0};
      return;
    }
    const PixelCover c = CoverOfPixel(straight_edge, e, sigma_px);
    multiply(c.value, c.d_a, e, 0.0, e, c.d_sigma);
  };
  // A corner over a pixel: the product of its two edges' covers, which is exact where the
  // edges are far apart (and for two edges along the pixel's sides), plus what the corner of
  // the two half-planes adds to the product of their steps under a Gaussian of the blur and the
  // pixel's variance, σc² = σ² + 1/12 (EdgeSigmaOfBlur; the pixel taken as Gaussian in that
  // small part):
  // Φ2(h, k; ρ) - Φ(h) Φ(k), h = -a1 σ/σc, k = -a2 σ/σc, ρ the cosine between their normals in
  // pixels (exact for two straight edges at a blur much wider than the pixel; a product alone
  // would bias a sector's apex). Beyond kCornerSigmas σc of the second edge that is below 3e-7.
  const double corner_sigma = EdgeSigmaOfBlur(sigma_px);
  const double to_corner = sigma_px / corner_sigma;
  size_t first_straight = 0;
  if (b.count >= 2 && std::abs(edges[1].a) * to_corner < kCornerSigmas) {
    const Edge& e1 = edges[0];
    const Edge& e2 = edges[1];
    const PixelCover c1 = CoverOfPixel(straight_edge, e1, sigma_px);
    const PixelCover c2 = CoverOfPixel(straight_edge, e2, sigma_px);
    const double rho = std::clamp(e1.normal_px.dot(e2.normal_px), -0.999, 0.999);
    const double root = std::sqrt(1.0 - rho * rho);
    const double h = -e1.a * to_corner, k = -e2.a * to_corner;
    // d Φ2(h, k) / dh = φ(h) Φ((k - ρ h) / √(1 - ρ²)); less the product's φ(h) Φ(k).
    const double cdf_h = NormalCdf(h), cdf_k = NormalCdf(k);
    const double d_h = NormalDensity(h) * (NormalCdf((k - rho * h) / root) - cdf_k);
    const double d_k = NormalDensity(k) * (NormalCdf((h - rho * k) / root) - cdf_h);
    const double product = cdf_h * cdf_k;
    const double excess = (product + CornerIntegral(h, k, rho)) - product;
    // d(σ/σc)/dσ = (1/12)/σc³.
    const double d_to_corner = kPixelAreaVariance / (corner_sigma * corner_sigma * corner_sigma);
    multiply(
        c1.value * c2.value + excess,
        c1.d_a * c2.value - d_h * to_corner,
        e1,
        c1.value * c2.d_a - d_k * to_corner,
        e2,
        c1.d_sigma * c2.value + c1.value * c2.d_sigma - (d_h * e1.a + d_k * e2.a) * d_to_corner);
    first_straight = 2;
  }
  for (size_t i = first_straight; i < b.count; ++i) multiply_edge(edges[i]);
  return cover;
}

}  // namespace

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double NormalDensity(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI); }

double BivariateNormalCdf(double h, double k, double rho) {
  return NormalCdf(h) * NormalCdf(k) + CornerIntegral(h, k, rho);
}

BlurredDesign::BlurredDesign(const MarkerSpec& marker)
    : marker_(marker), straight_edge_(std::numeric_limits<double>::infinity()) {
  // The fitted colours, whose lumas At moves by its `level_shifts`; which one a colour is (-1:
  // none).
  const std::vector<Rgb> fitted = FittedColors(marker);
  const auto fitted_level = [&](const Rgb& color) {
    const auto found = std::find(fitted.begin(), fitted.end(), color);
    return found == fitted.end() ? -1 : static_cast<int>(found - fitted.begin());
  };
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
    fitted_painted_.push_back(fitted_level(layer.color));
    fitted_under_.push_back(fitted_level(under));
  }
  fitted_levels_ = static_cast<int>(fitted.size());
}

BlurredLuma BlurredDesign::At(const Eigen::Vector2d& p,
                              const Eigen::Matrix2d& marker_from_px,
                              double sigma_px,
                              const std::array<double, kMaxFittedLevels>& level_shifts) const {
  const auto shift = [&](int level) { return level < 0 ? 0.0 : level_shifts[level]; };
  BlurredLuma out;
  out.luma = Luma(marker_.background);  // never a fitted colour
  // Layer l's share `cover` of the pixel: its colour's, less the one it is painted on.
  const auto add_shares = [&](size_t l, double cover) {
    if (fitted_painted_[l] >= 0) out.d_levels[fitted_painted_[l]] += cover;
    if (fitted_under_[l] >= 0) out.d_levels[fitted_under_[l]] -= cover;
  };
  // An edge farther than this from p is farther than kSharpSigmas + 1 σc and a pixel in the
  // image (the map's Frobenius norm bounds the metres a pixel spans; the 1 σc covers the
  // curvature's shift of a circle's blurred edge, σc/2ρ σc for ρ ≥ σc).
  const double sharp_beyond_m =
      ((kSharpSigmas + 1.0) * EdgeSigmaOfBlur(sigma_px) + 1.0) * marker_from_px.norm();
  for (size_t l = 0; l < marker_.layers.size(); ++l) {
    const PaintedShape& layer = marker_.layers[l];
    const BoundaryDistances b = DistancesTo(layer.shape, p);
    if (b.count == 0) {
      // Sharp: where it paints, its colour replaces the layers below.
      if (PaintAt(layer, p).color) {
        out = BlurredLuma();
        out.luma = Luma(layer.color) + shift(fitted_painted_[l]);
        if (fitted_painted_[l] >= 0) out.d_levels[fitted_painted_[l]] = 1.0;
      }
      continue;
    }
    const double step = steps_[l] + shift(fitted_painted_[l]) - shift(fitted_under_[l]);
    bool inside = true, far = true;
    for (size_t i = 0; i < b.count; ++i) {
      inside &= b.terms[i].metres < 0.0;
      far &= std::abs(b.terms[i].metres) > sharp_beyond_m;
    }
    if (far) {  // what BlurredCover gives there, to double precision
      if (inside) {
        out.luma += step;
        add_shares(l, 1.0);
      }
      continue;
    }
    const Cover cover = BlurredCover(b, marker_from_px, sigma_px, straight_edge_);
    out.luma += step * cover.value;
    out.gradient += step * cover.gradient;
    out.d_sigma += step * cover.d_sigma;
    add_shares(l, cover.value);
  }
  return out;
}

}  // namespace markerbench
