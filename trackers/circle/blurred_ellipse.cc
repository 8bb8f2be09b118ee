#include "trackers/circle/blurred_ellipse.h"

#include <array>

#include "trackers/circle/blurred_design.h"

namespace markerbench {
namespace {

constexpr int kNodes = 32;

// Gauss-Legendre nodes and weights on [-π/2, π/2], the nodes as (sin θ, cos θ): the roots of
// the Legendre polynomial P_n by Newton's method from Chebyshev guesses.
struct Quadrature {
  std::array<double, kNodes> sin_theta, cos_theta, weight;
  Quadrature() {
    for (int i = 0; i < kNodes; ++i) {
      double x = std::cos(M_PI * (i + 0.75) / (kNodes + 0.5));
      double derivative = 0.0;
      for (int step = 0; step < 100; ++step) {
        double p0 = 1.0, p1 = x;  // P_0, P_1, then up to P_n by the three-term recurrence
        for (int n = 2; n <= kNodes; ++n) {
          const double p2 = ((2.0 * n - 1.0) * x * p1 - (n - 1.0) * p0) / n;
          p0 = p1;
          p1 = p2;
        }
        derivative = kNodes * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / derivative;
        x -= dx;
        if (std::abs(dx) < 1e-15) break;
      }
      const double theta = 0.5 * M_PI * x;
      sin_theta[i] = std::sin(theta);
      cos_theta[i] = std::cos(theta);
      weight[i] = 0.5 * M_PI * 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
  }
};

const Quadrature& TheQuadrature() {
  static const Quadrature quadrature;
  return quadrature;
}

}  // namespace

BlurredEllipseValue BlurredEllipseAt(const EllipseChords<double>& e,
                                     double sigma,
                                     const Eigen::Vector2d& pixel) {
  const Quadrature& q = TheQuadrature();
  const double X = e.x0 - pixel.x(), Y = e.y0 - pixel.y();
  const double k = e.slope, W = e.half_width, h = e.half_height;
  BlurredEllipseValue out;
  Eigen::Matrix<double, 6, 1>& d = out.gradient;
  for (int i = 0; i < kNodes; ++i) {
    const double s = q.sin_theta[i], c = q.cos_theta[i];
    const double z_row = (Y + h * s) / sigma;
    if (std::abs(z_row) > 9.0) continue;  // φ < 1e-17
    const double z_right = (X + k * h * s + W * c) / sigma;
    const double z_left = (X + k * h * s - W * c) / sigma;
    const double across = NormalCdf(z_right) - NormalCdf(z_left);
    const double at_right = NormalDensity(z_right), at_left = NormalDensity(z_left);
    // w f = w (h c / σ) φ(z_row) across, and its derivatives.
    const double row = q.weight[i] * (h * c / sigma) * NormalDensity(z_row);
    const double f = row * across;
    out.value += f;
    const double d_x = row * (at_right - at_left) / sigma;  // ∂/∂X, moving both ends
    const double d_y = -row * z_row * across / sigma;       // ∂/∂Y
    d[0] += d_x;
    d[1] += d_y;
    d[2] += d_x * h * s;
    d[3] += row * (at_right + at_left) * c / sigma;
    d[4] += f / h + d_y * s + d_x * k * s;
    d[5] += -f / sigma - d_y * z_row - row * (at_right * z_right - at_left * z_left) / sigma;
  }
  return out;
}

}  // namespace markerbench
