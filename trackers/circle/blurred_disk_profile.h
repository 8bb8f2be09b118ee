// The fraction of a disk's ink seen at a point after Gaussian blur (circle-method.md §11):
//   G(s, z) = P(|c + Z| <= s), Z ~ N(0, I₂), |c| = s - z,
// for a disk of radius s and a point z inside its edge, both in units of the blur σ. This is
// 1 - Q₁(s, s - z) (Marcum Q). As s → ∞, G → Φ(z - 1/(2s)): the first-order curvature bias
// σ²/(2R); at R = 2σ the first-order form misplaces the 50% level by about 0.9 px at σ = 10.
// Tabulated once over t = 1/s in [0, 2] (t = 0 the straight edge, Φ(z)) and z in [-7, 7];
// bilinear, with its gradient.
//
// A pixel averages the image over its area. Near a locally straight edge with outward normal
// n, the pixel's offsets project on n as the sum of two uniforms, of half-widths a = |n_x|/2
// and b = |n_y|/2 px (A = a/σ and B = b/σ in σ), so the pixel reads
//   V(z) = E[G(s, z + u)] = [H(z+A+B) - H(z+A-B) - H(z-A+B) + H(z-A-B)] / 4AB,
// with H = ∫∫G dz dz: the same table integrated twice in z (cumulative trapezoids), H
// interpolated by cubic Hermite from its values and slopes (G's first integral), and V's
// derivatives that interpolant's, so that they are V's own to rounding.
#pragma once

#include <Eigen/Core>

namespace markerbench {

struct ProfileValue {
  double value = 0.0;
  double d_ds = 0.0;  // ∂G/∂s
  double d_dz = 0.0;  // ∂G/∂z
};

// V over a pixel (above): its value and derivatives, and A ∂V/∂A + B ∂V/∂B, the change of V
// as both half-widths grow in proportion (∂V/∂σ through them is that over -σ).
struct PixelProfileValue {
  double value = 0.0;
  double d_ds = 0.0;
  double d_dz = 0.0;
  double d_dlog_width = 0.0;
};

// The least σ of a model that averages over each pixel (as OverPixel does; its σ is
// BlurSigmaOfEdges of the edges', pixel_area_blur.h): a sharp image takes it to 0; not quite,
// for z = -d/σ.
constexpr double kMinBlurSigmaPx = 0.02;

// G for one disk radius s, evaluated at many z (one table row interpolation per disk).
// s below 0.5 is taken as 0.5; beyond 80 (the table's first step in t) G is the straight edge's
// Φ(z - 1/2s), within about 1e-5. Sharp images have s of hundreds to thousands (R/σ, σ → 0):
// clamped at 40, as it was, their edges sat σ/80 - σ/2s off, and noise-free frames at 0.6 m and σ
// 0.3-0.6 px gave poses 0.09-0.11 mm off (median; now 0.012-0.014).
class BlurredDiskProfile {
 public:
  explicit BlurredDiskProfile(double s);
  ProfileValue At(double z) const;
  // V at z averaged over a pixel whose half-widths along the normal are A and B (in σ; each
  // taken as at least 1e-3).
  PixelProfileValue OverPixel(double z, double a, double b) const;

  // How OverPixel reads the tables at its four corners: one corner at a time, or all four in
  // the lanes of one AVX2 vector, with the same operations lane by lane in the same order, so
  // the same bits (tested). OverPixel takes the vector where the CPU has AVX2: about 40 % less
  // time a call, the fit on the pixels 7 % less, full detection 4 % (results/speed.md).
  enum class Corners { kOneByOne, kAvx2 };
  PixelProfileValue OverPixel(double z, double a, double b, Corners corners) const;

 private:
  // H, G's second integral in z, at x, with its derivatives in x (the interpolant's, about
  // G's first integral) and in s.
  struct Integral {
    double value = 0.0, d_dx = 0.0, d_ds = 0.0;
  };
  Integral SecondIntegralAt(double x) const;
  // OverPixel with its corners in AVX2 lanes (kCpuHasAvx2 only; A and B at their floor).
  PixelProfileValue OverPixelAvx2(double z, double a, double b) const;
  static PixelProfileValue FromCorners(const Integral (&corner)[4], double a, double b);

  // The first of the two table rows around s, of G and of its two integrals in z (the second
  // follows it).
  const double* values_;
  const double* first_;
  const double* second_;
  double weight_ = 0.0;  // of the second rows
  double d_weight_ds_ = 0.0;
  double shift_ = 0.0;  // in z, of the straight edge (beyond the first row, where s > 80)
  double d_shift_ds_ = 0.0;
};

// Builds the profiles' table now, if no profile has (about 0.1 s, once per process): a tracker
// calls it when it is made, so that the time of its first frame is the frame's own (`markerbench
// track` on a noise-free frame of the paper's took 111-160 ms for it, now 28-32 ms; the same
// frame again, 27 ms).
void PrepareBlurredDiskProfiles();

// A point's signed distance (px, positive outside) from an edge near its point e, n the
// edge's outward unit normal there and `curvature` 1/ρ, ρ its radius of curvature (0: a straight
// edge): the edge falls behind its tangent by a²/2ρ at a = t·(x − e) along it, t = (−n_y, n_x), so
//   d = n·(x − e) + a²/2ρ,
// exact on the edge to second order in a (a circle's is off by a⁴/8ρ³ there), and off it by
// a² d/2ρ(ρ + d), which scales the distances on both sides about alike and moves no edge.
// Its derivative in e is −(n + (a/ρ) t).
struct EdgeOffset {
  double distance;
  double along;  // a
};
inline EdgeOffset OffsetFromCurvedEdge(const Eigen::Vector2d& point,
                                       const Eigen::Vector2d& edge_point,
                                       const Eigen::Vector2d& normal,
                                       double curvature) {
  const Eigen::Vector2d offset = point - edge_point;
  const double along = normal.x() * offset.y() - normal.y() * offset.x();
  return {normal.x() * offset.x() + normal.y() * offset.y() + 0.5 * curvature * along * along,
          along};
}

}  // namespace markerbench
