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

}  // namespace

const char* ToString(AnalyticDepth depth) { return depth == AnalyticDepth::kLx ? "lx" : "radius"; }

std::optional<AnalyticSolution> SolveAnalytic(const CircleGeometry& geometry,
                                              const Eigen::Matrix3d& K,
                                              const CircleMeasurements& measurements,
                                              const AnalyticOptions& options,
                                              std::string* error) {
  const size_t n = geometry.centers.size();
  if (measurements.conics_px.size() != n) return Fail(error, "one conic per circle expected");
  std::vector<Eigen::Matrix3d> conics_n;
  for (const Eigen::Matrix3d& C : measurements.conics_px) {
    conics_n.push_back(CanonicalConic(K.transpose() * C * K));
  }
  const Eigen::Matrix3d K_inv = K.inverse();

  Eigen::Vector3d l_inf;
  switch (geometry.layout) {
    case CircleLayout::kTwoCircles: {
      const std::optional<Eigen::Vector3d> l =
          LineAtInfinityFromTwoCircles(conics_n[0], conics_n[1]);
      if (!l) return Fail(error, "no line in the pencil passes the quasi-affine test");
      l_inf = *l;
      break;
    }
    case CircleLayout::kConcentric: {
      const std::optional<ConcentricSolution> s =
          LineAtInfinityFromConcentric(conics_n[0], conics_n[1]);
      if (!s) return Fail(error, "the concentric pencil has no finite centre");
      l_inf = s->l_inf;
      break;
    }
    case CircleLayout::kCircleWithCenter:
      if (!measurements.m0_px) return Fail(error, "the centre point m0 was not detected");
      l_inf = LineAtInfinityFromCenter(conics_n[0], K_inv * measurements.m0_px->homogeneous());
      break;
  }
  if (options.k_normal) l_inf = KNormalLineAtInfinity(conics_n, l_inf);

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
  } else if (measurements.m1_px) {
    m1 = K_inv * measurements.m1_px->homogeneous();
  } else {
    return Fail(error, "the feature point m1 was not detected");
  }

  std::optional<AnalyticPose> pose = AnalyticPoseFromLine(l_inf, m0, m1, geometry.Lx);
  if (!pose) return Fail(error, "edge-on view: m0 and m1 coincide in the image");
  if (options.depth == AnalyticDepth::kRadius) {
    const Eigen::Matrix3d& R = pose->cam_from_paper.rotation;
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < n; ++i) {
      const double s =
          DepthFromRadius(conics_n[i], R.col(0), R.col(1), centers_n[i], geometry.radii_m[i]);
      t += s * centers_n[i] - geometry.centers[i].x() * R.col(0) -
           geometry.centers[i].y() * R.col(1);
    }
    t /= static_cast<double>(n);
    if (!t.allFinite() || !(t.z() > 0.0)) return Fail(error, "no positive depth from the radii");
    pose->cam_from_paper.translation = t;
  }

  AnalyticSolution solution;
  solution.l_inf_norm = l_inf;
  solution.l_inf_px = OrientLineAtInfinity(K_inv.transpose() * l_inf, K * m0);
  for (const Eigen::Vector3d& m : centers_n)
    solution.imaged_centers_px.push_back(Dehomogenized(K * m));
  solution.m0_px = Dehomogenized(K * m0);
  solution.m1_px = Dehomogenized(K * m1);
  solution.pose = *pose;
  return solution;
}

}  // namespace markerbench
