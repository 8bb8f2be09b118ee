#include "trackers/runetag/ring_decoder.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <iterator>

#include "core/random.h"
#include "trackers/circle/analytic_pose.h"
#include "trackers/circle/conic.h"
#include "trackers/circle/conic_fit.h"
#include "trackers/circle/line_at_infinity.h"
#include "trackers/runetag/cyclic_code.h"

namespace markerbench {
namespace {

// The conic through five points (pixels), or nullopt when it is not a real ellipse.
std::optional<Eigen::Matrix3d> ConicThrough(const std::array<Eigen::Vector2d, 5>& points,
                                            const Eigen::Vector2d& origin,
                                            double scale) {
  Eigen::Matrix<double, 5, 6> A;
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector2d p = (points[i] - origin) / scale;
    A.row(i) << p.x() * p.x(), p.x() * p.y(), p.y() * p.y(), p.x(), p.y(), 1.0;
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, 5, 6>> lu(A);
  if (lu.rank() < 5) return std::nullopt;
  const Eigen::Matrix<double, 6, 1> c = lu.kernel().col(0);
  Eigen::Matrix3d C_n;
  C_n << c(0), c(1) / 2, c(3) / 2, c(1) / 2, c(2), c(4) / 2, c(3) / 2, c(4) / 2, c(5);
  Eigen::Matrix3d T;  // pixels -> the normalized frame of the fit
  T << 1 / scale, 0, -origin.x() / scale, 0, 1 / scale, -origin.y() / scale, 0, 0, 1;
  const Eigen::Matrix3d C = T.transpose() * C_n * T;
  if (!IsRealEllipse(C)) return std::nullopt;
  return CanonicalConic(C);
}

// Whether inlier sets a and b (sorted) share more than half of the smaller one.
bool Overlap(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> common;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
  return 2 * common.size() > std::min(a.size(), b.size());
}

// RANSAC for ring conics: the inlier sets (dot centres within tolerance) of the
// options.ring_candidates conics with the most inliers that do not overlap, most first. A
// conic through dots of two rings (an ellipse can cross both in a tilted view) may have more
// inliers than a true ring, so the caller tries each.
std::vector<std::vector<int>> RingCandidates(const std::vector<ImagedDot>& dots,
                                             uint64_t seed,
                                             const RingDecoderOptions& options) {
  const int n = static_cast<int>(dots.size());
  std::vector<std::vector<int>> candidates;
  if (n < options.min_ring_dots) return candidates;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  for (const ImagedDot& d : dots) origin += d.center_px / n;
  double scale = 0.0;
  for (const ImagedDot& d : dots) scale += (d.center_px - origin).norm() / n;
  if (!(scale > 0.0)) return candidates;

  Rng rng(seed);
  std::vector<int> inliers, similar;
  int iterations = options.max_ransac_iterations;
  for (int it = 0; it < iterations; ++it) {
    // A seed dot, then four of similar size (dots of one ring are alike) within reach: a
    // ring's diameter is 2 × kRuneDotRadiusRatio dot radii, with a margin for perspective.
    const int first = static_cast<int>(rng.NextU64() % static_cast<uint64_t>(n));
    const double reach = 2.5 * kRuneDotRadiusRatio * std::max(dots[first].semi_major_px, 1.0);
    similar.clear();
    for (int j = 0; j < n; ++j) {
      const double ratio = dots[j].area_px / dots[first].area_px;
      if (j != first && ratio > 0.5 && ratio < 2.0 &&
          (dots[j].center_px - dots[first].center_px).squaredNorm() < reach * reach) {
        similar.push_back(j);
      }
    }
    if (similar.size() < 4) continue;
    std::array<Eigen::Vector2d, 5> sample;
    sample[0] = dots[first].center_px;
    for (int k = 1; k < 5; ++k) {
      const size_t pick = k - 1 + rng.NextU64() % (similar.size() - (k - 1));
      std::swap(similar[k - 1], similar[pick]);
      sample[k] = dots[similar[k - 1]].center_px;
    }
    const std::optional<Eigen::Matrix3d> C = ConicThrough(sample, origin, scale);
    if (!C) continue;
    inliers.clear();
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector2d& p = dots[j].center_px;
      if (std::abs(PndResidual<double>(*C, p.x(), p.y())) < options.ring_tolerance_px) {
        inliers.push_back(j);
      }
    }
    if (static_cast<int>(inliers.size()) < options.min_ring_dots) continue;
    const auto same = std::find_if(
        candidates.begin(), candidates.end(), [&](const auto& c) { return Overlap(c, inliers); });
    if (same != candidates.end()) {
      if (same->size() >= inliers.size()) continue;
      candidates.erase(same);
    }
    candidates.insert(std::find_if(candidates.begin(),
                                   candidates.end(),
                                   [&](const auto& c) { return c.size() < inliers.size(); }),
                      inliers);
    if (static_cast<int>(candidates.size()) > options.ring_candidates) candidates.pop_back();
    // Adaptive stop at 99.9 % confidence with the best inlier ratio so far.
    const double w = static_cast<double>(candidates.front().size()) / n;
    const double needed = std::log(1e-3) / std::log(1.0 - std::pow(w, 4.0));
    iterations = std::min(options.max_ransac_iterations, static_cast<int>(needed) + 1);
  }
  return candidates;
}

// Plane coordinates of the dots in units of the ring's radius, for one of the two plane
// orientations a calibrated circle allows (§4.7) and a right-handed plane frame with z
// towards the camera (so a rotation, not a reflection, from the marker frame).
std::optional<std::vector<Eigen::Vector2d>> Rectify(const Eigen::Matrix3d& C_n,
                                                    const Eigen::Vector3d& normal,
                                                    const std::vector<Eigen::Vector3d>& rays) {
  const Eigen::Vector3d centre_guess = EllipseFromConic(C_n).center.homogeneous();
  const Eigen::Vector3d l_inf = OrientLineAtInfinity(normal, centre_guess);
  const std::optional<Eigen::Vector3d> m = ImagedCenter(C_n, l_inf);
  if (!m) return std::nullopt;
  const Eigen::Vector3d r3 = l_inf.normalized();
  const Eigen::Vector3d r1 = r3.unitOrthogonal();
  const Eigen::Vector3d r2 = r3.cross(r1);
  const double depth = DepthFromRadius(C_n, r1, r2, *m, 1.0);
  if (!(depth > 0.0)) return std::nullopt;
  const Eigen::Vector3d X_c = depth * *m;
  std::vector<Eigen::Vector2d> plane;
  for (const Eigen::Vector3d& v : rays) {
    const Eigen::Vector3d X = (r3.dot(X_c) / r3.dot(v)) * v - X_c;
    plane.emplace_back(r1.dot(X), r2.dot(X));
  }
  return plane;
}

// Sweeps the sectors for dots at plane coordinates `plane` (units of R) and decodes.
std::optional<RingMatch> SweepAndDecode(const std::vector<Eigen::Vector2d>& plane,
                                        const RingDecoderOptions& options) {
  std::vector<int> ring_of(plane.size(), -1);
  std::complex<double> phase_sum = 0.0;
  for (size_t i = 0; i < plane.size(); ++i) {
    const double radius = plane[i].norm();
    for (int j = 0; j < 3; ++j) {
      if (std::abs(radius - kRuneRingFractions[j]) < options.radius_tolerance) ring_of[i] = j;
    }
    if (ring_of[i] >= 0) {
      phase_sum += std::polar(1.0, kRuneSectors * std::atan2(plane[i].y(), plane[i].x()));
    }
  }
  if (std::abs(phase_sum) == 0.0) return std::nullopt;
  const double phase = std::arg(phase_sum) / kRuneSectors;
  RuneWord read{};
  std::vector<int> sector_of(plane.size(), -1);
  for (size_t i = 0; i < plane.size(); ++i) {
    if (ring_of[i] < 0) continue;
    const double position =
        (std::atan2(plane[i].y(), plane[i].x()) - phase) * kRuneSectors / (2.0 * M_PI);
    const double nearest = std::round(position);
    if (std::abs(position - nearest) > options.angle_tolerance) continue;
    const int sector = ((static_cast<int>(nearest) % kRuneSectors) + kRuneSectors) % kRuneSectors;
    sector_of[i] = sector;
    read[sector] |= static_cast<uint8_t>(4 >> ring_of[i]);
  }
  std::optional<RuneDecoded> decoded = RuneDecode(read);
  if (!decoded) decoded = RuneDecodeMissingDots(read);
  if (!decoded) return std::nullopt;
  RingMatch match;
  match.id = decoded->id;
  match.mismatches = decoded->mismatches;
  match.erasures = decoded->erasures;
  const RuneWord& codeword = RuneCodeword(decoded->id);
  for (size_t i = 0; i < plane.size(); ++i) {
    if (sector_of[i] < 0) continue;
    const int sector = (sector_of[i] + decoded->rotation) % kRuneSectors;
    if (codeword[sector] & (4 >> ring_of[i])) {
      match.dot_slots.emplace_back(static_cast<int>(i), 3 * sector + ring_of[i]);
    }
  }
  return match;
}

}  // namespace

