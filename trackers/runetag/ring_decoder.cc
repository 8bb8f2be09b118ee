#include "trackers/runetag/ring_decoder.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <iterator>
#include <utility>

#include "core/codes/runetag_cyclic_code.h"
#include "core/random.h"
#include "trackers/bilinear_sample.h"
#include "trackers/circle/analytic_pose.h"
#include "trackers/circle/conic.h"
#include "trackers/circle/conic_fit.h"
#include "trackers/circle/line_at_infinity.h"
#include "trackers/upper_median.h"

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

// A dot's moment-ellipse area over π: steadier than its pixel count, which for a dot of
// radius 1.2 px ranges over 2-10 px^2 with its sub-pixel position.
double MomentArea(const ImagedDot& dot) { return dot.semi_major_px * dot.semi_minor_px; }

// Whether inlier sets a and b (sorted) share more than half of the smaller one.
bool Overlap(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> common;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
  return 2 * common.size() > std::min(a.size(), b.size());
}

// Dots sorted by y, for the scans of a band of rows: their index, centre and (where asked)
// moment area in arrays of their own.
struct DotsByY {
  std::vector<int> index;  // into the dots, by increasing y
  std::vector<double> x, y, area;

  void Add(const ImagedDot& dot, int i) {
    index.push_back(i);
    x.push_back(dot.center_px.x());
    y.push_back(dot.center_px.y());
  }
  void AddWithArea(const ImagedDot& dot, int i) {
    Add(dot, i);
    area.push_back(MomentArea(dot));
  }
  // The range of `index` with y in [low, high].
  std::pair<size_t, size_t> Band(double low, double high) const {
    return {static_cast<size_t>(std::lower_bound(y.begin(), y.end(), low) - y.begin()),
            static_cast<size_t>(std::upper_bound(y.begin(), y.end(), high) - y.begin())};
  }
};

// The dots `which` names, sorted by y, without their areas.
DotsByY SortByY(const std::vector<ImagedDot>& dots, std::vector<int> which) {
  std::sort(which.begin(), which.end(), [&](int a, int b) {
    return dots[a].center_px.y() < dots[b].center_px.y();
  });
  DotsByY sorted;
  for (int i : which) sorted.Add(dots[i], i);
  return sorted;
}

// Whether the k-th dot of `sorted` has another within `reach`: a scan visiting the dots
// outwards from it in y (below, above, in turn), so that a neighbour ends it soon and a lone
// dot's ends at the reach in y.
bool HasNeighbour(const DotsByY& sorted, size_t k, double reach) {
  const double x = sorted.x[k], y = sorted.y[k];
  auto near = [&](size_t m) {
    const double dx = sorted.x[m] - x, dy = sorted.y[m] - y;
    return dx * dx + dy * dy < reach * reach;
  };
  auto in_reach_y = [&](size_t m) { return std::abs(sorted.y[m] - y) < reach; };
  const size_t n = sorted.index.size();
  size_t below = k, above = k + 1;
  bool down = below > 0 && in_reach_y(below - 1), up = above < n && in_reach_y(above);
  while (down || up) {
    if (down && near(--below)) return true;
    if (up && near(above++)) return true;
    down = down && below > 0 && in_reach_y(below - 1);
    up = up && above < n && in_reach_y(above);
  }
  return false;
}

// Marks dot indices in a bitset, to read them back in increasing order without a sort.
class DotMarks {
 public:
  explicit DotMarks(int n) : words_((n + 63) / 64, 0) {}
  void Mark(int i) { words_[i >> 6] |= uint64_t{1} << (i & 63); }
  // The marked indices, in increasing order, into `out`; clears the marks.
  void TakeInOrder(std::vector<int>* out) {
    out->clear();
    for (size_t w = 0; w < words_.size(); ++w) {
      for (uint64_t bits = words_[w]; bits != 0; bits &= bits - 1) {
        out->push_back(static_cast<int>(64 * w) + __builtin_ctzll(bits));
      }
      words_[w] = 0;
    }
  }

