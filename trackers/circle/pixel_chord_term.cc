#include "trackers/circle/pixel_chord_term.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "trackers/circle/normal_tables.h"

namespace markerbench {
namespace {

// Normals within this of an axis (sin, about 0.06°) have q within s² of zero: taken as zero.
constexpr double kMinSine = 1e-3;
// Beyond this many σ from a piece the Gaussian is zero in NormalCdfTable.
constexpr double kReachSigmas = NormalCdfTable::kEnd;

// ∫ P(y) φ((y - centre)/σ)/σ dy over [lo, hi] for the cubic P = Σ k_j y^j, with its
// derivatives in the centre and in σ.
struct PieceIntegral {
  double value = 0.0, d_centre = 0.0, d_sigma = 0.0;
};

PieceIntegral IntegrateCubicPiece(
    const std::array<double, 4>& k, double lo, double hi, double centre, double sigma) {
  PieceIntegral out;
  if (hi <= lo || centre < lo - kReachSigmas * sigma || centre > hi + kReachSigmas * sigma) {
    return out;
  }
  const auto cubic = [&](double y) { return k[0] + y * (k[1] + y * (k[2] + y * k[3])); };
  if (hi - lo <= 2.0 * sigma) {
    // The Gaussian smooth over the piece: Gauss-Legendre, 5 nodes (exact to degree 9).
    static constexpr std::array<double, 5> kNodes = {
        -0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
    static constexpr std::array<double, 5> kWeights = {0.2369268850561891,
                                                       0.4786286704993665,
                                                       0.5688888888888889,
                                                       0.4786286704993665,
                                                       0.2369268850561891};
    const double half = 0.5 * (hi - lo), middle = 0.5 * (hi + lo), per_sigma = 1.0 / sigma;
    for (int i = 0; i < 5; ++i) {
      const double y = middle + half * kNodes[i];
      const double x = (y - centre) * per_sigma;
      const double term = half * kWeights[i] * cubic(y) * kNormalCdfTable.At(x).density * per_sigma;
      out.value += term;
      out.d_centre += term * x * per_sigma;
      out.d_sigma += term * (x * x - 1.0) * per_sigma;
    }
    return out;
  }
  // The piece wide against the Gaussian: P(centre + σx) = Σ p_j x^j against the truncated
  // normal's moments M_j = ∫ x^j φ(x) dx over the piece, M_j = x^(j-1) φ at its ends + (j-1)
  // M_(j-2); the derivatives move x by -1/σ (the centre) and scale the density (σ).
  const double c = centre;
  const std::array<double, 4> p = {cubic(c),
                                   sigma * (k[1] + c * (2.0 * k[2] + 3.0 * c * k[3])),
                                   sigma * sigma * (k[2] + 3.0 * c * k[3]),
                                   sigma * sigma * sigma * k[3]};
  const double per_sigma = 1.0 / sigma;
  const double x_lo = (lo - c) * per_sigma, x_hi = (hi - c) * per_sigma;
  const NormalCdfTable::Values at_lo = kNormalCdfTable.At(x_lo), at_hi = kNormalCdfTable.At(x_hi);
  std::array<double, 6> moments;
  moments[0] = at_hi.cdf - at_lo.cdf;
  double power_lo = 1.0, power_hi = 1.0;  // x^(j-1) at the ends
  for (int j = 1; j < 6; ++j) {
    moments[j] = power_lo * at_lo.density - power_hi * at_hi.density;
    if (j >= 2) moments[j] += (j - 1) * moments[j - 2];
    power_lo *= x_lo;
    power_hi *= x_hi;
  }
  for (int j = 0; j < 4; ++j) {
    out.value += p[j] * moments[j];
    out.d_centre += p[j] * moments[j + 1] * per_sigma;
    out.d_sigma += p[j] * (moments[j + 2] - moments[j]) * per_sigma;
  }
  return out;
}

}  // namespace

PixelChordTerm PixelChordTermAt(double distance_px,
                                double sigma_px,
                                const Eigen::Vector2d& normal,
                                double radius_px) {
  const double c = std::max(std::abs(normal.x()), std::abs(normal.y()));
  const double s = std::min(std::abs(normal.x()), std::abs(normal.y()));
  PixelChordTerm out;
  const double inner = 0.5 * (c - s), outer = 0.5 * (c + s);
  if (s < kMinSine || std::abs(distance_px) > outer + kReachSigmas * sigma_px) return out;
  const double alpha = s / c, beta = c / s;
  const std::array<double, 4> middle = {s * s / (12.0 * c * c * c), 0.0, s * s / (c * c * c), 0.0};
  const std::array<double, 4> end = {0.0,
                                     (alpha + beta) * (inner * inner - 1.0 / 12.0),
                                     inner * (alpha * alpha - beta * beta),
                                     (alpha * alpha * alpha + beta * beta * beta) / 3.0};
  // The middle piece in w (its Gaussian centred at w = -D), the ends in y = outer - |w| (at
  // y = outer + D for w > 0 and outer - D for w < 0).
  const PieceIntegral in_middle =
      IntegrateCubicPiece(middle, -inner, inner, -distance_px, sigma_px);
  const PieceIntegral at_plus = IntegrateCubicPiece(end, 0.0, s, outer + distance_px, sigma_px);
  const PieceIntegral at_minus = IntegrateCubicPiece(end, 0.0, s, outer - distance_px, sigma_px);
  const double scale = -0.5 / radius_px;
  out.value = scale * (in_middle.value + at_plus.value + at_minus.value);
  out.d_distance = scale * (-in_middle.d_centre + at_plus.d_centre - at_minus.d_centre);
  out.d_sigma = scale * (in_middle.d_sigma + at_plus.d_sigma + at_minus.d_sigma);
  return out;
}

}  // namespace markerbench
