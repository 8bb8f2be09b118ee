#include "trackers/circle/photometric_refinement.h"

#include <ceres/jet.h>
#include <ceres/rotation.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <vector>

#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/circle/conic.h"

namespace markerbench {
namespace {

// A printed disk and the colour step across its edge (its colour minus what lies under it),
// its edge sampled at `bins` angles.
struct EdgeLayer {
  DiskShape disk;
  Rgb jump;
  int bins = 0;
  std::vector<Eigen::Vector2d> edge;  // the bins' points on the circle, marker plane
};

// A pixel and the one edge it lies near: its signed distance to that edge is taken along the
// edge's normal at the start pose, from the edge point at the pixel's angle about the disk.
struct Pixel {
  Eigen::Vector2d ideal_px;  // undistorted pixel coordinates
  Eigen::Vector3d value;     // measured, 0-1, per channel used
  Rgb base;                  // the printed colour without the near layer's step
  int layer = 0;
  int bin = 0;
  Eigen::Vector2d normal;  // outward unit normal of the edge at the start pose
};

// The least-squares problem measured - model over every pixel and channel, in the parameters
// θ = (angle-axis (3), translation (3), σ, then offset and gain per channel). The edge points
// and disk sizes are differentiated by Jets once per bin; each pixel then chains them by hand
// and adds its rows straight into the normal equations (a dense Jacobian of thousands of rows
// would cost more than the model).
class PixelModel {
 public:
  using Jet = ceres::Jet<double, 7>;  // the pose (6) and σ

  PixelModel(const Eigen::Matrix3d& K,
             const std::vector<EdgeLayer>& layers,
             const std::vector<Pixel>& pixels,
             int channels)
      : K_(K), layers_(layers), pixels_(pixels), channels_(channels) {}

  int Parameters() const { return 7 + 2 * channels_; }

