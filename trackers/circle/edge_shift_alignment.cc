#include "trackers/circle/edge_shift_alignment.h"

#include <ceres/jet.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/shapes.h"
#include "trackers/bilinear_sample.h"
#include "trackers/circle/conic.h"

namespace markerbench {
namespace {

// One ray: the image of a point of a circle's edge at the pose, the outward unit normal of the
// circle's image there, and the levels expected inside and outside it (0-1).
struct EdgeRay {
  Eigen::Vector2d px = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
  double inside_level = 0.0, outside_level = 0.0;
  double inward_px = 0.0, outward_px = 0.0;  // how far the ray looks each way
  int channel = -1;                          // of the image; -1: luma
};

// The level a channel (-1: luma of an RGB image) reads where `color` is printed.
double ExpectedLevel(const Eigen::VectorXd& levels, const Rgb& color, int channels, int channel) {
  const auto level = [&](int c, double printed) {
    return levels[2 * c] + levels[2 * c + 1] * printed;
  };
  if (channels == 1) return level(0, Luma(color));
  if (channel >= 0) return level(channel, color[channel]);
  return Luma(Rgb(level(0, color[0]), level(1, color[1]), level(2, color[2])));
}

double LevelAt(const Image8& image, int channel, const Eigen::Vector2d& p) {
  const auto at = [&](int c) {
    return BilinearSample(image.pixels.data(), image.width, image.height, image.channels, c, p);
  };
  if (image.channels == 1) return at(0) / 255.0;
  if (channel >= 0) return at(channel) / 255.0;
  return Luma(Rgb(at(0), at(1), at(2))) / 255.0;
}

// The rays of circle `i` at `cam_from_paper`, looking at most `max_shift_px` (plus the blur's
// reach) from the predicted edge each way, within the circle's ink-free margins.
std::vector<EdgeRay> RaysOf(size_t i,
                            const Image8& image,
                            const Camera& camera,
                            const MarkerSpec& marker,
                            const CircleGeometry& geometry,
                            const CircleDetector::EdgeClearance& clearance,
                            const Rigid3& cam_from_paper,
                            const Eigen::VectorXd& levels,
                            double max_shift_px,
                            double blur_sigma_px,
                            int rays) {
  const Eigen::Vector2d& center = geometry.centers[i];
  const double radius = geometry.radii_m[i];
  const double step = 1e-3 * radius;  // for the local map from the paper to the image
  const auto image_of = [&](const Eigen::Vector2d& p) {
    return camera.ImgFromCam(cam_from_paper * Eigen::Vector3d(p.x(), p.y(), 0.0));
  };
  const auto printed = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector3d on_marker = geometry.marker_from_paper * Eigen::Vector3d(p.x(), p.y(), 0);
    return *marker.ColorAt(on_marker.head<2>()).color;
  };
  const double reach = max_shift_px + 2.0 * blur_sigma_px + 2.0;
  std::vector<EdgeRay> out;
  for (int k = 0; k < rays; ++k) {
    const double theta = 2.0 * M_PI * (k + 0.5) / rays;
    const Eigen::Vector2d radial(std::cos(theta), std::sin(theta));
    const Eigen::Vector2d p = center + radius * radial;
    EdgeRay ray;
    const Eigen::Vector3d x_cam = cam_from_paper * Eigen::Vector3d(p.x(), p.y(), 0.0);
    if (!(x_cam.z() > 0.0)) continue;
    ray.px = camera.ImgFromCam(x_cam);
    const Eigen::Vector2d outward = image_of(p + step * radial) - ray.px;
    const Eigen::Vector2d along =
        image_of(p + step * Eigen::Vector2d(-radial.y(), radial.x())) - ray.px;
    ray.normal = Eigen::Vector2d(along.y(), -along.x()).normalized();
    if (ray.normal.dot(outward) < 0.0) ray.normal = -ray.normal;
    const double px_per_m = ray.normal.dot(outward) / step;
    if (!(px_per_m > 0.0) || !ray.px.allFinite()) continue;
    ray.channel = clearance.channel;
    // The printed colours 1 % of the radius inside and outside the edge.
    ray.inside_level =
        ExpectedLevel(levels, printed(p - 10.0 * step * radial), image.channels, ray.channel);
    ray.outside_level =
        ExpectedLevel(levels, printed(p + 10.0 * step * radial), image.channels, ray.channel);
    ray.inward_px = std::min({reach, 0.6 * clearance.inward_m * px_per_m, 0.8 * radius * px_per_m});
    ray.outward_px = std::min(reach, 0.6 * clearance.outward_m * px_per_m);
    out.push_back(ray);
  }
  return out;
}

// The edge's offset along the ray's outward normal from its predicted place, in px: the best
// step of the expected polarity between two levels, placed to a fraction of a sample by the
// area under the profile about it (each sample the mean of `samples_across`). nullopt where the
// ray leaves the image or shows no step of at least `min_step_per_contrast` of the contrast
// expected.
std::optional<double> EdgeShift(const Image8& image,
                                const EdgeRay& ray,
                                double blur_sigma_px,
                                int samples_across,
                                const EdgeShiftOptions& options) {
  const double h = options.sample_step_px;
  const int before = static_cast<int>(std::floor(ray.inward_px / h));
  const int n = before + static_cast<int>(std::floor(ray.outward_px / h)) + 1;
  if (n < 5) return std::nullopt;
  const Eigen::Vector2d across(-ray.normal.y(), ray.normal.x());
  const auto in_image = [&](const Eigen::Vector2d& p) {
    return p.x() >= 0.0 && p.y() >= 0.0 && p.x() <= image.width - 1.0 &&
           p.y() <= image.height - 1.0;
  };
  const double s0 = -before * h;
  const double side = 0.5 * (samples_across - 1);
  for (const double s : {s0, s0 + (n - 1) * h}) {
    for (const double a : {-side, side}) {
      if (!in_image(ray.px + s * ray.normal + a * across)) return std::nullopt;
    }
  }
  std::vector<double> profile(static_cast<size_t>(n));
  std::vector<double> sums(static_cast<size_t>(n) + 1, 0.0);
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d p = ray.px + (s0 + j * h) * ray.normal;
    profile[j] = 0.0;
    for (int a = 0; a < samples_across; ++a) {
      profile[j] += LevelAt(image, ray.channel, p + (a - side) * across);
    }
    profile[j] /= samples_across;
    sums[j + 1] = sums[j] + profile[j];
  }
  // The split maximising the step's share of the profile's variance, (mean_in - mean_out)² k
  // (n - k) / n, among steps of the expected polarity.
  const double contrast = ray.inside_level - ray.outside_level;
  int best = -1;
  double best_score = 0.0;
  for (int k = 2; k <= n - 2; ++k) {
    const double step = sums[k] / k - (sums[n] - sums[k]) / (n - k);
    const double score = step * step * k * (n - k);
    if (step * contrast > 0.0 && score > best_score) {
      best = k;
      best_score = score;
    }
  }
  if (best < 0) return std::nullopt;
  // The levels each side, beyond the blurred edge's reach about the step where the ray leaves
  // room for a sample there.
  const int half = static_cast<int>(std::ceil((2.0 * blur_sigma_px + 1.0) / h));
  const int inside_end = std::max(1, best - half), outside_start = std::min(n - 1, best + half);
  const double inside = sums[inside_end] / inside_end;
  const double outside = (sums[n] - sums[outside_start]) / (n - outside_start);
  if (!((inside - outside) * contrast >= options.min_step_per_contrast * contrast * contrast)) {
    return std::nullopt;
  }
  // Each sample stands for h of the ray: summed over the blurred edge about the step, the
  // profile scaled to 1 inside and 0 outside covers the length from its first sample to the edge.
  const int first = inside_end, last = outside_start;
  double covered = 0.0;
  for (int j = first; j < last; ++j) covered += (profile[j] - outside) / (inside - outside);
  const double edge = s0 + (first - 0.5) * h + h * covered;
  return std::clamp(edge, s0, s0 + (n - 1) * h);
}

