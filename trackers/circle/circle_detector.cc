#include "trackers/circle/circle_detector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "trackers/byte_histogram.h"
#include "trackers/circle/conic.h"
#include "trackers/noise_estimate.h"

namespace markerbench {
namespace {

// A thresholded blob whose outline is close to an ellipse.
struct Hole {
  double area_px = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  std::optional<Eigen::Matrix3d> conic;
};
struct Candidate {
  Eigen::Matrix3d conic = Eigen::Matrix3d::Zero();
  Ellipse ellipse;
  double area_px = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  std::vector<Hole> holes;
};

std::vector<Eigen::Vector2d> ToPoints(const std::vector<cv::Point>& contour) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(contour.size());
  for (const cv::Point& p : contour) points.emplace_back(p.x, p.y);
  return points;
}

Eigen::Vector2d Centroid(const std::vector<cv::Point>& contour) {
  const cv::Moments m = cv::moments(contour);
  if (m.m00 <= 0.0) return ToPoints(contour).front();
  return {m.m10 / m.m00, m.m01 / m.m00};
}

struct Threshold {
  double paper = 0.0;  // level of the paper
  double level = 0.0;  // between paper and the most extreme ink
  double contrast = 0.0;
};

// `fraction`: how far from the paper's level towards the most extreme ink's the level sits.
Threshold FindThreshold(const cv::Mat& smoothed, bool ink_dark, double fraction) {
  ByteHistogram levels;
  for (int y = 0; y < smoothed.rows; ++y) levels.Add(smoothed.ptr<uint8_t>(y), smoothed.cols);
  const std::array<int, 256> histogram = levels.Counts();
  const int median = levels.Median();
  int extreme = ink_dark ? 0 : 255;
  while (histogram[extreme] == 0 && extreme != median) extreme += ink_dark ? 1 : -1;
  Threshold t;
  t.paper = median;
  t.level = median + fraction * (extreme - median);
  t.contrast = std::abs(median - extreme) / 255.0;
  return t;
}

bool TouchesBorder(const cv::Rect& box, const cv::Size& size) {
  return box.x <= 0 || box.y <= 0 || box.x + box.width >= size.width ||
         box.y + box.height >= size.height;
}

// Ellipse hypothesis for a contour, if its outline is close enough to one.
std::optional<Eigen::Matrix3d> OutlineEllipse(const std::vector<cv::Point>& contour,
                                              double area_px,
                                              const CircleDetectorOptions& options) {
  if (contour.size() < 6) return std::nullopt;
  const std::vector<Eigen::Vector2d> points = ToPoints(contour);
  ConicFitOptions direct;
  direct.refine_pnd = false;
  const std::optional<ConicFit> fit = FitEllipse(points, direct);
  if (!fit) return std::nullopt;
  const Ellipse e = EllipseFromConic(fit->conic);
  const double ellipse_area = M_PI * e.semi_major * e.semi_minor;
  // Contour pixels sit half a pixel inside the region's outline.
  const double outline_area = M_PI * (e.semi_major + 0.5) * (e.semi_minor + 0.5);
  if (!(area_px > 0.6 * ellipse_area && area_px < 1.25 * outline_area)) return std::nullopt;
  if (fit->rms_px > options.max_outline_rms_px + 0.08 * e.semi_minor) return std::nullopt;
  return fit->conic;
}

std::vector<Candidate> FindCandidates(const cv::Mat& smoothed,
                                      bool ink_dark,
                                      const Threshold& threshold,
                                      const CircleDetectorOptions& options) {
  cv::Mat binary;
  cv::threshold(
      smoothed, binary, threshold.level, 255, ink_dark ? cv::THRESH_BINARY_INV : cv::THRESH_BINARY);
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(binary, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);
  std::vector<Candidate> candidates;
  for (size_t i = 0; i < contours.size(); ++i) {
    if (hierarchy[i][3] >= 0) continue;  // a hole; handled with its parent
    const double area = cv::contourArea(contours[i]);
    if (area < options.min_area_px) continue;
    if (TouchesBorder(cv::boundingRect(contours[i]), smoothed.size())) continue;
    const std::optional<Eigen::Matrix3d> conic = OutlineEllipse(contours[i], area, options);
    if (!conic) continue;
    Candidate c;
    c.conic = *conic;
    c.ellipse = EllipseFromConic(*conic);
    c.area_px = area;
    c.centroid = Centroid(contours[i]);
    for (int h = hierarchy[i][2]; h >= 0; h = hierarchy[h][0]) {
      Hole hole;
      hole.area_px = cv::contourArea(contours[h]);
      hole.centroid = Centroid(contours[h]);
      hole.conic = OutlineEllipse(contours[h], hole.area_px, options);
      c.holes.push_back(hole);
    }
    candidates.push_back(std::move(c));
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.area_px > b.area_px;
  });
  return candidates;
}

