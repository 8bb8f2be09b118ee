// Conic toolbox (circle-method.md §0-§2). A conic is a symmetric 3x3 matrix C with
// xᵀ C x = 0 on the curve (paper eq. 1). Lines are 3-vectors; points are homogeneous.
// Transforms between frames: if points map as x' = M x, lines map as M⁻ᵀ l and conics as
// M⁻ᵀ C M⁻¹ (so pixel -> normalized is C_n = Kᵀ C_pix K, l_n = Kᵀ l_pix).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace markerbench {

// adj(C) = det(C) C⁻¹ (the cofactor transpose), defined for singular C too.
Eigen::Matrix3d Adjugate(const Eigen::Matrix3d& C);

// The canonical scale and sign (§0): ‖C‖_F = 1 and C₀₀ + C₁₁ > 0, so a real ellipse has
// det C < 0 and xᵀ C x < 0 inside. Symmetrizes C.
Eigen::Matrix3d CanonicalConic(const Eigen::Matrix3d& C);

// True for a real, non-degenerate ellipse (any scale or sign of C).
bool IsRealEllipse(const Eigen::Matrix3d& C);

// Geometric parameters of an ellipse conic (§1), for diagnostics and tests.
struct Ellipse {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double semi_major = 0.0;
  double semi_minor = 0.0;
  double angle_rad = 0.0;  // of the major axis, from +u towards +v
};
Ellipse EllipseFromConic(const Eigen::Matrix3d& C);
Eigen::Matrix3d ConicFromEllipse(const Ellipse& ellipse);
// The ellipse's quadratic form A about its centre c: (x - c)ᵀ A (x - c) = 1 on it, < 1 inside.
Eigen::Matrix2d EllipseForm(const Ellipse& ellipse);

// The distance from the centre of the real ellipse `e` beyond which every point is more
// than `distance` PND (PndResidual) from it, for scans that skip far points. Outside an
// ellipse |PND| is at least the Sampson distance, which at distance D from an ellipse of
// semi-axes a >= b exceeds D b² / (2 a²) (the point is s v with v on the ellipse, s > 1,
// and Sampson = (s² - 1) / (2 s |A v|) for the normalized quadric A). Hence
// a + 2 distance (a / b)², with a margin for rounding; infinity where the axes are NaN.
double PndReach(const Ellipse& e, double distance);

// The scales of the real ellipse `e` about its centre between which lie all the points within
// `distance` PND of it: every point of e scaled by more than `outer`, or by less than `inner`,
// is farther, for scans that skip those (an ellipse's band, where PndReach's is a circle). For
// a point s v, v on e: outside, |PND| is at least the Sampson distance (s² - 1) / (2 s |A v|)
// (PndReach), and |A v| <= 1/b, so beyond (s² - 1) b / 2s = distance it is farther; inside,
// |PND| is the distance to the ellipse along the normal line (d1), at least the nearest, and e
// scaled by 1 - distance / b lies that far within it (a disk of radius distance about each of
// its points lies in e: support functions s h + distance <= h, as h >= b). With margins for
// rounding; `inner` 0 where no point lies that deep, and nothing skipped (0 and infinity) where
// the axes are NaN.
struct PndBand {
  double inner = 0.0;
  double outer = INFINITY;
};
PndBand PndBandScales(const Ellipse& e, double distance);

// The line l misses the real ellipse C iff lᵀ adj(C) l > 0 (§1; invariant to scale and sign).
bool LineMissesEllipse(const Eigen::Vector3d& l, const Eigen::Matrix3d& C);

// Image of the plane circle with centre `center` and radius `radius` under the plane-to-image
// homography H: adj(H)ᵀ C_w adj(H) (§1), unnormalized. Templated for ceres::Jet.
template <typename T>
Eigen::Matrix<T, 3, 3> ImageOfCircle(const Eigen::Matrix<T, 3, 3>& H,
                                     const Eigen::Vector2d& center,
                                     double radius) {
  Eigen::Matrix<T, 3, 3> C_w;
  C_w << T(1), T(0), T(-center.x()), T(0), T(1), T(-center.y()), T(-center.x()), T(-center.y()),
      T(center.squaredNorm() - radius * radius);
  Eigen::Matrix<T, 3, 3> adj;
  adj(0, 0) = H(1, 1) * H(2, 2) - H(1, 2) * H(2, 1);
  adj(0, 1) = H(0, 2) * H(2, 1) - H(0, 1) * H(2, 2);
  adj(0, 2) = H(0, 1) * H(1, 2) - H(0, 2) * H(1, 1);
  adj(1, 0) = H(1, 2) * H(2, 0) - H(1, 0) * H(2, 2);
  adj(1, 1) = H(0, 0) * H(2, 2) - H(0, 2) * H(2, 0);
  adj(1, 2) = H(0, 2) * H(1, 0) - H(0, 0) * H(1, 2);
  adj(2, 0) = H(1, 0) * H(2, 1) - H(1, 1) * H(2, 0);
  adj(2, 1) = H(0, 1) * H(2, 0) - H(0, 0) * H(2, 1);
  adj(2, 2) = H(0, 0) * H(1, 1) - H(0, 1) * H(1, 0);
  return adj.transpose() * C_w * adj;
}

// Signed polar-n-direction distance of the point (x, y, 1) to C (§2.1; paper eqs. 15-18):
// d1 on the set 𝒴, the Sampson distance on 𝒩, in the units of x and y. Invariant to the
// scale and sign of C; the sign of the result is that of xᵀ C x. Templated for ceres::Jet; a
// point that is data (S = double beside a Jet C) skips the products of its zero derivatives.
template <typename T, typename S = T>
T PndResidual(const Eigen::Matrix<T, 3, 3>& C, const S& x, const S& y) {
  using std::sqrt;
  const T n1 = C(0, 0) * x + C(0, 1) * y + C(0, 2);
  const T n2 = C(1, 0) * x + C(1, 1) * y + C(1, 2);
  const T n3 = C(2, 0) * x + C(2, 1) * y + C(2, 2);
  const T q = n1 * x + n2 * y + n3;
  T g = n1 * n1 + n2 * n2;
  if (g < T(1e-300)) g = T(1e-300);
  const T w = C(0, 0) * n1 * n1 + T(2) * C(0, 1) * n1 * n2 + C(1, 1) * n2 * n2;
  const T disc = T(1) - q * w / (g * g);
  if (disc >= T(1e-12)) return q / (sqrt(g) * (T(1) + sqrt(disc)));
  if (disc >= T(0)) return q / (sqrt(g) * T(1.000001));
  return q / (T(2) * sqrt(g));
}

}  // namespace markerbench
