#include "renderer/degradations.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "core/gamma_curve.h"
#include "core/random.h"

// The blurs' loops (a weight times a row, added to a row) are compiled twice, for AVX2 and for
// the baseline, and the loader picks the copy the CPU can run: AVX2 takes twice the floats an
// instruction. AVX2 alone brings no FMA, so each element's product and sum are rounded as before:
// the same bits. The tag's frame 3.6 % less time, circles_a's 5.1 % (results/speed.md).
#if defined(__x86_64__)
#define MARKERBENCH_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define MARKERBENCH_AVX2_CLONE
#endif

namespace markerbench {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<float> GaussianKernel(double sigma, int radius) {
  std::vector<float> kernel(static_cast<size_t>(2 * radius + 1));
  double sum = 0.0;
  for (int i = -radius; i <= radius; ++i) sum += std::exp(-0.5 * i * i / (sigma * sigma));
  for (int i = -radius; i <= radius; ++i) {
    kernel[static_cast<size_t>(i + radius)] =
        static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)) / sum);
  }
  return kernel;
}

}  // namespace

bool Degradations::IsValid(std::string* error) const {
  std::ostringstream msg;
  if (!(blur_sigma_px >= 0.0 && blur_sigma_px <= 100.0)) {
    msg << "blur_sigma_px=" << blur_sigma_px << " must be in [0, 100]";
  } else if (!(motion_blur_px >= 0.0 && motion_blur_px <= 200.0)) {
    msg << "motion_blur_px=" << motion_blur_px << " must be in [0, 200]";
  } else if (!std::isfinite(motion_blur_angle_deg)) {
    msg << "motion_blur_angle_deg must be finite";
  } else if (!(gain >= 0.0 && gain <= 100.0) || !std::isfinite(offset) || !gradient.allFinite()) {
    msg << "lighting gain=" << gain << " must be in [0, 100], offset and gradient finite";
  } else if (!(noise_var >= 0.0 && noise_var <= 10.0)) {
    msg << "noise_var=" << noise_var << " must be in [0, 10]";
  } else if (!IsValidGamma(gamma)) {
    msg << "gamma=" << gamma << " must be in [" << kMinGamma << ", " << kMaxGamma << "]";
  } else if (jpeg_quality < 0 || jpeg_quality > 100) {
    msg << "jpeg_quality=" << jpeg_quality << " must be 0 (off) or 1..100";
  } else {
    return true;
  }
  if (error) *error = msg.str();
  return false;
}

int Degradations::MarginPx() const {
  int margin = 0;
  if (blur_sigma_px > 0.0) margin += static_cast<int>(std::ceil(4.0 * blur_sigma_px));
  if (motion_blur_px > 0.0) margin += static_cast<int>(std::ceil(0.5 * motion_blur_px)) + 1;
  return margin;
}

PixelRect GrowWithin(const PixelRect& r, int by, const ImageF& image) {
  return {std::max(0, r.x0 - by),
          std::max(0, r.y0 - by),
          std::min(image.width, r.x1 + by),
          std::min(image.height, r.y1 + by)};
}

int BlurSubsampling(double sigma_px) {
  if (!(sigma_px > 0.0) || sigma_px >= kMinSampledBlurSigma) return 1;
  return std::min(kMaxBlurSubsampling,
                  static_cast<int>(std::ceil(kMinSampledBlurSigma / sigma_px)));
}

MARKERBENCH_AVX2_CLONE PixelRect GaussianBlur(double sigma_px,
                                              const PixelRect& roi,
                                              ImageF* image) {
  if (!(sigma_px > 0.0) || roi.Empty()) return roi;
  const int radius = static_cast<int>(std::ceil(4.0 * sigma_px));
  const std::vector<float> kernel = GaussianKernel(sigma_px, radius);
  const PixelRect out = GrowWithin(roi, radius, *image);
  const int w = image->width, h = image->height;
  const int span = out.x1 - out.x0;
  std::vector<float> row(static_cast<size_t>(span + 2 * radius));
  std::vector<float> tmp(static_cast<size_t>(span) * (out.y1 - out.y0 + 2 * radius));
  for (int c = 0; c < image->channels; ++c) {
    float* plane = image->plane(c);
    // Horizontal pass into tmp for rows out.y0 - radius .. out.y1 + radius (clamped reads).
    for (int yy = out.y0 - radius; yy < out.y1 + radius; ++yy) {
      const float* src = plane + static_cast<size_t>(std::clamp(yy, 0, h - 1)) * w;
      for (int i = 0; i < span + 2 * radius; ++i) {
        row[static_cast<size_t>(i)] = src[std::clamp(out.x0 - radius + i, 0, w - 1)];
      }
      float* dst = tmp.data() + static_cast<size_t>(yy - out.y0 + radius) * span;
      std::fill_n(dst, span, 0.0f);
      for (int k = 0; k <= 2 * radius; ++k) {
        const float wk = kernel[static_cast<size_t>(k)];
        const float* r = row.data() + k;
        for (int x = 0; x < span; ++x) dst[x] += wk * r[x];
      }
    }
    // Vertical pass back into the image.
    for (int y = out.y0; y < out.y1; ++y) {
      float* dst = plane + static_cast<size_t>(y) * w + out.x0;
      std::fill_n(dst, span, 0.0f);
      for (int k = 0; k <= 2 * radius; ++k) {
        const float wk = kernel[static_cast<size_t>(k)];
        const float* src = tmp.data() + static_cast<size_t>(y - out.y0 + k) * span;
        for (int x = 0; x < span; ++x) dst[x] += wk * src[x];
      }
    }
  }
  return out;
}

