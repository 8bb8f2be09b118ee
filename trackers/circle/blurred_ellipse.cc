#include "trackers/circle/blurred_ellipse.h"

#include <array>
#include <limits>

#include "core/gauss_legendre.h"
#include "trackers/circle/normal_tables.h"

namespace markerbench {

namespace {

// A Gauss-Legendre rule of `nodes` on [0, 1], and the largest semi-major axis in σ it takes
// within 1e-7 (measured against 128 nodes over ellipses of axis ratios to 2.5 and chord
// slopes to 0.7, on a grid of pixels around them).
struct Rule {
  int nodes;
  double max_semi_major_per_sigma;
  const double* x;
  const double* w;
};

template <int N>
Rule RuleOf(double max_semi_major_per_sigma) {
  static const GaussLegendre<N> rule;
  return {N, max_semi_major_per_sigma, rule.x.data(), rule.w.data()};
}

const std::array<Rule, 6>& Rules() {
  static const std::array<Rule, 6> rules = {RuleOf<12>(1.25),
                                            RuleOf<16>(2.0),
                                            RuleOf<24>(3.5),
                                            RuleOf<32>(5.25),
                                            RuleOf<48>(8.25),
                                            RuleOf<BlurredEllipse::kMaxNodes>(11.0)};
  return rules;
}

}  // namespace

int BlurredEllipse::NodesFor(double semi_major_per_sigma) {
  for (const Rule& rule : Rules()) {
    if (semi_major_per_sigma <= rule.max_semi_major_per_sigma) return rule.nodes;
  }
  return kMaxNodes;
}

BlurredEllipse::BlurredEllipse(const EllipseChords<double>& e, double sigma, int nodes)
    : e_(e), sigma_(sigma), row_y_(std::numeric_limits<double>::quiet_NaN()), nodes_used_(0) {
  const Rule* rule = &Rules().back();
  for (auto candidate = Rules().rbegin(); candidate != Rules().rend(); ++candidate) {
    if (candidate->nodes >= nodes) rule = &*candidate;
  }
  nodes_used_ = rule->nodes;
  for (int i = 0; i < nodes_used_; ++i) {
    const double theta = M_PI * (rule->x[i] - 0.5);
    nodes_.sin_theta[i] = std::sin(theta);
    nodes_.cos_theta[i] = std::cos(theta);
    nodes_.weight[i] = M_PI * rule->w[i];  // the rule's on [0, 1] taken to θ in [-π/2, π/2]
    nodes_.chord_middle[i] = e.slope * e.half_height * nodes_.sin_theta[i];
    nodes_.chord_half[i] = e.half_width * nodes_.cos_theta[i];
  }
}

void BlurredEllipse::TakeRow(double y) {
  if (y == row_y_) return;
  row_y_ = y;
  const double h = e_.half_height, per_sigma = 1.0 / sigma_;
  const double Y = e_.y0 - y;
  for (int i = 0; i < nodes_used_; ++i) {
    nodes_.z_row[i] = (Y + h * nodes_.sin_theta[i]) * per_sigma;
    nodes_.row[i] = nodes_.weight[i] * (h * nodes_.cos_theta[i] * per_sigma) *
                    kNormalCdfTable.At(nodes_.z_row[i]).density;
  }
}

void BlurredEllipse::TermsOneByOne(double X, bool with_gradient, NodeTerms* terms) const {
  const double per_sigma = 1.0 / sigma_;
  for (int i = 0; i < nodes_used_; ++i) {
    const double row = nodes_.row[i];
    if (row == 0.0) continue;  // |z| beyond the table's end: φ < 1e-17
    const double z_right = (X + nodes_.chord_middle[i] + nodes_.chord_half[i]) * per_sigma;
    const double z_left = (X + nodes_.chord_middle[i] - nodes_.chord_half[i]) * per_sigma;
    if (!with_gradient) {
      terms->f[i] = row * (kNormalCdfTable.Cdf(z_right) - kNormalCdfTable.Cdf(z_left));
      continue;
    }
    const NormalCdfTable::Values right = kNormalCdfTable.At(z_right);
    const NormalCdfTable::Values left = kNormalCdfTable.At(z_left);
    terms->f[i] = row * (right.cdf - left.cdf);
    terms->across_x[i] = row * (right.density - left.density);  // σ ∂f/∂X
    terms->width[i] = row * (right.density + left.density) * nodes_.cos_theta[i];
    terms->ends[i] = row * (right.density * z_right - left.density * z_left);
  }
}

#if defined(__x86_64__)
void BlurredEllipse::TermsInLanes(double X, bool with_gradient, NodeTerms* terms) const {
  static_assert(kMaxNodes % 4 == 0, "the rules' nodes fill whole vectors");
  using avx2::All;
  const __m256d per_sigma = All(1.0 / sigma_);
  for (int i = 0; i < nodes_used_; i += 4) {
    const __m256d row = _mm256_loadu_pd(&nodes_.row[i]);
    const __m256d middle = _mm256_add_pd(All(X), _mm256_loadu_pd(&nodes_.chord_middle[i]));
    const __m256d half = _mm256_loadu_pd(&nodes_.chord_half[i]);
    const __m256d z_right = _mm256_mul_pd(_mm256_add_pd(middle, half), per_sigma);
    const __m256d z_left = _mm256_mul_pd(_mm256_sub_pd(middle, half), per_sigma);
    if (!with_gradient) {
      const __m256d across =
          _mm256_sub_pd(kNormalCdfTable.CdfLanes(z_right), kNormalCdfTable.CdfLanes(z_left));
      _mm256_storeu_pd(&terms->f[i], _mm256_mul_pd(row, across));
      continue;
    }
    const NormalCdfTable::Lanes right = kNormalCdfTable.AtLanes(z_right);
    const NormalCdfTable::Lanes left = kNormalCdfTable.AtLanes(z_left);
    _mm256_storeu_pd(&terms->f[i], _mm256_mul_pd(row, _mm256_sub_pd(right.cdf, left.cdf)));
    _mm256_storeu_pd(&terms->across_x[i],
                     _mm256_mul_pd(row, _mm256_sub_pd(right.density, left.density)));
    _mm256_storeu_pd(&terms->width[i],
                     _mm256_mul_pd(_mm256_mul_pd(row, _mm256_add_pd(right.density, left.density)),
                                   _mm256_loadu_pd(&nodes_.cos_theta[i])));
    _mm256_storeu_pd(&terms->ends[i],
                     _mm256_mul_pd(row,
                                   _mm256_sub_pd(_mm256_mul_pd(right.density, z_right),
                                                 _mm256_mul_pd(left.density, z_left))));
  }
}
#endif

void BlurredEllipse::TermsAt(const Eigen::Vector2d& pixel,
                             NodeLanes lanes,
                             bool with_gradient,
                             NodeTerms* terms) {
  TakeRow(pixel.y());
  const double X = e_.x0 - pixel.x();
  if (lanes == NodeLanes::kAvx2 && kCpuHasAvx2) {
#if defined(__x86_64__)
    return TermsInLanes(X, with_gradient, terms);
#endif
  }
  TermsOneByOne(X, with_gradient, terms);
}

double BlurredEllipse::ValueAt(const Eigen::Vector2d& pixel) {
  return ValueAt(pixel, kCpuHasAvx2 ? NodeLanes::kAvx2 : NodeLanes::kOneByOne);
}

double BlurredEllipse::ValueAt(const Eigen::Vector2d& pixel, NodeLanes lanes) {
  NodeTerms terms;
  TermsAt(pixel, lanes, false, &terms);
  double value = 0.0;
  for (int i = 0; i < nodes_used_; ++i) {
    if (nodes_.row[i] != 0.0) value += terms.f[i];
  }
  return value;
}

BlurredEllipseValue BlurredEllipse::At(const Eigen::Vector2d& pixel) {
  return At(pixel, kCpuHasAvx2 ? NodeLanes::kAvx2 : NodeLanes::kOneByOne);
}

BlurredEllipseValue BlurredEllipse::At(const Eigen::Vector2d& pixel, NodeLanes lanes) {
  NodeTerms terms;
  TermsAt(pixel, lanes, true, &terms);
  const double h = e_.half_height, k = e_.slope, per_sigma = 1.0 / sigma_;
  // Σ over the nodes of w f and of the parts of its derivatives; the gradient is assembled
  // from these sums.
  double value = 0.0, d_x = 0.0, d_x_s = 0.0, d_y = 0.0, d_y_s = 0.0, d_y_z = 0.0;
  double d_width = 0.0, d_ends = 0.0;
  for (int i = 0; i < nodes_used_; ++i) {
    if (nodes_.row[i] == 0.0) continue;
    const double across_y = -terms.f[i] * nodes_.z_row[i];  // σ ∂f/∂Y
    value += terms.f[i];
    d_x += terms.across_x[i];
    d_x_s += terms.across_x[i] * nodes_.sin_theta[i];
    d_y += across_y;
    d_y_s += across_y * nodes_.sin_theta[i];
    d_y_z += across_y * nodes_.z_row[i];
    d_width += terms.width[i];
    d_ends += terms.ends[i];
  }
  BlurredEllipseValue out;
  out.value = value;
  out.gradient << d_x * per_sigma, d_y * per_sigma, d_x_s * h * per_sigma, d_width * per_sigma,
      value / h + (d_y_s + d_x_s * k) * per_sigma, (-value - d_y_z - d_ends) * per_sigma;
  return out;
}

}  // namespace markerbench
