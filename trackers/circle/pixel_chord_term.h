// What a pixel's square adds to its average of a blurred curved edge beyond the mean shift.
//
// A pixel whose centre is at signed distance D (px, positive outside) from an edge with unit
// normal n and radius of curvature ρ reads the blurred step at its offsets u: across the edge
// w = n·u, along it v = t·u, where the edge falls behind its tangent by v²/2ρ, so it reads
//   E[G(-(D + w + v²/2ρ)/σ)].
// The fits take v² at its mean over the square, 1/12 (the shift 1/24ρ), and average over w
// alone (BlurredDiskProfile::OverPixel). But v² is not 1/12 on every chord of the square: a
// chord through a diagonal pixel's middle is √2 long. To first order in 1/ρ the rest is
//   Δ = -(1/2ρ) ∫ q(w) φ((w + D)/σ)/σ dw,   q(w) = ∫ v² dv - L(w)/12 on the chord at w,
// L its length, taking the blurred step's slope as the straight edge's φ. q is zero in the
// mean over w, so Δ fades as the blur widens past the pixel; on sharp edges it is the largest
// part of the model's error (over the pixels a sharp disk's edge crosses, against their exact
// cover: 3.8e-4 of the step RMS at 30 px, 6.5e-6 with Δ; 1.3e-3 and 1.0e-4 at 8 px; tested).
//
// For n = (c, s) with c >= s >= 0 (the square's symmetries take any normal there) q is even:
//   |w| <= m = (c - s)/2:  q = s² (w² + 1/12) / c³   (chords of length 1/c, centred at -ws/c)
//   m <= |w| <= (c + s)/2: with y = (c + s)/2 - |w| from the corner, which lies v₀ = (c - s)/2
//     along the edge, the chord runs from v₀ - y c/s to v₀ + y s/c, so with α = s/c, β = c/s
//     q = (α + β)(v₀² - 1/12) y + v₀ (α² - β²) y² + (α³ + β³) y³ / 3.
// Each piece's integral against the Gaussian is a sum of truncated normal moments.
#pragma once

#include <Eigen/Core>

namespace markerbench {

struct PixelChordTerm {
  double value = 0.0;       // Δ, a fraction of the step
  double d_distance = 0.0;  // ∂Δ/∂D
  double d_sigma = 0.0;     // ∂Δ/∂σ at D held
};

// Δ (above) for a pixel at `distance_px` from an edge of unit `normal` and `radius_px` of
// curvature (positive: the edge bends away from the pixel's outside), under a Gaussian blur
// of `sigma_px`.
PixelChordTerm PixelChordTermAt(double distance_px,
                                double sigma_px,
                                const Eigen::Vector2d& normal,
                                double radius_px);

}  // namespace markerbench
