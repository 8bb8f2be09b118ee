#include "renderer/degradations.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/marker_yaml.h"
#include "core/random.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"

namespace markerbench {
namespace {

constexpr double kNoiseVarRelTol = 0.03;  // issue: noise variance to 3 %
constexpr double kPi = 3.14159265358979323846;

// A 0.3 m black square whose left edge falls on the pixel boundary u = 319.5 (fronto-
// parallel at 1 m), so the unblurred edge is an exact step.
FrameRequest SquareEdgeRequest(const MarkerSpec& square) {
  FrameRequest request;
  request.scene.marker = &square;
  request.scene.cam_from_marker = TiltedView(1.0, 0.0, 0.0);
  request.keep_linear = true;
  return request;
}

// Standard deviation of the line-spread function (ink derivative) along row 239.
double EdgeSpreadSigma(const ImageF& image, int from, int to) {
  double w = 0.0, m1 = 0.0, m2 = 0.0;
  for (int u = from; u < to; ++u) {
    const double d = image.at(u, 239) - image.at(u + 1, 239);  // ink rises to the right
    w += d;
    m1 += d * (u + 0.5);
    m2 += d * (u + 0.5) * (u + 0.5);
  }
  m1 /= w;
  return std::sqrt(m2 / w - m1 * m1);
}

// A straight edge at u = e, ink to its right, blurred by the optics' Gaussian and averaged over
// each pixel: 1 - [F(u + ½ - e) - F(u - ½ - e)], F(x) = x Φ(x/σ) + σ φ(x/σ) the step's
// blur integrated once more.
double ContinuousEdgeModel(int u, double e, double sigma) {
  const auto F = [sigma](double x) {
    const double z = x / sigma;
    return x * 0.5 * std::erfc(-z / std::sqrt(2.0)) +
           sigma * std::exp(-0.5 * z * z) / std::sqrt(2.0 * kPi);
  };
  return 1.0 - (F(u + 0.5 - e) - F(u - 0.5 - e));
}

TEST(Degradations, BlurredEdgeIsTheContinuousModel) {
  constexpr double kTol = 0.5 / 255.0;  // half an 8-bit level (degradations.h: 0.45 at most)
  const MarkerSpec square = BlackSquareMarker(0.0, -0.15, 0.3);
  for (double sigma : {0.3, 0.45, 0.6, 1.0, 1.5, 2.0, 3.0, 3.5, 5.0}) {
    for (double offset : {0.0, 0.1, 0.25, 0.4}) {
      FrameRequest request = SquareEdgeRequest(square);
      request.scene.cam_from_marker.translation.x() = offset / 600.0;  // edge at 319.5 + offset
      request.degradations.blur_sigma_px = sigma;
      const RenderedFrame frame = RenderFrame(request);
      const int reach = static_cast<int>(std::ceil(5 * sigma)) + 2;
      for (int u = 319 - reach; u <= 320 + reach; ++u) {
        const double error =
            std::abs(frame.linear.at(u, 239) - ContinuousEdgeModel(u, 319.5 + offset, sigma));
        EXPECT_LE(error, kTol) << "sigma " << sigma << " edge offset " << offset << " u " << u;
      }
    }
  }
}

// BlurOntoPixels is GaussianBlur on the grid, then each pixel's mean of its sub-pixels.
TEST(Degradations, BlurOntoPixelsIsTheBlurOnTheGridAveragedOverEachPixel) {
  constexpr float kTol = 1e-5f;               // float sums in another order
  const SubpixelGrid grid{3, {2, 1, 12, 9}};  // 10×8 pixels, 30×24 sub-pixels
  ImageF fine(30, 24, 2);
  Rng rng(5);
  for (float& value : fine.data) value = static_cast<float>(rng.Uniform(0.0, 1.0));
  for (const double sigma : {0.4, 1.1}) {
    ImageF blurred = fine;
    GaussianBlur(3 * sigma, {0, 0, 30, 24}, &blurred);
    ImageF image(14, 10, 2);  // its pixel (0, 0) is canvas pixel (1, 0)
    std::fill(image.data.begin(), image.data.end(), -1.0f);
    BlurOntoPixels(sigma, grid, fine, {1, 0}, &image);
    for (int c = 0; c < 2; ++c) {
      for (int y = 0; y < 10; ++y) {
        for (int x = 0; x < 14; ++x) {
          const int u = x + 1 - 2, v = y - 1;  // the pixel in the region
          float expected = -1.0f;              // outside it: untouched
          if (u >= 0 && u < 10 && v >= 0 && v < 8) {
            expected = 0.0f;
            for (int j = 3 * v; j < 3 * v + 3; ++j) {
              for (int i = 3 * u; i < 3 * u + 3; ++i) expected += blurred.at(i, j, c) / 9.0f;
            }
          }
          EXPECT_NEAR(image.at(x, y, c), expected, kTol) << sigma << ": " << x << ", " << y;
        }
      }
    }
  }
}

TEST(Degradations, MotionBlurSpreadsTheEdgeOverItsLength) {
  const MarkerSpec square = BlackSquareMarker(0.0, -0.15, 0.3);
  FrameRequest request = SquareEdgeRequest(square);
  constexpr double kLength = 12.0;
  request.degradations.motion_blur_px = kLength;
  const RenderedFrame frame = RenderFrame(request);
  // A box of length L has variance L²/12; bilinear sampling adds about 1/6 px².
  const double sigma = EdgeSpreadSigma(frame.linear, 319 - 12, 319 + 12);
  const double length = std::sqrt(12.0 * (sigma * sigma - 1.0 / 6.0));
  EXPECT_LE(std::abs(length / kLength - 1.0), 0.03);
}

TEST(Degradations, BlurIsExactAtTheImageBorder) {
  // The same scene seen by a wider camera, cropped, must equal the border render: with the
  // sampled kernel and on the sub-pixel grid.
  const MarkerSpec square = BlackSquareMarker(0.0, -0.15, 0.3);
  for (const double sigma : {4.0, 1.0}) {
    FrameRequest request = SquareEdgeRequest(square);
    const double edge_u = 2.0 * sigma;
    request.scene.cam_from_marker.translation.x() = (edge_u - 319.5) / 600.0;
    request.degradations.blur_sigma_px = sigma;
    const RenderedFrame border = RenderFrame(request);
    FrameRequest wide = request;
    wide.scene.camera.width += 100;
    wide.scene.camera.cx += 100;
    const RenderedFrame reference = RenderFrame(wide);
    for (int u = 0; u < 40; ++u) {
      EXPECT_NEAR(border.linear.at(u, 239), reference.linear.at(u + 100, 239), 1e-5)
          << "sigma " << sigma << " u " << u;
    }
    EXPECT_LT(border.linear.at(0, 239), 0.9999) << sigma;  // the edge's blur reaches the border
  }
}

TEST(Degradations, NoiseVarianceInFlatGrey) {
  MarkerSpec flat = BlackSquareMarker(0.0, 0.0, 0.01);  // tiny square in a corner of view
  flat.background = Rgb::Constant(0.5);
  for (double var : {0.005, 0.01, 0.02}) {
    FrameRequest request;
    request.scene.marker = &flat;
    request.scene.cam_from_marker = TiltedView(1.0, 0.0, 0.0);
    request.scene.cam_from_marker.translation.head<2>() = Eigen::Vector2d(0.4, 0.3);
    request.degradations.noise_var = var;
    request.noise_seed = SeedFor(1, 0, 0, SeedPurpose::kNoise);
    const Image8 image = RenderFrame(request).image;
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (int y = 0; y < 400; ++y) {
      for (int x = 0; x < 600; ++x) {
        const double v = image.at(x, y) / 255.0;
        sum += v;
        sum2 += v * v;
        ++n;
      }
    }
    const double mean = sum / n;
    const double measured = sum2 / n - mean * mean - 1.0 / (12.0 * 255.0 * 255.0);
    EXPECT_LE(std::abs(measured / var - 1.0), kNoiseVarRelTol) << "var " << var;
    EXPECT_NEAR(mean, 0.5, 0.002);
  }
}

TEST(Degradations, SameSeedSameBytesOtherSeedOtherNoise) {
  const MarkerSpec square = BlackSquareMarker(-0.05, -0.05, 0.1);
  FrameRequest request;
  request.scene.marker = &square;
  request.scene.cam_from_marker = TiltedView(0.6, 30.0, 10.0);
  request.degradations.blur_sigma_px = 2.0;
  request.degradations.noise_var = 0.02;
  request.noise_seed = 42;
  const Image8 a = RenderFrame(request).image;
  const Image8 b = RenderFrame(request).image;
  EXPECT_EQ(a.pixels, b.pixels);
  request.noise_seed = 43;
  const Image8 c = RenderFrame(request).image;
  EXPECT_NE(a.pixels, c.pixels);
}

TEST(Degradations, LightingGainOffsetAndGradient) {
  MarkerSpec flat = BlackSquareMarker(5.0, 5.0, 0.01);  // out of view
  flat.background = Rgb::Constant(0.5);
  FrameRequest request;
  request.scene.marker = &flat;
  request.scene.cam_from_marker = TiltedView(1.0, 0.0, 0.0);
  request.degradations.gain = 0.5;
  request.degradations.offset = 0.1;
  request.degradations.gradient = Eigen::Vector2d(0.2, 0.0);
  const Image8 image = RenderFrame(request).image;
  // 0.5·0.5 + 0.1 ± 0.2·(half width)/width at the left and right edges.
  EXPECT_NEAR(image.at(0, 100) / 255.0, 0.35 - 0.1 * 639.0 / 640.0, 0.5 / 255);
  EXPECT_NEAR(image.at(639, 100) / 255.0, 0.35 + 0.1 * 639.0 / 640.0, 0.5 / 255);
}

TEST(Degradations, JpegKeepsTheImageClose) {
  const MarkerSpec square = BlackSquareMarker(-0.05, -0.05, 0.1);
  FrameRequest request;
  request.scene.marker = &square;
  request.scene.cam_from_marker = TiltedView(0.6, 20.0, 10.0);
  const Image8 clean = RenderFrame(request).image;
  request.degradations.jpeg_quality = 50;
  const Image8 jpeg = RenderFrame(request).image;
  EXPECT_NE(clean.pixels, jpeg.pixels);
  double mse = 0.0;
  for (size_t i = 0; i < clean.pixels.size(); ++i) {
    const double d = clean.pixels[i] - jpeg.pixels[i];
    mse += d * d;
  }
  EXPECT_LT(mse / clean.pixels.size(), 20.0);  // quality 50: PSNR above 35 dB
}

// The camera's response after the noise: each written value is the clipped linear one (noise
// included) to the power 1/gamma, rounded; gamma 1 writes the linear values as before.
TEST(Degradations, GammaEncodesTheNoisyLinearValues) {
  const MarkerSpec square = BlackSquareMarker(-0.05, -0.05, 0.1);
  FrameRequest request = MarkerFrameRequest(square, TiltedView(0.6, 20.0, 10.0), 0.01, 1.5, 1);
  request.keep_linear = true;
  request.degradations.gain = 0.8;  // the paper mostly below white, where noise is not clipped
  request.degradations.offset = 0.05;
  const RenderedFrame linear = RenderFrame(request);
  request.degradations.gamma = 2.2;
  const RenderedFrame encoded = RenderFrame(request);
  EXPECT_EQ(encoded.linear.data, linear.linear.data);  // the same noise, clipped
  int differing = 0;
  for (int y = 0; y < 480; ++y) {
    for (int x = 0; x < 640; ++x) {
      const double v = linear.linear.at(x, y);
      EXPECT_NEAR(encoded.image.at(x, y), 255.0 * std::pow(v, 1.0 / 2.2), 0.5 + 1e-6);
      EXPECT_NEAR(linear.image.at(x, y), 255.0 * v, 0.5 + 1e-4);
      differing += encoded.image.at(x, y) != linear.image.at(x, y);
    }
  }
  EXPECT_GT(differing, 640 * 480 / 2);
}

TEST(Degradations, InvalidValuesAreRejected) {
  Degradations d;
  std::string error;
  d.noise_var = -0.1;
  EXPECT_FALSE(d.IsValid(&error));
  EXPECT_NE(error.find("noise_var"), std::string::npos);
  for (const double gamma : {0.0, 0.05, 11.0, std::nan("")}) {
    d = Degradations();
    d.gamma = gamma;
    EXPECT_FALSE(d.IsValid(&error)) << gamma;
    EXPECT_NE(error.find("gamma"), std::string::npos);
  }
}

}  // namespace
}  // namespace markerbench