// From search-image to region pixels: x = scale x_search + (scale - 1)/2.
void ToFullResolution(int scale, Candidate* c) {
  if (scale == 1) return;
  const double k = (scale - 1) / 2.0;
  Eigen::Matrix3d to_search;  // x_search = to_search x
  to_search << 1.0 / scale, 0, -k / scale, 0, 1.0 / scale, -k / scale, 0, 0, 1;
  auto conic = [&](const Eigen::Matrix3d& C) {
    return CanonicalConic(to_search.transpose() * C * to_search);
  };
  c->conic = conic(c->conic);
  c->ellipse = EllipseFromConic(c->conic);
  c->area_px *= scale * scale;
  c->centroid = scale * c->centroid + Eigen::Vector2d(k, k);
  for (Hole& h : c->holes) {
    h.area_px *= scale * scale;
    h.centroid = scale * h.centroid + Eigen::Vector2d(k, k);
    if (h.conic) h.conic = conic(*h.conic);
  }
}

// Pixels per metre near a candidate, from its minor axis (the smaller, conservative scale).
double PixelsPerMetre(const Ellipse& e, double radius_m) { return e.semi_minor / radius_m; }

// The hole nearest `where` within `max_distance`, with area in [min_area, max_area].
const Hole* FindHole(const Candidate& c,
                     const Eigen::Vector2d& where,
                     double max_distance,
                     double min_area,
                     double max_area) {
  const Hole* best = nullptr;
  double best_distance = max_distance;
  for (const Hole& h : c.holes) {
    const double d = (h.centroid - where).norm();
    if (h.area_px >= min_area && h.area_px <= max_area && d <= best_distance) {
      best = &h;
      best_distance = d;
    }
  }
  return best;
}

}  // namespace