 private:
  std::vector<uint64_t> words_;
};

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

  // Samples come from dots with a neighbour within options.neighbour_reach of their radii: a
  // marker's dots are 2π × kRuneDotRadiusRatio / 43 = 2.6 radii apart along a ring and 3-4.4
  // across rings, while noise blobs lie scattered.
  // Dots off the image plane have no neighbours and are no inliers (their PND is NaN).
  std::vector<int> placed;
  for (int i = 0; i < n; ++i) {
    if (dots[i].center_px.allFinite()) placed.push_back(i);
  }
  const DotsByY placed_by_y = SortByY(dots, std::move(placed));
  // The scans below visit a band of rows and read what they found back in dot order: the
  // same samples and inlier sets as scans of all dots, in a fraction of the time where
  // there are thousands (fuzzing found textures of 5000 dots).
  DotMarks marks(n);
  DotsByY pool_by_y;  // the placed dots with a neighbour, still by y, with their areas
  for (size_t k = 0; k < placed_by_y.index.size(); ++k) {
    const int i = placed_by_y.index[k];
    const double reach = options.neighbour_reach * std::max(dots[i].semi_major_px, 1.0);
    if (!HasNeighbour(placed_by_y, k, reach)) continue;
    marks.Mark(i);
    pool_by_y.AddWithArea(dots[i], i);
  }
  std::vector<int> pool;  // in dot order, which the samples are drawn in
  marks.TakeInOrder(&pool);
  if (static_cast<int>(pool.size()) < options.min_ring_dots) return candidates;
  Rng rng(seed);
  std::vector<int> inliers, similar;
  int iterations = options.max_ransac_iterations;
  for (int it = 0; it < iterations; ++it) {
    // A seed dot, then four of similar size (dots of one ring are alike) within reach: a
    // ring's diameter is 2 × kRuneDotRadiusRatio dot radii, with a margin for perspective.
    const int first = pool[rng.NextU64() % pool.size()];
    const double reach = 2.5 * kRuneDotRadiusRatio * std::max(dots[first].semi_major_px, 1.0);
    const Eigen::Vector2d& at = dots[first].center_px;
    const double first_area = MomentArea(dots[first]), band = 1.000001 * reach;
    const auto [near_low, near_high] = pool_by_y.Band(at.y() - band, at.y() + band);
    for (size_t k = near_low; k < near_high; ++k) {
      const double ratio = pool_by_y.area[k] / first_area;
      const double dx = pool_by_y.x[k] - at.x(), dy = pool_by_y.y[k] - at.y();
      if (ratio > 0.5 && ratio < 2.0 && dx * dx + dy * dy < reach * reach &&
          pool_by_y.index[k] != first) {
        marks.Mark(pool_by_y.index[k]);
      }
    }
    marks.TakeInOrder(&similar);
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
    const double tolerance = std::min(options.ring_tolerance_px,
                                      options.ring_tolerance_radii * dots[first].semi_major_px);
    const Ellipse ellipse = EllipseFromConic(*C);
    const double inlier_reach = PndReach(ellipse, tolerance);
    const auto [row_low, row_high] =
        placed_by_y.Band(ellipse.center.y() - inlier_reach, ellipse.center.y() + inlier_reach);
    for (size_t k = row_low; k < row_high; ++k) {
      const double x = placed_by_y.x[k], y = placed_by_y.y[k];
      if (std::abs(x - ellipse.center.x()) <= inlier_reach &&
          std::abs(PndResidual<double>(*C, x, y)) < tolerance) {
        marks.Mark(placed_by_y.index[k]);
      }
    }
    marks.TakeInOrder(&inliers);
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
    // Adaptive stop at 99.9 % confidence with the best inlier ratio so far (of the pool the
    // samples are drawn from; at most 1).
    const double w = std::min(
        1.0, static_cast<double>(candidates.front().size()) / static_cast<double>(pool.size()));
    // Capped before the cast: a tiny w needs more than an int holds (fuzzing found 8e10; the
    // cast's undefined result had ended the search there), and one whose fourth power rounds
    // 1 - w^4 to 1 needs infinitely many.
    const double miss = std::log(1.0 - std::pow(w, 4.0));
    const double needed = miss < 0.0 ? std::log(1e-3) / miss : INFINITY;
    iterations = static_cast<int>(
        std::min(std::floor(needed) + 1.0, static_cast<double>(options.max_ransac_iterations)));
  }
  return candidates;
}