MARKERBENCH_AVX2_CLONE void BlurOntoPixels(double sigma_px,
                                           const SubpixelGrid& grid,
                                           const ImageF& fine,
                                           const Eigen::Vector2i& image_origin,
                                           ImageF* image) {
  const int s = grid.scale;
  const int radius = static_cast<int>(std::ceil(4.0 * s * sigma_px));
  const std::vector<float> gauss = GaussianKernel(s * sigma_px, radius);
  // pixel[d + radius] = (1/s) Σ_{m<s} gauss(m - d) weighs the sub-pixel d from a pixel's first
  // one; zeros pad it to `groups` groups of s.
  const int groups = (2 * radius + s + s - 1) / s;
  std::vector<float> pixel(static_cast<size_t>(groups * s), 0.0f);
  for (int d = -radius; d < radius + s; ++d) {
    for (int m = std::max(0, d - radius); m < std::min(s, d + radius + 1); ++m) {
      pixel[static_cast<size_t>(d + radius)] += gauss[static_cast<size_t>(m - d + radius)] / s;
    }
  }
  const int w = grid.region.x1 - grid.region.x0, h = grid.region.y1 - grid.region.y0;
  std::vector<float> columns(static_cast<size_t>(h) * fine.width);  // the vertical pass
  // One row of it in s phases: phases[p · span + k] = row[s·k + p - radius] (clamped).
  const int span = w + groups;
  std::vector<float> phases(static_cast<size_t>(s) * span);
  for (int c = 0; c < image->channels; ++c) {
    const float* src = fine.plane(c);
    for (int v = 0; v < h; ++v) {
      float* out = columns.data() + static_cast<size_t>(v) * fine.width;
      std::fill_n(out, fine.width, 0.0f);
      for (int t = 0; t < groups * s; ++t) {
        const float weight = pixel[static_cast<size_t>(t)];
        const int j = std::clamp(s * v - radius + t, 0, fine.height - 1);
        const float* in = src + static_cast<size_t>(j) * fine.width;
        for (int i = 0; i < fine.width; ++i) out[i] += weight * in[i];
      }
    }
    float* dst = image->plane(c);
    for (int v = 0; v < h; ++v) {
      const float* row = columns.data() + static_cast<size_t>(v) * fine.width;
      for (int p = 0; p < s; ++p) {
        for (int k = 0; k < span; ++k) {
          phases[static_cast<size_t>(p * span + k)] =
              row[std::clamp(s * k + p - radius, 0, fine.width - 1)];
        }
      }
      float* out = dst + static_cast<size_t>(grid.region.y0 - image_origin.y() + v) * image->width +
                   (grid.region.x0 - image_origin.x());
      std::fill_n(out, w, 0.0f);
      for (int q = 0; q < groups; ++q) {
        for (int p = 0; p < s; ++p) {
          const float weight = pixel[static_cast<size_t>(s * q + p)];
          const float* in = phases.data() + static_cast<size_t>(p * span + q);
          for (int u = 0; u < w; ++u) out[u] += weight * in[u];
        }
      }
    }
  }
}