  // Σ r² at θ; with jtj and jtr, also JᵀJ and Jᵀr.
  double Evaluate(const Eigen::VectorXd& theta, Eigen::MatrixXd* jtj, Eigen::VectorXd* jtr) const {
    if (jtj) {
      jtj->setZero(Parameters(), Parameters());
      jtr->setZero(Parameters());
    }
    Jet angle_axis[3], translation[3];
    for (int k = 0; k < 3; ++k) {
      angle_axis[k] = Jet(theta[k], k);
      translation[k] = Jet(theta[3 + k], 3 + k);
    }
    const Jet sigma(theta[6], 6);
    const double* levels = theta.data() + 7;
    double cost = 0.0;
    Eigen::Matrix<Jet, 3, 3> R;
    ceres::AngleAxisToRotationMatrix(angle_axis, ceres::ColumnMajorAdapter3x3(R.data()));
    const Eigen::Matrix<Jet, 3, 1> t(translation[0], translation[1], translation[2]);
    // Each layer's edge points in the image.
    std::vector<std::vector<Eigen::Matrix<Jet, 2, 1>>> edges(layers_.size());
    // Each layer's radius in blur σ, s = R/σ (R in pixels, from its depth), and the exact
    // profile of a disk of that size blurred (blurred_disk_profile.h).
    std::vector<Jet> radii;
    std::vector<BlurredDiskProfile> profiles;
    // H = K [r1 r2 t]: plane points (X, Y, 1) to pixels.
    Eigen::Matrix<Jet, 3, 3> H;
    H << R.col(0), R.col(1), t;
    H = K_.cast<Jet>() * H;
    for (size_t l = 0; l < layers_.size(); ++l) {
      const EdgeLayer& layer = layers_[l];
      edges[l].reserve(layer.edge.size());
      for (const Eigen::Vector2d& X : layer.edge) {
        const Eigen::Matrix<Jet, 3, 1> p = H.col(0) * X.x() + H.col(1) * X.y() + H.col(2);
        edges[l].emplace_back(p.x() / p.z(), p.y() / p.z());
      }
      const Eigen::Matrix<Jet, 3, 1> center(
          Jet(layer.disk.center.x()), Jet(layer.disk.center.y()), Jet(0.0));
      radii.push_back(K_(0, 0) * layer.disk.radius / (R * center + t).z() / sigma);
      profiles.emplace_back(radii.back().a);
    }
    // Per pixel in doubles: d = n·(x - e) (px, positive outside), z = -d/σ, inside = G(s, z),
    // chained to the 7 Jet parameters through e, s and σ.
    const double sigma_value = sigma.a;
    Eigen::Matrix<double, 7, 1> d_sigma = Eigen::Matrix<double, 7, 1>::Zero();
    d_sigma[6] = 1.0;
    for (size_t i = 0; i < pixels_.size(); ++i) {
      const Pixel& p = pixels_[i];
      const Eigen::Matrix<Jet, 2, 1>& edge = edges[p.layer][p.bin];
      const double d = p.normal.x() * (p.ideal_px.x() - edge.x().a) +
                       p.normal.y() * (p.ideal_px.y() - edge.y().a);
      const Eigen::Matrix<double, 7, 1> d_d =
          -p.normal.x() * edge.x().v - p.normal.y() * edge.y().v;
      const double z = -d / sigma_value;
      const Eigen::Matrix<double, 7, 1> d_z =
          -d_d / sigma_value + (d / (sigma_value * sigma_value)) * d_sigma;
      const ProfileValue g = profiles[p.layer].At(z);
      const double inside = g.value;
      const Eigen::Matrix<double, 7, 1> d_inside = g.d_dz * d_z + g.d_ds * radii[p.layer].v;
      const Rgb& jump = layers_[p.layer].jump;
      // Each channel's row is (-gain step d_inside, -1, -printed) on (θ 0-6, its offset and
      // gain): the θ part is one vector scaled, so the channels share one outer product.
      double pose_weight = 0.0;    // Σ_c (gain step)²
      double pose_residual = 0.0;  // Σ_c r (-gain step)
      for (int c = 0; c < channels_; ++c) {
        const double base = channels_ == 3 ? p.base[c] : Luma(p.base);
        const double step = channels_ == 3 ? jump[c] : Luma(jump);
        const double printed = base + step * inside;
        const double gain = levels[2 * c + 1];
        const double r = p.value[c] - (levels[2 * c] + gain * printed);
        cost += r * r;
        if (!jtj) continue;
        const double scale = -gain * step;
        pose_weight += scale * scale;
        pose_residual += r * scale;
        const int level = 7 + 2 * c;
        const Eigen::Vector2d level_row(-1.0, -printed);
        jtj->block<7, 2>(0, level) += (scale * d_inside) * level_row.transpose();
        jtj->block<2, 2>(level, level) += level_row * level_row.transpose();
        jtr->segment<2>(level) += r * level_row;
      }
      if (!jtj) continue;
      jtj->topLeftCorner<7, 7>() += pose_weight * d_inside * d_inside.transpose();
      jtr->head<7>() += pose_residual * d_inside;
    }
    if (jtj) {
      // The lower blocks of the levels' columns, by symmetry.
      jtj->bottomLeftCorner(2 * channels_, 7) = jtj->topRightCorner(7, 2 * channels_).transpose();
    }
    return cost;
  }