// The plane of a ring, for one of the two orientations a calibrated circle allows (§4.7):
// a right-handed frame with r3 towards the camera (so a rotation, not a reflection, from the
// marker frame) and the ring's centre in the camera frame, in units of the ring's radius.
struct RingPlane {
  Eigen::Vector3d r1, r2, r3, centre;

  Eigen::Vector2d FromRay(const Eigen::Vector3d& ray) const {
    const Eigen::Vector3d X = (r3.dot(centre) / r3.dot(ray)) * ray - centre;
    return {r1.dot(X), r2.dot(X)};
  }
  Eigen::Vector3d ToCamera(const Eigen::Vector2d& xy) const {
    return centre + xy.x() * r1 + xy.y() * r2;
  }
};

std::optional<RingPlane> RingPlaneFor(const Eigen::Matrix3d& C_n, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d centre_guess = EllipseFromConic(C_n).center.homogeneous();
  const Eigen::Vector3d l_inf = OrientLineAtInfinity(normal, centre_guess);
  const std::optional<Eigen::Vector3d> m = ImagedCenter(C_n, l_inf);
  if (!m) return std::nullopt;
  RingPlane plane;
  plane.r3 = l_inf.normalized();
  plane.r1 = plane.r3.unitOrthogonal();
  plane.r2 = plane.r3.cross(plane.r1);
  const double depth = DepthFromRadius(C_n, plane.r1, plane.r2, *m, 1.0);
  if (!(depth > 0.0)) return std::nullopt;
  plane.centre = depth * *m;
  return plane;
}

// The symbols read from the dots at plane coordinates `plane` (units of R): each dot near a
// ring and a sector angle sets that slot's bit.
struct DotReading {
  RuneWord read{};
  double phase = 0.0;                   // plane angle of sector 0
  std::vector<int> ring_of, sector_of;  // per dot, -1 when on no slot
};

std::optional<DotReading> ReadDots(const std::vector<Eigen::Vector2d>& plane,
                                   const RingDecoderOptions& options) {
  DotReading reading;
  reading.ring_of.assign(plane.size(), -1);
  reading.sector_of.assign(plane.size(), -1);
  std::complex<double> phase_sum = 0.0;
  for (size_t i = 0; i < plane.size(); ++i) {
    const double radius = plane[i].norm();
    for (int j = 0; j < 3; ++j) {
      if (std::abs(radius - kRuneRingFractions[j]) < options.radius_tolerance) {
        reading.ring_of[i] = j;
      }
    }
    if (reading.ring_of[i] >= 0) {
      phase_sum += std::polar(1.0, kRuneSectors * std::atan2(plane[i].y(), plane[i].x()));
    }
  }
  if (std::abs(phase_sum) == 0.0) return std::nullopt;
  reading.phase = std::arg(phase_sum) / kRuneSectors;
  for (size_t i = 0; i < plane.size(); ++i) {
    if (reading.ring_of[i] < 0) continue;
    const double position =
        (std::atan2(plane[i].y(), plane[i].x()) - reading.phase) * kRuneSectors / (2.0 * M_PI);
    const double nearest = std::round(position);
    if (std::abs(position - nearest) > options.angle_tolerance) continue;
    const int sector = ((static_cast<int>(nearest) % kRuneSectors) + kRuneSectors) % kRuneSectors;
    reading.sector_of[i] = sector;
    reading.read[sector] |= static_cast<uint8_t>(4 >> reading.ring_of[i]);
  }
  return reading;
}

