#include "trackers/runetag/original_ellipse_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace markerbench {

std::vector<ImagedDot> DetectEllipsesAsOriginal(const cv::Mat& grey,
                                                const OriginalEllipseOptions& options) {
  cv::Mat white;
  cv::adaptiveThreshold(grey,
                        white,
                        255,
                        cv::ADAPTIVE_THRESH_MEAN_C,
                        cv::THRESH_BINARY,
                        options.block_size_px,
                        options.threshold_offset);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(white, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
  std::vector<ImagedDot> dots;
  for (const std::vector<cv::Point>& contour : contours) {
    const int points = static_cast<int>(contour.size());
    if (points < options.min_contour_points || points > options.max_contour_points) continue;
    const cv::RotatedRect ellipse = cv::fitEllipse(contour);
    const double width = ellipse.size.width, height = ellipse.size.height;
    const double area = M_PI * width * height;
    if (!(area >= options.min_area_px && area <= options.max_area_px)) continue;
    const double ratio = width / height;
    if (!(ratio >= options.min_axis_ratio && ratio <= 1.0 / options.min_axis_ratio)) continue;
    const double major = std::max(width, height), minor = std::min(width, height);
    const double angle = ellipse.angle * M_PI / 180.0 + (width < height ? M_PI / 2.0 : 0.0);
    const double focal = std::sqrt(std::max(0.0, major * major / 4.0 - minor * minor / 4.0));
    const cv::Point2d center(ellipse.center.x, ellipse.center.y);
    const cv::Point2d to_focus(std::cos(angle) * focal, std::sin(angle) * focal);
    double sum_sq = 0.0;
    for (const cv::Point& p : contour) {
      const cv::Point2d q(p.x, p.y);
      const double d = cv::norm(q - center + to_focus) + cv::norm(q - center - to_focus) - major;
      sum_sq += d * d;
    }
    if (std::sqrt(sum_sq) / points > options.max_fit_error) continue;
    const double semi_major = 0.5 * (major + options.size_compensation_px);
    const double semi_minor = 0.5 * (minor + options.size_compensation_px);
    dots.push_back({Eigen::Vector2d(center.x, center.y),
                    M_PI * std::max(semi_major, 0.0) * std::max(semi_minor, 0.0),
                    semi_major,
                    semi_minor});
  }
  return dots;
}

}  // namespace markerbench
