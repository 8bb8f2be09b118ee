#include "bench/run/pose_overlay.h"

#include <cmath>
#include <iterator>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>

namespace markerbench {
namespace {

// Segments are split so that their images bend with the lens distortion.
constexpr int kStepsPerSegment = 16;
// cv::line's fractional bits: lines drawn to 1/16 px.
constexpr int kShift = 4;

cv::Point Subpixel(const Eigen::Vector2d& px) {
  return {static_cast<int>(std::lround(px.x() * (1 << kShift))),
          static_cast<int>(std::lround(px.y() * (1 << kShift)))};
}

}  // namespace

PoseOverlay::PoseOverlay(std::string path, const Camera& camera, const MarkerSpec& marker)
    : path_(std::move(path)),
      camera_(camera),
      center_(marker.InkBounds().center()),
      axis_m_(0.5 * marker.InkBounds().sizes().maxCoeff()) {}

PoseOverlay::~PoseOverlay() = default;

void PoseOverlay::Add(const Image8& frame, const TrackResult& result, double fps) {
  Add(frame, {{std::string(), result}}, fps);
}

void PoseOverlay::Add(const Image8& frame,
                      const std::vector<std::pair<std::string, TrackResult>>& results,
                      double fps) {
  if (!writer_) {
    writer_ = std::make_unique<cv::VideoWriter>(path_,
                                                cv::CAP_FFMPEG,
                                                cv::VideoWriter::fourcc('m', 'p', '4', 'v'),
                                                fps > 0.0 ? fps : 10.0,
                                                cv::Size(camera_.width, camera_.height));
    if (!writer_->isOpened()) throw std::runtime_error(path_ + ": cannot write a video there");
  }
  cv::Mat bgr;
  const cv::Mat pixels(frame.height,
                       frame.width,
                       frame.channels == 3 ? CV_8UC3 : CV_8UC1,
                       const_cast<uint8_t*>(frame.pixels.data()));
  cv::cvtColor(pixels, bgr, frame.channels == 3 ? cv::COLOR_RGB2BGR : cv::COLOR_GRAY2BGR);
  // Cube colours (BGR), the first yellow; the axes keep red, green and blue.
  const cv::Scalar kCubeColors[] = {
      {0, 220, 255}, {255, 0, 255}, {255, 255, 0}, {0, 140, 255}, {255, 255, 255}, {128, 0, 128}};
  for (size_t t = 0; t < results.size(); ++t) {
    const cv::Scalar cube_color = kCubeColors[t % std::size(kCubeColors)];
    if (results.size() > 1) {
      cv::putText(bgr,
                  results[t].first,
                  cv::Point(8, 18 + 16 * static_cast<int>(t)),
                  cv::FONT_HERSHEY_SIMPLEX,
                  0.45,
                  cube_color,
                  1,
                  cv::LINE_AA);
    }
    const TrackResult& result = results[t].second;
    if (result.status != TrackStatus::kOk || result.hypotheses.empty()) continue;
    const Rigid3& cam_from_marker = result.hypotheses.front();
    const auto segment = [&](const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b,
                             const cv::Scalar& color,
                             int thickness) {
      for (int i = 0; i < kStepsPerSegment; ++i) {
        const Eigen::Vector3d p = cam_from_marker * (a + (b - a) * i / kStepsPerSegment);
        const Eigen::Vector3d q = cam_from_marker * (a + (b - a) * (i + 1) / kStepsPerSegment);
        if (!(p.z() > 0.0 && q.z() > 0.0)) continue;  // behind the camera
        const Eigen::Vector2d u = camera_.ImgFromCam(p), v = camera_.ImgFromCam(q);
        constexpr double kFarPx = 1e5;  // beyond any image, and within int at 1/16 px
        if (!(u.cwiseAbs().maxCoeff() < kFarPx && v.cwiseAbs().maxCoeff() < kFarPx)) continue;
        cv::line(bgr, Subpixel(u), Subpixel(v), color, thickness, cv::LINE_AA, kShift);
      }
    };
    const double s = axis_m_;
    const Eigen::Vector3d o(center_.x(), center_.y(), 0.0);
    // The cube: its bottom square on the marker around the ink centre, its top towards +z.
    const double h = 0.5 * s;
    for (const double z : {0.0, s}) {
      const Eigen::Vector3d c[4] = {o + Eigen::Vector3d(-h, -h, z),
                                    o + Eigen::Vector3d(h, -h, z),
                                    o + Eigen::Vector3d(h, h, z),
                                    o + Eigen::Vector3d(-h, h, z)};
      for (int k = 0; k < 4; ++k) {
        segment(c[k], c[(k + 1) % 4], cube_color, 1);
        if (z == 0.0) segment(c[k], c[k] + Eigen::Vector3d(0.0, 0.0, s), cube_color, 1);
      }
    }
    // The axes from the marker frame's origin (BGR: x red, y green, z blue).
    const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    segment(origin, Eigen::Vector3d(s, 0.0, 0.0), cv::Scalar(0, 0, 255), 3);
    segment(origin, Eigen::Vector3d(0.0, s, 0.0), cv::Scalar(0, 255, 0), 3);
    segment(origin, Eigen::Vector3d(0.0, 0.0, s), cv::Scalar(255, 0, 0), 3);
  }
  writer_->write(bgr);
}

}  // namespace markerbench