// The move δ = (ω, v) of the circles, x_cam → c + exp(ω) (x_cam - c) + v with c their mean
// centre (turned about the marker, not the camera, so that turn and shift stay apart).
Rigid3 Moved(const Rigid3& cam_from_paper,
             const Eigen::Vector3d& center,
             const Eigen::Matrix<double, 6, 1>& move) {
  const Eigen::Matrix3d turn = RotationFromVector(move.head<3>());
  return {turn * cam_from_paper.rotation,
          center + turn * (cam_from_paper.translation - center) + move.tail<3>()};
}

// An edge point found, in the ideal (pinhole) image, and its circle.
struct EdgePoint {
  Eigen::Vector2d ideal_px;
  size_t circle;
};

// Each point's PND distance (conic.h) to its circle's image at `cam_from_paper` moved by δ, with
// its derivative at δ = 0.
using Jet6 = ceres::Jet<double, 6>;
std::vector<Jet6> DistancesAt(const Camera& camera,
                              const CircleGeometry& geometry,
                              const Rigid3& cam_from_paper,
                              const Eigen::Vector3d& center,
                              const std::vector<EdgePoint>& points) {
  Eigen::Matrix<Jet6, 3, 1> turn, shift;
  for (int k = 0; k < 3; ++k) {
    turn(k) = Jet6(0.0, k);
    shift(k) = Jet6(0.0, 3 + k);
  }
  // To first order in δ: R' = R + ω × R, t' = t + ω × (t - c) + v.
  const Eigen::Matrix3d& R = cam_from_paper.rotation;
  const Eigen::Vector3d& t = cam_from_paper.translation;
  Eigen::Matrix<Jet6, 3, 3> plane_to_ray;
  for (int col = 0; col < 2; ++col) {
    const Eigen::Matrix<Jet6, 3, 1> axis = R.col(col).cast<Jet6>();
    plane_to_ray.col(col) = axis + turn.cross(axis);
  }
  const Eigen::Matrix<Jet6, 3, 1> arm = (t - center).cast<Jet6>();
  plane_to_ray.col(2) = t.cast<Jet6>() + turn.cross(arm) + shift;
  const Eigen::Matrix<Jet6, 3, 3> H = camera.K().cast<Jet6>() * plane_to_ray;
  std::vector<Eigen::Matrix<Jet6, 3, 3>> conics;
  for (size_t i = 0; i < geometry.radii_m.size(); ++i) {
    Eigen::Matrix<Jet6, 3, 3> C = ImageOfCircle<Jet6>(H, geometry.centers[i], geometry.radii_m[i]);
    conics.push_back(C / C.norm());  // the distance ignores C's scale; Jets stay well scaled
  }
  std::vector<Jet6> distances;
  for (const EdgePoint& p : points) {
    distances.push_back(PndResidual(conics[p.circle], p.ideal_px.x(), p.ideal_px.y()));
  }
  return distances;
}

