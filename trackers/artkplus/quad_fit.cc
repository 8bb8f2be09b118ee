#include "trackers/artkplus/quad_fit.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace markerbench {
namespace {

// Squared distance of contour[k] from the chord contour[a] -> contour[b] (indices mod n).
double ChordDistanceSq(const std::vector<Eigen::Vector2i>& contour, size_t a, size_t b, size_t k) {
  const size_t n = contour.size();
  const Eigen::Vector2d p = contour[a % n].cast<double>();
  const Eigen::Vector2d chord = contour[b % n].cast<double>() - p;
  const Eigen::Vector2d to_k = contour[k % n].cast<double>() - p;
  const double cross = chord.x() * to_k.y() - chord.y() * to_k.x();
  const double length_sq = chord.squaredNorm();
  return length_sq > 0.0 ? cross * cross / length_sq : to_k.squaredNorm();
}

// Douglas-Peucker split of the contour between indices a < b (mod n): appends, in order, the
// vertices strictly between them. Stops once more than 5 vertices are known
// (a quadrilateral gives at most one spurious vertex, see FindQuadVertices).
void SplitAtVertices(const std::vector<Eigen::Vector2i>& contour,
                     size_t a,
                     size_t b,
                     double threshold_sq,
                     std::vector<size_t>* vertices) {
  if (b <= a + 1 || vertices->size() > 5) return;
  size_t farthest = a + 1;
  double best = -1.0;
  for (size_t k = a + 1; k < b; ++k) {
    const double d = ChordDistanceSq(contour, a, b, k);
    if (d > best) best = d, farthest = k;
  }
  if (best <= threshold_sq) return;
  SplitAtVertices(contour, a, farthest, threshold_sq, vertices);
  vertices->push_back(farthest);
  SplitAtVertices(contour, farthest, b, threshold_sq, vertices);
}

struct Line {
  Eigen::Vector2d normal;  // unit
  double offset = 0.0;     // normal . x = offset
};

// Total least squares (PCA) line through points.
std::optional<Line> FitLine(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 2) return std::nullopt;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : points) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  const Eigen::Vector2d normal = eig.eigenvectors().col(0);  // least spread
  return Line{normal, normal.dot(mean)};
}

}  // namespace

