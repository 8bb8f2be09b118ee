#include "trackers/circle/blurred_dot_search.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/circle/blurred_ellipse.h"
#include "trackers/circle/clipped_noise.h"
#include "trackers/circle/conic.h"

namespace markerbench {
namespace {

constexpr double kMinSigmaPx = 0.3;

// c(μ) of clipped_noise.h in 0-255 units; `noise` 0-1.
double Clipped(double mu, double noise) { return 255.0 * ClippedMean(mu / 255.0, noise).mean; }

}  // namespace

BlurredDotSearch::BlurredDotSearch(const cv::Mat& raw,
                                   const BlurredDisk& disk,
                                   const cv::Rect& area,
                                   double noise_sigma,
                                   const BlurredDotOptions& options)
    : disk_(disk),
      area_(area & cv::Rect(0, 0, raw.cols, raw.rows)),
      noise_sigma_(255.0 * ModelNoiseSigma(noise_sigma / 255.0)),
      options_(options) {
  disk_.sigma_px = std::max(disk_.sigma_px, kMinSigmaPx);
  stride_ = std::max(1,
                     static_cast<int>(std::ceil(
                         std::sqrt(static_cast<double>(area_.area()) / options_.max_area_pixels))));
  raw(area_).convertTo(observed_, CV_64F);
  if (options_.fit_disk) FitDisk();
  Paint();
}

void BlurredDotSearch::Paint() {
  printed_.create(observed_.size(), CV_64F);
  expected_.create(observed_.size(), CV_64F);
  const double noise = noise_sigma_ / 255.0;
  const std::optional<EllipseChords<double>> chords = ChordsOfConic(disk_.conic_px);
  std::optional<BlurredEllipse> blurred;
  if (chords) {
    const double semi_major = std::max(chords->half_width, chords->half_height);
    blurred.emplace(
        *chords, disk_.sigma_px, BlurredEllipse::NodesFor(1.25 * semi_major / disk_.sigma_px));
  }
  for (int y = 0; y < area_.height; y += stride_) {
    for (int x = 0; x < area_.width; x += stride_) {
      const double ink =
          blurred ? blurred->At(Eigen::Vector2d(area_.x + x, area_.y + y)).value : 0.0;
      const double printed = disk_.outside_level + (disk_.inside_level - disk_.outside_level) * ink;
      printed_.at<double>(y, x) = printed;
      expected_.at<double>(y, x) = Clipped(printed, noise);
    }
  }
}

void BlurredDotSearch::FitDisk() {
  const std::optional<EllipseChords<double>> chords = ChordsOfConic(disk_.conic_px);
  if (!chords || area_.empty()) return;
  const Ellipse e = EllipseFromConic(disk_.conic_px);
  const Eigen::Vector2d major(std::cos(e.angle_rad), std::sin(e.angle_rad));
  const Eigen::Vector2d minor(-major.y(), major.x());
  const double inner = options_.fit_band_inner, outer = options_.fit_band_outer;
  const double band_area = M_PI * e.semi_major * e.semi_minor * (outer * outer - inner * inner);
  const int stride =
      std::max(1, static_cast<int>(std::ceil(std::sqrt(band_area / options_.fit_max_pixels))));
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> values;
  for (int y = 0; y < area_.height; y += stride) {
    for (int x = 0; x < area_.width; x += stride) {
      const Eigen::Vector2d pixel(area_.x + x, area_.y + y);
      const Eigen::Vector2d u = pixel - e.center;
      const double q = std::hypot(u.dot(major) / e.semi_major, u.dot(minor) / e.semi_minor);
      if (q < inner || q > outer) continue;
      pixels.push_back(pixel);
      values.push_back(observed_.at<double>(y, x) / 255.0);
    }
  }
  if (pixels.size() < 20) return;
  double noise = noise_sigma_ / 255.0;
  const double semi_major = std::max(chords->half_width, chords->half_height);
  // θ = (σ, in, out), levels 0-1.
  std::vector<ModelledPixel> modelled;
  auto evaluate = [&](const Eigen::Vector3d& t, Eigen::Matrix3d* JtJ, Eigen::Vector3d* Jtr) {
    modelled.clear();
    BlurredEllipse blurred(*chords, t[0], BlurredEllipse::NodesFor(1.25 * semi_major / t[0]));
    // Each dot blurred, G(s, z) with s = ρ/σ and z = (ρ - |x - p|)/σ.
    std::vector<BlurredDiskProfile> dots;
    for (const DotInFit& dot : disk_.dots) dots.emplace_back(dot.radius_px / t[0]);
    JtJ->setZero();
    Jtr->setZero();
    double cost = 0.0;
    for (size_t i = 0; i < pixels.size(); ++i) {
      const BlurredEllipseValue g = blurred.At(pixels[i]);
      double ink = g.value, d_ink_d_sigma = g.gradient[5];
      for (size_t k = 0; k < dots.size(); ++k) {
        const DotInFit& dot = disk_.dots[k];
        const double beyond = dot.radius_px - (pixels[i] - dot.position_px).norm();
        const ProfileValue v = dots[k].At(beyond / t[0]);
        ink += dot.contrast * v.value;
        d_ink_d_sigma -= dot.contrast * (v.d_ds * dot.radius_px + v.d_dz * beyond) / (t[0] * t[0]);
      }
      const ClippedMeanValue c = ClippedMean(t[2] + (t[1] - t[2]) * ink, noise);
      const Eigen::Vector3d J =
          c.d_mu * Eigen::Vector3d((t[1] - t[2]) * d_ink_d_sigma, ink, 1.0 - ink);
      const double residual = values[i] - c.mean;
      modelled.push_back({residual, c.mean});
      *JtJ += J * J.transpose();
      *Jtr += J * residual;
      cost += residual * residual;
    }
    return cost;
  };
  Eigen::Vector3d theta(disk_.sigma_px, disk_.inside_level / 255.0, disk_.outside_level / 255.0);
  Eigen::Matrix3d JtJ;
  Eigen::Vector3d Jtr;
  // At the noise the residuals show between 0.2 and 0.8 (the estimate from the image reads
  // clipped paper: 14.7 of 36 levels on d's frames at σ² = 0.02), again while it moves by more
  // than a tenth.
  for (int round = 0; round < 3; ++round) {
    double cost = evaluate(theta, &JtJ, &Jtr);
    double damping = 1e-3;
    for (int iteration = 0; iteration < options_.fit_iterations; ++iteration) {
      Eigen::Matrix3d damped = JtJ;
      damped.diagonal() *= 1.0 + damping;
      const Eigen::Vector3d step = damped.ldlt().solve(Jtr);
      if (!step.allFinite()) return;
      Eigen::Vector3d next = theta + step;
      next[0] = std::max(next[0], kMinSigmaPx);
      Eigen::Matrix3d next_JtJ;
      Eigen::Vector3d next_Jtr;
      const double next_cost = evaluate(next, &next_JtJ, &next_Jtr);
      if (next_cost < cost) {
        const bool converged = std::abs(step[0]) < 1e-3;
        theta = next;
        cost = next_cost;
        JtJ = next_JtJ;
        Jtr = next_Jtr;
        damping = std::max(1e-6, 0.3 * damping);
        if (converged) break;
      } else {
        damping *= 10.0;
      }
    }
    evaluate(theta, &JtJ, &Jtr);
    const std::optional<double> shown = MidRangeNoise(modelled);
    if (!shown || std::abs(*shown / noise - 1.0) <= 0.1) break;
    noise = ModelNoiseSigma(*shown);
  }
  // A fit gone astray leaves the start.
  if (!theta.allFinite() || !(theta[0] <= 2.0 * semi_major)) return;
  noise_sigma_ = 255.0 * noise;
  disk_.sigma_px = theta[0];
  disk_.inside_level = 255.0 * theta[1];
  disk_.outside_level = 255.0 * theta[2];
}

bool BlurredDotSearch::Passes(const FoundDot& found, double contrast, double tolerance) const {
  if (!(found.significance >= options_.min_significance)) return false;
  const double gamma = found.contrast / contrast;
  const double standard_error = gamma / found.significance;
  return std::abs(gamma - 1.0) <=
         std::min(options_.contrast_tolerance,
                  tolerance + options_.contrast_standard_errors * standard_error);
}

double BlurredDotSearch::Reach(double radius_px) const {
  return radius_px + options_.window_sigmas * disk_.sigma_px;
}

FoundDot BlurredDotSearch::FitAt(const Eigen::Vector2d& p,
                                 double radius_px,
                                 double contrast,
                                 const Eigen::Vector2d& window_center,
                                 double window_radius) const {
  const double sigma = disk_.sigma_px, noise = noise_sigma_ / 255.0;
  const double step = contrast * (disk_.inside_level - disk_.outside_level);  // Δ
  const BlurredDiskProfile profile(radius_px / sigma);
  const Eigen::Vector2d& c = window_center;
  const double w = window_radius;
  // The window's sampled pixels: multiples of the stride within the area.
  auto first = [this](int from) { return std::max(0, (from + stride_ - 1) / stride_ * stride_); };
  const int x0 = first(static_cast<int>(std::floor(c.x() - w)) - area_.x);
  const int x1 = std::min(area_.width - 1, static_cast<int>(std::ceil(c.x() + w)) - area_.x);
  const int y0 = first(static_cast<int>(std::floor(c.y() - w)) - area_.y);
  const int y1 = std::min(area_.height - 1, static_cast<int>(std::ceil(c.y() + w)) - area_.y);
  double n = 0.0, sum_t = 0.0, sum_tt = 0.0, sum_r = 0.0, sum_tr = 0.0;
  for (int y = y0; y <= y1; y += stride_) {
    const double* observed = observed_.ptr<double>(y);
    const double* printed = printed_.ptr<double>(y);
    const double* expected = expected_.ptr<double>(y);
    const double wy = area_.y + y - c.y(), dy = area_.y + y - p.y();
    for (int x = x0; x <= x1; x += stride_) {
      const double wx = area_.x + x - c.x(), dx = area_.x + x - p.x();
      if (wx * wx + wy * wy > w * w) continue;
      const double dot = profile.At((radius_px - std::sqrt(dx * dx + dy * dy)) / sigma).value;
      const double without = expected[x];
      const double t = Clipped(printed[x] + step * dot, noise) - without;
      const double r = observed[x] - without;
      n += 1.0;
      sum_t += t;
      sum_tt += t * t;
      sum_r += r;
      sum_tr += t * r;
    }
  }
  FoundDot found;
  found.position_px = p;
  const double det = n * sum_tt - sum_t * sum_t;
  if (!(det > 1e-9 * n * n)) return found;
  const double gamma = (n * sum_tr - sum_t * sum_r) / det;
  found.contrast = gamma * contrast;
  found.significance = gamma / (noise_sigma_ * std::sqrt(n / det));
  return found;
}

std::optional<FoundDot> BlurredDotSearch::Find(const std::vector<Eigen::Vector2d>& positions,
                                               double radius_px,
                                               double contrast,
                                               double tolerance) const {
  if (positions.empty() || area_.empty() || contrast == 0.0) return std::nullopt;
  const double reach = Reach(radius_px);
  auto fit = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& center, double radius) {
    return FitAt(p, radius_px, contrast, center, radius);
  };
  FoundDot best = fit(positions.front(), positions.front(), reach);
  double spacing = std::numeric_limits<double>::infinity();  // between neighbours
  for (size_t i = 1; i < positions.size(); ++i) {
    const double apart = (positions[i] - positions[i - 1]).norm();
    if (apart > 0.0) spacing = std::min(spacing, apart);
    const FoundDot f = fit(positions[i], positions[i], reach);
    if (f.significance > best.significance) best = f;
  }
  // Pattern search from the best trial position, in steps halved down to a quarter pixel, on
  // the pixels around it (a window that moved with the dot would make the score jump).
  const double first_step = std::clamp(0.5 * spacing, 0.25, 2.0);
  const Eigen::Vector2d window_center = best.position_px;
  const double window_radius = reach + 8.0 * first_step;  // 8 moves at most a step
  best = fit(window_center, window_center, window_radius);
  for (double step = first_step; step >= 0.25; step *= 0.5) {
    bool moved = true;
    for (int rounds = 0; moved && rounds < 8; ++rounds) {
      moved = false;
      const Eigen::Vector2d center = best.position_px;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0) continue;
          const FoundDot f =
              fit(center + step * Eigen::Vector2d(dx, dy), window_center, window_radius);
          if (f.significance > best.significance) {
            best = f;
            moved = true;
          }
        }
      }
    }
  }
  if (!Passes(best, contrast, tolerance)) return std::nullopt;
  return best;
}

}  // namespace markerbench