 private:
  Eigen::Matrix3d K_;
  const std::vector<EdgeLayer>& layers_;
  const std::vector<Pixel>& pixels_;
  int channels_;
};

// The marker's disks as edges seen through H (nullopt for other shapes, or a disk too small
// for the blur), with their image conics.
std::optional<std::vector<EdgeLayer>> EdgeLayers(const MarkerSpec& marker,
                                                 const Eigen::Matrix3d& H,
                                                 double sigma_px,
                                                 const PhotometricOptions& options,
                                                 std::vector<Eigen::Matrix3d>* conics) {
  std::vector<EdgeLayer> layers;
  for (size_t i = 0; i < marker.layers.size(); ++i) {
    const auto* disk = std::get_if<DiskShape>(&marker.layers[i].shape);
    if (!disk) return std::nullopt;
    Rgb below = marker.background;
    for (size_t j = 0; j < i; ++j) {
      const PaintSample under = PaintAt(marker.layers[j], disk->center);
      if (under.color) below = *under.color;
    }
    conics->push_back(CanonicalConic(ImageOfCircle<double>(H, disk->center, disk->radius)));
    const Ellipse e = EllipseFromConic(conics->back());
    // An image that is no finite ellipse (a disk across the horizon) cannot be modelled.
    if (!(e.semi_minor > 0.0 && e.semi_major < 1e5 && e.center.allFinite() &&
          e.center.cwiseAbs().maxCoeff() < 1e6)) {
      return std::nullopt;
    }
    if (sigma_px > options.max_blur_per_radius * std::sqrt(e.semi_major * e.semi_minor)) {
      return std::nullopt;
    }
    // Edge points about half a pixel apart.
    const int bins = std::max(32, static_cast<int>(std::ceil(4.0 * M_PI * e.semi_major)));
    layers.push_back({*disk, marker.layers[i].color - below, bins, {}});
    for (int k = 0; k < bins; ++k) {
      const double angle = 2.0 * M_PI * k / bins;
      layers.back().edge.push_back(
          disk->center + disk->radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
    }
  }
  return layers;
}

// The pixels within `band` of an edge through H, each tied to its nearest edge.
std::vector<Pixel> PixelsNearEdges(const Image8& image,
                                   const Camera& camera,
                                   const MarkerSpec& marker,
                                   const std::vector<EdgeLayer>& layers,
                                   const std::vector<Eigen::Matrix3d>& conics,
                                   const Eigen::Matrix3d& H,
                                   double band) {
  const Eigen::Matrix3d K = camera.K();
  const Eigen::Matrix3d plane_from_px = H.inverse();
  std::vector<Pixel> pixels;
  std::vector<uint8_t> taken(static_cast<size_t>(image.width) * image.height, 0);
  for (size_t l = 0; l < layers.size(); ++l) {
    const EdgeLayer& layer = layers[l];
    const Ellipse e = EllipseFromConic(conics[l]);
    const int reach = static_cast<int>(std::ceil(e.semi_major + band + 2.0));
    const int u0 = std::max(0, static_cast<int>(e.center.x()) - reach);
    const int v0 = std::max(0, static_cast<int>(e.center.y()) - reach);
    const int u1 = std::min(image.width - 1, static_cast<int>(e.center.x()) + reach);
    const int v1 = std::min(image.height - 1, static_cast<int>(e.center.y()) + reach);
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        uint8_t& seen = taken[static_cast<size_t>(v) * image.width + u];
        if (seen) continue;
        const Eigen::Vector3d ray = camera.CamFromImg(Eigen::Vector2d(u, v));
        const Eigen::Vector2d ideal(K(0, 0) * ray.x() + K(0, 2), K(1, 1) * ray.y() + K(1, 2));
        int nearest = -1;
        double nearest_distance = band;
        for (size_t m = 0; m < layers.size(); ++m) {
          const double d = std::abs(PndResidual<double>(conics[m], ideal.x(), ideal.y()));
          if (d <= nearest_distance) {
            nearest = static_cast<int>(m);
            nearest_distance = d;
          }
        }
        if (nearest != static_cast<int>(l)) continue;
        seen = 1;
        Pixel p;
        p.ideal_px = ideal;
        p.value = Eigen::Vector3d::Zero();
        for (int c = 0; c < image.channels; ++c) p.value[c] = image.at(u, v, c) / 255.0;
        p.layer = nearest;
        const Eigen::Vector2d on_plane = (plane_from_px * ideal.homogeneous()).hnormalized();
        const Eigen::Vector2d radial = on_plane - layer.disk.center;
        double angle = std::atan2(radial.y(), radial.x());
        if (angle < 0.0) angle += 2.0 * M_PI;
        p.bin = static_cast<int>(std::lround(angle / (2.0 * M_PI) * layer.bins)) % layer.bins;
        // The printed colour without this layer: the top-most other layer painting it.
        p.base = marker.background;
        for (size_t m = 0; m < layers.size(); ++m) {
          const PaintSample other = PaintAt(marker.layers[m], on_plane);
          if (m != l && other.color) p.base = *other.color;
        }
        // The edge's outward normal at the start pose, at the pixel's bin.
        const Eigen::Vector2d edge_plane = layer.edge[p.bin];
        const Eigen::Vector2d edge_px = (H * edge_plane.homogeneous()).hnormalized();
        const Eigen::Vector2d outward_px =
            (H * (edge_plane + 1e-3 * (edge_plane - layer.disk.center)).homogeneous())
                .hnormalized() -
            edge_px;
        p.normal = (conics[l] * edge_px.homogeneous()).head<2>().normalized();
        if (p.normal.dot(outward_px) < 0.0) p.normal = -p.normal;
        pixels.push_back(p);
      }
    }
  }
  return pixels;
}

// Levenberg-Marquardt on the normal equations (Marquardt's diagonal scaling) from a pose and
// σ, gains 1 and offsets 0.
PhotometricResult Solve(const PixelModel& model,
                        const Rigid3& cam_from_marker,
                        double sigma_px,
                        int max_iterations) {
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(model.Parameters());
  ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(cam_from_marker.rotation.data()),
                                   theta.data());
  theta.segment<3>(3) = cam_from_marker.translation;
  theta[6] = sigma_px;
  for (int gain = 8; gain < model.Parameters(); gain += 2) theta[gain] = 1.0;
  Eigen::MatrixXd jtj;
  Eigen::VectorXd jtr;
  double cost = model.Evaluate(theta, &jtj, &jtr);
  PhotometricResult result;
  result.initial_cost = 0.5 * cost;
  double damping = 1e-3;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Eigen::MatrixXd damped = jtj;
    damped.diagonal() += damping * jtj.diagonal();
    Eigen::VectorXd trial = theta + damped.ldlt().solve(-jtr);
    trial[6] = std::max(trial[6], 0.2);
    const double trial_cost = model.Evaluate(trial, nullptr, nullptr);
    ++result.iterations;
    if (!(trial_cost < cost)) {
      damping *= 10.0;
      if (damping > 1e6) break;
      continue;
    }
    const bool converged = cost - trial_cost < 1e-6 * cost;  // Ceres's function tolerance
    theta = trial;
    cost = model.Evaluate(theta, &jtj, &jtr);
    damping = std::max(damping / 10.0, 1e-9);
    if (converged) break;
  }
  ceres::AngleAxisToRotationMatrix(
      theta.data(), ceres::ColumnMajorAdapter3x3(result.cam_from_marker.rotation.data()));
  result.cam_from_marker.translation = theta.segment<3>(3);
  result.sigma_px = theta[6];
  result.final_cost = 0.5 * cost;
  return result;
}