namespace markerbench {
namespace {

// The motion-blurred frame (FrameRequest::cam_from_marker_at, exposure_s) against its definition,
// the mean of many still renders along the exposure (midpoint rule, 400 sub-frames): within
// half an 8-bit level, for a fast sideways and turning motion. A still "motion" gives the
// still render, and a hidden marker only the paper.
TEST(Degradations, ExposureIntegratesTheMotion) {
  const MarkerSpec tag = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
  FrameRequest request;
  request.scene.marker = &tag;
  request.scene.camera.width = 160;
  request.scene.camera.height = 120;
  request.scene.camera.cx = 79.5;
  request.scene.camera.cy = 59.5;
  request.keep_linear = true;
  const Rigid3 start = TiltedView(0.9, 25.0, 10.0);
  const auto pose_at = [&](double u) {  // 12 px sideways and 3° about the optical axis
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(3.0 * M_PI / 180.0 * u, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return Rigid3(turn, Eigen::Vector3d(0.012 * 0.9 / 0.6 * u, 0.0, 0.0)) * start;
  };
  request.scene.cam_from_marker = pose_at(0.5);
  request.cam_from_marker_at = pose_at;  // over an exposure of 1 s
  request.exposure_s = 1.0;
  const ImageF blurred = RenderFrame(request).linear;
  ImageF mean(blurred.width, blurred.height, blurred.channels);
  constexpr int kSubframes = 400;
  FrameRequest still = request;
  still.cam_from_marker_at = nullptr;
  for (int i = 0; i < kSubframes; ++i) {
    still.scene.cam_from_marker = pose_at((i + 0.5) / kSubframes);
    const ImageF sub = RenderFrame(still).linear;
    for (size_t p = 0; p < mean.data.size(); ++p) mean.data[p] += sub.data[p] / kSubframes;
  }
  double worst = 0.0, moved = 0.0;
  still.scene.cam_from_marker = pose_at(0.5);
  const ImageF middle = RenderFrame(still).linear;
  for (size_t p = 0; p < mean.data.size(); ++p) {
    worst = std::max(worst, static_cast<double>(std::abs(blurred.data[p] - mean.data[p])));
    moved = std::max(moved, static_cast<double>(std::abs(blurred.data[p] - middle.data[p])));
  }
  EXPECT_LT(worst, 0.5 / 255.0);
  EXPECT_GT(moved, 0.2);  // the blur is there

  request.cam_from_marker_at = [&](double) { return start; };
  request.scene.cam_from_marker = start;
  still.scene.cam_from_marker = start;
  const ImageF held = RenderFrame(request).linear;
  const ImageF at_rest = RenderFrame(still).linear;
  for (size_t p = 0; p < held.data.size(); ++p) ASSERT_NEAR(held.data[p], at_rest.data[p], 1e-6);

  still.scene.marker_hidden = true;
  const ImageF paper = RenderFrame(still).linear;
  for (const float v : paper.data) ASSERT_EQ(v, paper.data.front());
}

}  // namespace
}  // namespace markerbench

namespace markerbench {
namespace {

// The u where row v of `image` crosses 0.5 going right (linear between pixel centres: exact
// for an area-sampled step).
double EdgeCrossing(const ImageF& image, int v) {
  for (int u = 0; u + 1 < image.width; ++u) {
    const double a = image.at(u, v), b = image.at(u + 1, v);
    if (a >= 0.5 && b < 0.5) return u + (a - 0.5) / (a - b);
  }
  return NAN;
}

// A rolling shutter (FrameRequest::readout_s) skews a vertical edge seen from a camera moving
// sideways: row v sees it readout_s × v / (height - 1) later, so shifted by the image speed
// times that; the first row where a still camera would. Without exposure the edge stays a
// sharp step in every row.
TEST(Degradations, RollingShutterSkewsAMovingEdge) {
  const MarkerSpec square = BlackSquareMarker(0.0, -0.6, 1.2);  // taller than the image
  FrameRequest request = SquareEdgeRequest(square);
  const Rigid3 start = request.scene.cam_from_marker;
  constexpr double kSpeedPxPerS = 600.0, kReadoutS = 0.1;  // 1 m/s sideways at 1 m, f = 600
  request.cam_from_marker_at = [&](double t) {
    return Rigid3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(t * 1.0, 0.0, 0.0)) * start;
  };
  request.readout_s = kReadoutS;
  const ImageF image = RenderFrame(request).linear;
  for (const int v : {0, 40, 239, 440, 479}) {
    const double expected = 319.5 + kSpeedPxPerS * kReadoutS * v / 479.0;
    EXPECT_NEAR(EdgeCrossing(image, v), expected, 0.08) << "row " << v;
    const int u = static_cast<int>(std::lround(expected));
    EXPECT_EQ(image.at(u - 2, v), 1.0f) << "row " << v;  // sharp: paper, then ink
    EXPECT_EQ(image.at(u + 2, v), 0.0f) << "row " << v;
  }
}

}  // namespace
}  // namespace markerbench
