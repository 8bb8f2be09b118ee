#include "trackers/printed_appearance.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

#include "trackers/pixel_area_blur.h"

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

// The design's colours: the paper's and each layer's.
std::vector<Rgb> DesignColors(const MarkerSpec& marker) {
  std::vector<Rgb> colors = {marker.background};
  for (const PaintedShape& layer : marker.layers) colors.push_back(layer.color);
  return colors;
}

// The lumas of the design's darkest and lightest colours.
Eigen::Vector2d LumaRange(const MarkerSpec& marker) {
  Eigen::Vector2d range(std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity());
  for (const Rgb& color : DesignColors(marker)) {
    range = Eigen::Vector2d(std::min(range.x(), Luma(color)), std::max(range.y(), Luma(color)));
  }
  return range;
}

// A printed colour as a pixel sees it, and the share of it each fitted colour covers.
struct PrintedColor {
  Rgb color = Rgb::Zero();
  std::array<double, kMaxFittedLevels> shares = {};
};

// The colour at one point, all of it from a fitted colour if it is one.
PrintedColor SharpColor(const std::vector<Rgb>& fitted, const Rgb& color) {
  PrintedColor out{color, {}};
  const auto found = std::find(fitted.begin(), fitted.end(), color);
  if (found != fitted.end()) out.shares[found - fitted.begin()] = 1.0;
  return out;
}

// The printed colour around plane point `p` under an image Gaussian of `sigma_px`, through
// the local map plane_from_px (metres per pixel; min_scale: its inverse's smallest singular
// value). Where no edge is within the rule's reach, that is the colour at p.
PrintedColor BlurredColor(const MarkerSpec& marker,
                          const std::vector<Rgb>& fitted,
                          const Eigen::Vector2d& p,
                          double min_scale,
                          const Eigen::Matrix2d& plane_from_px,
                          double sigma_px) {
  const PaintSample here = marker.ColorAt(p);
  if (here.clearance_m * min_scale > kReachSigmas * sigma_px) {
    return SharpColor(fitted, *here.color);
  }
  PrintedColor sum;
  for (size_t i = 0; i < kNodes.size(); ++i) {
    for (size_t j = 0; j < kNodes.size(); ++j) {
      const Eigen::Vector2d offset_px = sigma_px * Eigen::Vector2d(kNodes[i], kNodes[j]);
      const PrintedColor node =
          SharpColor(fitted, *marker.ColorAt(p + plane_from_px * offset_px).color);
      const double weight = kWeights[i] * kWeights[j];
      sum.color += weight * node.color;
      for (int k = 0; k < kMaxFittedLevels; ++k) sum.shares[k] += weight * node.shares[k];
    }
  }
  return sum;
}

// The design blurred as the image is, over a box of pixels (AppearanceOptions::design_image):
// each pixel's colour the mean of its 2x2 points' (its area), blurred by the rest of σ,
// √(σ² - 1/12), as the renderer blurs. The rule above puts a blurred edge on a staircase of its
// nodes' weights instead (up to a quarter of the contrast off beside the centre node). On
// circle_d's frames of the paper sweep at σ 7-10, a dense 33x33 rule found the same successes
// within one frame per σ; the image adds about 7.5 ms a frame there, the dense rule eight times
// that.
class BlurredDesignImage {
 public:
  // The most pixels it takes, margins included (a marker filling a 640x480 frame at σ 10 takes
  // about 0.4 M); beyond, the rule (a bound on the time of a blur estimated wildly).
  static constexpr double kMaxPixels = 4e6;
  static bool Fits(const Eigen::AlignedBox2i& read, double blur_sigma_px) {
    const Eigen::Array2d sides =
        read.sizes().cast<double>().array() + 2.0 * std::ceil(4.0 * blur_sigma_px) + 1.0;
    return sides.prod() <= kMaxPixels;
  }