PixelRect MotionBlur(double length_px, double angle_deg, const PixelRect& roi, ImageF* image) {
  if (!(length_px > 0.0) || roi.Empty()) return roi;
  const PixelRect out = GrowWithin(roi, static_cast<int>(std::ceil(0.5 * length_px)) + 1, *image);
  // Midpoint rule along the segment, 4 bilinear samples per pixel of length.
  const int samples = std::max(2, static_cast<int>(std::ceil(4.0 * length_px)));
  const double a = angle_deg * kPi / 180.0;
  const int w = image->width, h = image->height;
  std::vector<std::pair<double, double>> offsets;
  for (int j = 0; j < samples; ++j) {
    const double s = length_px * ((j + 0.5) / samples - 0.5);
    offsets.emplace_back(s * std::cos(a), s * std::sin(a));
  }
  const float inv = 1.0f / static_cast<float>(samples);
  std::vector<float> src;
  for (int c = 0; c < image->channels; ++c) {
    float* plane = image->plane(c);
    src.assign(plane, plane + image->plane_size());
    auto at = [&](int x, int y) {
      return src[static_cast<size_t>(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)];
    };
    for (int y = out.y0; y < out.y1; ++y) {
      for (int x = out.x0; x < out.x1; ++x) {
        float sum = 0.0f;
        for (const auto& [dx, dy] : offsets) {
          const double px = x + dx, py = y + dy;
          const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
          const float fx = static_cast<float>(px - x0), fy = static_cast<float>(py - y0);
          sum += (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                 fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
        }
        plane[static_cast<size_t>(y) * w + x] = sum * inv;
      }
    }
  }
  return out;
}

void ApplyLighting(const Degradations& d, ImageF* image) {
  if (d.gain == 1.0 && d.offset == 0.0 && d.gradient.isZero()) return;
  const double uc = 0.5 * (image->width - 1), vc = 0.5 * (image->height - 1);
  for (int c = 0; c < image->channels; ++c) {
    float* plane = image->plane(c);
    for (int y = 0; y < image->height; ++y) {
      const double row_offset = d.offset + d.gradient.y() * (y - vc) / image->height;
      float* p = plane + static_cast<size_t>(y) * image->width;
      for (int x = 0; x < image->width; ++x) {
        const double add = row_offset + d.gradient.x() * (x - uc) / image->width;
        p[x] = static_cast<float>(d.gain * p[x] + add);
      }
    }
  }
}

Image8 AddNoiseAndQuantize(double noise_var, double gamma, uint64_t seed, ImageF* image) {
  Image8 out;
  out.width = image->width;
  out.height = image->height;
  out.channels = image->channels;
  out.pixels.resize(image->plane_size() * image->channels);
  Rng rng(seed);
  const size_t n = image->plane_size();
  const int channels = image->channels;
  const float sigma = static_cast<float>(std::sqrt(noise_var));
  constexpr size_t kChunk = 4096;  // noise in cache-sized chunks, no frame-sized scratch
  float noise[kChunk];
  for (int c = 0; c < channels; ++c) {
    float* value = image->plane(c);
    if (noise_var > 0.0) {
      for (size_t start = 0; start < n; start += kChunk) {
        const size_t count = std::min(kChunk, n - start);
        rng.FillGaussian(sigma, count, noise);
        float* v = value + start;
        for (size_t i = 0; i < count; ++i) v[i] = std::clamp(v[i] + noise[i], 0.0f, 1.0f);
      }
    } else {
      for (size_t i = 0; i < n; ++i) value[i] = std::clamp(value[i], 0.0f, 1.0f);
    }
    uint8_t* dst = out.pixels.data() + c;
    if (gamma != 1.0) {
      const double exponent = 1.0 / gamma;
      for (size_t i = 0; i < n; ++i) {
        dst[i * channels] = static_cast<uint8_t>(255.0 * std::pow(value[i], exponent) + 0.5);
      }
    } else if (channels == 1) {
      for (size_t i = 0; i < n; ++i) dst[i] = static_cast<uint8_t>(value[i] * 255.0f + 0.5f);
    } else {
      for (size_t i = 0; i < n; ++i) {
        dst[i * channels] = static_cast<uint8_t>(value[i] * 255.0f + 0.5f);
      }
    }
  }
  return out;
}

void JpegRoundTrip(int quality, Image8* image) {
  if (quality <= 0) return;
  const int type = image->channels == 1 ? CV_8UC1 : CV_8UC3;
  cv::Mat mat(image->height, image->width, type, image->pixels.data());
  cv::Mat bgr;
  if (image->channels == 3) {
    cv::cvtColor(mat, bgr, cv::COLOR_RGB2BGR);
  } else {
    bgr = mat;
  }
  std::vector<uint8_t> buffer;
  cv::imencode(".jpg", bgr, buffer, {cv::IMWRITE_JPEG_QUALITY, quality});
  cv::Mat decoded =
      cv::imdecode(buffer, image->channels == 1 ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
  if (image->channels == 3) cv::cvtColor(decoded, decoded, cv::COLOR_BGR2RGB);
  std::copy(decoded.data, decoded.data + image->pixels.size(), image->pixels.begin());
}

}  // namespace markerbench