std::optional<std::array<size_t, 4>> FindQuadVertices(const std::vector<Eigen::Vector2i>& contour,
                                                      const DarkRegion& region,
                                                      const QuadFitOptions& options) {
  const size_t n = contour.size();
  if (n < 8) return std::nullopt;
  // The farthest point from any contour point is a vertex of a convex quadrilateral; so is
  // the farthest point from that one.
  const auto farthest_from = [&](size_t from) {
    size_t best = from;
    int best_d = -1;
    for (size_t k = 0; k < n; ++k) {
      const int d = (contour[k] - contour[from]).squaredNorm();
      if (d > best_d) best_d = d, best = k;
    }
    return best;
  };
  const size_t v0 = farthest_from(0);
  const size_t v2 = v0 + (farthest_from(v0) + n - v0) % n;
  const double threshold_sq = options.vertex_area_fraction * region.area_px;
  std::vector<size_t> vertices = {v0};
  SplitAtVertices(contour, v0, v2, threshold_sq, &vertices);
  vertices.push_back(v2);
  SplitAtVertices(contour, v2, v0 + n, threshold_sq, &vertices);
  // When v0 and v2 are adjacent, the split of the side v0-v2 picks an arbitrary point of the
  // opposite (image-parallel) side; drop vertices that lie on the chord of their neighbours.
  for (size_t i = 0; i < vertices.size() && vertices.size() > 4;) {
    const size_t m = vertices.size();
    if (ChordDistanceSq(contour, vertices[(i + m - 1) % m], vertices[(i + 1) % m], vertices[i]) <=
        threshold_sq) {
      vertices.erase(vertices.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
      ++i;
    }
  }
  if (vertices.size() != 4) return std::nullopt;
  return std::array<size_t, 4>{vertices[0], vertices[1], vertices[2], vertices[3]};
}

std::optional<std::array<Eigen::Vector2d, 4>> FitQuadCorners(
    const std::vector<Eigen::Vector2i>& contour,
    const std::array<size_t, 4>& vertices,
    const uint8_t* grey,
    double edge_level,
    const DarkRegions& regions,
    const Camera& camera,
    const QuadFitOptions& options) {
  const size_t n = contour.size();
  const bool distorted = camera.HasDistortion();
  const auto ideal = [&](const Eigen::Vector2d& px) -> Eigen::Vector2d {
    return distorted ? camera.IdealFromImg(px) : px;
  };
  const auto inside_image = [&](const Eigen::Vector2i& p) {
    return p.x() >= 0 && p.y() >= 0 && p.x() < regions.width && p.y() < regions.height;
  };
  const auto level = [&](const Eigen::Vector2i& p) {
    return static_cast<double>(grey[static_cast<size_t>(p.y() * regions.width + p.x())]);
  };

  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (size_t v : vertices) centroid += ideal(contour[v % n].cast<double>()) / 4.0;

  std::array<Line, 4> lines;
  for (size_t s = 0; s < 4; ++s) {
    const size_t a = vertices[s];
    const size_t b = s == 3 ? vertices[0] + n : vertices[s + 1];
    const size_t trim = static_cast<size_t>(std::lround(options.side_trim * (b - a)));
    std::vector<Eigen::Vector2d> points;
    for (size_t k = a + trim; k + trim <= b; ++k)
      points.push_back(ideal(contour[k % n].cast<double>()));
    std::optional<Line> line = FitLine(points);
    if (!line) return std::nullopt;
    if (line->normal.dot(centroid) > line->offset) line->normal *= -1.0, line->offset *= -1.0;
    if (options.subpixel_edges) {
      // Crossings of edge_level on each boundary pixel's outward 4-neighbour steps: the one
      // nearest the pixel within kReach steps either way.
      constexpr int kReach = 2;
      points.clear();
      const Eigen::Vector2i steps[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (size_t k = a + trim; k + trim <= b; ++k) {
        const Eigen::Vector2i p = contour[k % n];
        for (const Eigen::Vector2i& step : steps) {
          if (line->normal.dot(step.cast<double>()) <= 0.0) continue;
          std::optional<Eigen::Vector2d> crossing;
          for (int j = 0; j <= kReach && !crossing; ++j) {
            for (int j0 : {-j, j}) {
              const Eigen::Vector2i a0 = p + j0 * step, a1 = a0 + step;
              if (crossing || !inside_image(a0) || !inside_image(a1)) continue;
              if (level(a0) < edge_level && level(a1) >= edge_level) {
                const double f = (edge_level - level(a0)) / (level(a1) - level(a0));
                crossing = a0.cast<double>() + f * step.cast<double>();
              }
            }
          }
          if (crossing) points.push_back(ideal(*crossing));
        }
      }
      const std::optional<Line> refined = FitLine(points);
      if (!refined) return std::nullopt;
      line = refined;
    }
    lines[s] = *line;
  }

  std::array<Eigen::Vector2d, 4> corners;
  for (size_t s = 0; s < 4; ++s) {
    // Corner s joins side s-1 (ending at vertex s) and side s (starting there).
    const Line& before = lines[(s + 3) % 4];
    const Line& after = lines[s];
    const Eigen::Vector3d l0(before.normal.x(), before.normal.y(), -before.offset);
    const Eigen::Vector3d l1(after.normal.x(), after.normal.y(), -after.offset);
    const Eigen::Vector3d x = l0.cross(l1);
    if (!(std::abs(x.z()) > 1e-12)) return std::nullopt;
    const Eigen::Vector2d corner = x.hnormalized();
    corners[s] = distorted ? camera.ImgFromIdeal(corner) : corner;
  }
  return corners;
}

}  // namespace markerbench
