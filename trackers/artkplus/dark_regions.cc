#include "trackers/artkplus/dark_regions.h"

#include <opencv2/imgproc.hpp>

namespace markerbench {

DarkRegions FindDarkRegions(const uint8_t* grey,
                            int width,
                            int height,
                            const DarkRegionOptions& options) {
  const cv::Mat image(height, width, CV_8UC1, const_cast<uint8_t*>(grey));
  cv::Mat dark;
  cv::threshold(image, dark, options.threshold - 1, 255, cv::THRESH_BINARY_INV);
  DarkRegions result;
  result.width = width;
  result.height = height;
  result.labels.resize(static_cast<size_t>(width) * height);
  cv::Mat labels(height, width, CV_32S, result.labels.data());
  cv::Mat stats, centroids;
  const int count = cv::connectedComponentsWithStats(dark, labels, stats, centroids, 8, CV_32S);
  for (int label = 1; label < count; ++label) {
    const int x = stats.at<int>(label, cv::CC_STAT_LEFT);
    const int y = stats.at<int>(label, cv::CC_STAT_TOP);
    const int w = stats.at<int>(label, cv::CC_STAT_WIDTH);
    const int h = stats.at<int>(label, cv::CC_STAT_HEIGHT);
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (area < options.min_area_px || area > options.max_area_px) continue;
    if (x == 0 || y == 0 || x + w == width || y + h == height) continue;
    int first_x = x;
    while (result.LabelAt(first_x, y) != label) ++first_x;
    result.regions.push_back({label, area, {first_x, y}});
  }
  return result;
}

}  // namespace markerbench