// The same distances' values alone, at `cam_from_paper`.
std::vector<double> DistanceValuesAt(const Camera& camera,
                                     const CircleGeometry& geometry,
                                     const Rigid3& cam_from_paper,
                                     const std::vector<EdgePoint>& points) {
  const std::vector<Eigen::Matrix3d> conics =
      ConicsImagedThrough(geometry, camera.K() * RayFromPlane(cam_from_paper));
  std::vector<double> distances;
  for (const EdgePoint& p : points) {
    distances.push_back(PndResidual<double>(conics[p.circle], p.ideal_px.x(), p.ideal_px.y()));
  }
  return distances;
}

// Gauss-Newton on the points' distances to their circles' images, from `cam_from_paper`
// (points not `kept` left out). The move from `start` counts too, a turn of kPriorTurnRad or a
// shift of kPriorShiftM as much as a pixel of one point's distance: directions the edges hardly
// fix (the roll of a single circle or of two concentric ones) stay the prediction's. A step that
// moves no kept point's distance by more than kSettledMovePx (to first order) is the last: the
// steps shrink about twentyfold each, and the fit on the pixels starts from the result. Stopping
// at a turn of 1e-6 rad and a shift of 0.1 µm instead, half the fits took all five steps, the
// last moving the points by about 1e-4 px; paired on the tracked sequences' frames, the errors
// moved by a geometric mean within 4e-6, and no frame's success (results/speed.md).
constexpr double kPriorTurnRad = 0.05;
constexpr double kPriorShiftM = 0.02;
constexpr int kGaussNewtonSteps = 5;
constexpr double kSettledMovePx = 0.01;
Rigid3 FitToPoints(const Camera& camera,
                   const CircleGeometry& geometry,
                   const Rigid3& start,
                   const Eigen::Vector3d& center,
                   const std::vector<EdgePoint>& points,
                   const std::vector<bool>& kept,
                   Eigen::Matrix<double, 6, 1>* moved_from_start) {
  Eigen::Matrix<double, 6, 1> prior = Eigen::Matrix<double, 6, 1>::Zero();
  prior.head<3>().setConstant(1.0 / (kPriorTurnRad * kPriorTurnRad));
  prior.tail<3>().setConstant(1.0 / (kPriorShiftM * kPriorShiftM));
  Rigid3 pose = start;
  for (int step = 0; step < kGaussNewtonSteps; ++step) {
    const std::vector<Jet6> distances = DistancesAt(camera, geometry, pose, center, points);
    Eigen::Matrix<double, 6, 6> JtJ = prior.asDiagonal();
    Eigen::Matrix<double, 6, 1> Jtr = prior.cwiseProduct(*moved_from_start);
    for (size_t k = 0; k < points.size(); ++k) {
      if (!kept[k]) continue;
      JtJ += distances[k].v * distances[k].v.transpose();
      Jtr += distances[k].v * distances[k].a;
    }
    const Eigen::Matrix<double, 6, 1> delta = -JtJ.ldlt().solve(Jtr);
    pose = Moved(pose, center, delta);
    *moved_from_start += delta;
    double largest_move_px = 0.0;
    for (size_t k = 0; k < points.size(); ++k) {
      if (kept[k]) largest_move_px = std::max(largest_move_px, std::abs(distances[k].v.dot(delta)));
    }
    if (!(largest_move_px >= kSettledMovePx)) break;
  }
  return pose;
}

