// The imaged line at infinity l_inf and the imaged circle centres (circle-method.md §4).
// Everything here is in normalized camera coordinates (C_n = Kᵀ C_pix K) with canonical
// conics; in those coordinates l_inf = ±r3 (paper eq. 11, erratum 4). Lines are returned
// unit length; their sign is fixed only by OrientLineAtInfinity.
#pragma once

#include <Eigen/Core>
#include <array>
#include <complex>
#include <optional>
#include <vector>

namespace markerbench {

// Eigenvalues of C2⁻¹ C1 (the pencil C1 - λ C2), sorted by real part.
std::array<std::complex<double>, 3> PencilEigenvalues(const Eigen::Matrix3d& C1,
                                                      const Eigen::Matrix3d& C2);

// Two separate (or intersecting) coplanar circles (§4.3): the real line pairs of the pencil's
// degenerate members, filtered by the quasi-affine criterion (the line misses both ellipses
// and has both on one side). With noise, the candidate closest to rank 2 wins.
std::optional<Eigen::Vector3d> LineAtInfinityFromTwoCircles(const Eigen::Matrix3d& C1,
                                                            const Eigen::Matrix3d& C2);

struct ConcentricSolution {
  Eigen::Vector3d l_inf;
  Eigen::Vector3d center;  // imaged common centre, w = 1
};
// Two concentric circles (§4.4): the common centre from the isolated eigenvalue, l_inf from
// the aligned polars of that centre.
std::optional<ConcentricSolution> LineAtInfinityFromConcentric(const Eigen::Matrix3d& C1,
                                                               const Eigen::Matrix3d& C2);

// One circle and its detected centre m (w = 1): l_inf = C m, the polar of the centre (§4.5).
Eigen::Vector3d LineAtInfinityFromCenter(const Eigen::Matrix3d& C, const Eigen::Vector3d& m);

// The imaged centre of a circle: the pole adj(C) l_inf with w = 1 (§4.6; not the ellipse
// centre). nullopt if the pole is at infinity.
std::optional<Eigen::Vector3d> ImagedCenter(const Eigen::Matrix3d& C, const Eigen::Vector3d& l_inf);

// The two plane normals that one circle allows with a calibrated camera (§4.7):
// sqrt(μ1 - μ2) e1 ± sqrt(μ2 - μ3) e3 from the eigen-decomposition of C; one is ±r3.
std::array<Eigen::Vector3d, 2> SingleCircleNormals(const Eigen::Matrix3d& C);

// The K-normal l_inf (§5.5): per circle, the §4.7 candidate closest to `l_inf`, signs aligned
// with it, averaged.
Eigen::Vector3d KNormalLineAtInfinity(const std::vector<Eigen::Matrix3d>& conics,
                                      const Eigen::Vector3d& l_inf);

// The sign rule of §0: unit length and l · m0 < 0 (m0 with w = 1), so that l_inf = r3.
Eigen::Vector3d OrientLineAtInfinity(const Eigen::Vector3d& l_inf, const Eigen::Vector3d& m0);

}  // namespace markerbench