  // Over the pixels in `read` (a box of the image's pixel grid, which may leave the image).
  BlurredDesignImage(const Camera& camera,
                     const MarkerSpec& marker,
                     const Rigid3& cam_from_marker,
                     const std::vector<Rgb>& fitted,
                     const Eigen::AlignedBox2i& read,
                     double blur_sigma_px)
      : shares_(fitted.size()) {
    const int reach = static_cast<int>(std::ceil(4.0 * blur_sigma_px));
    origin_ = read.min() - Eigen::Vector2i::Constant(reach);
    const Eigen::Vector2i size = read.sizes() + Eigen::Vector2i::Constant(2 * reach + 1);
    planes_.resize(3 + shares_);
    for (cv::Mat& plane : planes_) plane = cv::Mat::zeros(size.y(), size.x(), CV_64F);
    // A pixel's ray meets the plane at X = λ Rᵀ ray - Rᵀ t, z = 0.
    const Eigen::Matrix3d marker_from_cam = cam_from_marker.rotation.transpose();
    const Eigen::Vector3d camera_in_marker = CameraCenterInMarker(cam_from_marker);
    for (int y = 0; y < size.y(); ++y) {
      for (int x = 0; x < size.x(); ++x) {
        for (const double dy : {-0.25, 0.25}) {
          for (const double dx : {-0.25, 0.25}) {
            const Eigen::Vector2d px =
                (origin_ + Eigen::Vector2i(x, y)).cast<double>() + Eigen::Vector2d(dx, dy);
            const Eigen::Vector3d ray = marker_from_cam * camera.CamFromImg(px);
            const double depth = -camera_in_marker.z() / ray.z();
            const Rgb& color =
                depth > 0.0 ? *marker.ColorAt((camera_in_marker + depth * ray).head<2>()).color
                            : marker.background;
            const PrintedColor point = SharpColor(fitted, color);
            for (int c = 0; c < 3; ++c) planes_[c].at<double>(y, x) += 0.25 * point.color[c];
            for (size_t k = 0; k < shares_; ++k) {
              planes_[3 + k].at<double>(y, x) += 0.25 * point.shares[k];
            }
          }
        }
      }
    }
    const double rest_sigma = BlurSigmaOfEdges(blur_sigma_px);
    for (cv::Mat& plane : planes_) {
      cv::GaussianBlur(plane,
                       plane,
                       cv::Size(2 * reach + 1, 2 * reach + 1),
                       rest_sigma,
                       rest_sigma,
                       cv::BORDER_REPLICATE);
    }
  }

  // The printed colour at pixel (u, v) of the box.
  PrintedColor At(int u, int v) const {
    const int x = u - origin_.x(), y = v - origin_.y();
    PrintedColor out;
    for (int c = 0; c < 3; ++c) out.color[c] = planes_[c].at<double>(y, x);
    for (size_t k = 0; k < shares_; ++k) out.shares[k] = planes_[3 + k].at<double>(y, x);
    return out;
  }

 private:
  size_t shares_;
  Eigen::Vector2i origin_;
  std::vector<cv::Mat> planes_;  // the colour's channels, then each fitted colour's share
};

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

// A sample's printed (model) and measured values at its two pixels, in one channel.
struct Pair {
  double x[2];
  double y[2];
  std::array<double, kMaxFittedLevels> shares[2];  // of the fitted colours
  int part;  // the top-most layer at the sample + 1; 0: the paper
  int i, j;  // the sample's lattice point
  int channel;
  bool in_blocks;  // in blocks of more than one: no pair in them read its pixels before
};

// measured = offset + contrast * (printed + Σ shift_k share_k): each fitted colour's level
// moved by its shift.
struct Line {
  double offset = 0.0;
  double contrast = 0.0;
  std::array<double, kMaxFittedLevels> shifts = {};
  double Moved(double printed, const std::array<double, kMaxFittedLevels>& shares) const {
    for (int k = 0; k < kMaxFittedLevels; ++k) printed += shifts[k] * shares[k];
    return printed;
  }
  double Residual(double measured,
                  double printed,
                  const std::array<double, kMaxFittedLevels>& shares) const {
    return measured - offset - contrast * Moved(printed, shares);
  }
};

