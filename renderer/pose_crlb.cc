#include "renderer/pose_crlb.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/gauss_legendre.h"
#include "renderer/boundary_pieces.h"
#include "renderer/subpixel_grid.h"

namespace markerbench {
namespace {

constexpr double kPi = 3.14159265358979323846;
// F is singular when its smallest eigenvalue, after scaling its diagonal to 1, is below this.
constexpr double kSingularEigenvalue = 1e-12;

// Pixel (x, y) covers [x ± ½] × [y ± ½].
int PixelIndex(double coordinate) { return static_cast<int>(std::floor(coordinate + 0.5)); }

// Calls add(x, y, fraction) for every pixel that the segment a → b crosses, with the
// fraction of the segment inside it; `cuts` is scratch space.
template <typename Add>
void ForEachPixelPart(const Eigen::Vector2d& a,
                      const Eigen::Vector2d& b,
                      std::vector<double>* cuts,
                      Add add) {
  cuts->assign({0.0, 1.0});
  const Eigen::Vector2d d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) continue;
    const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
    for (double border = std::floor(lo - 0.5) + 1.5; border < hi; border += 1.0) {
      cuts->push_back((border - a[axis]) / d[axis]);
    }
  }
  std::sort(cuts->begin(), cuts->end());
  for (size_t i = 0; i + 1 < cuts->size(); ++i) {
    const double fraction = (*cuts)[i + 1] - (*cuts)[i];
    if (!(fraction > 0.0)) continue;
    const Eigen::Vector2d mid = a + 0.5 * ((*cuts)[i] + (*cuts)[i + 1]) * d;
    add(PixelIndex(mid.x()), PixelIndex(mid.y()), fraction);
  }
}

// d(pixel)/dθ of a point x_cam of the marker imaged at a pose T = D·exp(θ)·T0, D the
// camera's motion since the truth pose T0 (rotation R_D; the identity for a still camera):
// dx_cam/dθ = R_D·[e_k × y | I] with y = R0·x_marker = R_Dᵀ(x_cam - t), t that of T.
Eigen::Matrix<double, 2, 6> ImageVelocity(const Camera& camera,
                                          const Eigen::Vector3d& x_cam,
                                          const Rigid3& cam_from_marker,
                                          const Eigen::Matrix3d& motion_rotation) {
  const Eigen::Vector3d y = motion_rotation.transpose() * (x_cam - cam_from_marker.translation);
  Eigen::Matrix<double, 3, 6> dx_dtheta;
  for (int k = 0; k < 3; ++k) dx_dtheta.col(k) = Eigen::Vector3d::Unit(k).cross(y);
  dx_dtheta.rightCols<3>().setIdentity();
  return ImgFromCamJacobian(camera, x_cam) * motion_rotation * dx_dtheta;
}

// ∫ of the unit tent max(0, 1 - |s|) from -∞ to s.
double TentIntegral(double s) {
  if (s <= -1.0) return 0.0;
  if (s <= 0.0) return 0.5 * (s + 1.0) * (s + 1.0);
  if (s <= 1.0) return 1.0 - 0.5 * (1.0 - s) * (1.0 - s);
  return 1.0;
}

// One instant of a moving camera's exposure: its pose, the rotation of its motion since the
// truth pose, and each canvas row's weight (rows -margin .. height + margin - 1).
struct ExposureSample {
  Rigid3 cam_from_marker;
  Eigen::Matrix3d motion_rotation = Eigen::Matrix3d::Identity();
  std::vector<double> row_weight;
};

