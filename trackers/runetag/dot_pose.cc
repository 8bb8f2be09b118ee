#include "trackers/runetag/dot_pose.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>

#include "core/random.h"
#include "trackers/circle/conic.h"
#include "trackers/upper_median.h"

namespace markerbench {
namespace {

const cv::TermCriteria kLmCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12);

Rigid3 PoseFromVectors(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  Rigid3 pose;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) pose.rotation(r, c) = R.at<double>(r, c);
    pose.translation[r] = tvec.at<double>(r);
  }
  return pose;
}

// A pose (OpenCV vectors) and the correspondences it was fitted to.
struct PnpFit {
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
};

// RANSAC: IPPE on 4 random correspondences, scored by the reprojection inliers; then IPPE
// and LM on the inliers, which are narrowed to 3 robust sigmas of that fit for a last LM.
std::optional<PnpFit> RansacIppePose(const std::vector<cv::Point3d>& object,
                                     const std::vector<cv::Point2d>& measured,
                                     const cv::Mat& K_cv,
                                     const DotPoseOptions& options) {
  const auto residuals = [&](const cv::Mat& r, const cv::Mat& t) {
    std::vector<cv::Point2d> projected;
    cv::projectPoints(object, r, t, K_cv, cv::noArray(), projected);
    std::vector<double> e(object.size());
    for (size_t i = 0; i < object.size(); ++i) e[i] = cv::norm(projected[i] - measured[i]);
    return e;
  };
  const auto inliers_below = [](const std::vector<double>& e, double threshold) {
    std::vector<int> index;
    for (size_t i = 0; i < e.size(); ++i) {
      if (e[i] < threshold) index.push_back(static_cast<int>(i));
    }
    return index;
  };
  Rng rng(options.ransac_seed);
  const size_t n = object.size();
  cv::Mat rvec, tvec;
  std::vector<int> inlier_index;
  for (int it = 0; it < options.ransac_iterations; ++it) {
    std::array<size_t, 4> pick;
    for (size_t k = 0; k < 4; ++k) {
      bool repeated = true;
      while (repeated) {
        pick[k] = static_cast<size_t>(rng.NextU64() % n);
        repeated = std::find(pick.begin(), pick.begin() + k, pick[k]) != pick.begin() + k;
      }
    }
    std::vector<cv::Point3d> sample_object;
    std::vector<cv::Point2d> sample_image;
    for (size_t k : pick) {
      sample_object.push_back(object[k]);
      sample_image.push_back(measured[k]);
    }
    cv::Mat r, t;
    if (!cv::solvePnP(
            sample_object, sample_image, K_cv, cv::noArray(), r, t, false, cv::SOLVEPNP_IPPE)) {
      continue;
    }
    std::vector<int> index = inliers_below(residuals(r, t), options.ransac_reprojection_px);
    if (index.size() > inlier_index.size()) {
      inlier_index = index;
      rvec = r;
      tvec = t;
      if (inlier_index.size() == n) break;
    }
  }
  if (inlier_index.size() < 4) return std::nullopt;
  // A small or distant marker seen nearly face-on fits a 4-dot sample in both of the
  // planar pose's mirror-image solutions within the RANSAC threshold, so the sample's choice
  // between them is arbitrary: choose again with IPPE on all the inliers, each of its two
  // solutions refined by LM, by the lower reprojection error.
  std::vector<cv::Point3d> inlier_object;
  std::vector<cv::Point2d> inlier_measured;
  const auto select = [&](const std::vector<int>& index) {
    inlier_object.clear();
    inlier_measured.clear();
    for (int i : index) {
      inlier_object.push_back(object[i]);
      inlier_measured.push_back(measured[i]);
    }
  };
  select(inlier_index);
  std::vector<cv::Mat> rvecs, tvecs;
  cv::solvePnPGeneric(
      inlier_object, inlier_measured, K_cv, cv::noArray(), rvecs, tvecs, false, cv::SOLVEPNP_IPPE);
  double best_error = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < rvecs.size(); ++k) {
    cv::solvePnPRefineLM(
        inlier_object, inlier_measured, K_cv, cv::noArray(), rvecs[k], tvecs[k], kLmCriteria);
    const std::vector<double> e = residuals(rvecs[k], tvecs[k]);
    double error = 0.0;
    for (int i : inlier_index) error += e[i] * e[i];
    if (error < best_error) {
      best_error = error;
      rvec = rvecs[k];
      tvec = tvecs[k];
    }
  }
  // Keep the inliers within 3 robust sigmas (at least kMinInlierPx) of that fit, and LM
  // again: dots mis-centred by a px or two are not RANSAC outliers at
  // ransac_reprojection_px but still bias the pose.
  constexpr double kMinInlierPx = 0.3;
  std::vector<double> e = residuals(rvec, tvec);
  std::vector<double> sorted;
  for (int i : inlier_index) sorted.push_back(e[i]);
  const double sigma = 1.4826 * UpperMedian(sorted);
  inlier_index = inliers_below(
      e, std::min(options.ransac_reprojection_px, std::max(kMinInlierPx, 3.0 * sigma)));
  if (inlier_index.size() < 4) return std::nullopt;
  select(inlier_index);
  cv::solvePnPRefineLM(
      inlier_object, inlier_measured, K_cv, cv::noArray(), rvec, tvec, kLmCriteria);
  return PnpFit{rvec, tvec, inlier_index};
}

}  // namespace

