#include "trackers/circle/subpixel_edges.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/circle/conic.h"
#include "trackers/upper_median.h"

namespace markerbench {
namespace {

// Bilinear sample; callers keep (x, y) inside [0, w-1] x [0, h-1].
double Sample(const cv::Mat& image, double x, double y) {
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = std::min(x0 + 1, image.cols - 1), y1 = std::min(y0 + 1, image.rows - 1);
  const double fx = x - x0, fy = y - y0;
  const uint8_t* r0 = image.ptr<uint8_t>(y0);
  const uint8_t* r1 = image.ptr<uint8_t>(y1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x1]);
}

// In the affine frame y = M (x - centre), M = diag(ρ/a, ρ/b) Rᵀ, the hypothesised ellipse is
// a circle of radius ρ = √(ab) and the blur an anisotropic Gaussian σ² M Mᵀ. A ray along the
// image normal moves radially in that frame by `radial_gain` per pixel; the blur there has
// normal and tangential widths σ·normal_blur and σ·tangential_blur.
struct Ray {
  Eigen::Vector2d base;    // on the hypothesised ellipse
  Eigen::Vector2d normal;  // unit, outward
  double radial_gain = 1.0;
  double normal_blur = 1.0;
  double tangential_blur = 1.0;
  std::vector<double> offsets;
  std::vector<double> values;
  double edge = 0.0;  // fitted e
};

double Median(const std::vector<double>& v) { return v.empty() ? 0.0 : UpperMedian(v); }

struct LevelState {
  double inside, outside, sigma;
};

// The model in the affine frame, where the ellipse with its edge at `edge` on this ray is a
// disk of radius ρ + edge·gain: its blurred-disk profile with the normal width setting z and
// the tangential width setting the curvature shift σ_t²/(2ρ). One per ray and state.
struct RayModel {
  RayModel(const Ray& ray, double rho, double edge, double sigma)
      : sigma_n(sigma * ray.normal_blur),
        s((rho + edge * ray.radial_gain) * sigma_n /
          (sigma * ray.tangential_blur * sigma * ray.tangential_blur)),
        ds_dedge(ray.radial_gain * sigma_n /
                 (sigma * ray.tangential_blur * sigma * ray.tangential_blur)),
        dz_dedge(ray.radial_gain / sigma_n),
        edge(edge),
        profile(s) {}
  double z(double offset) const { return (edge - offset) * dz_dedge; }
  double sigma_n, s, ds_dedge, dz_dedge, edge;
  BlurredDiskProfile profile;
};

// The model's residuals at (levels, edges) and its Gauss-Newton normal equations, arranged
// for the Schur complement: global block A (levels), per-ray diagonal D and coupling B.
struct Linearization {
  double cost = 0.0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  std::vector<double> D, c, ray_cost;
  std::vector<Eigen::Vector3d> B;
};

Linearization Linearize(const std::vector<Ray>& rays,
                        double rho,
                        const LevelState& s,
                        const std::vector<double>& edges) {
  Linearization lin;
  lin.D.resize(rays.size());
  lin.c.resize(rays.size());
  lin.ray_cost.resize(rays.size());
  lin.B.resize(rays.size());
  const double delta = s.inside - s.outside;
  // The sums written out in scalars, A's upper triangle (it is symmetric): Eigen's outer
  // products went through the stack, where each sample's loads waited on its stores (a fifth
  // of this function's time). The same products, summed in the same order.
  double a00 = 0.0, a01 = 0.0, a02 = 0.0, a11 = 0.0, a12 = 0.0, a22 = 0.0;
  double b0 = 0.0, b1 = 0.0, b2 = 0.0;
  for (size_t k = 0; k < rays.size(); ++k) {
    const Ray& ray = rays[k];
    double Dk = 0.0, ck = 0.0, cost = 0.0, B0 = 0.0, B1 = 0.0, B2 = 0.0;
    const RayModel m(ray, rho, edges[k], s.sigma);
    for (size_t j = 0; j < ray.offsets.size(); ++j) {
      const double z = m.z(ray.offsets[j]);
      const ProfileValue G = m.profile.At(z);
      const double r = s.outside + delta * G.value - ray.values[j];
      // The levels' and σ's derivatives (s and z both scale as 1/σ), and the edge's.
      const double g0 = G.value, g1 = 1.0 - G.value;
      const double g2 = -delta * (G.d_ds * m.s + G.d_dz * z) / s.sigma;
      const double Je = delta * (G.d_ds * m.ds_dedge + G.d_dz * m.dz_dedge);
      a00 += g0 * g0;
      a01 += g0 * g1;
      a02 += g0 * g2;
      a11 += g1 * g1;
      a12 += g1 * g2;
      a22 += g2 * g2;
      b0 += g0 * r;
      b1 += g1 * r;
      b2 += g2 * r;
      Dk += Je * Je;
      B0 += g0 * Je;
      B1 += g1 * Je;
      B2 += g2 * Je;
      ck += Je * r;
      cost += r * r;
    }
    lin.D[k] = Dk;
    lin.B[k] = Eigen::Vector3d(B0, B1, B2);
    lin.c[k] = ck;
    lin.ray_cost[k] = cost;
    lin.cost += cost;
  }
  lin.A << a00, a01, a02, a01, a11, a12, a02, a12, a22;
  lin.b = Eigen::Vector3d(b0, b1, b2);
  return lin;
}

}  // namespace

