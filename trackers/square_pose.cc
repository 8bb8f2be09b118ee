#include "trackers/square_pose.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/calib3d.hpp>

namespace markerbench {

std::vector<Rigid3> SquarePoseHypotheses(const std::array<Eigen::Vector2d, 4>& corners_px,
                                         double size_m,
                                         const Camera& camera) {
  const float s = static_cast<float>(0.5 * size_m);
  // IPPE_SQUARE's required object order equals our square corner order.
  const std::vector<cv::Point3f> object = {{-s, s, 0}, {s, s, 0}, {s, -s, 0}, {-s, -s, 0}};
  std::vector<cv::Point2f> image;
  for (const Eigen::Vector2d& c : corners_px) {
    image.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()));
  }
  cv::Mat K = (cv::Mat_<double>(3, 3) << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  cv::Mat dist(1, 5, CV_64F);
  for (int i = 0; i < 5; ++i) dist.at<double>(i) = camera.distortion[static_cast<size_t>(i)];
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat errors;
  cv::solvePnPGeneric(object,
                      image,
                      K,
                      dist,
                      rvecs,
                      tvecs,
                      false,
                      cv::SOLVEPNP_IPPE_SQUARE,
                      cv::noArray(),
                      cv::noArray(),
                      errors);
  // IPPE is closed-form from the homography's Jacobian at the centre; near fronto-parallel
  // views it is off by about 2°. Each hypothesis is polished by LM on the four corners.
  std::vector<double> rms(rvecs.size());
  for (size_t i = 0; i < rvecs.size(); ++i) {
    cv::solvePnPRefineLM(object, image, K, dist, rvecs[i], tvecs[i]);
    std::vector<cv::Point2f> projected;
    cv::projectPoints(object, rvecs[i], tvecs[i], K, dist, projected);
    double sum = 0.0;
    for (size_t k = 0; k < 4; ++k) {
      const cv::Point2f d = projected[k] - image[k];
      sum += d.dot(d);
    }
    rms[i] = std::sqrt(sum / 4.0);
  }
  std::vector<size_t> order(rvecs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return rms[a] < rms[b]; });
  std::vector<Rigid3> hypotheses;
  for (size_t i : order) {
    cv::Mat R;
    cv::Rodrigues(rvecs[i], R);
    Rigid3 pose;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) pose.rotation(r, c) = R.at<double>(r, c);
      pose.translation[r] = tvecs[i].at<double>(r);
    }
    hypotheses.push_back(pose);
  }
  return hypotheses;
}

}  // namespace markerbench