// The image is each row's mean over its exposure of the still images along the path, and so
// is ∇θI. Times τ_j on an even grid over every row's exposure, close enough that the image
// moves at most max_motion_step_px between two; each row's mean is that of the piecewise
// linear interpolation between them (for a global shutter, the trapezoidal rule; a row
// without exposure reads the interpolation at its start).
std::vector<ExposureSample> ExposureSamples(const FrameRequest& request,
                                            int margin,
                                            const CrlbOptions& options) {
  const Scene& scene = request.scene;
  const int rows = scene.camera.height + 2 * margin;
  if (!request.cam_from_marker_at) {
    return {ExposureSample{scene.cam_from_marker,
                           Eigen::Matrix3d::Identity(),
                           std::vector<double>(static_cast<size_t>(rows), 1.0)}};
  }
  const double exposure = request.exposure_s;
  const auto row_start = [&](int y) {  // image row y; margin rows extrapolate
    return request.readout_s * y / std::max(1, scene.camera.height - 1);
  };
  const double first = row_start(-margin), last = row_start(rows - 1 - margin) + exposure;
  const double motion = ImageMotionPx(scene, request.cam_from_marker_at, first, last);
  // Clamped as a double: a point near the camera plane can move by any amount (or NaN).
  const double wanted = std::ceil(motion / options.max_motion_step_px);
  int intervals = 0;  // none: every row is exposed at the one instant `first`
  if (last > first) {
    intervals =
        std::isnan(wanted)
            ? kMaxExposureSubframes
            : static_cast<int>(std::clamp(wanted, 1.0, static_cast<double>(kMaxExposureSubframes)));
  }
  const double step = intervals > 0 ? (last - first) / intervals : 0.0;
  const Eigen::Matrix3d truth_rotation = scene.cam_from_marker.rotation;
  std::vector<ExposureSample> samples;
  for (int j = 0; j <= intervals; ++j) {
    const double tau = first + j * step;
    ExposureSample sample;
    sample.cam_from_marker = request.cam_from_marker_at(tau);
    sample.motion_rotation = sample.cam_from_marker.rotation * truth_rotation.transpose();
    for (int y = -margin; y < rows - margin; ++y) {
      const double a = row_start(y);
      double w = 1.0;
      if (intervals > 0 && exposure > 0.0) {
        w = step * (TentIntegral((a + exposure - tau) / step) - TentIntegral((a - tau) / step)) /
            exposure;
      } else if (intervals > 0) {
        w = std::max(0.0, 1.0 - std::abs(a - tau) / step);
      }
      sample.row_weight.push_back(w);
    }
    samples.push_back(std::move(sample));
  }
  return samples;
}

// P(|e| <= r) for e with independent components of variances l1 >= l2 >= l3 >= 0, l1 > 0:
// E over (z2, z3) of P(l1·z1² <= r² - l2·z2² - l3·z3²), in polar coordinates (s, a) of
// (z2, z3) on one quadrant.
double GaussianNormCdf(double r, double l1, double l2, double l3) {
  static const GaussLegendre<16> angle_rule;
  static const GaussLegendre<48> radial_rule;
  constexpr double kRadialEnd = 9.0;  // s e^{-s²/2} is below 1e-16 beyond
  const double inv = 1.0 / std::sqrt(2.0 * l1);
  double total = 0.0;
  for (size_t i = 0; i < angle_rule.x.size(); ++i) {
    const double a = 0.5 * kPi * angle_rule.x[i];
    const double m = l2 * std::cos(a) * std::cos(a) + l3 * std::sin(a) * std::sin(a);
    double inner = 0.0;
    const double s_max = m > 0.0 ? r / std::sqrt(m) : std::numeric_limits<double>::infinity();
    if (s_max > kRadialEnd) {
      for (size_t j = 0; j < radial_rule.x.size(); ++j) {
        const double s = kRadialEnd * radial_rule.x[j];
        inner += radial_rule.w[j] * kRadialEnd * s * std::exp(-0.5 * s * s) *
                 std::erf(std::sqrt(std::max(0.0, r * r - s * s * m)) * inv);
      }
    } else {
      // s = s_max sin β removes the square root's kink at s_max.
      for (size_t j = 0; j < radial_rule.x.size(); ++j) {
        const double beta = 0.5 * kPi * radial_rule.x[j];
        const double s = s_max * std::sin(beta);
        inner += radial_rule.w[j] * 0.5 * kPi * s_max * std::cos(beta) * s *
                 std::exp(-0.5 * s * s) * std::erf(r * std::cos(beta) * inv);
      }
    }
    total += angle_rule.w[i] * inner;
  }
  return total;  // (2/π) ∫ da over [0, π/2] = the mean over the quadrant
}