CircleEdges FindCircleEdges(const cv::Mat& image,
                            const Eigen::Matrix3d& ellipse_px,
                            double max_inward_px,
                            double max_outward_px,
                            double sigma_start_px,
                            const EdgeSearchOptions& options) {
  CircleEdges out;
  const Eigen::Matrix3d C = CanonicalConic(ellipse_px);
  const Ellipse e = EllipseFromConic(C);
  const double perimeter = M_PI * (e.semi_major + e.semi_minor);
  const int n_rays = std::clamp(
      static_cast<int>(perimeter / options.ray_spacing_px), options.min_rays, options.max_rays);
  const double reach = EdgeSearchReachPx(sigma_start_px, options);
  const double reach_out = std::min(reach, max_outward_px);
  const double reach_in = std::min(reach, max_inward_px);
  const Eigen::Vector2d u(std::cos(e.angle_rad), std::sin(e.angle_rad)), v(-u.y(), u.x());
  const double rho = std::sqrt(e.semi_major * e.semi_minor);

  // A ray's samples, reserved: grown one at a time, their allocations took a tenth of the
  // search's instructions.
  const size_t samples_per_ray =
      static_cast<size_t>(std::max(0.0, (reach_in + reach_out) / options.sample_step_px)) + 2;
  std::vector<Ray> rays;
  rays.reserve(static_cast<size_t>(n_rays));
  for (int k = 0; k < n_rays; ++k) {
    const double t = 2.0 * M_PI * k / n_rays;
    Ray ray;
    ray.base = e.center + e.semi_major * std::cos(t) * u + e.semi_minor * std::sin(t) * v;
    ray.normal = (C * ray.base.homogeneous()).head<2>().normalized();
    // Affine frame: the base maps to ρ (cos t, sin t); M = diag(ρ/a, ρ/b) [u v]ᵀ.
    const Eigen::Vector2d radial(std::cos(t), std::sin(t)), tangent(-std::sin(t), std::cos(t));
    Eigen::Matrix2d M;
    M.row(0) = rho / e.semi_major * u.transpose();
    M.row(1) = rho / e.semi_minor * v.transpose();
    ray.radial_gain = radial.dot(M * ray.normal);
    ray.normal_blur = (M.transpose() * radial).norm();
    ray.tangential_blur = (M.transpose() * tangent).norm();
    ray.offsets.reserve(samples_per_ray);
    ray.values.reserve(samples_per_ray);
    bool inside_image = true;
    for (double d = -reach_in; d <= reach_out + 1e-9; d += options.sample_step_px) {
      const Eigen::Vector2d p = ray.base + d * ray.normal;
      if (!(p.x() >= 0 && p.y() >= 0 && p.x() <= image.cols - 1 && p.y() <= image.rows - 1)) {
        inside_image = false;
        break;
      }
      ray.offsets.push_back(d);
      ray.values.push_back(Sample(image, p.x(), p.y()));
    }
    if (inside_image && ray.offsets.size() >= 4) rays.push_back(std::move(ray));
  }
  out.rays = n_rays;
  if (rays.size() < static_cast<size_t>(options.min_rays) / 2) return out;

  // Start: levels from the ray ends, σ given, edges on the hypothesis.
  std::vector<double> inner, outer;
  for (const Ray& ray : rays) {
    inner.push_back(ray.values.front());
    outer.push_back(ray.values.back());
  }
  LevelState s{Median(inner), Median(outer), std::max(0.5, sigma_start_px)};
  std::vector<double> edges(rays.size(), 0.0);
  Linearization lin = Linearize(rays, rho, s, edges);
  double lambda = 1e-3;
  for (int it = 0; it < options.iterations; ++it) {
    // Levenberg-Marquardt step, the per-ray edges eliminated (Schur complement).
    Eigen::Matrix3d S = lin.A;
    S.diagonal() *= 1.0 + lambda;
    Eigen::Vector3d rhs = lin.b;
    std::vector<double> D(rays.size());
    for (size_t k = 0; k < rays.size(); ++k) {
      D[k] = lin.D[k] * (1.0 + lambda) + 1e-12;
      S -= lin.B[k] * lin.B[k].transpose() / D[k];
      rhs -= lin.B[k] * lin.c[k] / D[k];
    }
    const Eigen::Vector3d dg = -S.ldlt().solve(rhs);
    LevelState trial{s.inside + dg(0), s.outside + dg(1), std::clamp(s.sigma + dg(2), 0.3, 40.0)};
    std::vector<double> trial_edges(rays.size());
    for (size_t k = 0; k < rays.size(); ++k) {
      const double de = -(lin.c[k] + lin.B[k].dot(dg)) / D[k];
      trial_edges[k] = std::clamp(edges[k] + de, -reach_in, reach_out);
    }
    Linearization trial_lin = Linearize(rays, rho, trial, trial_edges);
    if (trial_lin.cost < lin.cost) {
      const bool converged = lin.cost - trial_lin.cost < 1e-4 * lin.cost;
      s = trial;
      edges = std::move(trial_edges);
      lin = std::move(trial_lin);
      lambda = std::max(1e-6, lambda / 10);
      if (converged) break;
    } else {
      lambda *= 10;
    }
  }

  // Per-ray residuals: drop rays whose profile the model does not explain (other edges,
  // occlusion) and edges pinned at the reach limits.
  std::vector<double> ray_rms(rays.size());
  for (size_t k = 0; k < rays.size(); ++k) {
    ray_rms[k] = std::sqrt(lin.ray_cost[k] / rays[k].offsets.size());
  }
  const double typical = Median(ray_rms);
  for (size_t k = 0; k < rays.size(); ++k) {
    const bool at_limit = edges[k] <= -reach_in + 1e-6 || edges[k] >= reach_out - 1e-6;
    if (at_limit || ray_rms[k] > 3.0 * typical + 1.0) continue;
    out.points_px.push_back(rays[k].base + edges[k] * rays[k].normal);
  }
  out.sigma_px = s.sigma;
  out.inside_level = s.inside;
  out.outside_level = s.outside;
  return out;
}

}  // namespace markerbench