// Sweeps the slots (baselines.md, step 3): the symbols read from the image's grey level at
// every slot centre, projected through the ring's plane (whose unit is scale × R),
// against the paper inside and outside the rings and the ring's own dark level. A sector is
// erased when one of its slots is outside the image, too near the threshold or on a ring
// without contrast. This reads dots too small or too close to be told apart as blobs.
RuneWord ReadSlots(const DotImage& image,
                   const Camera& camera,
                   const RingPlane& plane,
                   double scale,
                   double phase,
                   const RingDecoderOptions& options) {
  const cv::Mat& grey = image.smoothed;
  const auto sample = [&](double radius, double angle) -> std::optional<double> {
    const Eigen::Vector2d xy = radius / scale * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d px = camera.ImgFromCam(plane.ToCamera(xy));
    if (!(px.x() >= 1.0 && px.y() >= 1.0 && px.x() <= grey.cols - 2.0 &&
          px.y() <= grey.rows - 2.0)) {
      return std::nullopt;
    }
    return BilinearSample(grey.data, grey.cols, grey.rows, px);
  };
  const double sector_angle = 2.0 * M_PI / kRuneSectors;
  std::vector<double> paper;
  for (int s = 0; s < kRuneSectors; ++s) {
    for (double radius : options.paper_radii) {
      if (const std::optional<double> v = sample(radius, phase + (s + 0.5) * sector_angle)) {
        paper.push_back(*v);
      }
    }
  }
  RuneWord read{};
  if (paper.empty()) return read;
  const double paper_level = UpperMedian(paper);
  std::array<uint8_t, kRuneSectors> known{};  // bit r: ring r's slot was read
  for (int r = 0; r < 3; ++r) {
    std::array<std::optional<double>, kRuneSectors> level;
    std::vector<double> seen;
    for (int s = 0; s < kRuneSectors; ++s) {
      level[s] = sample(kRuneRingFractions[r], phase + s * sector_angle);
      if (level[s]) seen.push_back(*level[s]);
    }
    if (seen.size() < 4) continue;
    // Every ring of a codeword is at least a quarter dots.
    std::nth_element(seen.begin(), seen.begin() + seen.size() / 4, seen.end());
    const double dark = seen[seen.size() / 4];
    const double contrast = paper_level - dark;
    if (contrast <
        std::max(options.min_slot_contrast, options.slot_contrast_per_noise * image.noise)) {
      continue;
    }
    for (int s = 0; s < kRuneSectors; ++s) {
      if (!level[s]) continue;
      const double t = (*level[s] - dark) / contrast;  // 0 dot, 1 paper
      if (std::abs(t - 0.5) < options.slot_margin) continue;
      known[s] |= static_cast<uint8_t>(4 >> r);
      if (t < 0.5) read[s] |= static_cast<uint8_t>(4 >> r);
    }
  }
  for (int s = 0; s < kRuneSectors; ++s) {
    if (known[s] != 7) read[s] = 0;
  }
  return read;
}

// How far a read is from its codeword: a mismatch costs what two erasures do (RuneDecode).
int Cost(int mismatches, int erasures) { return 2 * mismatches + erasures; }

// The better of the decodings of the dots and of the swept slots (when read), or nullopt.
std::optional<RuneDecoded> DecodeReadings(const RuneWord& dots,
                                          const std::optional<RuneWord>& slots,
                                          int expected_id,
                                          const RingDecoderOptions& options) {
  std::optional<RuneDecoded> from_dots = RuneDecode(dots);
  if (!from_dots && options.decode_missing_dots) {
    from_dots = RuneDecodeMissingDots(dots, expected_id);
  }
  const std::optional<RuneDecoded> from_slots = slots ? RuneDecode(*slots) : std::nullopt;
  if (!from_dots) return from_slots;
  if (!from_slots) return from_dots;
  return Cost(from_slots->mismatches, from_slots->erasures) <
                 Cost(from_dots->mismatches, from_dots->erasures)
             ? from_slots
             : from_dots;
}

}  // namespace