// Below this noise (8-bit levels) the rounding's covariance is its noiseless sum (the series
// would need more than 10^4 terms).
constexpr double kNoiselessLevels = 1e-4;
// F takes a pixel's channels jointly only where their rounding's covariance is above this
// (levels²; it falls to it at about 0.53 levels of noise, 1.2e-5 of the rounding's variance).
constexpr double kLeastRoundingCovariance = 1e-6;

// The frame's noise-free linear image (lit and clipped): its channels' values, for their
// rounding and the camera's response.
ImageF NoiseFreeImage(const FrameRequest& request) {
  FrameRequest noise_free = request;
  noise_free.degradations.noise_var = 0.0;
  noise_free.degradations.gamma = 1.0;  // the linear values are the same; skip the encoding
  noise_free.keep_linear = true;
  return RenderFrame(noise_free).linear;
}

// de/dv of the camera's response e = v^(1/γ) (Degradations::gamma) at a linear value v, taken
// at v >= 1e-6 (infinite at 0 for γ > 1, where the clipping the bound leaves out rules).
double ResponseSlope(double gamma, double v) {
  if (gamma == 1.0) return 1.0;
  const double exponent = 1.0 / gamma;
  return exponent * std::pow(std::max(v, 1e-6), exponent - 1.0);
}

// F = Σ_pixels ∇θeᵀ Σ⁻¹ ∇θe over `pixels`, e a pixel's written values: the lit noise-free
// `values` v through the camera's response, ∇θe = g'(v)·∇θv. Σ is the channels' noise g'(v)²σ²
// plus their rounding, shared by channels of equal values; `derivative`'s planes k · channels
// + c hold ∂I_c/∂θ_k over `area`, and ∇θv = gain·∇θI (the caller multiplies F by gain²).
Matrix6d PixelwiseFisher(const ImageF& derivative,
                         const PixelRect& area,
                         const PixelRect& pixels,
                         const ImageF& values,
                         const Degradations& d) {
  const int channels = values.channels;
  const double noise_levels = 255.0 * std::sqrt(d.noise_var);
  const auto shared_rounding = [&](double slope) {
    return EqualChannelsRoundingCovariance(slope * noise_levels) / (255.0 * 255.0);
  };
  const double linear_shared_rounding = shared_rounding(1.0);
  Matrix6d fisher = Matrix6d::Zero();
  Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 3, 6> gradient(channels, 6);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> covariance(channels, channels);
  Eigen::Vector3d slope;
  for (int y = pixels.y0; y < pixels.y1; ++y) {
    for (int x = pixels.x0; x < pixels.x1; ++x) {
      const size_t at = static_cast<size_t>(y - area.y0) * derivative.width + (x - area.x0);
      for (int c = 0; c < channels; ++c) {
        for (int k = 0; k < 6; ++k) gradient(c, k) = derivative.plane(k * channels + c)[at];
      }
      if (gradient.isZero(0.0)) continue;
      const size_t value_at = static_cast<size_t>(y) * values.width + x;
      for (int c = 0; c < channels; ++c) {
        slope(c) = ResponseSlope(d.gamma, values.plane(c)[value_at]);
        gradient.row(c) *= slope(c);
      }
      for (int a = 0; a < channels; ++a) {
        covariance(a, a) = slope(a) * slope(a) * d.noise_var + kQuantisationVariance;
        for (int b = a + 1; b < channels; ++b) {
          double shared = 0.0;
          if (values.plane(a)[value_at] == values.plane(b)[value_at]) {
            shared = d.gamma == 1.0 ? linear_shared_rounding : shared_rounding(slope(a));
          }
          covariance(a, b) = covariance(b, a) = shared;
        }
      }
      // Σ is singular where channels are equal without noise: its pseudo-inverse takes each
      // group of equal channels as one observation.
      const Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 3, 6> information =
          covariance.completeOrthogonalDecomposition().solve(gradient);
      fisher += gradient.transpose() * information;
    }
  }
  return fisher;
}
}  // namespace