std::optional<RingMatch> MatchRings(const std::vector<ImagedDot>& dots,
                                    const Camera& camera,
                                    uint64_t seed,
                                    const RingDecoderOptions& options) {
  const Eigen::Matrix3d K = camera.K();
  std::vector<Eigen::Vector3d> rays;
  for (const ImagedDot& d : dots) rays.push_back(camera.CamFromImg(d.center_px));
  ConicFitOptions fit_options;
  fit_options.refine_pnd = false;
  std::optional<RingMatch> best;
  for (const std::vector<int>& ring : RingCandidates(dots, seed, options)) {
    std::vector<Eigen::Vector2d> ring_px;
    for (int i : ring) ring_px.push_back(dots[i].center_px);
    const std::optional<ConicFit> fit = FitEllipse(ring_px, fit_options);
    if (!fit) continue;
    const Eigen::Matrix3d C_n = CanonicalConic(K.transpose() * fit->conic * K);
    for (const Eigen::Vector3d& normal : SingleCircleNormals(C_n)) {
      const std::optional<std::vector<Eigen::Vector2d>> unit_plane = Rectify(C_n, normal, rays);
      if (!unit_plane) continue;
      for (double found_ring : kRuneRingFractions) {
        std::vector<Eigen::Vector2d> plane = *unit_plane;
        for (Eigen::Vector2d& p : plane) p *= found_ring;
        std::optional<RingMatch> match = SweepAndDecode(plane, options);
        if (!match) continue;
        const int score = 2 * match->mismatches + match->erasures;
        if (!best || score < 2 * best->mismatches + best->erasures) {
          match->ring_dots = static_cast<int>(ring.size());
          best = match;
        }
      }
    }
  }
  return best;
}

}  // namespace markerbench
