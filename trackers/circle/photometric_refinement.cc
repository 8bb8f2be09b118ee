#include "trackers/circle/photometric_refinement.h"

#include <ceres/jet.h>
#include <ceres/rotation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "trackers/circle/blurred_disk_profile.h"
#include "trackers/circle/blurred_ellipse.h"
#include "trackers/circle/clipped_noise.h"
#include "trackers/circle/conic.h"
#include "trackers/circle/pixel_chord_term.h"
#include "trackers/circle/pixel_fit.h"
#include "trackers/pixel_area_blur.h"

namespace markerbench {
namespace {

// Through a lens with distortion, the pixel's own units about an ideal point c, where the lens's
// local map is A (Camera::IdealFromImgJacobian): y = A⁻¹ (x - c) for an ideal pixel x. A pixel's
// area and the blur, a unit square and σ px in the image, are isotropic in them to first order
// about c.
struct LocalPixelUnits {
  Eigen::Vector2d center;
  Eigen::Matrix3d ideal_from_local;  // [A c; 0 1]
  Eigen::Matrix2d local_from_ideal;  // A⁻¹

  LocalPixelUnits(const Camera& camera, const Eigen::Vector2d& ideal_center)
      : center(ideal_center) {
    const Eigen::Matrix2d a = camera.IdealFromImgJacobian(camera.CamFromIdeal(ideal_center));
    ideal_from_local << a, center, 0.0, 0.0, 1.0;
    local_from_ideal = a.inverse();
  }
  Eigen::Vector2d LocalOf(const Eigen::Vector2d& ideal_px) const {
    return local_from_ideal * (ideal_px - center);
  }
  // A conic on ideal pixels (x̃ᵀ C x̃ = 0) in these units.
  template <typename T>
  Eigen::Matrix<T, 3, 3> LocalConic(const Eigen::Matrix<T, 3, 3>& ideal_conic) const {
    const Eigen::Matrix<T, 3, 3> m = ideal_from_local.cast<T>();
    return m.transpose() * ideal_conic * m;
  }
};

// A printed disk and the colour step across its edge (its colour minus what lies under it, in
// the channels used), its edge sampled at `bins` angles, and that edge in the image at the
// start pose.
struct EdgeLayer {
  DiskShape disk;
  Eigen::Vector3d jump;
  Eigen::Matrix3d start_conic;  // its image at the start pose (canonical)
  Ellipse start_ellipse;        // the same as an ellipse
  int bins = 0;
  std::vector<Eigen::Vector2d> edge;  // the bins' points on the circle, marker plane
  std::vector<Eigen::Vector2d> start_px;
  std::vector<Eigen::Vector2d> start_normal;  // outward, unit
  std::vector<double> start_curvature_radius_px;
  std::vector<double> start_curvature_per_px;  // 1/ρ of the same (0 where ρ is infinite)
  double start_depth_m = 0.0;                  // of the disk's centre
  // Through a lens with distortion (empty without), per bin at its edge point's pixel: Aᵀ, the
  // lens's local map A transposed (Camera::IdealFromImgJacobian); the ideal pixels a pixel
  // spans across the edge, k = |Aᵀ n|; and the edge's curvature in pixels per its curvature in
  // ideal pixels, det(A)² / k³ (a curve's under the linear map A⁻¹). The pixel's area and the
  // blur, a pixel's and σ px wide in the image, are modelled in the pixel's own units.
  std::vector<Eigen::Matrix2d> ideal_from_px_t;
  std::vector<double> ideal_per_px_across;
  std::vector<double> px_curvature_per_ideal;
  // Under blur of a good part of its size: modelled whole, its exact blurred ellipse
  // (blurred_ellipse.h), on every pixel of its image and within reach of it, with the
  // quadrature nodes its size in σ needs at the start pose. Through a lens with distortion, the
  // ellipse and the pixels are taken in the pixel's own units about its centre at the start
  // pose, where the blur is isotropic (in ideal pixels, near wide_distorted's side, noise-free
  // frames at blur 8-10 fitted 83-280 mm off).
  bool whole = false;
  int whole_nodes = 0;
  std::optional<LocalPixelUnits> whole_units;
};

// Each grey level in units of 0-1, as g / 255.0 gives it, without a division per pixel and
// channel (they took a tenth of choosing the pixels).
const std::array<double, 256> kUnitOfGreyLevel = [] {
  std::array<double, 256> units{};
  for (int g = 0; g < 256; ++g) units[g] = g / 255.0;
  return units;
}();

// An edge within reach of a pixel: the pixel's signed distance to it is taken along the edge's
// normal at the start pose, from the edge point nearest the pixel then; or, for a layer
// modelled whole, its whole disk (bin -1).
struct NearEdge {
  int layer = 0;
  int bin = 0;
};

// A pixel within reach of one or more edges; the blurred design there is `base` plus each
// near edge's step times its blurred-disk profile. The design is a sum of disk indicators
// (each disk's step is uniform over it), and blur is linear, so this holds however the blurred
// edges overlap.
struct Pixel {
  Eigen::Vector2d ideal_px;  // undistorted pixel coordinates
  Eigen::Vector3d value;     // measured, 0-1, per channel used
  Eigen::Vector3d base;      // the background plus the steps of the disks it lies deep inside
  int first_edge = 0;        // its edges: PixelSet::near_edges[first_edge, first_edge + edges)
  int edges = 0;
};

struct PixelSet {
  std::vector<Pixel> pixels;
  std::vector<NearEdge> near_edges;
};

// The radius of the circle through three points (infinite for collinear ones).
double CircumRadius(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a, bc = c - b, ca = a - c;
  const double twice_area = std::abs(ab.x() * bc.y() - ab.y() * bc.x());
  if (!(twice_area > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(ab.squaredNorm() * bc.squaredNorm() * ca.squaredNorm()) / (2.0 * twice_area);
}

// The pose (6) and σ, the parameters differentiated by Jets.
using PoseJet = ceres::Jet<double, 7>;

// The image through H of a point X on the marker's plane with its derivatives: the Jets'
// arithmetic written out (their temporaries took a third of the model's time, one point per
// half pixel of every edge).
Eigen::Matrix<PoseJet, 2, 1> ProjectPlanePoint(const Eigen::Matrix<PoseJet, 3, 3>& H,
                                               const Eigen::Vector2d& X) {
  PoseJet p[3];
  for (int r = 0; r < 3; ++r) {
    p[r].a = H(r, 0).a * X.x() + H(r, 1).a * X.y() + H(r, 2).a;
    for (int i = 0; i < p[r].v.size(); ++i) {
      p[r].v[i] = H(r, 0).v[i] * X.x() + H(r, 1).v[i] * X.y() + H(r, 2).v[i];
    }
  }
  Eigen::Matrix<PoseJet, 2, 1> x;
  const double inverse_depth = 1.0 / p[2].a;
  for (int r = 0; r < 2; ++r) {
    x[r].a = p[r].a * inverse_depth;
    for (int i = 0; i < p[r].v.size(); ++i) {
      x[r].v[i] = (p[r].v[i] - x[r].a * p[2].v[i]) * inverse_depth;
    }
  }
  return x;
}

// Its value alone, to the bit: the same operations on the Jets' values.
Eigen::Vector2d ProjectPlanePointValue(const Eigen::Matrix<PoseJet, 3, 3>& H,
                                       const Eigen::Vector2d& X) {
  double p[3];
  for (int r = 0; r < 3; ++r) p[r] = H(r, 0).a * X.x() + H(r, 1).a * X.y() + H(r, 2).a;
  const double inverse_depth = 1.0 / p[2];
  return {p[0] * inverse_depth, p[1] * inverse_depth};
}

// The fit of the model to every pixel and channel (least squares where a pixel is not clipped,
// its likelihood where it is: clipped_noise.h), in the parameters
// θ = (angle-axis (3), translation (3), σ, then offset and gain per channel). The edge points
// are differentiated by Jets once per bin and the disks' scales once per disk; each pixel then
// chains them by hand and adds its rows straight into the normal equations (a dense Jacobian
// of thousands of rows would cost more than the model).
class PixelModel {
 public:
  using Jet = PoseJet;

  PixelModel(const Eigen::Matrix3d& K,
             const std::vector<EdgeLayer>& layers,
             const PixelSet& pixels,
             int channels,
             double noise_sigma,
             double chords_below_noise)
      : K_(K),
        layers_(layers),
        pixels_(pixels),
        channels_(channels),
        noise_sigma_(noise_sigma),
        chords_below_noise_(chords_below_noise) {}

  int Parameters() const { return 7 + 2 * channels_; }
  Eigen::VectorXd StartLevels() const { return UnitGainLevels(Parameters()); }
  // Each channel's offset and gain that fit the edges listed at StartLevels() (clipped_noise.h).
  Eigen::VectorXd LevelsShownAtStart(std::vector<ModelledPixel>* listed) const {
    Eigen::VectorXd levels = StartLevels();
    FitOffsetsAndGains(channels_, &levels, listed);
    return levels;
  }
  double MinSigmaPx() const { return kMinBlurSigmaPx; }
  double noise_sigma() const { return noise_sigma_; }
  void set_noise_sigma(double noise_sigma) { noise_sigma_ = noise_sigma; }

  // The cost at θ (each pixel's and channel's ClippedPixelTerm); with jtj and jtr, also JᵀJ
  // and Jᵀr; and each pixel's and channel's residual and modelled mean if `modelled` is given.
  double Evaluate(const Eigen::VectorXd& theta,
                  Eigen::MatrixXd* jtj,
                  Eigen::VectorXd* jtr,
                  std::vector<ModelledPixel>* modelled) const {
    // Summed in fixed-size matrices (at most 3 channels), copied out at the end.
    Eigen::Matrix<double, 13, 13> normal = Eigen::Matrix<double, 13, 13>::Zero();
    Eigen::Matrix<double, 13, 1> gradient = Eigen::Matrix<double, 13, 1>::Zero();
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
    // Each layer's edge points in the image, and at each the edge's radius of curvature in
    // blur σ, s = ρ/σ, with the exact profile of a disk of that size blurred
    // (blurred_disk_profile.h): a tilted disk's image is an ellipse, whose blurred edge
    // matches the osculating disk's to first order in σ/ρ (the shift σ²/2ρ of its midpoint).
    // ρ changes with the pose by the disk's scale, 1/depth; its shape is the start pose's,
    // where the pixels are chosen again at each round.
    // Their values, and with the normal equations their derivatives too.
    std::vector<std::vector<Eigen::Vector2d>> edges_px(layers_.size());
    // (n·∂e/∂θ, t·∂e/∂θ) per edge point e, n and t its normal and tangent at the start pose:
    // all a pixel's distance to the edge there takes of its derivatives.
    std::vector<std::vector<Eigen::Matrix<double, 7, 2>>> edges_along_frame(layers_.size());
    std::vector<Jet> size_per_sigma(layers_.size());  // per layer: s = start ρ · this
    std::vector<std::vector<BlurredDiskProfile>> profiles(layers_.size());
    // H = K [r1 r2 t]: plane points (X, Y, 1) to pixels.
    Eigen::Matrix<Jet, 3, 3> H;
    H << R.col(0), R.col(1), t;
    H = K_.cast<Jet>() * H;
    // The layers modelled whole: each disk's image as the chords of its ellipse, and that
    // ellipse blurred, with the pixel's area as a blur of its variance (1/12: beside a blur of
    // a good part of the disk's size, all it changes).
    const double whole_sigma = EdgeSigmaOfBlur(sigma.a);
    std::vector<EllipseChords<Jet>> whole(layers_.size());
    std::vector<std::optional<BlurredEllipse>> blurred(layers_.size());
    for (size_t l = 0; l < layers_.size(); ++l) {
      const EdgeLayer& layer = layers_[l];
      if (layer.whole) {
        Eigen::Matrix<Jet, 3, 3> conic =
            ImageOfCircle<Jet>(H, layer.disk.center, layer.disk.radius);
        if (layer.whole_units) conic = layer.whole_units->LocalConic(conic);
        const std::optional<EllipseChords<Jet>> chords = ChordsOfConic(conic);
        if (!chords) return std::numeric_limits<double>::infinity();  // no ellipse: a bad step
        whole[l] = *chords;
        const EllipseChords<Jet>& e = *chords;
        blurred[l].emplace(
            EllipseChords<double>{e.x0.a, e.y0.a, e.slope.a, e.half_width.a, e.half_height.a},
            whole_sigma,
            layer.whole_nodes);
        continue;
      }
      edges_px[l].reserve(layer.bins);
      if (jtj) {
        edges_along_frame[l].resize(layer.bins);
        for (int bin = 0; bin < layer.bins; ++bin) {
          const Eigen::Matrix<Jet, 2, 1> edge = ProjectPlanePoint(H, layer.edge[bin]);
          const Eigen::Vector2d& n = layer.start_normal[bin];
          for (int i = 0; i < 7; ++i) {
            edges_along_frame[l][bin](i, 0) = n.x() * edge.x().v[i] + n.y() * edge.y().v[i];
            edges_along_frame[l][bin](i, 1) = n.x() * edge.y().v[i] - n.y() * edge.x().v[i];
          }
          edges_px[l].emplace_back(edge.x().a, edge.y().a);
        }
      } else {
        for (const Eigen::Vector2d& X : layer.edge) {
          edges_px[l].push_back(ProjectPlanePointValue(H, X));
        }
      }
      const Eigen::Matrix<Jet, 3, 1> center(
          Jet(layer.disk.center.x()), Jet(layer.disk.center.y()), Jet(0.0));
      size_per_sigma[l] = layer.start_depth_m / ((R * center + t).z() * sigma);
      profiles[l].reserve(layer.bins);
      if (layer.ideal_per_px_across.empty()) {
        for (const double rho : layer.start_curvature_radius_px) {
          profiles[l].emplace_back(rho * size_per_sigma[l].a);
        }
      } else {
        for (int bin = 0; bin < layer.bins; ++bin) {
          profiles[l].emplace_back(layer.start_curvature_radius_px[bin] /
                                   layer.px_curvature_per_ideal[bin] * size_per_sigma[l].a);
        }
      }
    }
    // Per pixel in doubles, for each near edge: d = n·(x - e) + a²/2ρ (px, positive outside; a =
    // t·(x - e)), z = -d/σ, inside = G(s, z) over the pixel, chained to the 7 Jet parameters
    // through e, s and σ.
    const double sigma_value = sigma.a;
    const double per_sigma = 1.0 / sigma_value, half_per_sigma = 0.5 * per_sigma;
    const bool with_chords = noise_sigma_ < chords_below_noise_;
    Eigen::Matrix<double, 7, 1> d_whole_sigma = Eigen::Matrix<double, 7, 1>::Zero();
    d_whole_sigma[6] = sigma_value / whole_sigma;
    // The fraction of a near edge's disk seen at a pixel, with its gradient if asked.
    const auto inside = [&](const Pixel& p, const NearEdge& near, Eigen::Matrix<double, 7, 1>* d) {
      if (near.bin < 0) {
        const std::optional<LocalPixelUnits>& units = layers_[near.layer].whole_units;
        const Eigen::Vector2d at = units ? units->LocalOf(p.ideal_px) : p.ideal_px;
        if (!d) return blurred[near.layer]->ValueAt(at);
        const EllipseChords<Jet>& e = whole[near.layer];
        const BlurredEllipseValue g = blurred[near.layer]->At(at);
        *d = g.gradient[0] * e.x0.v + g.gradient[1] * e.y0.v + g.gradient[2] * e.slope.v +
             g.gradient[3] * e.half_width.v + g.gradient[4] * e.half_height.v +
             g.gradient[5] * d_whole_sigma;
        return g.value;
      }
      const EdgeLayer& layer = layers_[near.layer];
      double rho = layer.start_curvature_radius_px[near.bin];
      double per_rho = layer.start_curvature_per_px[near.bin];
      const Eigen::Vector2d& normal = layer.start_normal[near.bin];
      const EdgeOffset offset =
          OffsetFromCurvedEdge(p.ideal_px, edges_px[near.layer][near.bin], normal, per_rho);
      const double along_tangent = offset.along * per_rho;
      Eigen::Vector2d pixel_normal =
          (normal + along_tangent * Eigen::Vector2d(-normal.y(), normal.x())).normalized();
      // Through a lens, the edge in the pixel's own units (EdgeLayer::ideal_from_px_t).
      double offset_distance = offset.distance, per_k = 1.0;
      if (!layer.ideal_per_px_across.empty()) {
        per_k = 1.0 / layer.ideal_per_px_across[near.bin];
        offset_distance *= per_k;
        rho /= layer.px_curvature_per_ideal[near.bin];
        per_rho *= layer.px_curvature_per_ideal[near.bin];
        pixel_normal = (layer.ideal_from_px_t[near.bin] * pixel_normal).normalized();
      }
      // Over the pixel's area (blurred_disk_profile.h): its offsets along the edge (variance
      // 1/12) put it a²/2ρ further out on average, 1/24ρ; and across it, along the normal at
      // the pixel's own foot on the edge, turned from the edge point's by a/ρ (with the edge
      // point's, 2 px apart on a sharp disk of 40 px, the model sat 0.23 grey levels RMS from
      // the exact cover of the pixels it crosses; with the pixel's, 0.10).
      const double distance = offset_distance + per_rho / 24.0;
      const PixelProfileValue g =
          profiles[near.layer][near.bin].OverPixel(-distance * per_sigma,
                                                   half_per_sigma * std::abs(pixel_normal.x()),
                                                   half_per_sigma * std::abs(pixel_normal.y()));
      // And what the square's chords add beyond the mean shift (pixel_chord_term.h).
      const PixelChordTerm chord = with_chords
                                       ? PixelChordTermAt(distance, sigma_value, pixel_normal, rho)
                                       : PixelChordTerm{};
      if (d) {
        const Eigen::Matrix<double, 7, 2>& edge_along_frame =
            edges_along_frame[near.layer][near.bin];
        // ∂G/∂θ = G_z ∂z/∂θ + G_s ρ ∂(s/ρ)/∂θ, z = -d/σ, ∂d/∂θ = -(n + (a/ρ) t)·∂e/∂θ (and
        // ∂σ/∂θ = e₇).
        const double along_edge = g.d_dz * per_sigma;
        const double across_edge = (along_edge - chord.d_distance) * per_k;  // -∂V/∂d, d ideal
        const double along_size = g.d_ds * rho;
        const Jet& size = size_per_sigma[near.layer];
        for (int i = 0; i < 7; ++i) {
          (*d)[i] =
              across_edge * (edge_along_frame(i, 0) + along_tangent * edge_along_frame(i, 1)) +
              along_size * size.v[i];
        }
        (*d)[6] += (along_edge * distance - g.d_dlog_width) * per_sigma + chord.d_sigma;
      }
      return g.value + chord.value;
    };
    if (modelled) modelled->reserve(modelled->size() + pixels_.pixels.size() * channels_);
    for (const Pixel& p : pixels_.pixels) {
      // The printed colour and its gradient, ∂printed_c/∂θ = Σ_k jump_kc ∂inside_k/∂θ: with
      // one edge (most pixels) jump_c ∂inside/∂θ, else summed in d_printed.
      const bool one_edge = p.edges == 1;
      Eigen::Vector3d printed = p.base;
      Eigen::Matrix<double, 7, 3> d_printed;
      Eigen::Matrix<double, 7, 1> d_inside;
      if (jtj && !one_edge) d_printed.setZero();
      for (int k = p.first_edge; k < p.first_edge + p.edges; ++k) {
        const NearEdge& near = pixels_.near_edges[k];
        const Eigen::Vector3d& jump = layers_[near.layer].jump;
        printed += inside(p, near, jtj ? &d_inside : nullptr) * jump;
        if (jtj && !one_edge) d_printed += d_inside * jump.transpose();
      }
      // Each channel's term at μ_c = offset_c + gain_c printed_c, the pixel clipped and
      // rounded (clipped_noise.h).
      PixelTerm terms[3];
      for (int c = 0; c < channels_; ++c) {
        const double mu = levels[2 * c] + levels[2 * c + 1] * printed[c];
        terms[c] = ClippedPixelTerm(p.value[c], mu, noise_sigma_);
        cost += terms[c].cost;
        if (modelled) modelled->push_back({p.value[c] - mu, mu});
      }
      if (!jtj) continue;
      // Channel c's row is -∂μ_c/∂θ = (-gain_c ∂printed_c/∂θ, -1, -printed_c) on (θ 0-6, its
      // offset and gain), with its term's residual in Jᵀr and weight in JᵀJ. With one edge
      // the rows' pose parts are ∂inside/∂θ scaled by -gain_c jump_c, so the channels share
      // one outer product and one gradient, and a channel the edge does not change adds to
      // its levels alone. Upper triangles, written out (Eigen's products of these small
      // blocks took twice as long here).
      double shared_weight = 0.0, shared_residual = 0.0;  // one edge: Σ_c w_c scale_c², r_c scale_c
      for (int c = 0; c < channels_; ++c) {
        const double gain = levels[2 * c + 1];
        const double r = terms[c].residual, w = terms[c].weight;
        const int level = 7 + 2 * c;
        normal(level, level) += w;
        normal(level, level + 1) += w * printed[c];
        normal(level + 1, level + 1) += w * printed[c] * printed[c];
        gradient[level] -= r;
        gradient[level + 1] -= r * printed[c];
        Eigen::Matrix<double, 7, 1> row;
        if (one_edge) {
          const double scale = -gain * layers_[pixels_.near_edges[p.first_edge].layer].jump[c];
          if (scale == 0.0) continue;
          shared_weight += w * scale * scale;
          shared_residual += r * scale;
          row = scale * d_inside;
        } else {
          row = -gain * d_printed.col(c);
          for (int i = 0; i < 7; ++i) {
            gradient[i] += r * row[i];
            for (int j = 0; j <= i; ++j) normal(j, i) += w * row[i] * row[j];
          }
        }
        for (int i = 0; i < 7; ++i) {
          normal(i, level) -= w * row[i];
          normal(i, level + 1) -= w * row[i] * printed[c];
        }
      }
      if (one_edge) {
        for (int i = 0; i < 7; ++i) {
          gradient[i] += shared_residual * d_inside[i];
          for (int j = 0; j <= i; ++j) normal(j, i) += shared_weight * d_inside[i] * d_inside[j];
        }
      }
    }
    if (jtj) {
      // The lower triangle, by symmetry.
      normal.triangularView<Eigen::StrictlyLower>() = normal.transpose();
      *jtj = normal.topLeftCorner(Parameters(), Parameters());
      *jtr = gradient.head(Parameters());
    }
    return cost;
  }

 private:
  Eigen::Matrix3d K_;
  const std::vector<EdgeLayer>& layers_;
  const PixelSet& pixels_;
  int channels_;
  double noise_sigma_;         // the image's, 0-1 units, for the clipping
  double chords_below_noise_;  // PhotometricOptions::chords_below_noise
};

// The colour in the channels used: RGB, or its luma in the first for a grey image.
Eigen::Vector3d InChannels(const Rgb& color, int channels) {
  return channels == 3 ? color : Eigen::Vector3d(Luma(color), 0.0, 0.0);
}

// The marker's disks as edges seen through H (nullopt for other shapes).
std::optional<std::vector<EdgeLayer>> EdgeLayers(const MarkerSpec& marker,
                                                 const Eigen::Matrix3d& H,
                                                 int channels) {
  std::vector<EdgeLayer> layers;
  for (size_t i = 0; i < marker.layers.size(); ++i) {
    const auto* disk = std::get_if<DiskShape>(&marker.layers[i].shape);
    if (!disk) return std::nullopt;
    Rgb below = marker.background;
    for (size_t j = 0; j < i; ++j) {
      const PaintSample under = PaintAt(marker.layers[j], disk->center);
      if (under.color) below = *under.color;
    }
    EdgeLayer layer;
    layer.start_conic = CanonicalConic(ImageOfCircle<double>(H, disk->center, disk->radius));
    layer.start_ellipse = EllipseFromConic(layer.start_conic);
    const Ellipse& e = layer.start_ellipse;
    // An image that is no finite ellipse (a disk across the horizon) cannot be modelled.
    if (!(e.semi_minor > 0.0 && e.semi_major < 1e5 && e.center.allFinite() &&
          e.center.cwiseAbs().maxCoeff() < 1e6)) {
      return std::nullopt;
    }
    // Edge points at most two pixels apart: a pixel's distance to the edge is taken from the
    // nearest to second order in its offset a along the edge (OffsetFromCurvedEdge); the
    // ellipse's curvature changing along it adds |dρ/ds| a³/6ρ² (|dρ/ds| < 0.8 up to 40° of
    // tilt): at most 5e-3 px at a = 1 px and ρ = 5 px, of opposite signs on the two sides.
    const int bins = std::max(32, static_cast<int>(std::ceil(M_PI * e.semi_major)));
    layer.disk = *disk;
    layer.jump = InChannels(marker.layers[i].color - below, channels);
    layer.bins = bins;
    layer.start_depth_m = (H * disk->center.homogeneous()).z();
    for (int k = 0; k < bins; ++k) {
      const Eigen::Vector2d radial(std::cos(2.0 * M_PI * k / bins),
                                   std::sin(2.0 * M_PI * k / bins));
      layer.edge.push_back(disk->center + disk->radius * radial);
      layer.start_px.push_back((H * layer.edge.back().homogeneous()).hnormalized());
      const Eigen::Vector2d outward_px =
          (H * (layer.edge.back() + 1e-3 * disk->radius * radial).homogeneous()).hnormalized() -
          layer.start_px.back();
      Eigen::Vector2d normal = (layer.start_conic * layer.start_px.back().homogeneous()).head<2>();
      layer.start_normal.push_back(normal.dot(outward_px) < 0.0 ? -normal.normalized()
                                                                : normal.normalized());
    }
    for (int k = 0; k < bins; ++k) {
      layer.start_curvature_radius_px.push_back(CircumRadius(layer.start_px[(k + bins - 1) % bins],
                                                             layer.start_px[k],
                                                             layer.start_px[(k + 1) % bins]));
      layer.start_curvature_per_px.push_back(1.0 / layer.start_curvature_radius_px.back());
    }
    layers.push_back(std::move(layer));
  }
  return layers;
}

// The bin at a point's angle about the disk's centre, `on_plane` (the marker's plane): where
// the search for a pixel's nearest bin starts when no pixel beside it has one.
int BinAtAngle(const EdgeLayer& layer, const Eigen::Vector2d& on_plane) {
  const Eigen::Vector2d radial = on_plane - layer.disk.center;
  // atan2's range puts the turn in [-bins/2, bins/2]; wrapped without a division (the two of
  // a remainder's wrap took a tenth of choosing the pixels).
  const int turn =
      static_cast<int>(std::lround(std::atan2(radial.y(), radial.x()) / (2.0 * M_PI) * layer.bins));
  return std::clamp(turn < 0 ? turn + layer.bins : turn, 0, layer.bins - 1);
}

// The bin of `layer`'s edge point nearest a pixel at `ideal_px` at the start pose (the foot of
// its perpendicular), searched downhill from bin `start`.
int NearestBin(const EdgeLayer& layer, const Eigen::Vector2d& ideal_px, int start) {
  int bin = start;
  // A neighbour's bin, wrapped without a division (two of them a step took 17 % of the
  // search's time).
  const auto beside = [&](int from, int step) {
    const int next = from + step;
    return next < 0 ? next + layer.bins : next >= layer.bins ? next - layer.bins : next;
  };
  double distance = (layer.start_px[bin] - ideal_px).squaredNorm();
  for (const int step : {1, -1}) {
    for (int next = beside(bin, step), n = 1; n < layer.bins; next = beside(next, step), ++n) {
      const double next_distance = (layer.start_px[next] - ideal_px).squaredNorm();
      if (!(next_distance < distance)) break;
      bin = next;
      distance = next_distance;
    }
  }
  return bin;
}

// The pixels that see the ideal (pinhole) image's square `center` ± `reach`, in pixel
// coordinates: the square itself without distortion; through the lens, the box of its sides'
// images (a point about every pixel of them, a pixel to spare), which holds the image of all of
// it where the lens maps it one to one (its Jacobian positive along the sides); else the
// whole image. Its sides' images may bow: near a wide lens's edge the pinhole image lies tens of
// pixels beyond the one the lens forms.
Eigen::AlignedBox2d PixelsSeeingIdealSquare(const Image8& image,
                                            const Camera& camera,
                                            const Eigen::Vector2d& center,
                                            double reach) {
  const Eigen::Vector2d half = Eigen::Vector2d::Constant(reach);
  if (!camera.HasDistortion()) return {center - half, center + half};
  const Eigen::AlignedBox2d whole(Eigen::Vector2d(0.0, 0.0),
                                  Eigen::Vector2d(image.width - 1.0, image.height - 1.0));
  constexpr int kMaxSteps = 4096;  // a side's points; beyond, the box is clamped to the image
  const int steps = static_cast<int>(std::clamp(std::ceil(2.0 * reach), 1.0, 1.0 * kMaxSteps));
  Eigen::AlignedBox2d box;
  for (int k = 0; k <= steps; ++k) {
    const double along = reach * (2.0 * k / steps - 1.0);
    for (const Eigen::Vector2d& offset : {Eigen::Vector2d(along, -reach),
                                          Eigen::Vector2d(along, reach),
                                          Eigen::Vector2d(-reach, along),
                                          Eigen::Vector2d(reach, along)}) {
      const Eigen::Vector3d ray = camera.CamFromIdeal(center + offset);
      const Eigen::Vector2d px = camera.ImgFromCam(ray);
      if (!(camera.DistortJacobian(ray.head<2>()).determinant() > 0.0 && px.allFinite())) {
        return whole;
      }
      box.extend(px);
    }
  }
  return {box.min() - Eigen::Vector2d::Ones(), box.max() + Eigen::Vector2d::Ones()};
}

// The span of x where row y meets the ellipse of form F about `center` (xᵀ F x <= 1); nullopt
// where it does not.
std::optional<std::pair<double, double>> RowWithinEllipse(const Eigen::Matrix2d& form,
                                                          const Eigen::Vector2d& center,
                                                          double y) {
  // F₀₀ dx² + 2 F₀₁ dx dy + F₁₁ dy² = 1, for dx.
  const double dy = y - center.y();
  const double discriminant =
      form(0, 1) * form(0, 1) * dy * dy - form(0, 0) * (form(1, 1) * dy * dy - 1.0);
  if (!(discriminant >= 0.0)) return std::nullopt;
  const double middle = center.x() - form(0, 1) * dy / form(0, 0);
  const double half_width = std::sqrt(discriminant) / form(0, 0);
  return std::make_pair(middle - half_width, middle + half_width);
}

// The pixels within `band` of an edge through H, each with every edge within `band` of it,
// but none deeper inside a disk than `max_depth_per_curvature` of its edge's radius of
// curvature there (PhotometricOptions). In ideal pixels, but for a disk modelled whole through
// a lens: in the pixel's own units about its centre (EdgeLayer::whole_units); measured on 400
// paired frames through wide_distorted at 1 m, its errors at blur 5 were ×0.955 (p 0.001) those
// with the band in ideal pixels, at blur 8 ×0.985 (p 0.09).
PixelSet PixelsNearEdges(const Image8& image,
                         const Camera& camera,
                         const MarkerSpec& marker,
                         const std::vector<EdgeLayer>& layers,
                         const Eigen::Matrix3d& H,
                         double band,
                         double max_depth_per_curvature) {
  const Eigen::Matrix3d plane_from_px = H.inverse();
  const Eigen::Vector3d background = InChannels(marker.background, image.channels);
  PixelSet set;
  // Each edge's reach in the image; a pixel in two is taken once.
  struct Box {
    int u0, v0, u1, v1;
  };
  std::vector<Box> boxes;
  // Each edge's ellipse: a pixel farther than its semi-major axis + band from its centre, or
  // nearer than its semi-minor axis - band, is beyond the band (with a pixel to spare for
  // the distance's first-order form), and needs no distance; nor is one outside the ellipse
  // scaled by PndBandScales' outer scale, or inside it scaled by its inner (but for a disk
  // modelled whole, whose pixels inside are all taken), x outside or inside where
  // xᵀ F x > 1 or < 1 for the scaled ellipse's form F about its centre. The rows' spans are
  // cut by those ellipses grown by a pixel each way, and shrunk by one (the ellipse scaled by
  // 1/b more or less, b its semi-minor axis). Not for a disk modelled whole through a lens,
  // whose distances are in the pixel's own units.
  struct Annulus {
    Eigen::Vector2d center;
    double outer_squared, inner_squared;
    std::optional<Eigen::Matrix2d> outside, inside, span_outside, span_inside;
  };
  std::vector<Annulus> annuli;
  // Each edge's reach in ideal pixels: the band, but for a disk modelled whole through a lens,
  // whose band is in the pixel's own units (its conic in them, for the distances).
  std::vector<double> reaches;
  std::vector<Eigen::Matrix3d> local_conics(layers.size());
  Box all{image.width, image.height, -1, -1};
  // Pixel coordinates clamped to the image (as doubles first: an ellipse may lie far off it).
  const auto column = [&](double u) {
    return static_cast<int>(std::clamp(std::floor(u), 0.0, image.width - 1.0));
  };
  const auto row = [&](double v) {
    return static_cast<int>(std::clamp(std::floor(v), 0.0, image.height - 1.0));
  };
  for (size_t m = 0; m < layers.size(); ++m) {
    const EdgeLayer& layer = layers[m];
    const Ellipse& e = layer.start_ellipse;
    double layer_reach = band;
    if (layer.whole_units) {
      local_conics[m] = layer.whole_units->LocalConic(layer.start_conic);
      layer_reach *= layer.whole_units->ideal_from_local.topLeftCorner<2, 2>().norm();
    }
    reaches.push_back(layer_reach);
    const double inner = std::max(0.0, e.semi_minor - layer_reach - 1.0);
    Annulus& annulus = annuli.emplace_back();
    annulus.center = e.center;
    annulus.outer_squared = std::pow(e.semi_major + layer_reach + 1.0, 2);
    annulus.inner_squared = inner * inner;
    if (!layer.whole_units) {
      const PndBand scales = PndBandScales(e, band);
      // The form of the ellipse scaled by k.
      const auto scaled = [&](double k) {
        return EllipseForm({e.center, k * e.semi_major, k * e.semi_minor, e.angle_rad});
      };
      const double pixel_scale = 1.0 / e.semi_minor;
      if (std::isfinite(scales.outer)) {
        annulus.outside = scaled(scales.outer);
        annulus.span_outside = scaled(scales.outer + pixel_scale);
      }
      if (!layer.whole && scales.inner > 0.0) {
        annulus.inside = scaled(scales.inner);
        if (scales.inner > pixel_scale) annulus.span_inside = scaled(scales.inner - pixel_scale);
      }
    }
    const Eigen::AlignedBox2d reach =
        PixelsSeeingIdealSquare(image, camera, e.center, e.semi_major + layer_reach + 2.0);
    boxes.push_back({column(reach.min().x()),
                     row(reach.min().y()),
                     column(reach.max().x()),
                     row(reach.max().y())});
    all = {std::min(all.u0, boxes.back().u0),
           std::min(all.v0, boxes.back().v0),
           std::max(all.u1, boxes.back().u1),
           std::max(all.v1, boxes.back().v1)};
  }
  const int all_width = all.u1 - all.u0 + 1;
  std::vector<uint8_t> taken(
      static_cast<size_t>(std::max(0, all_width)) * std::max(0, all.v1 - all.v0 + 1), 0);
  std::vector<double> distances(layers.size());
  // Per layer, the pixel last tied to its edge, and its bin.
  struct LastBin {
    int u = -2, v = -1, bin = 0;
  };
  std::vector<LastBin> last_bins(layers.size());
  const bool ideal_is_pixel = !camera.HasDistortion();
  // Without distortion a pixel's ideal x depends on its column alone and its y on its row
  // alone: taken once per column and row of the box (the divisions of one per pixel took a
  // sixth of the pixels' choice).
  std::vector<double> ideal_x, ideal_y;
  if (ideal_is_pixel) {
    for (int u = all.u0; u <= all.u1; ++u) {
      ideal_x.push_back(camera.IdealFromImg(Eigen::Vector2d(u, all.v0)).x());
    }
    for (int v = all.v0; v <= all.v1; ++v) {
      ideal_y.push_back(camera.IdealFromImg(Eigen::Vector2d(all.u0, v)).y());
    }
  }
  // The columns of row v that may lie within an annulus: without distortion a pixel's ideal
  // coordinates are its own (to rounding; a pixel to spare each way), and outside the outer
  // circles or (but for a disk modelled whole) inside an inner one no pixel is near; with
  // distortion, all of them. As spans of columns, in order and apart.
  std::vector<std::pair<int, int>> spans;
  const auto columns_near = [&](int v, const Box& box) {
    spans.clear();
    if (!ideal_is_pixel) {
      spans.emplace_back(box.u0, box.u1);
      return;
    }
    for (size_t m = 0; m < annuli.size(); ++m) {
      const Annulus& annulus = annuli[m];
      const double dy = std::max(0.0, std::abs(v - annulus.center.y()) - 1.0);
      if (dy * dy > annulus.outer_squared) continue;
      const double half_width = std::sqrt(annulus.outer_squared - dy * dy) + 1.0;
      int first = column(annulus.center.x() - half_width);
      int last = column(annulus.center.x() + half_width + 1.0);
      std::pair<double, double> hole(annulus.center.x(), annulus.center.x());
      if (annulus.span_outside) {
        const std::optional<std::pair<double, double>> within =
            RowWithinEllipse(*annulus.span_outside, annulus.center, v);
        if (!within) continue;
        first = std::max(first, column(within->first));
        last = std::min(last, column(within->second + 1.0));
        if (annulus.span_inside) {
          hole = RowWithinEllipse(*annulus.span_inside, annulus.center, v).value_or(hole);
        }
      } else {
        const double dy_inner = std::abs(v - annulus.center.y()) + 1.0;
        const double inner_half_width =
            layers[m].whole || dy_inner * dy_inner >= annulus.inner_squared
                ? 0.0
                : std::sqrt(annulus.inner_squared - dy_inner * dy_inner) - 1.0;
        hole = {annulus.center.x() - inner_half_width, annulus.center.x() + inner_half_width};
      }
      if (hole.second - hole.first < 2.0) {
        spans.emplace_back(first, last);
      } else {
        spans.emplace_back(first, column(hole.first));
        spans.emplace_back(column(hole.second), last);
      }
    }
    std::sort(spans.begin(), spans.end());
    size_t merged = 0;
    for (const auto& [first, last] : spans) {
      const int u0 = std::max(box.u0, first), u1 = std::min(box.u1, last);
      if (u0 > u1) continue;
      if (merged > 0 && u0 <= spans[merged - 1].second + 1) {
        spans[merged - 1].second = std::max(spans[merged - 1].second, u1);
      } else {
        spans[merged++] = {u0, u1};
      }
    }
    spans.resize(merged);
  };
  // A pixel in a span: taken once, with its edges, if it is near one.
  const auto consider = [&](int u, int v) {
    uint8_t& seen = taken[static_cast<size_t>(v - all.v0) * all_width + (u - all.u0)];
    if (seen) return;
    seen = 1;
    const Eigen::Vector2d ideal = ideal_is_pixel
                                      ? Eigen::Vector2d(ideal_x[u - all.u0], ideal_y[v - all.v0])
                                      : camera.IdealFromImg(Eigen::Vector2d(u, v));
    // Signed distance to each edge, negative inside.
    bool near_any = false;
    for (size_t m = 0; m < layers.size(); ++m) {
      const Annulus& annulus = annuli[m];
      const Eigen::Vector2d from_center = ideal - annulus.center;
      const double from_center_squared = from_center.squaredNorm();
      const auto beyond = [&](const std::optional<Eigen::Matrix2d>& form, bool outside) {
        if (!form) return false;
        const double scaled = from_center.dot(*form * from_center);
        return outside ? scaled > 1.0 : scaled < 1.0;
      };
      if (from_center_squared > annulus.outer_squared || beyond(annulus.outside, true)) {
        distances[m] = std::numeric_limits<double>::infinity();
      } else if (from_center_squared < annulus.inner_squared || beyond(annulus.inside, false)) {
        distances[m] = -std::numeric_limits<double>::infinity();
      } else if (layers[m].whole_units) {
        const Eigen::Vector2d local = layers[m].whole_units->LocalOf(ideal);
        distances[m] = PndResidual<double>(local_conics[m], local.x(), local.y());
      } else {
        distances[m] = PndResidual<double>(layers[m].start_conic, ideal.x(), ideal.y());
      }
      near_any =
          near_any || std::abs(distances[m]) <= band || (layers[m].whole && distances[m] < 0.0);
    }
    if (!near_any) return;
    Pixel p;
    p.ideal_px = ideal;
    p.value = Eigen::Vector3d::Zero();
    for (int c = 0; c < image.channels; ++c) p.value[c] = kUnitOfGreyLevel[image.at(u, v, c)];
    p.base = background;
    p.first_edge = static_cast<int>(set.near_edges.size());
    bool modelled = true;
    for (size_t m = 0; m < layers.size(); ++m) {
      if (layers[m].whole) {
        if (distances[m] <= band) {
          set.near_edges.push_back({static_cast<int>(m), -1});
          ++p.edges;
        }
      } else if (std::abs(distances[m]) <= band) {
        // The search starts from the bin of the pixel to the left where it was tied to this
        // edge (its foot a bin or two away) and this pixel lies within a quarter of the edge's
        // radius of curvature of it; else at the pixel's angle on the plane. Deeper inside a
        // disk of a few pixels, bins far apart are nearly as near, and from the pixel beside
        // the search ended at another (on the CI suite's frames, 119 of 13.6 million pixels
        // with no bound; none with it, nor on the paper sweeps').
        LastBin& last = last_bins[m];
        const int start =
            last.v == v && last.u == u - 1 &&
                    std::abs(distances[m]) < 0.25 * layers[m].start_curvature_radius_px[last.bin]
                ? last.bin
                : BinAtAngle(layers[m], (plane_from_px * ideal.homogeneous()).hnormalized());
        const int bin = NearestBin(layers[m], ideal, start);
        last = {u, v, bin};
        set.near_edges.push_back({static_cast<int>(m), bin});
        ++p.edges;
        modelled = modelled && distances[m] >= -max_depth_per_curvature *
                                                   layers[m].start_curvature_radius_px[bin];
      } else if (distances[m] < 0.0) {
        p.base += layers[m].jump;
      }
    }
    if (modelled) {
      set.pixels.push_back(p);
    } else {
      set.near_edges.resize(p.first_edge);
    }
  };
  for (const Box& box : boxes) {
    for (int v = box.v0; v <= box.v1; ++v) {
      columns_near(v, box);
      for (const auto& [u0, u1] : spans) {
        for (int u = u0; u <= u1; ++u) consider(u, v);
      }
    }
  }
  return set;
}

// The pixels near the edges at `cam_from_marker` for the blur σ (the band taken for 0.3 px at
// least), each tied to its edges' points, with the layers they are tied to; nullopt as for
// RefinePhotometric.
struct ModelledPixels {
  std::vector<EdgeLayer> layers;
  PixelSet pixels;
  double sigma_px = 0.0;  // the fit's start: σ, at kMinBlurSigmaPx at least
};
std::optional<ModelledPixels> PixelsAt(const Image8& image,
                                       const Camera& camera,
                                       const MarkerSpec& marker,
                                       const Rigid3& cam_from_marker,
                                       double sigma_px,
                                       const PhotometricOptions& options) {
  const Eigen::Matrix3d H = camera.K() * RayFromPlane(cam_from_marker);
  std::optional<std::vector<EdgeLayer>> layers = EdgeLayers(marker, H, image.channels);
  if (!layers) return std::nullopt;
  if (camera.HasDistortion()) {
    for (EdgeLayer& layer : *layers) {
      for (int bin = 0; bin < layer.bins; ++bin) {
        const Eigen::Vector3d ray = camera.CamFromIdeal(layer.start_px[bin]);
        const Eigen::Matrix2d& a_t =
            layer.ideal_from_px_t.emplace_back(camera.IdealFromImgJacobian(ray).transpose());
        const double k = (a_t * layer.start_normal[bin]).norm();
        const double det = a_t.determinant();
        layer.ideal_per_px_across.push_back(k);
        layer.px_curvature_per_ideal.push_back(det * det / (k * k * k));
      }
    }
  }
  const double sigma = std::max(sigma_px, 0.3);
  double largest_radius_px = 0.0;
  for (EdgeLayer& layer : *layers) {
    // The disk's size in the pixel's own units (about its centre through a lens).
    std::optional<LocalPixelUnits> units;
    if (camera.HasDistortion()) units.emplace(camera, layer.start_ellipse.center);
    const Ellipse e = units ? EllipseFromConic(CanonicalConic(units->LocalConic(layer.start_conic)))
                            : layer.start_ellipse;
    largest_radius_px = std::max(largest_radius_px, std::sqrt(e.semi_major * e.semi_minor));
    layer.whole = sigma >= options.whole_disk_from_blur_per_axis * e.semi_minor;
    // A quarter more for the fit's moves of σ and the axes.
    layer.whole_nodes = BlurredEllipse::NodesFor(1.25 * e.semi_major / sigma);
    if (layer.whole) layer.whole_units = units;
  }
  if (!(sigma_px <= options.max_blur_per_radius * largest_radius_px)) return std::nullopt;
  PixelSet pixels = PixelsNearEdges(image,
                                    camera,
                                    marker,
                                    *layers,
                                    H,
                                    options.band_sigmas * sigma + options.band_px,
                                    options.max_depth_per_curvature);
  if (pixels.pixels.size() < 20) return std::nullopt;
  return ModelledPixels{std::move(*layers), std::move(pixels), std::max(sigma_px, kMinBlurSigmaPx)};
}

// One solve on the pixels near the edges at `cam_from_marker`, each tied to its edges' points,
// at the noise they show, as `round` of a fit in rounds (pixel_fit.h); a first round from
// `start_levels` if given (FitPixelsAtTheirNoise).
std::optional<PixelRefinement> RefineOnce(const Image8& image,
                                          const Camera& camera,
                                          const MarkerSpec& marker,
                                          const Rigid3& cam_from_marker,
                                          double sigma_px,
                                          double noise_sigma,
                                          const FitRound& round,
                                          const PhotometricOptions& options,
                                          const Eigen::VectorXd* start_levels) {
  PhotometricOptions round_options = options;
  if (round.first_of_several) round_options.band_sigmas = options.first_round_band_sigmas;
  const std::optional<ModelledPixels> at =
      PixelsAt(image, camera, marker, cam_from_marker, sigma_px, round_options);
  if (!at) return std::nullopt;
  PixelModel model(camera.K(),
                   at->layers,
                   at->pixels,
                   image.channels,
                   ModelNoiseSigma(noise_sigma),
                   options.chords_below_noise);
  const std::optional<PixelFit> fit = FitPixelsAtTheirNoise(
      model, cam_from_marker, at->sigma_px, options.max_iterations, round, start_levels);
  if (!fit) return std::nullopt;
  return PixelRefinement{*fit, static_cast<int>(at->pixels.pixels.size()), model.noise_sigma()};
}

// How much less likely each of several fits is than the best: the cost (the clipped pixels'
// likelihood) over the pixels near the edges at each of them in turn (each fit judged on the same
// pixels, its own σ and levels), less the least, over the noise's variance and the number of
// those sets of pixels (2 ln Λ on each set, averaged). For the circle's two tilts, whose images
// nearly coincide far away or under heavy blur. `fits` not empty.
std::vector<double> PhotometricLogRatios(const Image8& image,
                                         const Camera& camera,
                                         const MarkerSpec& marker,
                                         const std::vector<PixelRefinement>& fits,
                                         const PhotometricOptions& options) {
  double noise = 0.0;
  for (const PixelRefinement& fit : fits) noise += fit.noise_sigma / fits.size();
  std::vector<double> costs(fits.size(), 0.0);
  for (const PixelRefinement& at_fit : fits) {
    const std::optional<ModelledPixels> at =
        PixelsAt(image, camera, marker, at_fit.fit.cam_from_marker, at_fit.fit.sigma_px, options);
    if (!at) continue;  // no fit's pixels: the same for all
    const PixelModel model(
        camera.K(), at->layers, at->pixels, image.channels, noise, options.chords_below_noise);
    for (size_t i = 0; i < fits.size(); ++i) {
      const PixelFit& fit = fits[i].fit;
      costs[i] += model.Evaluate(PixelFitParameters(fit.cam_from_marker, fit.sigma_px, fit.levels),
                                 nullptr,
                                 nullptr,
                                 nullptr);
    }
  }
  const double least = *std::min_element(costs.begin(), costs.end());
  std::vector<double> ratios;
  for (const double cost : costs) {
    ratios.push_back((cost - least) /
                     (fits.size() * ModelNoiseSigma(noise) * ModelNoiseSigma(noise)));
  }
  return ratios;
}

}  // namespace

std::optional<PixelRefinement> RefinePhotometric(const Image8& image,
                                                 const Camera& camera,
                                                 const MarkerSpec& marker,
                                                 const Rigid3& cam_from_marker,
                                                 double sigma_px,
                                                 double noise_sigma,
                                                 const PhotometricOptions& options,
                                                 const std::optional<Eigen::VectorXd>& levels) {
  // Whether a round moved the pose by less than `standard_errors` from its start.
  const auto moved_less_than = [](double standard_errors) {
    return [standard_errors](const Rigid3& start, const PixelRefinement& round) {
      return PoseMoveInStandardErrors(round.fit, start, round.noise_sigma) < standard_errors;
    };
  };
  RoundSettles<PixelRefinement> first_settles;
  if (sigma_px < options.settle_below_sigma_px) {
    first_settles = moved_less_than(options.settle_within_standard_errors);
  }
  return FitInRoundsAtTheirNoise<PixelRefinement>(
      cam_from_marker,
      BlurSigmaOfEdges(sigma_px),
      noise_sigma,
      options.max_rounds,
      [&](const Rigid3& start, double sigma, double noise, const FitRound& round) {
        return RefineOnce(image,
                          camera,
                          marker,
                          start,
                          sigma,
                          noise,
                          round,
                          options,
                          levels ? &*levels : nullptr);
      },
      first_settles,
      moved_less_than(options.later_round_settles_within_standard_errors));
}

std::vector<RankedFit<PixelRefinement>> RefinePhotometricFromStarts(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const std::vector<Rigid3>& starts,
    double sigma_px,
    double noise_sigma,
    const PhotometricOptions& options,
    const std::optional<Eigen::VectorXd>& levels) {
  return RankedFitsFromStarts<PixelRefinement>(
      starts,
      [&](const Rigid3& start, const std::vector<PixelRefinement>&) {
        return RefinePhotometric(
            image, camera, marker, start, sigma_px, noise_sigma, options, levels);
      },
      [&](const std::vector<PixelRefinement>& fits) {
        return PhotometricLogRatios(image, camera, marker, fits, options);
      });
}

std::optional<PhotometricNormalEquations> PhotometricNormalEquationsAt(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const Rigid3& cam_from_marker,
    double sigma_px,
    double noise_sigma,
    const Eigen::VectorXd& theta,
    const PhotometricOptions& options) {
  const std::optional<ModelledPixels> at =
      PixelsAt(image, camera, marker, cam_from_marker, sigma_px, options);
  if (!at) return std::nullopt;
  const PixelModel model(camera.K(),
                         at->layers,
                         at->pixels,
                         image.channels,
                         ModelNoiseSigma(noise_sigma),
                         options.chords_below_noise);
  PhotometricNormalEquations equations;
  equations.cost = model.Evaluate(theta, &equations.jtj, &equations.jtr, nullptr);
  return equations;
}

}  // namespace markerbench