double ProbabilityNormWithin(double r, const Eigen::Vector3d& variances) {
  if (std::isnan(r) || variances.hasNaN()) return NAN;
  if (!(r > 0.0) || !std::isfinite(variances.maxCoeff())) return 0.0;
  Eigen::Vector3d l = variances.cwiseMax(0.0);
  std::sort(l.data(), l.data() + 3);
  if (!(l(2) > 0.0)) return 1.0;  // no error at all
  return std::min(1.0, GaussianNormCdf(r, l(2), l(1), l(0)));
}

double MedianGaussianNorm(const Eigen::Matrix3d& covariance) {
  const Eigen::Vector3d l =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .cwiseMax(0.0);  // ascending
  if (!(l(2) > 0.0)) return 0.0;
  const double rms = std::sqrt(l.sum());
  // The median lies between the 1-D (0.674 rms) and the isotropic (0.888 rms) cases.
  double lo = 0.6 * rms, hi = 0.95 * rms;
  double f_lo = GaussianNormCdf(lo, l(2), l(1), l(0)) - 0.5;
  double f_hi = GaussianNormCdf(hi, l(2), l(1), l(0)) - 0.5;
  // Illinois false position.
  int side = 0;
  for (int iteration = 0; iteration < 100 && hi - lo > 1e-10 * rms; ++iteration) {
    const double r = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    const double f = GaussianNormCdf(r, l(2), l(1), l(0)) - 0.5;
    if (f == 0.0) return r;
    if ((f < 0.0) == (f_lo < 0.0)) {
      lo = r;
      f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = r;
      f_hi = f;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}

Matrix6d PoseFisherInformation(const FrameRequest& request, const CrlbOptions& options) {
  const Camera& camera = request.scene.camera;
  const Degradations& d = request.degradations;
  const int channels = request.channels;
  // The canvas: the image and the margin whose scene the blur carries into it.
  const int margin = d.MarginPx();
  const Eigen::AlignedBox2d window(
      Eigen::Vector2d(-margin - 0.5, -margin - 0.5),
      Eigen::Vector2d(camera.width - 0.5 + margin, camera.height - 0.5 + margin));
  const std::vector<ExposureSample> samples = ExposureSamples(request, margin, options);
  // The pieces at sample j: kept for a still camera, computed again for each pass otherwise
  // (a fast motion has hundreds of samples).
  Scene scene = request.scene;
  std::vector<BoundaryPiece> pieces;
  const auto pieces_at = [&](size_t j) -> const std::vector<BoundaryPiece>& {
    if (samples.size() > 1 || pieces.empty()) {
      scene.cam_from_marker = samples[j].cam_from_marker;
      pieces = ImageBoundaryPieces(scene, channels, window, options.max_piece_px);
    }
    return pieces;
  };

  // The pixels a piece crosses lie between the pixels of its ends.
  PixelRect deposits{camera.width + margin, camera.height + margin, -margin, -margin};
  for (size_t j = 0; j < samples.size(); ++j) {
    for (const BoundaryPiece& piece : pieces_at(j)) {
      for (const Eigen::Vector2d& end : {piece.a_px, piece.b_px}) {
        deposits.x0 = std::min(deposits.x0, PixelIndex(end.x()));
        deposits.y0 = std::min(deposits.y0, PixelIndex(end.y()));
        deposits.x1 = std::max(deposits.x1, PixelIndex(end.x()) + 1);
        deposits.y1 = std::max(deposits.y1, PixelIndex(end.y()) + 1);
      }
    }
  }
  // Clip to the canvas, then leave room for the blur around the deposits.
  deposits = {std::max(deposits.x0, -margin),
              std::max(deposits.y0, -margin),
              std::min(deposits.x1, camera.width + margin),
              std::min(deposits.y1, camera.height + margin)};
  if (deposits.Empty()) return Matrix6d::Zero();
  const int pad = margin + 1;
  const PixelRect area{std::max(deposits.x0 - pad, -margin),
                       std::max(deposits.y0 - pad, -margin),
                       std::min(deposits.x1 + pad, camera.width + margin),
                       std::min(deposits.y1 + pad, camera.height + margin)};
  // Planes k · channels + c hold dI_c/dθ_k over `area`, first on the grid of the optics' blur
  // (degradations.h), where a sub-pixel's area is 1/s².
  const SubpixelGrid grid{BlurSubsampling(d.blur_sigma_px), area};
  const int s = grid.scale;
  const double per_area = static_cast<double>(s) * s;
  ImageF fine(s * (area.x1 - area.x0), s * (area.y1 - area.y0), 6 * channels);
  std::vector<double> cuts;
  for (size_t j = 0; j < samples.size(); ++j) {
    const ExposureSample& sample = samples[j];
    for (const BoundaryPiece& piece : pieces_at(j)) {
      // dI/dθ_k per unit jump: -(image velocity · normal) × length.
      const Eigen::Matrix<double, 6, 1> rate =
          -ImageVelocity(camera, piece.mid_cam, sample.cam_from_marker, sample.motion_rotation)
               .transpose() *
          piece.normal_px;
      ForEachPixelPart(
          grid.FineFromCanvas(piece.a_px),
          grid.FineFromCanvas(piece.b_px),
          &cuts,
          [&](int x, int y, double fraction) {
            x -= s * area.x0;
            y -= s * area.y0;
            if (x < 0 || y < 0 || x >= fine.width || y >= fine.height) return;
            const double weight = per_area * fraction *
                                  sample.row_weight[static_cast<size_t>(area.y0 + y / s + margin)];
            if (weight == 0.0) return;
            const size_t at = static_cast<size_t>(y) * fine.width + x;
            for (int k = 0; k < 6; ++k) {
              for (int c = 0; c < channels; ++c) {
                fine.plane(k * channels + c)[at] +=
                    static_cast<float>(weight * rate[k] * piece.jump[static_cast<size_t>(c)]);
              }
            }
          });
    }
  }
  ImageF derivative;
  PixelRect blurred;
  if (s == 1) {
    const PixelRect local{
        deposits.x0 - area.x0, deposits.y0 - area.y0, deposits.x1 - area.x0, deposits.y1 - area.y0};
    blurred = GaussianBlur(d.blur_sigma_px, local, &fine);
    derivative = std::move(fine);
  } else {
    derivative = ImageF(area.x1 - area.x0, area.y1 - area.y0, 6 * channels);
    BlurOntoPixels(d.blur_sigma_px, grid, fine, {area.x0, area.y0}, &derivative);
    blurred = {0, 0, derivative.width, derivative.height};
  }
  MotionBlur(d.motion_blur_px, d.motion_blur_angle_deg, blurred, &derivative);

  // F over the image's pixels; lighting scales the image by the gain.
  const int x0 = std::max(area.x0, 0), x1 = std::min(area.x1, camera.width);
  const int y0 = std::max(area.y0, 0), y1 = std::min(area.y1, camera.height);
  const double noise_levels = 255.0 * std::sqrt(d.noise_var);
  if (d.gamma != 1.0 ||
      (channels > 1 && EqualChannelsRoundingCovariance(noise_levels) > kLeastRoundingCovariance)) {
    return d.gain * d.gain *
           PixelwiseFisher(derivative, area, {x0, y0, x1, y1}, NoiseFreeImage(request), d);
  }
  Matrix6d fisher = Matrix6d::Zero();
  for (int c = 0; c < channels; ++c) {
    for (int k = 0; k < 6; ++k) {
      for (int l = k; l < 6; ++l) {
        const float* pk = derivative.plane(k * channels + c);
        const float* pl = derivative.plane(l * channels + c);
        double sum = 0.0;
        for (int y = y0; y < y1; ++y) {
          const size_t row = static_cast<size_t>(y - area.y0) * derivative.width;
          for (int x = x0 - area.x0; x < x1 - area.x0; ++x) {
            sum += static_cast<double>(pk[row + x]) * pl[row + x];
          }
        }
        fisher(k, l) += sum;
      }
    }
  }
  fisher = fisher.selfadjointView<Eigen::Upper>();
  return d.gain * d.gain / (d.noise_var + kQuantisationVariance) * fisher;
}

double EqualChannelsRoundingCovariance(double noise_levels) {
  // Terms until exp(-4π²k²s²) < 1e-17; without noise their sum, π²/6 / 2π².
  if (noise_levels < kNoiselessLevels) return 1.0 / 12.0;
  double sum = 0.0;
  for (int k = 1;; ++k) {
    const double damping = std::exp(-4.0 * kPi * kPi * k * k * noise_levels * noise_levels);
    if (damping < 1e-17) break;
    sum += damping / (2.0 * kPi * kPi * k * k);
  }
  return sum;
}

PoseBound PoseCrlb(const FrameRequest& request, const CrlbOptions& options) {
  PoseBound bound;
  bound.fisher = PoseFisherInformation(request, options);
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  bound.position_rms_m = bound.position_median_m = kInfinity;
  bound.rotation_rms_deg = bound.rotation_median_deg = kInfinity;
  bound.position_covariance.setConstant(kInfinity);
  bound.position_variances_m2.setConstant(kInfinity);
  bound.rotation_covariance.setConstant(kInfinity);
  const Eigen::Matrix<double, 6, 1> diagonal = bound.fisher.diagonal();
  if (!(diagonal.minCoeff() > 0.0)) return bound;
  // Equilibrate before inverting: ω and t have different units.
  const Eigen::Matrix<double, 6, 1> s = diagonal.cwiseSqrt().cwiseInverse();
  const Matrix6d scaled = s.asDiagonal() * bound.fisher * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(scaled);
  if (!(eigen.eigenvalues()(0) > kSingularEigenvalue * eigen.eigenvalues()(5))) return bound;
  const Matrix6d covariance =
      s.asDiagonal() *
      (eigen.eigenvectors() * eigen.eigenvalues().cwiseInverse().asDiagonal() *
       eigen.eigenvectors().transpose()) *
      s.asDiagonal();
  bound.observable = true;
  // C = -Rᵀt with R = exp([ω]×) R0: dC/dω = -R0ᵀ[t]×, dC/dt = -R0ᵀ.
  const Eigen::Matrix3d& R0 = request.scene.cam_from_marker.rotation;
  const Eigen::Vector3d& t = request.scene.cam_from_marker.translation;
  Eigen::Matrix3d t_cross;
  t_cross << 0.0, -t.z(), t.y(), t.z(), 0.0, -t.x(), -t.y(), t.x(), 0.0;
  Eigen::Matrix<double, 3, 6> dC_dtheta;
  dC_dtheta << -R0.transpose() * t_cross, -R0.transpose();
  bound.position_covariance = dC_dtheta * covariance * dC_dtheta.transpose();
  bound.position_variances_m2 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(
                                    bound.position_covariance, Eigen::EigenvaluesOnly)
                                    .eigenvalues()
                                    .cwiseMax(0.0);
  bound.rotation_covariance = covariance.topLeftCorner<3, 3>();
  constexpr double kDeg = 180.0 / kPi;
  bound.position_rms_m = std::sqrt(bound.position_covariance.trace());
  bound.position_median_m = MedianGaussianNorm(bound.position_covariance);
  bound.rotation_rms_deg = kDeg * std::sqrt(bound.rotation_covariance.trace());
  bound.rotation_median_deg = kDeg * MedianGaussianNorm(bound.rotation_covariance);
  return bound;
}

}  // namespace markerbench