bool CircleDetectorOptions::IsValid(std::string* error) const {
  std::ostringstream msg;
  if (!(smoothing_min_px > 0.0)) {
    msg << "smoothing_min_px=" << smoothing_min_px << " must be > 0";
  } else if (!(smoothing_max_px >= smoothing_min_px)) {
    msg << "smoothing_max_px=" << smoothing_max_px << " must be >= smoothing_min_px";
  } else if (!(smoothing_per_noise >= 0.0)) {
    msg << "smoothing_per_noise=" << smoothing_per_noise << " must be >= 0";
  } else if (!(min_contrast > 0.0 && min_contrast < 1.0)) {
    msg << "min_contrast=" << min_contrast << " must be in (0, 1)";
  } else if (!(min_contrast_snr >= 0.0)) {
    msg << "min_contrast_snr=" << min_contrast_snr << " must be >= 0";
  } else if (!(min_area_px >= 5.0)) {
    msg << "min_area_px=" << min_area_px << " must be >= 5";
  } else if (!(min_dot_area_px >= 1.0 && min_dot_area_px <= min_area_px)) {
    msg << "min_dot_area_px=" << min_dot_area_px << " must be in [1, min_area_px]";
  } else if (!(max_outline_rms_px > 0.0)) {
    msg << "max_outline_rms_px=" << max_outline_rms_px << " must be > 0";
  } else if (!(min_edge_fraction > 0.0 && min_edge_fraction <= 1.0)) {
    msg << "min_edge_fraction=" << min_edge_fraction << " must be in (0, 1]";
  } else if (edge_passes < 1) {
    msg << "edge_passes=" << edge_passes << " must be >= 1";
  } else if (max_blurred_dot_disks < 0) {
    msg << "max_blurred_dot_disks=" << max_blurred_dot_disks << " must be >= 0";
  } else if (!(max_blurred_dot_peak >= 0.0 && max_blurred_dot_peak <= 1.0)) {
    msg << "max_blurred_dot_peak=" << max_blurred_dot_peak << " must be in [0, 1]";
  } else if (!(min_blurred_dot_radius_px > 0.0)) {
    msg << "min_blurred_dot_radius_px=" << min_blurred_dot_radius_px << " must be > 0";
  } else if (!(min_dot_radius_px >= 0.0)) {
    msg << "min_dot_radius_px=" << min_dot_radius_px << " must be >= 0";
  } else if (!(blurred_dots.min_significance > 0.0)) {
    msg << "blurred_dot_min_significance=" << blurred_dots.min_significance << " must be > 0";
  } else if (edges.max_rays < edges.min_rays || edges.min_rays < 8) {
    msg << "max_rays=" << edges.max_rays << " must be >= " << std::max(8, edges.min_rays);
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

CircleDetector::ChannelPlan CircleDetector::PlanFor(const MarkerSpec& marker, size_t i) const {
  const Rgb& bg = marker.background;
  Rgb color = marker.circles[i].color;
  // A circle painted in the paper colour (the inner circle of c) is the edge of the ink
  // around it: same channel and polarity as circle 0.
  if ((color - bg).cwiseAbs().maxCoeff() < 0.1) color = marker.circles[0].color;
  ChannelPlan plan;
  if (!needs_color_) {
    plan.ink_dark = Luma(color) < Luma(bg);
    return plan;
  }
  double best = -std::numeric_limits<double>::infinity();
  for (int ch = 0; ch < 3; ++ch) {
    double others = 0.0;
    for (size_t j = 0; j < marker.circles.size(); ++j) {
      if (j != i) others = std::max(others, std::abs(bg[ch] - marker.circles[j].color[ch]));
    }
    const double score = std::abs(bg[ch] - color[ch]) - others;
    if (score > best) {
      best = score;
      plan.channel = ch;
      plan.ink_dark = color[ch] < bg[ch];
    }
  }
  return plan;
}

CircleDetector::CircleDetector(const MarkerSpec& marker,
                               const CircleGeometry& geometry,
                               const CircleDetectorOptions& options)
    : kind_(marker.kind), geometry_(geometry), options_(options), needs_color_(marker.HasColor()) {
  for (size_t i = 0; i < marker.circles.size(); ++i) plans_.push_back(PlanFor(marker, i));
  // Ink-free margins around each circle's edge, in the circle's own channel: from every other
  // painted disk, with a floor so that small dots (which cost a few rays) do not shrink them.
  for (size_t i = 0; i < marker.circles.size(); ++i) {
    const Disk& circle = marker.circles[i];
    double inward = circle.radius_m, outward = std::numeric_limits<double>::infinity();
    for (const PaintedShape& layer : marker.layers) {
      const auto* disk = std::get_if<DiskShape>(&layer.shape);
      if (!disk) {
        // Another shape painted inside the circle (the mouth of e, the wedge of f): clear of
        // it beyond its bounding box's farthest corner.
        const Eigen::AlignedBox2d box = ShapeBounds(layer.shape);
        double reach = 0.0;
        for (const auto corner : {Eigen::AlignedBox2d::BottomLeft,
                                  Eigen::AlignedBox2d::BottomRight,
                                  Eigen::AlignedBox2d::TopLeft,
                                  Eigen::AlignedBox2d::TopRight}) {
          reach = std::max(reach, (box.corner(corner) - circle.center).norm());
        }
        inward = std::min(inward, std::max(0.0, circle.radius_m - reach));
        continue;
      }
      const double d = (disk->center - circle.center).norm();
      if (d < 1e-12 && std::abs(disk->radius - circle.radius_m) < 1e-12) continue;
      if (needs_color_ &&
          std::abs(layer.color[plans_[i].channel] - marker.background[plans_[i].channel]) < 0.1)
        continue;
      if (d + disk->radius <= circle.radius_m) {
        inward = std::min(inward, circle.radius_m - d - disk->radius);
      } else if (d + circle.radius_m <= disk->radius) {
        outward = std::min(outward, disk->radius - d - circle.radius_m);
      } else if (d >= circle.radius_m + disk->radius) {
        outward = std::min(outward, d - circle.radius_m - disk->radius);
      }
    }
    inward_clear_m_.push_back(std::max(inward, 0.3 * circle.radius_m));
    outward_clear_m_.push_back(std::max(outward, 0.3 * circle.radius_m));
  }
  // Ink lighter than the circles (the grey wedge of f) must fall on the ink side of the
  // threshold: halfway between it and the paper.
  for (const PaintedShape& layer : marker.layers) {
    const double ink = std::abs(Luma(layer.color) - Luma(marker.background));
    const double circle_ink = std::abs(Luma(marker.circles[0].color) - Luma(marker.background));
    if (ink >= 0.1 && ink < circle_ink) {
      threshold_fraction_ = std::min(threshold_fraction_, 0.5 * ink / circle_ink);
    }
  }
  // The dots: every painted disk that is not one of the circles.
  for (const PaintedShape& layer : marker.layers) {
    const auto* disk = std::get_if<DiskShape>(&layer.shape);
    if (!disk) continue;
    bool is_circle = false;
    for (const Disk& circle : marker.circles) {
      is_circle |= (disk->center - circle.center).norm() < 1e-12 &&
                   std::abs(disk->radius - circle.radius_m) < 1e-12;
    }
    if (is_circle) continue;
    dot_radius_m_ = std::max(dot_radius_m_, disk->radius);
    // Contrasts in circle 0's channel, for the search of blurred dots.
    const ChannelPlan& plan = plans_[0];
    auto level = [&plan](const Rgb& c) { return plan.channel < 0 ? Luma(c) : c[plan.channel]; };
    const Disk& circle = marker.circles[0];
    const double ink = level(circle.color) - level(marker.background);
    const double distance = (disk->center - circle.center).norm();
    const Rgb& under = distance < circle.radius_m ? circle.color : marker.background;
    const double contrast = ink != 0.0 ? (level(layer.color) - level(under)) / ink : 0.0;
    (distance < 1e-12 ? center_dot_contrast_ : feature_dot_contrast_) = contrast;
  }
}

CircleEdges CircleDetector::EdgesOf(size_t i,
                                    const cv::Mat& smoothed,
                                    const Eigen::Matrix3d& hypothesis,
                                    double sigma_start_px) const {
  const Ellipse e = EllipseFromConic(hypothesis);
  const double scale = PixelsPerMetre(e, geometry_.radii_m[i]);
  const double inward = std::min(0.6 * inward_clear_m_[i] * scale, 0.8 * e.semi_minor);
  const double outward = 0.6 * outward_clear_m_[i] * scale;
  return FindCircleEdges(smoothed,
                         hypothesis,
                         std::max(1.5, inward),
                         std::max(1.5, outward),
                         sigma_start_px,
                         options_.edges);
}

CircleDetector::FittedEdges CircleDetector::FitEdgesInPasses(
    size_t i,
    const cv::Mat& smoothed,
    const Eigen::Matrix3d& start,
    double sigma_start_px,
    int passes,
    bool refine_last,
    const std::function<void()>& smooth_the_rest) const {
  ConicFitOptions direct = options_.fit;
  direct.refine_pnd = false;
  FittedEdges fitted;
  fitted.conic = start;
  double sigma = sigma_start_px;
  for (int pass = 0; pass < passes; ++pass) {
    if (pass > 0 && smooth_the_rest) smooth_the_rest();
    fitted.edges = EdgesOf(i, smoothed, fitted.conic, sigma);
    ++fitted.passes;
    const size_t kept = fitted.edges.points_px.size();
    if (kept < 8 || kept < options_.min_edge_fraction * fitted.edges.rays) {
      fitted.error = "edges found on only " + std::to_string(kept) + " of " +
                     std::to_string(fitted.edges.rays) + " rays of circle " + std::to_string(i);
      return fitted;
    }
    const bool last =
        pass + 1 == passes || (options_.edges_start_a_pixel_fit && fitted.edges.sigma_px <= sigma);
    const std::optional<ConicFit> fit =
        FitEllipse(fitted.edges.points_px, last && refine_last ? options_.fit : direct);
    if (!fit) {
      fitted.error = "the edge points of a circle give no ellipse";
      return fitted;
    }
    fitted.conic = fit->conic;
    sigma = fitted.edges.sigma_px;
    if (last) break;
  }
  return fitted;
}

std::optional<CircleDetector::DiskWithDots> CircleDetector::BlurredDots(
    const cv::Mat& raw,
    const cv::Mat& smoothed,
    const Eigen::Matrix3d& conic,
    double smoothing_sigma_px,
    double noise_sigma) const {
  // The disk's ellipse, blur and levels from its edges, in the detector's passes.
  const FittedEdges fitted =
      FitEdgesInPasses(0, smoothed, conic, smoothing_sigma_px + 1.0, options_.edge_passes, false);
  if (!fitted.error.empty()) return std::nullopt;
  const CircleEdges& edges = fitted.edges;
  const double sigma = edges.sigma_px;
  DiskWithDots found;
  found.conic = fitted.conic;
  const Ellipse e = EllipseFromConic(found.conic);
  // A disk within the region, blurred by less than its size (this also bounds the work).
  if (!(e.semi_major <= std::max(raw.cols, raw.rows)) || !(sigma <= e.semi_major)) {
    return std::nullopt;
  }
  const double r0 = geometry_.radii_m[0];
  const double per_radius = std::sqrt(e.semi_major * e.semi_minor) / r0;  // px per metre
  const double dot_px = dot_radius_m_ * per_radius;
  BlurredDisk disk;
  disk.conic_px = found.conic;
  disk.sigma_px =
      std::sqrt(std::max(0.0625, sigma * sigma - smoothing_sigma_px * smoothing_sigma_px));
  // Dots blurred (with the smoothing) below the threshold's reach, or small but sharp in the
  // image itself (CircleDetectorOptions).
  const auto peak = [&](double blur_sigma_px) {
    return 1.0 - std::exp(-0.5 * std::pow(dot_px / blur_sigma_px, 2));
  };
  const bool searched = dot_px >= options_.min_blurred_dot_radius_px
                            ? peak(sigma) < options_.max_blurred_dot_peak
                            : dot_px >= options_.min_dot_radius_px &&
                                  peak(disk.sigma_px) >= options_.max_blurred_dot_peak;
  if (!searched) return std::nullopt;
  disk.inside_level = edges.inside_level;
  disk.outside_level = edges.outside_level;
  // The centre dot, near the ellipse's centre, in the disk's fit.
  if (center_dot_contrast_ != 0.0) disk.dots.push_back({e.center, dot_px, center_dot_contrast_});
  // The dots' reach: the feature dot's ring at Lx (d), the disk itself (e), and the blur (the
  // edge points' σ is low by up to a fifth under heavy blur and clipped noise).
  const double window = dot_px + options_.blurred_dots.window_sigmas * 1.5 * disk.sigma_px;
  const double reach =
      (geometry_.roll_from_design ? 1.0 : geometry_.Lx / r0) * e.semi_major + window + 2.0;
  const cv::Rect area(static_cast<int>(std::floor(e.center.x() - reach)),
                      static_cast<int>(std::floor(e.center.y() - reach)),
                      static_cast<int>(std::ceil(2.0 * reach)) + 1,
                      static_cast<int>(std::ceil(2.0 * reach)) + 1);
  const BlurredDotSearch search(raw, disk, area, 255.0 * noise_sigma, options_.blurred_dots);
  // Trial positions a quarter of the blurred dot's size apart.
  const double spacing = std::max(1.0, 0.25 * std::hypot(0.5 * dot_px, search.disk().sigma_px));
  // m0: within 0.3 of the minor axis of the ellipse's centre, as for the threshold's holes.
  std::vector<Eigen::Vector2d> positions;
  const double center_reach = 0.3 * e.semi_minor;
  for (double y = -center_reach; y <= center_reach; y += spacing) {
    for (double x = -center_reach; x <= center_reach; x += spacing) {
      if (x * x + y * y <= center_reach * center_reach) {
        positions.push_back(e.center + Eigen::Vector2d(x, y));
      }
    }
  }
  const std::optional<FoundDot> center = search.Find(
      positions, dot_px, center_dot_contrast_, options_.blurred_dots.contrast_tolerance);
  if (!center) return std::nullopt;
  found.m0_px = center->position_px;
  if (geometry_.roll_from_design) return found;
  // m1 (d): on the image of the ring at Lx, the ellipse scaled about m0 (to first order).
  const double ring = geometry_.Lx / r0;
  const Eigen::Vector2d major(std::cos(e.angle_rad), std::sin(e.angle_rad));
  const Eigen::Vector2d minor(-major.y(), major.x());
  const int steps =
      std::max(16, static_cast<int>(std::ceil(2.0 * M_PI * ring * e.semi_major / spacing)));
  positions.clear();
  for (int k = 0; k < steps; ++k) {
    const double theta = 2.0 * M_PI * k / steps;
    positions.push_back(found.m0_px + ring * (e.semi_major * std::cos(theta) * major +
                                              e.semi_minor * std::sin(theta) * minor));
  }
  const std::optional<FoundDot> feature = search.Find(
      positions, dot_px, feature_dot_contrast_, options_.blurred_dots.feature_dot_tolerance);
  if (!feature) return std::nullopt;
  found.m1_px = feature->position_px;
  return found;
}

std::optional<MarkerDetection> CircleDetector::Detect(
    const Image8& image,
    const cv::Rect& roi,
    const std::vector<Eigen::Matrix3d>* predicted_conics_px,
    std::string* why) const {
  auto fail = [why](const std::string& message) -> std::optional<MarkerDetection> {
    if (why) *why = message;
    return std::nullopt;
  };
  if (needs_color_ && image.channels != 3) {
    return fail(std::string(ToString(kind_)) + " is told apart by colour and needs an RGB image");
  }
  const cv::Mat full(image.height,
                     image.width,
                     image.channels == 3 ? CV_8UC3 : CV_8UC1,
                     const_cast<uint8_t*>(image.pixels.data()));
  const cv::Rect region = roi & cv::Rect(0, 0, image.width, image.height);
  if (region.width < 8 || region.height < 8) return fail("search region is empty");
  const cv::Mat view = full(region);
  const Eigen::Vector2d offset(region.x, region.y);

  // One smoothed image per channel in use, smoothing adapted to the noise. The colour planes
  // come from one cv::split: a cv::extractChannel per plane took a fifth of the edge path, and
  // the split less than half of that. A region is copied whole first: cv::split works on its
  // rows one at a time, at a cost per row (tracking mode's split, 130 µs a frame, took 37 with
  // the copy).
  std::map<int, cv::Mat> raw;
  std::vector<cv::Mat> planes;
  for (const ChannelPlan& plan : plans_) {
    if (raw.count(plan.channel)) continue;
    cv::Mat channel;
    if (view.channels() == 1) {
      channel = view;
    } else if (plan.channel < 0) {
      cv::cvtColor(view, channel, cv::COLOR_RGB2GRAY);
    } else {
      if (planes.empty()) cv::split(view.isContinuous() ? view : view.clone(), planes);
      channel = planes[static_cast<size_t>(plan.channel)];
    }
    raw[plan.channel] = channel;
  }
  MarkerDetection detection;
  detection.noise_sigma = EstimateNoiseSigma(raw.begin()->second);
  detection.smoothing_sigma_px =
      std::clamp(options_.smoothing_min_px + options_.smoothing_per_noise * detection.noise_sigma,
                 options_.smoothing_min_px,
                 options_.smoothing_max_px);
  // x_roi = shift * x_full.
  Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
  shift.topRightCorner<2, 1>() = -offset;
  const bool from_prediction = predicted_conics_px &&
                               geometry_.layout == CircleLayout::kTwoCircles &&
                               geometry_.m1_circle >= 0;
  std::vector<Eigen::Matrix3d> initial;
  if (from_prediction) {
    const Eigen::Matrix3d inverse_shift = shift.inverse();
    for (const Eigen::Matrix3d& C : *predicted_conics_px) {
      initial.push_back(CanonicalConic(inverse_shift.transpose() * C * inverse_shift));
    }
  }

  // Candidates are searched at half resolution in large regions (2x2 means, then the
  // smoothing at half scale); x_full = scale x_search + (scale - 1)/2.
  // Markers told apart by small dots (b, c, d) are searched at full resolution.
  const int scale = dot_radius_m_ == 0.0 && region.width >= options_.half_resolution_min_px &&
                            region.height >= options_.half_resolution_min_px
                        ? 2
                        : 1;
  std::map<int, cv::Mat> search;
  for (const auto& [channel, mat] : raw) {
    if (from_prediction) break;
    cv::Mat source = mat;
    if (scale == 2) cv::resize(mat, source, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    cv::GaussianBlur(source,
                     search[channel],
                     cv::Size(0, 0),
                     std::max(0.5, detection.smoothing_sigma_px / scale));
  }

  std::map<int, std::vector<Candidate>> candidates;
  CircleDetectorOptions search_options = options_;
  // d's feature dot is a blob of its own (and found at full resolution).
  const bool dot_is_a_blob =
      geometry_.layout == CircleLayout::kCircleWithCenter && !geometry_.roll_from_design;
  if (dot_is_a_blob) search_options.min_area_px = options_.min_dot_area_px;
  search_options.min_area_px /= scale * scale;
  for (const ChannelPlan& plan : plans_) {
    if (from_prediction) break;
    if (candidates.count(plan.channel)) continue;
    const Threshold threshold =
        FindThreshold(search[plan.channel], plan.ink_dark, threshold_fraction_);
    if (threshold.contrast < options_.min_contrast) return fail("no ink in the search region");
    candidates[plan.channel] =
        FindCandidates(search[plan.channel], plan.ink_dark, threshold, search_options);
    for (Candidate& candidate : candidates[plan.channel]) ToFullResolution(scale, &candidate);
  }

  // Identify the circles: initial ellipses in geometry order, plus the dots.
  const std::vector<double>& r = geometry_.radii_m;
  switch (from_prediction ? CircleLayout::kTwoCircles : geometry_.layout) {
    case CircleLayout::kTwoCircles: {
      if (from_prediction) break;
      const std::vector<Candidate>& first = candidates[plans_[0].channel];
      const std::vector<Candidate>& second = candidates[plans_[1].channel];
      const double separation = geometry_.centers[1].norm();
      double best_score = 0.0;
      const Hole* best_dot = nullptr;
      for (size_t i = 0; i < first.size(); ++i) {
        for (size_t j = 0; j < second.size(); ++j) {
          if (plans_[0].channel == plans_[1].channel && i == j) continue;
          const Candidate& a = first[i];
          const Candidate& b = second[j];
          // Size ratio as designed, up to perspective; centre distance in radii likewise.
          const double size_ratio = std::sqrt(a.area_px / b.area_px) / (r[0] / r[1]);
          const double distance_ratio =
              (a.centroid - b.centroid).norm() / std::sqrt(a.area_px / M_PI) / (separation / r[0]);
          if (size_ratio < 0.4 || size_ratio > 2.5 || distance_ratio < 0.35 || distance_ratio > 2.5)
            continue;
          const Hole* pair_dot = nullptr;
          if (kind_ == MarkerKind::kCirclesB) {
            // The feature dot lies in the second circle, and only there.
            const double dot_area = b.area_px * std::pow(dot_radius_m_ / r[1], 2);
            const Hole* dot =
                FindHole(b, b.ellipse.center, b.ellipse.semi_major, 0.2 * dot_area, 4.0 * dot_area);
            if (!dot ||
                FindHole(a, a.ellipse.center, a.ellipse.semi_major, 0.2 * dot_area, 4.0 * dot_area))
              continue;
            pair_dot = dot;
          }
          const double score = std::min(a.area_px, b.area_px);
          if (score > best_score) {
            best_score = score;
            initial = {a.conic, b.conic};
            best_dot = pair_dot;
          }
        }
      }
      if (initial.empty()) return fail("no pair of ellipses matches the marker");
      if (best_dot && geometry_.m1_circle < 0) detection.m1_px = best_dot->centroid + offset;
      break;
    }
    case CircleLayout::kConcentric: {
      for (const Candidate& c : candidates[plans_[0].channel]) {
        const double inner_area = c.area_px * std::pow(r[1] / r[0], 2);
        const Hole* inner = FindHole(
            c, c.ellipse.center, 0.25 * c.ellipse.semi_minor, 0.5 * inner_area, 2.0 * inner_area);
        if (!inner || !inner->conic) continue;
        const double dot_area = c.area_px * std::pow(dot_radius_m_ / r[0], 2);
        const double ring_m = geometry_.Lx;  // the feature dot lies on the ring at Lx
        const double dot_distance = ring_m * PixelsPerMetre(c.ellipse, r[0]);
        const Hole* dot = nullptr;
        for (const Hole& h : c.holes) {
          if (&h == inner || h.area_px < 0.2 * dot_area || h.area_px > 4.0 * dot_area) continue;
          const double d = (h.centroid - inner->centroid).norm();
          if (d > 0.3 * dot_distance && d < 3.0 * dot_distance) dot = &h;
        }
        if (!dot) continue;
        initial = {c.conic, *inner->conic};
        detection.m1_px = dot->centroid + offset;
        break;
      }
      if (initial.empty()) return fail("no ring with its inner circle and feature dot");
      break;
    }
    case CircleLayout::kCircleWithCenter: {
      const std::vector<Candidate>& all = candidates[plans_[0].channel];
      for (const Candidate& c : all) {
        if (c.area_px < options_.min_area_px) continue;  // a dot's size: no disk
        const double dot_area = c.area_px * std::pow(dot_radius_m_ / r[0], 2);
        const Hole* center = FindHole(
            c, c.ellipse.center, 0.3 * c.ellipse.semi_minor, 0.2 * dot_area, 4.0 * dot_area);
        if (!center) continue;
        if (geometry_.roll_from_design) {  // e: the mouth gives the roll, later
          initial = {c.conic};
          detection.m0_px = center->centroid + offset;
          break;
        }
        const double expected = geometry_.Lx / r[0] * std::sqrt(c.area_px / M_PI);
        const Candidate* dot = nullptr;
        for (const Candidate& other : all) {
          if (&other == &c || other.area_px < 0.2 * dot_area || other.area_px > 4.0 * dot_area)
            continue;
          const double d = (other.centroid - center->centroid).norm();
          if (d > 0.4 * expected && d < 2.5 * expected && (!dot || other.area_px > dot->area_px)) {
            dot = &other;
          }
        }
        if (!dot) continue;
        initial = {c.conic};
        detection.m0_px = center->centroid + offset;
        detection.m1_px = dot->centroid + offset;
        break;
      }
      // Under blur the dots fall below the threshold: look for them by their blurred images.
      for (size_t i = 0; initial.empty() && scale == 1 && i < all.size() &&
                         i < static_cast<size_t>(options_.max_blurred_dot_disks);
           ++i) {
        const std::optional<DiskWithDots> disk = BlurredDots(raw[plans_[0].channel],
                                                             search[plans_[0].channel],
                                                             all[i].conic,
                                                             detection.smoothing_sigma_px,
                                                             detection.noise_sigma);
        if (!disk) continue;
        initial = {disk->conic};
        detection.m0_px = disk->m0_px + offset;
        if (disk->m1_px) detection.m1_px = *disk->m1_px + offset;
      }
      if (initial.empty()) return fail("no disk with its centre dot and feature dot");
      break;
    }
    case CircleLayout::kSingleCircle: {
      // f: the largest ellipse; the wedge and the printed design decide later.
      const std::vector<Candidate>& all = candidates[plans_[0].channel];
      if (all.empty()) return fail("no ellipse in the search region");
      initial = {all.front().conic};
      break;
    }
  }

  // Sub-pixel edges and the conic fit, in passes that each start from the previous fit; the
  // PND refinement of the conic only in the last. A prediction needs one pass, and no PND
  // refinement: the pose refinement (cost B) works on the edges themselves; nor do the edges
  // that start a fit on the pixels.
  const int passes = from_prediction ? 1 : options_.edge_passes;
  // Full-resolution smoothing only around the circles, with room for rays at σ up to 12 px.
  // Where a first pass may be the last, only as far as its rays reach at first, the rest
  // before a later pass: smoothing a view takes its neighbours from the whole image, so a
  // pixel is smoothed as in the whole patch (to the bit where the patch is itself a view:
  // OpenCV smooths a whole image by another path, up to 2 grey levels apart). On sharp images
  // this took 5-7 % off the tracker's time (results/speed.md).
  const auto box_around = [&](const Eigen::Matrix3d& conic, int margin_px) {
    const Ellipse e = EllipseFromConic(conic);
    const int half = static_cast<int>(std::ceil(e.semi_major)) + margin_px;
    return cv::Rect(static_cast<int>(e.center.x()) - half,
                    static_cast<int>(e.center.y()) - half,
                    2 * half + 1,
                    2 * half + 1);
  };
  cv::Rect patch;
  for (size_t i = 0; i < initial.size(); ++i) {
    patch = i == 0 ? box_around(initial[i], 50) : (patch | box_around(initial[i], 50));
  }
  patch &= cv::Rect(0, 0, view.cols, view.rows);
  if (patch.empty()) return fail("the circles lie outside the search region");
  std::map<int, cv::Mat> smoothed;
  const auto smooth = [&](const cv::Mat& channel, const cv::Rect& box, cv::Mat* out) {
    if (box.empty()) return;  // a circle beside the search region: its rays find no edge
    cv::Mat into = (*out)(box - patch.tl());
    cv::GaussianBlur(channel(box), into, cv::Size(0, 0), detection.smoothing_sigma_px);
  };
  // A sample takes the pixel below and the next one, and a ray's base lies within a pixel of
  // the box's centre.
  const int first_reach_px = static_cast<int>(std::ceil(EdgeSearchReachPx(
                                 detection.smoothing_sigma_px + 1.0, options_.edges))) +
                             2;
  const bool one_pass_may_do = passes == 1 || options_.edges_start_a_pixel_fit;
  for (const auto& [channel, mat] : raw) {
    cv::Mat& out = smoothed[channel];
    out.create(patch.size(), CV_8UC1);
    if (!one_pass_may_do) {
      smooth(mat, patch, &out);
      continue;
    }
    for (size_t i = 0; i < initial.size(); ++i) {
      if (plans_[i].channel == channel) {
        smooth(mat, box_around(initial[i], first_reach_px) & patch, &out);
      }
    }
  }
  bool smoothed_whole = !one_pass_may_do;
  const auto smooth_the_rest = [&] {
    if (smoothed_whole) return;
    for (const auto& [channel, mat] : raw) smooth(mat, patch, &smoothed[channel]);
    smoothed_whole = true;
  };
  // x_patch = to_patch x_region.
  Eigen::Matrix3d to_patch = Eigen::Matrix3d::Identity();
  to_patch.topRightCorner<2, 1>() = -Eigen::Vector2d(patch.x, patch.y);
  const Eigen::Matrix3d from_patch = to_patch.inverse();
  for (Eigen::Matrix3d& C : initial) C = CanonicalConic(from_patch.transpose() * C * from_patch);
  const Eigen::Vector2d patch_offset = offset + Eigen::Vector2d(patch.x, patch.y);
  shift.topRightCorner<2, 1>() = -patch_offset;
  for (size_t i = 0; i < initial.size(); ++i) {
    FittedEdges fitted = FitEdgesInPasses(i,
                                          smoothed[plans_[i].channel],
                                          initial[i],
                                          detection.smoothing_sigma_px + 1.0,
                                          passes,
                                          !from_prediction && !options_.edges_start_a_pixel_fit,
                                          smooth_the_rest);
    if (!fitted.error.empty()) return fail(fitted.error);
    DetectedCircle circle;
    circle.edges = std::move(fitted.edges);
    circle.edge_passes = fitted.passes;
    // The edge contrast must stand out of the noise left after smoothing (a Gaussian of σ_s
    // divides white noise by 2√π σ_s): blobs of pure noise reach about 6 of those σ.
    const double contrast =
        std::abs(circle.edges.inside_level - circle.edges.outside_level) / 255.0;
    const double smoothed_noise =
        detection.noise_sigma / (2.0 * std::sqrt(M_PI) * detection.smoothing_sigma_px);
    if (contrast < options_.min_contrast || contrast < options_.min_contrast_snr * smoothed_noise) {
      return fail("circle " + std::to_string(i) + " has too little contrast for the noise");
    }
    circle.conic_px = CanonicalConic(shift.transpose() * fitted.conic * shift);
    for (Eigen::Vector2d& p : circle.edges.points_px) p += patch_offset;
    detection.circles.push_back(std::move(circle));
  }
  return detection;
}

}  // namespace markerbench
