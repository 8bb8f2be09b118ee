#include "trackers/printed_appearance.h"

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace markerbench {
namespace {

// 5-point Gauss-Hermite rule for a standard normal variable: nodes and weights.
constexpr std::array<double, 5> kNodes = {-2.856970, -1.355626, 0.0, 1.355626, 2.856970};
constexpr std::array<double, 5> kWeights = {0.011257, 0.222076, 0.533333, 0.222076, 0.011257};
// The rule's farthest node from its centre, in σ (2.86 per axis, on the diagonal).
constexpr double kReachSigmas = 4.1;

// Smallest singular value of a 2x2 matrix.
double SmallestSingularValue(const Eigen::Matrix2d& m) {
  const double frobenius2 = m.squaredNorm();
  const double det = m.determinant();
  return std::sqrt(std::max(
      0.0,
      0.5 * (frobenius2 - std::sqrt(std::max(0.0, frobenius2 * frobenius2 - 4.0 * det * det)))));
}

// The printed colour around plane point `p` under an image Gaussian of `sigma_px`, through
// the local map plane_from_px (metres per pixel; min_scale: its inverse's smallest singular
// value). Where no edge is within the rule's reach, that is the colour at p.
Rgb BlurredColor(const MarkerSpec& marker,
                 const Eigen::Vector2d& p,
                 double min_scale,
                 const Eigen::Matrix2d& plane_from_px,
                 double sigma_px) {
  const PaintSample here = marker.ColorAt(p);
  if (here.clearance_m * min_scale > kReachSigmas * sigma_px) return *here.color;
  Rgb sum = Rgb::Zero();
  for (size_t i = 0; i < kNodes.size(); ++i) {
    for (size_t j = 0; j < kNodes.size(); ++j) {
      const Eigen::Vector2d offset_px = sigma_px * Eigen::Vector2d(kNodes[i], kNodes[j]);
      sum += kWeights[i] * kWeights[j] * *marker.ColorAt(p + plane_from_px * offset_px).color;
    }
  }
  return sum;
}

// A part's shared residual: the mean of its blocks' products of two means, each weighted by
// its samples (an estimate of the squared misfit over the part), and its standard error.
struct SharedResidual {
  double weight = 0.0, sum = 0.0;
  double sum_w2 = 0.0, sum_w2_product = 0.0, sum_w2_product2 = 0.0;  // weights squared
  void Add(double samples, double product) {
    weight += samples;
    sum += samples * product;
    const double w2 = samples * samples;
    sum_w2 += w2;
    sum_w2_product += w2 * product;
    sum_w2_product2 += w2 * product * product;
  }
  double Mean() const { return sum / weight; }
  // sqrt(Σ w² (product - mean)²) / Σ w.
  double StandardError() const {
    const double mean = Mean();
    return std::sqrt(std::max(
               0.0, sum_w2_product2 - 2.0 * mean * sum_w2_product + mean * mean * sum_w2)) /
           weight;
  }
};

// The fit on a grid x grid lattice.
AppearanceFit FitOnGrid(const Image8& image,
                        const Camera& camera,
                        const MarkerSpec& marker,
                        const Rigid3& cam_from_marker,
                        double blur_sigma_px,
                        const AppearanceOptions& options,
                        int grid) {
  Eigen::AlignedBox2d box = marker.InkBounds();
  const double grow = options.quiet_zone * box.sizes().minCoeff();
  box.extend(box.min() - Eigen::Vector2d::Constant(grow));
  box.extend(box.max() + Eigen::Vector2d::Constant(grow));
  // The lattice of grid + 1 points per side, projected once; samples sit on its points and
  // take the local affine map from their lattice neighbours.
  const int side = grid + 1;
  const Eigen::Vector2d spacing = box.sizes() / grid;
  auto lattice_point = [&](int i, int j) {
    return Eigen::Vector2d(box.min() + spacing.cwiseProduct(Eigen::Vector2d(i, j)));
  };
  std::vector<Eigen::Vector2d> lattice_px(static_cast<size_t>(side * side));
  std::vector<bool> in_front(lattice_px.size());
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const Eigen::Vector2d p = lattice_point(i, j);
      const Eigen::Vector3d x_cam = cam_from_marker * Eigen::Vector3d(p.x(), p.y(), 0.0);
      in_front[i * side + j] = x_cam.z() > 0.0;
      if (in_front[i * side + j]) lattice_px[i * side + j] = camera.ImgFromCam(x_cam);
    }
  }

  // Per sample and channel: printed (model) and measured values at the two pixels.
  struct Pair {
    double x[2];
    double y[2];
    int part;  // the top-most layer at the sample + 1; 0: the paper
    int i, j;  // the sample's lattice point
    int channel;
    bool in_blocks;  // in blocks of more than one: no pair in them read its pixels before
  };
  std::vector<Pair> pairs;
  pairs.reserve(static_cast<size_t>(grid * grid * image.channels));
  // Both pixels of a pair at px, (u, v) and (u + 2, v), in the image (compared before any
  // rounding, so that points far off it, or not finite, never reach an integer).
  auto pair_in_image = [&](const Eigen::Vector2d& px) {
    return px.x() > -0.5 && px.y() > -0.5 && px.x() < image.width - 2.5 &&
           px.y() < image.height - 0.5;
  };
  // Each lattice point's pair's first pixel, where both its pixels are in the image; and per
  // pixel of the rectangle the pairs read: read as a pair's first (bit 1), by a pair in blocks
  // (bit 2).
  std::vector<std::optional<Eigen::Vector2i>> first_pixel(lattice_px.size());
  Eigen::AlignedBox2i pixels_read;
  for (size_t k = 0; k < lattice_px.size(); ++k) {
    if (!in_front[k] || !pair_in_image(lattice_px[k])) continue;
    first_pixel[k] = Eigen::Vector2i(static_cast<int>(std::lround(lattice_px[k].x())),
                                     static_cast<int>(std::lround(lattice_px[k].y())));
    pixels_read.extend(*first_pixel[k]);
    pixels_read.extend(*first_pixel[k] + Eigen::Vector2i(2, 0));
  }
  const int read_width = pixels_read.isEmpty() ? 0 : pixels_read.sizes().x() + 1;
  constexpr uint8_t kReadFirst = 1, kReadInBlocks = 2;
  std::vector<uint8_t> read(
      pixels_read.isEmpty() ? 0 : static_cast<size_t>(read_width) * (pixels_read.sizes().y() + 1));
  AppearanceFit fit;
  fit.grid = grid;
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      const int here = i * side + j, right = here + side, up = here + 1;
      if (!first_pixel[here] || !in_front[right] || !in_front[up]) continue;
      const Eigen::Vector2d p = lattice_point(i, j);
      const Eigen::Vector2d& px = lattice_px[here];
      const int u = first_pixel[here]->x(), v = first_pixel[here]->y();
      // Where the lattice is finer than the pixels (a far marker), a pixel is read once as a
      // pair's first: the standard errors count independent readings. A pixel may be one
      // pair's second and another's first; the blocks (below) take only pairs whose pixels no
      // pair in blocks read before, so that no block's two means share a pixel's noise.
      uint8_t* first = &read[static_cast<size_t>(v - pixels_read.min().y()) * read_width + u -
                             pixels_read.min().x()];
      if (*first & kReadFirst) continue;
      *first |= kReadFirst;
      const bool in_blocks = !(first[0] & kReadInBlocks) && !(first[2] & kReadInBlocks);
      if (in_blocks) {
        first[0] |= kReadInBlocks;
        first[2] |= kReadInBlocks;
      }
      Eigen::Matrix2d px_from_plane;
      px_from_plane << (lattice_px[right] - px) / spacing.x(), (lattice_px[up] - px) / spacing.y();
      ++fit.samples;
      // Both pixels lie within 2.8 px of p: where no edge is within that and the rule's reach,
      // both see p's colour.
      const PaintSample at_p = marker.ColorAt(p);
      const double min_scale = SmallestSingularValue(px_from_plane);
      Rgb printed[2] = {*at_p.color, *at_p.color};
      if (!(at_p.clearance_m * min_scale > kReachSigmas * blur_sigma_px + 2.8)) {
        const Eigen::Matrix2d plane_from_px = px_from_plane.inverse();
        for (int k = 0; k < 2; ++k) {
          const Eigen::Vector2d pixel(u + 2 * k, v);
          printed[k] = BlurredColor(
              marker, p + plane_from_px * (pixel - px), min_scale, plane_from_px, blur_sigma_px);
        }
      }
      for (int c = 0; c < image.channels; ++c) {
        Pair pair;
        pair.part = at_p.layer + 1;
        pair.i = i;
        pair.j = j;
        pair.channel = c;
        pair.in_blocks = in_blocks;
        for (int k = 0; k < 2; ++k) {
          pair.x[k] = image.channels == 3 ? printed[k][c] : Luma(printed[k]);
          pair.y[k] = image.at(u + 2 * k, v, c) / 255.0;
        }
        pairs.push_back(pair);
      }
    }
  }
  // Least-squares line measured = offset + contrast * printed over every value.
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Pair& pair : pairs) {
    for (int k = 0; k < 2; ++k) {
      n += 1;
      sx += pair.x[k];
      sy += pair.y[k];
      sxx += pair.x[k] * pair.x[k];
      sxy += pair.x[k] * pair.y[k];
    }
  }
  const double var_x = sxx - sx * sx / n;
  fit.misfit = fit.misfit_upper = std::numeric_limits<double>::infinity();
  fit.surely_misfits = true;
  if (static_cast<int>(pairs.size()) < options.min_part_values || !(var_x > 1e-6 * n)) return fit;
  fit.contrast = (sxy - sx * sy / n) / var_x;
  const double offset = (sy - fit.contrast * sx) / n;
  if (!(fit.contrast > 0.0)) return fit;
  fit.surely_misfits = false;
  fit.misfit = 0.0;
  fit.misfit_upper = 0.0;
  // The shared residual per part of the design, and over all of it: a missing dot is a small
  // part of the whole, but the whole of its part.
  const int parts = static_cast<int>(marker.layers.size()) + 2;  // the last: everything
  std::vector<int> block_sides = {1};  // in lattice points; 1: each pair alone
  if (options.blocks_per_side > 0 && grid / options.blocks_per_side > 1) {
    block_sides.push_back(grid / options.blocks_per_side);
  }
  for (const int block : block_sides) {
    // The residuals' means over each block of block x block lattice points, per part and
    // channel, at the pairs' first and second pixels: a wrong design misfits alike over a
    // block, the noise averages out. Pairs come row by row, so blocks fill a row at a time.
    struct Means {
      double sum[2] = {0.0, 0.0};
      double count = 0.0;
    };
    const int blocks_per_row = (grid + block - 1) / block;
    std::vector<Means> row(static_cast<size_t>(blocks_per_row * parts * image.channels));
    std::vector<SharedResidual> shared(static_cast<size_t>(parts));
    auto add_row = [&]() {
      for (size_t e = 0; e < row.size(); ++e) {
        Means& m = row[e];
        if (m.count == 0.0) continue;
        shared[(e / image.channels) % parts].Add(m.count,
                                                 m.sum[0] * m.sum[1] / (m.count * m.count));
        m = Means();
      }
    };
    int row_of_blocks = 0;
    for (const Pair& pair : pairs) {
      if (block > 1 && !pair.in_blocks) continue;
      if (pair.i / block != row_of_blocks) {
        add_row();
        row_of_blocks = pair.i / block;
      }
      for (const int part : {pair.part, parts - 1}) {
        Means& m = row[(static_cast<size_t>(pair.j / block) * parts + part) * image.channels +
                       pair.channel];
        for (int k = 0; k < 2; ++k) m.sum[k] += pair.y[k] - offset - fit.contrast * pair.x[k];
        m.count += 1;
      }
    }
    add_row();
    for (const SharedResidual& part : shared) {
      if (part.weight < options.min_part_values) continue;
      const double mean = part.Mean();
      const double standard_error = part.StandardError();
      const double misfit = std::sqrt(std::max(0.0, mean)) / fit.contrast;
      const double significance = standard_error > 0.0 ? mean / standard_error : 0.0;
      if (block == 1) {  // a bound of the misfit; the blocks' bounds that of its smooth part
        const double upper =
            std::sqrt(std::max(0.0, mean + options.min_significance * standard_error)) /
            fit.contrast;
        fit.misfit_upper = std::max(fit.misfit_upper, upper);
      }
      const double max_misfit = block == 1 ? options.max_misfit : options.max_block_misfit;
      fit.surely_misfits |= misfit > max_misfit && significance > options.min_significance;
      // Report the part that misfits most surely.
      if (significance * misfit > fit.significance * fit.misfit) {
        fit.misfit = misfit;
        fit.significance = significance;
      }
    }
  }
  return fit;
}

}  // namespace

AppearanceFit CheckPrintedAppearance(const Image8& image,
                                     const Camera& camera,
                                     const MarkerSpec& marker,
                                     const Rigid3& cam_from_marker,
                                     double blur_sigma_px,
                                     const AppearanceOptions& options) {
  AppearanceFit fit = FitOnGrid(
      image, camera, marker, cam_from_marker, blur_sigma_px, options, options.coarse_grid);
  if (!(fit.misfit_upper <= options.max_misfit) && !fit.surely_misfits) {
    fit = FitOnGrid(image, camera, marker, cam_from_marker, blur_sigma_px, options, options.grid);
  }
  return fit;
}

}  // namespace markerbench
