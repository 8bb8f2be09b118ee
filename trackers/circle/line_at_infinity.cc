#include "trackers/circle/line_at_infinity.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <limits>

#include "trackers/circle/conic.h"

namespace markerbench {
namespace {

struct LinePair {
  std::array<Eigen::Vector3d, 2> lines;
  double rank_residual = 0.0;  // |μ_small| / max|μ|: 0 for an exact line pair
};

// Splits a (noisy) rank-2 symmetric conic into its two real lines by the eigen method (§4.2);
// nullopt for a point conic (complex lines).
std::optional<LinePair> SplitLinePair(const Eigen::Matrix3d& D) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (D + D.transpose()));
  const Eigen::Vector3d mu = eig.eigenvalues();
  int small = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(mu(k)) < std::abs(mu(small))) small = k;
  }
  const int a = (small + 1) % 3, b = (small + 2) % 3;
  if (mu(a) * mu(b) >= 0.0) return std::nullopt;
  const int plus = mu(a) > 0.0 ? a : b, minus = mu(a) > 0.0 ? b : a;
  const Eigen::Vector3d ep = std::sqrt(mu(plus)) * eig.eigenvectors().col(plus);
  const Eigen::Vector3d em = std::sqrt(-mu(minus)) * eig.eigenvectors().col(minus);
  LinePair pair;
  pair.lines = {(ep + em).normalized(), (ep - em).normalized()};
  pair.rank_residual = std::abs(mu(small)) / mu.cwiseAbs().maxCoeff();
  return pair;
}

Eigen::Vector3d EllipseCenterHomogeneous(const Eigen::Matrix3d& C) {
  const Eigen::Vector3d c = Adjugate(C) * Eigen::Vector3d::UnitZ();
  return c / c.z();
}

}  // namespace

std::array<std::complex<double>, 3> PencilEigenvalues(const Eigen::Matrix3d& C1,
                                                      const Eigen::Matrix3d& C2) {
  const Eigen::EigenSolver<Eigen::Matrix3d> eig(C2.inverse() * C1, false);
  std::array<std::complex<double>, 3> lambda;
  for (int k = 0; k < 3; ++k) lambda[k] = eig.eigenvalues()(k);
  std::sort(lambda.begin(), lambda.end(), [](const auto& x, const auto& y) {
    return x.real() < y.real();
  });
  return lambda;
}

std::optional<Eigen::Vector3d> LineAtInfinityFromTwoCircles(const Eigen::Matrix3d& C1,
                                                            const Eigen::Matrix3d& C2) {
  const Eigen::Vector3d c1 = EllipseCenterHomogeneous(C1), c2 = EllipseCenterHomogeneous(C2);
  std::optional<Eigen::Vector3d> best;
  double best_residual = std::numeric_limits<double>::infinity();
  for (const std::complex<double>& lambda : PencilEigenvalues(C1, C2)) {
    if (std::abs(lambda.imag()) > 1e-6 * std::max(1.0, std::abs(lambda))) continue;
    const std::optional<LinePair> pair = SplitLinePair(C1 - lambda.real() * C2);
    if (!pair) continue;
    for (const Eigen::Vector3d& l : pair->lines) {
      const bool same_side = (l.dot(c1) > 0.0) == (l.dot(c2) > 0.0);
      if (!same_side || !LineMissesEllipse(l, C1) || !LineMissesEllipse(l, C2)) continue;
      if (pair->rank_residual < best_residual) {
        best_residual = pair->rank_residual;
        best = l;
      }
    }
  }
  return best;
}

std::optional<ConcentricSolution> LineAtInfinityFromConcentric(const Eigen::Matrix3d& C1,
                                                               const Eigen::Matrix3d& C2) {
  const std::array<std::complex<double>, 3> lambda = PencilEigenvalues(C1, C2);
  int isolated = 0;
  double best_gap = -1.0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::min(std::abs(lambda[k] - lambda[(k + 1) % 3]),
                                std::abs(lambda[k] - lambda[(k + 2) % 3]));
    if (gap > best_gap) {
      best_gap = gap;
      isolated = k;
    }
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(C1 - lambda[isolated].real() * C2,
                                              Eigen::ComputeFullV);
  Eigen::Vector3d m = svd.matrixV().col(2);
  if (std::abs(m.z()) < 1e-12 * m.norm()) return std::nullopt;
  m /= m.z();
  const Eigen::Vector3d p1 = (C1 * m).normalized(), p2 = (C2 * m).normalized();
  const double sigma = p1.dot(p2) >= 0.0 ? 1.0 : -1.0;
  return ConcentricSolution{(p1 + sigma * p2).normalized(), m};
}

Eigen::Vector3d LineAtInfinityFromCenter(const Eigen::Matrix3d& C, const Eigen::Vector3d& m) {
  return (C * m).normalized();
}

std::optional<Eigen::Vector3d> ImagedCenter(const Eigen::Matrix3d& C,
                                            const Eigen::Vector3d& l_inf) {
  const Eigen::Vector3d m = Adjugate(C) * l_inf;
  if (!(std::abs(m.z()) > 1e-12 * m.norm())) return std::nullopt;
  return m / m.z();
}

std::array<Eigen::Vector3d, 2> SingleCircleNormals(const Eigen::Matrix3d& C) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (C + C.transpose()));
  // Ascending: μ3 = eigenvalues(0), μ2 = (1), μ1 = (2).
  const Eigen::Vector3d mu = eig.eigenvalues();
  const Eigen::Vector3d a = std::sqrt(std::max(0.0, mu(2) - mu(1))) * eig.eigenvectors().col(2);
  const Eigen::Vector3d b = std::sqrt(std::max(0.0, mu(1) - mu(0))) * eig.eigenvectors().col(0);
  return {(a + b).normalized(), (a - b).normalized()};
}

Eigen::Vector3d KNormalLineAtInfinity(const std::vector<Eigen::Matrix3d>& conics,
                                      const Eigen::Vector3d& l_inf) {
  const Eigen::Vector3d reference = l_inf.normalized();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Matrix3d& C : conics) {
    const std::array<Eigen::Vector3d, 2> normals = SingleCircleNormals(C);
    const Eigen::Vector3d& n =
        std::abs(normals[0].dot(reference)) >= std::abs(normals[1].dot(reference)) ? normals[0]
                                                                                   : normals[1];
    sum += n.dot(reference) >= 0.0 ? n : Eigen::Vector3d(-n);
  }
  return sum.normalized();
}

Eigen::Vector3d OrientLineAtInfinity(const Eigen::Vector3d& l_inf, const Eigen::Vector3d& m0) {
  const Eigen::Vector3d l = l_inf.normalized();
  return l.dot(m0) > 0.0 ? Eigen::Vector3d(-l) : l;
}

}  // namespace markerbench