std::optional<RingMatch> MatchRings(const std::vector<ImagedDot>& dots,
                                    const DotImage& image,
                                    const Camera& camera,
                                    uint64_t seed,
                                    int expected_id,
                                    const RingDecoderOptions& options) {
  const Eigen::Matrix3d K = camera.K();
  // The dots' rays, and where the pinhole would image them, as K^T C K below takes a ring's
  // ellipse (without distortion, their pixels).
  Camera reading = camera;
  if (!options.undistort_dots) reading.distortion = {};
  std::vector<Eigen::Vector3d> rays;
  std::vector<Eigen::Vector2d> pinhole_px;
  for (const ImagedDot& d : dots) {
    rays.push_back(reading.CamFromImg(d.center_px));
    pinhole_px.push_back(reading.HasDistortion() ? reading.IdealFromCam(rays.back()) : d.center_px);
  }
  ConicFitOptions fit_options;
  fit_options.refine_pnd = false;
  std::optional<RingMatch> best;
  for (const std::vector<int>& ring : RingCandidates(dots, seed, options)) {
    std::vector<Eigen::Vector2d> ring_px;
    for (int i : ring) ring_px.push_back(pinhole_px[i]);
    const std::optional<ConicFit> fit = FitEllipse(ring_px, fit_options);
    if (!fit) continue;
    const Eigen::Matrix3d C_n = CanonicalConic(K.transpose() * fit->conic * K);
    for (const Eigen::Vector3d& normal : SingleCircleNormals(C_n)) {
      const std::optional<RingPlane> ring_plane = RingPlaneFor(C_n, normal);
      if (!ring_plane) continue;
      for (double found_ring : kRuneRingFractions) {
        std::vector<Eigen::Vector2d> plane;
        for (const Eigen::Vector3d& ray : rays) {
          plane.push_back(found_ring * ring_plane->FromRay(ray));
        }
        const std::optional<DotReading> reading = ReadDots(plane, options);
        if (!reading) continue;
        const std::optional<RuneDecoded> decoded = DecodeReadings(
            reading->read,
            options.read_slot_levels
                ? std::optional(
                      ReadSlots(image, camera, *ring_plane, found_ring, reading->phase, options))
                : std::nullopt,
            expected_id,
            options);
        if (!decoded) continue;
        const int cost = Cost(decoded->mismatches, decoded->erasures);
        if (best && cost >= Cost(best->mismatches, best->erasures)) continue;
        RingMatch match;
        match.id = decoded->id;
        match.mismatches = decoded->mismatches;
        match.erasures = decoded->erasures;
        match.ring_dots = static_cast<int>(ring.size());
        const RuneWord& codeword = RuneCodeword(decoded->id);
        // Whether ring r of the codeword's sector was read otherwise (a dot lost or added).
        const auto read_wrong = [&](int sector, int r) {
          const int read_sector = (sector - decoded->rotation + kRuneSectors) % kRuneSectors;
          return ((reading->read[read_sector] ^ codeword[sector]) & (4 >> r)) != 0;
        };
        for (size_t i = 0; i < plane.size(); ++i) {
          if (reading->sector_of[i] < 0) continue;
          const int sector = (reading->sector_of[i] + decoded->rotation) % kRuneSectors;
          const int r = reading->ring_of[i];
          // The imaged dot's semi-major axis, f × radius / depth (plane units are the found
          // ring's radius); a blob much larger is dots merged, centred between them.
          const double dot_radius = kRuneRingFractions[r] / kRuneDotRadiusRatio / found_ring;
          const double semi_major_px =
              K(0, 0) * dot_radius / ring_plane->ToCamera(plane[i] / found_ring).z();
          const bool grown = options.max_dot_growth > 0.0 &&
                             dots[i].semi_major_px > options.max_dot_growth * semi_major_px;
          const bool next_to_error = options.exclude_next_to_errors &&
                                     (read_wrong((sector + 1) % kRuneSectors, r) ||
                                      read_wrong((sector + kRuneSectors - 1) % kRuneSectors, r));
          if ((codeword[sector] & (4 >> r)) && !grown && !next_to_error) {
            match.dot_slots.emplace_back(static_cast<int>(i), 3 * sector + r);
          }
        }
        best = std::move(match);
        if (cost == 0) return best;  // no later hypothesis can cost less
      }
    }
  }
  return best;
}

}  // namespace markerbench
