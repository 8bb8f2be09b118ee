// The exact image of a disk under Gaussian blur: a tilted disk's image is an ellipse E, and
// blurred by an isotropic Gaussian of σ it is, at a pixel x,
//   G(x) = P(x + n ∈ E),  n ~ N(0, σ² I).
// Cut E into horizontal chords: at height y0 + v (|v| <= h) the chord is centred at x0 + k v
// with half-width W √(1 - v²/h²). The Gaussian's two axes are independent, so with
// v = h sin θ (which takes the square root's edge away)
//   G = ∫_{-π/2}^{π/2} (h cos θ / σ) φ((y0 + h sin θ - y) / σ)
//         [Φ((x0 + k h sin θ + W cos θ - x) / σ) - Φ((x0 + k h sin θ - W cos θ - x) / σ)] dθ,
// taken by Gauss-Legendre quadrature, with its gradient in (x0, y0, k, W, h, σ). Unlike the
// osculating disk of blurred_disk_profile.h it holds however far the blur reaches across the
// ellipse. The integrand varies on the scale of the ellipse's semi-major axis in σ, and so do
// the nodes needed: from 12 up to 1.25 σ, to 64 up to 11 σ, each rule within 1e-7 of the
// integral for any ellipse of its range (tested; more nodes than these only cost time). Φ and
// φ come from tables (normal_tables.h), and the factors of the row, y, are computed once for
// the pixels of a row: a pixel then costs two table look-ups per node.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <optional>

#include "trackers/circle/avx2_lanes.h"

namespace markerbench {

template <class T>
struct EllipseChords {
  T x0, y0;       // centre, pixels
  T slope;        // k: the chords' centres move by k per unit of height
  T half_width;   // W: of the middle chord
  T half_height;  // h
};

// The chords of the ellipse of conic C ((x, y, 1) C (x, y, 1)ᵀ = 0, any scale or sign);
// nullopt if C is no real ellipse. T may be a ceres::Jet.
template <class T>
std::optional<EllipseChords<T>> ChordsOfConic(const Eigen::Matrix<T, 3, 3>& conic) {
  using std::sqrt;
  // A x² + 2B xy + C y² + 2D x + 2E y + F, scaled to A > 0.
  const T sign = conic(0, 0) < T(0.0) ? T(-1.0) : T(1.0);
  const T A = sign * conic(0, 0), B = sign * 0.5 * (conic(0, 1) + conic(1, 0));
  const T C = sign * conic(1, 1), D = sign * 0.5 * (conic(0, 2) + conic(2, 0));
  const T E = sign * 0.5 * (conic(1, 2) + conic(2, 1)), F = sign * conic(2, 2);
  const T det = A * C - B * B;
  if (!(A > T(0.0)) || !(det > T(0.0))) return std::nullopt;
  EllipseChords<T> e;
  e.x0 = (B * E - C * D) / det;
  e.y0 = (B * D - A * E) / det;
  // Around the centre: A u² + 2B uv + C v² = R.
  const T R = -(F + D * e.x0 + E * e.y0);
  if (!(R > T(0.0))) return std::nullopt;
  e.slope = -B / A;
  e.half_width = sqrt(R / A);
  e.half_height = sqrt(A * R / det);
  return e;
}

struct BlurredEllipseValue {
  double value = 0.0;
  // ∂G/∂(x0, y0, k, W, h, σ).
  Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
};

// G of the ellipse `e` blurred by σ > 0, at pixels taken row by row.
class BlurredEllipse {
 public:
  static constexpr int kMaxNodes = 64;

  // The nodes that take G within 1e-7 for a semi-major axis of `semi_major_per_sigma` σ.
  static int NodesFor(double semi_major_per_sigma);

  // With the first rule of at least `nodes` (12, 16, 24, 32, 48, 64), or 64.
  BlurredEllipse(const EllipseChords<double>& e, double sigma, int nodes);

  // G at the pixel (x, y); the row's factors are kept for the next pixel of the same y.
  BlurredEllipseValue At(const Eigen::Vector2d& pixel);
  // G alone, the same sum as At's value, to the bit: for a fit's costs without its normal
  // equations (Φ alone at each chord end, not φ too, and none of the gradient's sums).
  double ValueAt(const Eigen::Vector2d& pixel);

  // How At and ValueAt read the tables at the nodes' chord ends: one node at a time, or four
  // nodes in the lanes of AVX2 vectors, with the same operations lane by lane and the sums over
  // the nodes in their order, so the same bits (tested). They take the lanes where the CPU has
  // AVX2 (kCpuHasAvx2).
  enum class NodeLanes { kOneByOne, kAvx2 };
  BlurredEllipseValue At(const Eigen::Vector2d& pixel, NodeLanes lanes);
  double ValueAt(const Eigen::Vector2d& pixel, NodeLanes lanes);

 private:
  // The row's factors for pixels at height y, unless they are already y's.
  void TakeRow(double y);

  // The nodes θ with their weights w: the middle of each one's chord (k h sin θ) and half its
  // length (W cos θ), and in the row last asked for, the chord's height in σ,
  // z = (y0 + h sin θ - y)/σ, and its weight w (h cos θ / σ) φ(z). A quantity a row, so that
  // four nodes fill an AVX2 vector.
  struct Nodes {
    std::array<double, kMaxNodes> sin_theta, cos_theta, weight, chord_middle, chord_half, z_row,
        row;
  };
  // At a pixel, each node's terms of G and of its gradient's sums, f = w (h c / σ) φ(z_row)
  // across, and the parts of its derivatives At sums; set where the node's row is not 0.
  struct NodeTerms {
    std::array<double, kMaxNodes> f, across_x, width, ends;
  };
  // The terms at a pixel, for At (with_gradient) or ValueAt (f alone), its row's factors taken;
  // one by one or in lanes, at its X = x0 - x.
  void TermsAt(const Eigen::Vector2d& pixel, NodeLanes lanes, bool with_gradient, NodeTerms* terms);
  void TermsOneByOne(double X, bool with_gradient, NodeTerms* terms) const;
#if defined(__x86_64__)
  MARKERBENCH_AVX2 void TermsInLanes(double X, bool with_gradient, NodeTerms* terms) const;
#endif

  EllipseChords<double> e_;
  double sigma_;
  double row_y_;
  int nodes_used_;
  Nodes nodes_;
};

}  // namespace markerbench