std::optional<DotPose> EstimateDotPose(const std::vector<Eigen::Vector2d>& centers_px,
                                       const std::vector<Eigen::Vector2d>& dots_xy,
                                       const std::vector<double>& dot_radii_m,
                                       const Camera& camera,
                                       const DotPoseOptions& options) {
  if (centers_px.size() < 4) return std::nullopt;
  // Everything runs on undistorted pixels with an ideal camera.
  const Eigen::Matrix3d K = camera.K();
  const cv::Mat K_cv =
      (cv::Mat_<double>(3, 3) << K(0, 0), 0, K(0, 2), 0, K(1, 1), K(1, 2), 0, 0, 1);
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> measured;
  for (size_t i = 0; i < centers_px.size(); ++i) {
    object.emplace_back(dots_xy[i].x(), dots_xy[i].y(), 0.0);
    const Eigen::Vector2d ideal = camera.IdealFromImg(centers_px[i]);
    measured.emplace_back(ideal.x(), ideal.y());
  }
  std::optional<PnpFit> fit;
  if (options.ransac) {
    fit = RansacIppePose(object, measured, K_cv, options);
  } else {
    // The original's findPose: cv::solvePnP (iterative) on every matched dot.
    fit.emplace();
    for (size_t i = 0; i < object.size(); ++i) fit->inliers.push_back(static_cast<int>(i));
    if (!cv::solvePnP(object,
                      measured,
                      K_cv,
                      cv::noArray(),
                      fit->rvec,
                      fit->tvec,
                      false,
                      cv::SOLVEPNP_ITERATIVE)) {
      fit.reset();
    }
  }
  if (!fit) return std::nullopt;
  cv::Mat rvec = fit->rvec, tvec = fit->tvec;
  const std::vector<int>& inlier_index = fit->inliers;
  std::vector<cv::Point3d> inlier_object;
  std::vector<cv::Point2d> inlier_measured, corrected;
  for (int i : inlier_index) {
    inlier_object.push_back(object[i]);
    inlier_measured.push_back(measured[i]);
  }
  // Perspective bias (circle-method.md §4.6): under cam_from_marker, dot k's circle images to
  // an ellipse whose centre is off the image of the dot's centre; measure the centre of the
  // latter by removing that offset from the ellipse centre measured.
  for (int pass = 0; pass < options.refinement_passes; ++pass) {
    const Rigid3 pose = PoseFromVectors(rvec, tvec);
    const Eigen::Matrix3d H = K * RayFromPlane(pose);
    corrected.clear();
    for (size_t k = 0; k < inlier_index.size(); ++k) {
      const size_t i = static_cast<size_t>(inlier_index[k]);
      const Eigen::Vector2d center = dots_xy[i];
      const Eigen::Vector2d ellipse_center =
          EllipseFromConic(CanonicalConic(ImageOfCircle<double>(H, center, dot_radii_m[i]))).center;
      const Eigen::Vector2d imaged_center = (H * center.homogeneous()).hnormalized();
      const Eigen::Vector2d offset = ellipse_center - imaged_center;
      corrected.emplace_back(measured[i].x - offset.x(), measured[i].y - offset.y());
    }
    cv::solvePnPRefineLM(inlier_object, corrected, K_cv, cv::noArray(), rvec, tvec, kLmCriteria);
  }
  const std::vector<cv::Point2d>& final_points = corrected.empty() ? inlier_measured : corrected;
  std::vector<cv::Point2d> projected;
  cv::projectPoints(inlier_object, rvec, tvec, K_cv, cv::noArray(), projected);
  double sum_sq = 0.0;
  for (size_t k = 0; k < projected.size(); ++k) {
    const cv::Point2d d = projected[k] - final_points[k];
    sum_sq += d.dot(d);
  }
  return DotPose{PoseFromVectors(rvec, tvec),
                 static_cast<int>(inlier_index.size()),
                 std::sqrt(sum_sq / projected.size())};
}

}  // namespace markerbench