double Median(std::vector<double> values) {
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  return values[middle];
}

// The RMS of the kept points' distances to the circles at `cam_from_paper`.
double RmsDistance(const Camera& camera,
                   const CircleGeometry& geometry,
                   const Rigid3& cam_from_paper,
                   const std::vector<EdgePoint>& points,
                   const std::vector<bool>& kept) {
  const std::vector<double> distances = DistanceValuesAt(camera, geometry, cam_from_paper, points);
  double sum2 = 0.0;
  int counted = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    if (!kept[k]) continue;
    sum2 += distances[k] * distances[k];
    ++counted;
  }
  return std::sqrt(sum2 / counted);
}

}  // namespace

bool EdgeShiftOptions::IsValid(std::string* error) const {
  std::ostringstream msg;
  const auto fraction = [](double f) { return f > 0.0 && f <= 1.0; };
  if (!(first.rays_per_circle >= 3)) {
    msg << "edge_shift_first_rays=" << first.rays_per_circle << " must be >= 3";
  } else if (!(second.rays_per_circle >= 3)) {
    msg << "edge_shift_rays=" << second.rays_per_circle << " must be >= 3";
  } else if (!(first.max_shift_px > 0.0)) {
    msg << "edge_shift_max_px=" << first.max_shift_px << " must be > 0";
  } else if (!(second.max_shift_px > 0.0)) {
    msg << "edge_shift_second_max_px=" << second.max_shift_px << " must be > 0";
  } else if (!(sample_step_px > 0.0 && sample_step_px <= 4.0)) {
    msg << "edge_shift_step_px=" << sample_step_px << " must be in (0, 4]";
  } else if (!(first.samples_across >= 1)) {
    msg << "edge_shift_first_samples_across=" << first.samples_across << " must be >= 1";
  } else if (!(second.samples_across >= 1)) {
    msg << "edge_shift_samples_across=" << second.samples_across << " must be >= 1";
  } else if (!fraction(min_step_per_contrast)) {
    msg << "edge_shift_min_step_per_contrast=" << min_step_per_contrast << " must be in (0, 1]";
  } else if (!fraction(first.min_found_fraction)) {
    msg << "edge_shift_first_min_found_fraction=" << first.min_found_fraction
        << " must be in (0, 1]";
  } else if (!fraction(second.min_found_fraction)) {
    msg << "edge_shift_min_found_fraction=" << second.min_found_fraction << " must be in (0, 1]";
  } else if (!(max_rms_px > 0.0)) {
    msg << "edge_shift_max_rms_px=" << max_rms_px << " must be > 0";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

std::optional<EdgeShiftAlignment> AlignByEdgeShifts(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const CircleGeometry& geometry,
    const std::vector<CircleDetector::EdgeClearance>& clearances,
    const Rigid3& predicted_cam_from_paper,
    const Eigen::VectorXd& levels,
    double blur_sigma_px,
    const EdgeShiftOptions& options,
    std::string* why) {
  // The last fit's levels may be another image's (a grey frame before an RGB one).
  if (levels.size() < 2 * image.channels) {
    if (why) *why = "the levels given are not the image's channels";
    return std::nullopt;
  }
  EdgeShiftAlignment aligned;
  aligned.cam_from_paper = predicted_cam_from_paper;
  std::vector<EdgePoint> points;
  std::vector<bool> kept;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  for (const EdgeShiftRound& round : {options.first, options.second}) {
    points.clear();
    for (size_t i = 0; i < geometry.radii_m.size(); ++i) {
      const std::vector<EdgeRay> rays = RaysOf(i,
                                               image,
                                               camera,
                                               marker,
                                               geometry,
                                               clearances[i],
                                               aligned.cam_from_paper,
                                               levels,
                                               round.max_shift_px,
                                               blur_sigma_px,
                                               round.rays_per_circle);
      int found = 0;
      for (const EdgeRay& ray : rays) {
        const std::optional<double> shift =
            EdgeShift(image, ray, blur_sigma_px, round.samples_across, options);
        if (!shift) continue;
        ++found;
        const Eigen::Vector2d px = ray.px + *shift * ray.normal;
        points.push_back({camera.HasDistortion() ? camera.IdealFromImg(px) : px, i});
      }
      if (found < round.min_found_fraction * round.rays_per_circle) {
        if (why) {
          *why = "the edge of circle " + std::to_string(i) + " shifted on only " +
                 std::to_string(found) + " of " + std::to_string(round.rays_per_circle) + " rays";
        }
        return std::nullopt;
      }
    }
    // Fitted on every point, then again without those that lie off the pose by more than
    // three robust standard deviations (MAD) or half a pixel, whichever is more.
    center.setZero();
    for (const Eigen::Vector2d& c : geometry.centers) {
      center += aligned.cam_from_paper * Eigen::Vector3d(c.x(), c.y(), 0.0);
    }
    center /= static_cast<double>(geometry.centers.size());
    kept.assign(points.size(), true);
    Eigen::Matrix<double, 6, 1> moved = Eigen::Matrix<double, 6, 1>::Zero();
    Rigid3 fitted =
        FitToPoints(camera, geometry, aligned.cam_from_paper, center, points, kept, &moved);
    std::vector<double> sizes;
    for (const double d : DistanceValuesAt(camera, geometry, fitted, points)) {
      sizes.push_back(std::abs(d));
    }
    const double limit = std::max(0.5, 3.0 * 1.4826 * Median(sizes));
    for (size_t k = 0; k < points.size(); ++k) kept[k] = sizes[k] <= limit;
    aligned.cam_from_paper = FitToPoints(camera, geometry, fitted, center, points, kept, &moved);
  }
  aligned.points_kept = static_cast<int>(std::count(kept.begin(), kept.end(), true));
  aligned.rms_px = RmsDistance(camera, geometry, aligned.cam_from_paper, points, kept);
  if (!(aligned.rms_px <= options.max_rms_px)) {
    if (why) *why = "the edges' shifts disagree: RMS " + std::to_string(aligned.rms_px) + " px";
    return std::nullopt;
  }
  Eigen::Matrix<double, 6, 1> moved = Eigen::Matrix<double, 6, 1>::Zero();
  aligned.other_tilt = FitToPoints(
      camera, geometry, OtherTilt(aligned.cam_from_paper), center, points, kept, &moved);
  aligned.other_tilt_rms_px = RmsDistance(camera, geometry, aligned.other_tilt, points, kept);
  return aligned;
}

}  // namespace markerbench