// Least squares over every value, linear in (offset, contrast, contrast · shift_k). A shift
// out of its range (the fitted colours' `shift_ranges`) is held at the bound it passed and the
// rest fitted again. nullopt where the values cannot fix the line.
std::optional<Line> FitLine(const std::vector<Pair>& pairs,
                            const std::vector<Eigen::Vector2d>& shift_ranges) {
  const int fitted = static_cast<int>(shift_ranges.size());
  std::array<bool, kMaxFittedLevels> held = {};
  Line line;
  for (int round = 0; round <= fitted; ++round) {
    // Summed over the offset, the contrast and the fitted colours' shifts alone (the other rows
    // and columns stay zero), in the lower triangle, mirrored after.
    const int parameters = 2 + fitted;
    Eigen::Matrix4d JtJ = Eigen::Matrix4d::Zero();
    Eigen::Vector4d Jty = Eigen::Vector4d::Zero();
    for (const Pair& pair : pairs) {
      for (int k = 0; k < 2; ++k) {
        Eigen::Vector4d J(1.0, line.Moved(pair.x[k], pair.shares[k]), 0.0, 0.0);
        for (int c = 0; c < fitted; ++c) {
          if (!held[c]) J(2 + c) = pair.shares[k][c];
        }
        for (int a = 0; a < parameters; ++a) {
          for (int b = 0; b <= a; ++b) JtJ(a, b) += J(a) * J(b);
          Jty(a) += J(a) * pair.y[k];
        }
      }
    }
    JtJ.triangularView<Eigen::StrictlyUpper>() = JtJ.transpose();
    for (int p = 2; p < 4; ++p) {  // colours held, unseen or not there
      if (JtJ(p, p) == 0.0) JtJ(p, p) = 1.0;
    }
    const Eigen::Vector4d theta = JtJ.ldlt().solve(Jty);
    if (!theta.allFinite()) return std::nullopt;
    line.offset = theta(0);
    line.contrast = theta(1);
    if (!(line.contrast > 0.0)) return line;
    bool moved_out = false;
    for (int c = 0; c < fitted; ++c) {
      if (held[c]) continue;
      const double shift = line.shifts[c] + theta(2 + c) / line.contrast;
      const double in_range = std::clamp(shift, shift_ranges[c](0), shift_ranges[c](1));
      held[c] = in_range != shift;
      moved_out |= held[c];
      line.shifts[c] = in_range;
    }
    if (!moved_out) return line;
  }
  return line;
}

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

  const std::vector<Rgb> fitted = FittedColors(marker);
  // Per sample and channel: printed (model) and measured values at the two pixels.
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
  std::optional<BlurredDesignImage> blurred_design;
  if (options.design_image && blur_sigma_px >= kDesignImageMinBlurPx && !pixels_read.isEmpty() &&
      BlurredDesignImage::Fits(pixels_read, blur_sigma_px)) {
    blurred_design.emplace(camera, marker, cam_from_marker, fitted, pixels_read, blur_sigma_px);
  }
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
      PrintedColor printed[2] = {SharpColor(fitted, *at_p.color), SharpColor(fitted, *at_p.color)};
      if (!(at_p.clearance_m * min_scale > kReachSigmas * blur_sigma_px + 2.8)) {
        const Eigen::Matrix2d plane_from_px = px_from_plane.inverse();
        for (int k = 0; k < 2; ++k) {
          if (blurred_design) {
            printed[k] = blurred_design->At(u + 2 * k, v);
            continue;
          }
          const Eigen::Vector2d pixel(u + 2 * k, v);
          printed[k] = BlurredColor(marker,
                                    fitted,
                                    p + plane_from_px * (pixel - px),
                                    min_scale,
                                    plane_from_px,
                                    blur_sigma_px);
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
          pair.x[k] = image.channels == 3 ? printed[k].color[c] : Luma(printed[k].color);
          pair.y[k] = image.at(u + 2 * k, v, c) / 255.0;
          pair.shares[k] = printed[k].shares;
        }
        pairs.push_back(pair);
      }
    }
  }
  double n = 0, sx = 0, sxx = 0;
  for (const Pair& pair : pairs) {
    for (int k = 0; k < 2; ++k) {
      n += 1;
      sx += pair.x[k];
      sxx += pair.x[k] * pair.x[k];
    }
  }
  fit.misfit = fit.misfit_upper = std::numeric_limits<double>::infinity();
  fit.surely_misfits = true;
  if (static_cast<int>(pairs.size()) < options.min_part_values || !(sxx - sx * sx / n > 1e-6 * n)) {
    return fit;
  }
  // Each fitted colour's level kept within [kMinIntermediateLevel, kMaxIntermediateLevel].
  const Eigen::Vector2d lumas = LumaRange(marker);
  const double luma_range = lumas.y() - lumas.x();
  std::vector<double> printed_levels;
  std::vector<Eigen::Vector2d> shift_ranges;
  for (const Rgb& color : fitted) {
    printed_levels.push_back(PrintedLevel(marker, color));
    shift_ranges.push_back(luma_range *
                           (Eigen::Vector2d(kMinIntermediateLevel, kMaxIntermediateLevel) -
                            Eigen::Vector2d::Constant(printed_levels.back())));
  }
  const std::optional<Line> line = FitLine(pairs, shift_ranges);
  if (!line) return fit;
  fit.contrast = line->contrast;
  if (!(fit.contrast > 0.0)) return fit;
  for (size_t c = 0; c < fitted.size(); ++c) {
    fit.intermediate_levels.push_back(printed_levels[c] + line->shifts[c] / luma_range);
  }
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
        for (int k = 0; k < 2; ++k) {
          m.sum[k] += line->Residual(pair.y[k], pair.x[k], pair.shares[k]);
        }
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