// One solve on the pixels near the edges at `cam_from_marker`, each tied to its edge point.
std::optional<PhotometricResult> RefineOnce(const Image8& image,
                                            const Camera& camera,
                                            const MarkerSpec& marker,
                                            const Rigid3& cam_from_marker,
                                            double sigma_px,
                                            const PhotometricOptions& options) {
  const Eigen::Matrix3d H = camera.K() * RayFromPlane(cam_from_marker);
  std::vector<Eigen::Matrix3d> conics;
  const std::optional<std::vector<EdgeLayer>> layers =
      EdgeLayers(marker, H, sigma_px, options, &conics);
  if (!layers) return std::nullopt;
  const double sigma = std::max(sigma_px, 0.3);
  const std::vector<Pixel> pixels =
      PixelsNearEdges(image, camera, marker, *layers, conics, H, options.band_sigmas * sigma + 1.0);
  if (pixels.size() < 20) return std::nullopt;
  const PixelModel model(camera.K(), *layers, pixels, image.channels);
  PhotometricResult result = Solve(model, cam_from_marker, sigma, options.max_iterations);
  result.pixels = static_cast<int>(pixels.size());
  return result;
}

}  // namespace

std::optional<PhotometricResult> RefinePhotometric(const Image8& image,
                                                   const Camera& camera,
                                                   const MarkerSpec& marker,
                                                   const Rigid3& cam_from_marker,
                                                   double sigma_px,
                                                   const PhotometricOptions& options) {
  // Each solve ties pixels to edge points at its start; from a start a few pixels off that
  // tie is loose, so the pixels are chosen again at the result until it stays put.
  std::optional<PhotometricResult> result =
      RefineOnce(image, camera, marker, cam_from_marker, sigma_px, options);
  for (int round = 1; result && round < options.max_rounds; ++round) {
    const std::optional<PhotometricResult> next =
        RefineOnce(image, camera, marker, result->cam_from_marker, result->sigma_px, options);
    if (!next) break;
    const double moved_m =
        (next->cam_from_marker.translation - result->cam_from_marker.translation).norm();
    const int iterations = result->iterations + next->iterations;
    result = next;
    result->iterations = iterations;
    if (moved_m < 1e-4 * result->cam_from_marker.translation.norm()) break;
  }
  return result;
}

}  // namespace markerbench
