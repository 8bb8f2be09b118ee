#include "trackers/runetag/dot_detector.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <opencv2/imgproc.hpp>

#include "trackers/noise_estimate.h"
#include "trackers/pixel_area_blur.h"
#include "trackers/upper_median.h"

namespace markerbench {
namespace {

const std::function<bool(int, int)> kAnyPixel = [](int, int) { return true; };

// Contours of 12 points or fewer are too pixelated for the shape check.
constexpr size_t kMinContourForShapeCheck = 12;

// The median level of the rim of `box` (the paper around a dot; robust to noise).
double RimLevel(const cv::Mat& image, const cv::Rect& box) {
  std::vector<uint8_t> rim;
  for (int x = box.x; x < box.br().x; ++x) {
    rim.push_back(image.at<uint8_t>(box.y, x));
    rim.push_back(image.at<uint8_t>(box.br().y - 1, x));
  }
  for (int y = box.y + 1; y + 1 < box.br().y; ++y) {
    rim.push_back(image.at<uint8_t>(y, box.x));
    rim.push_back(image.at<uint8_t>(y, box.br().x - 1));
  }
  return UpperMedian(rim);
}

// Per-image acceptance limits of a dot.
struct DotLimits {
  double min_area = 0.0, max_area = 0.0;  // px^2
  double min_contrast = 0.0;              // 0..255
};

// The dot whose outline is `contour` (image coordinates), with a darkness-weighted centroid
// and moment ellipse over the blob grown by 1 px; nullopt when it fails the size or shape
// filters; misshapen says it failed the shape checks, so that merged dots can be split.
// owns(x, y): whether a pixel may count for this dot (not nearer another part of a split).
std::optional<ImagedDot> MeasureDot(const cv::Mat& image,
                                    const std::vector<cv::Point>& contour,
                                    const DotLimits& limits,
                                    const DotDetectorOptions& options,
                                    const std::function<bool(int, int)>& owns,
                                    bool* misshapen) {
  *misshapen = false;
  const cv::Rect frame(0, 0, image.cols, image.rows);
  const cv::Rect box = cv::boundingRect(contour);
  if (box.x == 0 || box.y == 0 || box.br().x >= image.cols || box.br().y >= image.rows) {
    return std::nullopt;
  }
  // Pixel area of the blob: the contour's area plus the half pixel its outline leaves out.
  const double area = cv::contourArea(contour) + 0.5 * static_cast<double>(contour.size()) + 1;
  if (area < limits.min_area || area > limits.max_area) {
    return std::nullopt;
  }
  const cv::Rect grown = (box + cv::Size(4, 4) - cv::Point(2, 2)) & frame;
  cv::Mat mask = cv::Mat::zeros(grown.size(), CV_8UC1);
  cv::drawContours(mask,
                   std::vector<std::vector<cv::Point>>{contour},
                   0,
                   255,
                   cv::FILLED,
                   cv::LINE_8,
                   cv::noArray(),
                   0,
                   -grown.tl());
  cv::dilate(mask, mask, cv::Mat());
  const double paper = RimLevel(image, grown);
  double m0 = 0.0, darkness = 0.0;
  Eigen::Vector2d m1 = Eigen::Vector2d::Zero();
  Eigen::Matrix2d m2 = Eigen::Matrix2d::Zero();
  for (int y = grown.y; y < grown.br().y; ++y) {
    for (int x = grown.x; x < grown.br().x; ++x) {
      if (!mask.at<uint8_t>(y - grown.y, x - grown.x) || !owns(x, y)) continue;
      const double w = std::max(0.0, paper - image.at<uint8_t>(y, x));
      darkness = std::max(darkness, w);
      const Eigen::Vector2d p(x, y);
      m0 += w;
      m1 += w * p;
      m2 += w * p * p.transpose();
    }
  }
  if (!(m0 > 0.0) || darkness < limits.min_contrast) return std::nullopt;
  const Eigen::Vector2d center = m1 / m0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(m2 / m0 - center * center.transpose());
  // A uniform ellipse with semi-axes a, b has variances a^2/4 and b^2/4; pixel sampling of a
  // box-filtered image adds the pixel's area.
  const double minor_var = std::max(eig.eigenvalues()(0) - kPixelAreaVariance, 1e-6);
  const double major_var = std::max(eig.eigenvalues()(1) - kPixelAreaVariance, 1e-6);
  const ImagedDot dot{center, area, 2.0 * std::sqrt(major_var), 2.0 * std::sqrt(minor_var)};
  if (dot.semi_minor_px < options.min_axis_ratio * dot.semi_major_px) {
    *misshapen = true;
    return std::nullopt;
  }
  if (contour.size() > kMinContourForShapeCheck) {
    // The outline (boundary pixel centres, about half a pixel inside the edge) should lie on
    // the moment ellipse shrunk by that half pixel.
    const Eigen::Matrix2d axes = eig.eigenvectors();
    double sum_sq = 0.0;
    for (const cv::Point& q : contour) {
      const Eigen::Vector2d d = axes.transpose() * (Eigen::Vector2d(q.x, q.y) - center);
      const double r = std::hypot(d.x() / std::max(dot.semi_minor_px - 0.5, 0.5),
                                  d.y() / std::max(dot.semi_major_px - 0.5, 0.5));
      sum_sq += (r - 1.0) * (r - 1.0);
    }
    if (std::sqrt(sum_sq / static_cast<double>(contour.size())) > options.max_fit_error) {
      *misshapen = true;
      return std::nullopt;
    }
  }
  return dot;
}

// Deliberate difference: a blob that is not one ellipse may be dots that the mean threshold
// merged across their anti-aliased gaps. Split it at levels from halfway between its darkest
// pixel and the paper around it towards the darkest (narrow gaps need a deeper cut), and keep
// the cut that yields the most dots.
std::vector<ImagedDot> SplitMergedDots(const cv::Mat& image,
                                       const std::vector<cv::Point>& contour,
                                       const DotLimits& limits,
                                       const DotDetectorOptions& options) {
  const cv::Rect box = cv::boundingRect(contour) + cv::Size(2, 2) - cv::Point(1, 1);
  const cv::Rect roi = box & cv::Rect(0, 0, image.cols, image.rows);
  double darkest = 0.0;
  cv::minMaxLoc(image(roi), &darkest);
  const double paper = RimLevel(image, roi);
  std::vector<ImagedDot> best;
  for (double depth : options.split_depths) {
    cv::Mat split;
    cv::threshold(
        image(roi), split, darkest + depth * (paper - darkest), 255, cv::THRESH_BINARY_INV);
    std::vector<std::vector<cv::Point>> parts;
    cv::findContours(split, parts, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE, roi.tl());
    if (parts.size() < 2) continue;
    // Each pixel of the box counts only for the part nearest to it.
    cv::Mat distance, nearest;
    cv::distanceTransform(
        255 - split, distance, nearest, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_CCOMP);
    std::vector<ImagedDot> found;
    for (const std::vector<cv::Point>& part : parts) {
      // The box may hold the edge of a neighbouring dot, which has its own contour.
      const cv::Rect part_box = cv::boundingRect(part);
      const cv::Point2f part_centre(part_box.x + 0.5f * (part_box.width - 1),
                                    part_box.y + 0.5f * (part_box.height - 1));
      if (cv::pointPolygonTest(contour, part_centre, false) < 0) continue;
      const cv::Point inside = part.front() - roi.tl();
      const int label = nearest.at<int>(inside.y, inside.x);
      const auto owns = [&](int x, int y) {
        return roi.contains({x, y}) && nearest.at<int>(y - roi.y, x - roi.x) == label;
      };
      bool part_misshapen = false;
      if (const std::optional<ImagedDot> dot =
              MeasureDot(image, part, limits, options, owns, &part_misshapen)) {
        found.push_back(*dot);
      }
    }
    if (found.size() > best.size()) best = found;
  }
  return best;
}

}  // namespace

DotImage SmoothForDots(const cv::Mat& grey, const DotDetectorOptions& options) {
  const double noise_sigma = EstimateNoiseSigma(grey);
  const double smoothing_px =
      std::min(options.max_smoothing_px, options.smoothing_per_noise * noise_sigma);
  DotImage result{grey, 255.0 * noise_sigma};
  if (smoothing_px > 0.3) {
    // Into a buffer of its own: `grey` is the caller's frame, which other trackers read after
    // this one (blurred into result.smoothed, which shared it, it was blurred in place).
    cv::Mat smoothed;
    cv::GaussianBlur(grey, smoothed, cv::Size(), smoothing_px);
    result.smoothed = smoothed;
    result.noise /= 2.0 * std::sqrt(M_PI) * smoothing_px;  // white noise under a Gaussian of σ_s
  }
  return result;
}

std::vector<ImagedDot> DetectDots(const DotImage& dot_image, const DotDetectorOptions& options) {
  const cv::Mat& image = dot_image.smoothed;
  const double noise = dot_image.noise;
  const int width = image.cols, height = image.rows;
  cv::Mat dark;
  cv::adaptiveThreshold(image,
                        dark,
                        255,
                        cv::ADAPTIVE_THRESH_MEAN_C,
                        cv::THRESH_BINARY_INV,
                        options.block_size_px,
                        std::max(options.threshold_offset, options.offset_per_noise * noise));
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(dark, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const double scale_sq = static_cast<double>(width) * height / (640.0 * 480.0);
  DotLimits limits;
  limits.min_area = options.min_area_px * scale_sq;
  limits.max_area = options.max_area_px * scale_sq;
  limits.min_contrast = std::max(options.min_contrast, options.contrast_per_noise * noise);
  std::vector<ImagedDot> dots;
  for (const std::vector<cv::Point>& contour : contours) {
    bool misshapen = false;
    if (const std::optional<ImagedDot> dot =
            MeasureDot(image, contour, limits, options, kAnyPixel, &misshapen)) {
      dots.push_back(*dot);
      continue;
    }
    if (!misshapen) continue;
    const std::vector<ImagedDot> parts = SplitMergedDots(image, contour, limits, options);
    dots.insert(dots.end(), parts.begin(), parts.end());
  }
  return dots;
}

}  // namespace markerbench