bool IsIntermediateColor(const MarkerSpec& marker, const Rgb& color) {
  const std::vector<Rgb> colors = DesignColors(marker);
  for (int c = 0; c < 3; ++c) {
    double darkest = color[c], lightest = color[c];
    for (const Rgb& other : colors) {
      darkest = std::min(darkest, other[c]);
      lightest = std::max(lightest, other[c]);
    }
    if (!(darkest < color[c] && color[c] < lightest)) return false;
  }
  // In luma too: a colour whose luma is the darkest's or the lightest's has no level between
  // them.
  const Eigen::Vector2d lumas = LumaRange(marker);
  return lumas.x() < Luma(color) && Luma(color) < lumas.y();
}

std::vector<Rgb> FittedColors(const MarkerSpec& marker) {
  std::vector<Rgb> fitted;
  for (const PaintedShape& layer : marker.layers) {
    if (static_cast<int>(fitted.size()) == kMaxFittedLevels) break;
    if (IsIntermediateColor(marker, layer.color) && layer.color != marker.background &&
        std::find(fitted.begin(), fitted.end(), layer.color) == fitted.end()) {
      fitted.push_back(layer.color);
    }
  }
  return fitted;
}

double PrintedLevel(const MarkerSpec& marker, const Rgb& color) {
  const Eigen::Vector2d range = LumaRange(marker);
  return (Luma(color) - range.x()) / (range.y() - range.x());
}

AppearanceFit CheckPrintedAppearance(const Image8& image,
                                     const Camera& camera,
                                     const MarkerSpec& marker,
                                     const Rigid3& cam_from_marker,
                                     double blur_sigma_px,
                                     const AppearanceOptions& options) {
  AppearanceFit fit = FitOnGrid(
      image, camera, marker, cam_from_marker, blur_sigma_px, options, options.coarse_grid);
  if (options.grid != options.coarse_grid && !(fit.misfit_upper <= options.max_misfit) &&
      !fit.surely_misfits) {
    fit = FitOnGrid(image, camera, marker, cam_from_marker, blur_sigma_px, options, options.grid);
  }
  return fit;
}

}  // namespace markerbench
