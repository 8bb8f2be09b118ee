#include "trackers/circle/analytic_solver.h"

#include <Eigen/LU>

#include "trackers/circle/conic.h"
#include "trackers/circle/line_at_infinity.h"

namespace markerbench {
namespace {

std::optional<AnalyticSolution> Fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return std::nullopt;
}

Eigen::Vector2d Dehomogenized(const Eigen::Vector3d& x) { return x.head<2>() / x.z(); }

std::vector<Eigen::Matrix3d> NormalizedConics(const Eigen::Matrix3d& K,
                                              const CircleMeasurements& measurements) {
  std::vector<Eigen::Matrix3d> conics_n;
  for (const Eigen::Matrix3d& C : measurements.conics_px) {
    conics_n.push_back(CanonicalConic(K.transpose() * C * K));
  }
  return conics_n;
}

// The projective l_inf of the layout (§4.3-4.5), before any use of K's normals.
std::optional<Eigen::Vector3d> ProjectiveLineAtInfinity(
    const CircleGeometry& geometry,
    const Eigen::Matrix3d& K_inv,
    const std::vector<Eigen::Matrix3d>& conics_n,
    const CircleMeasurements& measurements,
    std::string* error) {
  switch (geometry.layout) {
    case CircleLayout::kTwoCircles: {
      const std::optional<Eigen::Vector3d> l =
          LineAtInfinityFromTwoCircles(conics_n[0], conics_n[1]);
      if (!l && error) *error = "no line in the pencil passes the quasi-affine test";
      return l;
    }
    case CircleLayout::kConcentric: {
      const std::optional<ConcentricSolution> s =
          LineAtInfinityFromConcentric(conics_n[0], conics_n[1]);
      if (!s) {
        if (error) *error = "the concentric pencil has no finite centre";
        return std::nullopt;
      }
      return s->l_inf;
    }
    case CircleLayout::kCircleWithCenter:
      if (!measurements.m0_px) {
        if (error) *error = "the centre point m0 was not detected";
        return std::nullopt;
      }
      return LineAtInfinityFromCenter(conics_n[0], K_inv * measurements.m0_px->homogeneous());
    case CircleLayout::kSingleCircle:
      // One of the two; AnalyticCandidates gives both, and the design tells them apart.
      return SingleCircleNormals(conics_n[0])[0];
  }
  return std::nullopt;
}

// Given l_inf: imaged centres as poles (§4.6), the pose (§5.2) and the depth (§5.3).
std::optional<AnalyticSolution> SolutionFromLine(const CircleGeometry& geometry,
                                                 const Eigen::Matrix3d& K,
                                                 const std::vector<Eigen::Matrix3d>& conics_n,
                                                 const CircleMeasurements& measurements,
                                                 Eigen::Vector3d l_inf,
                                                 AnalyticDepth depth,
                                                 std::string* error) {
  const Eigen::Matrix3d K_inv = K.inverse();
  std::vector<Eigen::Vector3d> centers_n;
  for (const Eigen::Matrix3d& C : conics_n) {
    const std::optional<Eigen::Vector3d> m = ImagedCenter(C, l_inf);
    if (!m) return Fail(error, "an imaged centre is at infinity");
    centers_n.push_back(*m);
  }
  const Eigen::Vector3d& m0 = centers_n[0];
  l_inf = OrientLineAtInfinity(l_inf, m0);

  Eigen::Vector3d m1;
  if (geometry.m1_circle >= 0) {
    m1 = centers_n[geometry.m1_circle];
  } else if (geometry.roll_from_design) {
    // Any direction: the caller turns the pose about the circle's axis to the design
    // (roll_feature.h), and the depth comes from the radius.
    m1 = m0 + Eigen::Vector3d(0.01, 0.0, 0.0);
    depth = AnalyticDepth::kRadius;
  } else if (measurements.m1_px) {
    m1 = K_inv * measurements.m1_px->homogeneous();
  } else {
    return Fail(error, "the feature point m1 was not detected");
  }

  std::optional<AnalyticPose> pose = AnalyticPoseFromLine(l_inf, m0, m1, geometry.Lx);
  if (!pose) return Fail(error, "edge-on view: m0 and m1 coincide in the image");
  if (depth == AnalyticDepth::kRadius) {
    const Eigen::Matrix3d& R = pose->cam_from_paper.rotation;
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < conics_n.size(); ++i) {
      const double s =
          DepthFromRadius(conics_n[i], R.col(0), R.col(1), centers_n[i], geometry.radii_m[i]);
      t += s * centers_n[i] - geometry.centers[i].x() * R.col(0) -
           geometry.centers[i].y() * R.col(1);
    }
    t /= static_cast<double>(conics_n.size());
    if (!t.allFinite() || !(t.z() > 0.0)) return Fail(error, "no positive depth from the radii");
    pose->cam_from_paper.translation = t;
  }

  AnalyticSolution solution;
  solution.l_inf_norm = l_inf;
  solution.l_inf_px = OrientLineAtInfinity(K_inv.transpose() * l_inf, K * m0);
  for (const Eigen::Vector3d& m : centers_n) {
    solution.imaged_centers_px.push_back(Dehomogenized(K * m));
  }
  solution.m0_px = Dehomogenized(K * m0);
  solution.m1_px = Dehomogenized(K * m1);
  solution.pose = *pose;
  return solution;
}

}  // namespace

const char* ToString(AnalyticDepth depth) { return depth == AnalyticDepth::kLx ? "lx" : "radius"; }

std::optional<AnalyticSolution> SolveAnalytic(const CircleGeometry& geometry,
                                              const Eigen::Matrix3d& K,
                                              const CircleMeasurements& measurements,
                                              const AnalyticOptions& options,
                                              std::string* error) {
  if (measurements.conics_px.size() != geometry.centers.size()) {
    return Fail(error, "one conic per circle expected");
  }
  const std::vector<Eigen::Matrix3d> conics_n = NormalizedConics(K, measurements);
  std::optional<Eigen::Vector3d> l_inf =
      ProjectiveLineAtInfinity(geometry, K.inverse(), conics_n, measurements, error);
  if (!l_inf) return std::nullopt;
  if (options.k_normal) l_inf = KNormalLineAtInfinity(conics_n, *l_inf);
  return SolutionFromLine(geometry, K, conics_n, measurements, *l_inf, options.depth, error);
}

std::vector<AnalyticSolution> AnalyticCandidates(const CircleGeometry& geometry,
                                                 const Eigen::Matrix3d& K,
                                                 const CircleMeasurements& measurements,
                                                 AnalyticDepth depth) {
  std::vector<AnalyticSolution> candidates;
  if (measurements.conics_px.size() != geometry.centers.size()) return candidates;
  const std::vector<Eigen::Matrix3d> conics_n = NormalizedConics(K, measurements);
  std::vector<Eigen::Vector3d> lines;
  const std::optional<Eigen::Vector3d> projective =
      ProjectiveLineAtInfinity(geometry, K.inverse(), conics_n, measurements, nullptr);
  if (projective) {
    lines.push_back(*projective);
    lines.push_back(KNormalLineAtInfinity(conics_n, *projective));
  }
  for (const Eigen::Matrix3d& C : conics_n) {
    for (const Eigen::Vector3d& normal : SingleCircleNormals(C)) lines.push_back(normal);
  }
  for (const Eigen::Vector3d& l : lines) {
    std::optional<AnalyticSolution> s =
        SolutionFromLine(geometry, K, conics_n, measurements, l, depth, nullptr);
    if (s) candidates.push_back(std::move(*s));
  }
  return candidates;
}

}  // namespace markerbench
