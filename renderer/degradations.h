// Image degradations in physical order (architecture.md; applied by RenderFrame):
// optics (Gaussian blur), motion (linear blur), lighting, sensor noise, 8-bit quantisation,
// then optional JPEG.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "core/image.h"
#include "renderer/rasterizer.h"
#include "renderer/subpixel_grid.h"

namespace markerbench {

struct Degradations {
  // The optics' blur: a Gaussian point-spread function of σ pixels (0: none) before each
  // pixel's area average (BlurSubsampling says how it is computed).
  double blur_sigma_px = 0.0;
  // Linear motion blur: a box along a segment of this length (px) and angle (deg, from +u
  // towards +v). 0: none.
  double motion_blur_px = 0.0;
  double motion_blur_angle_deg = 0.0;
  // Lighting: I' = gain·I + offset + gradient·((u - u_c)/W, (v - v_c)/H), (u_c, v_c) the
  // image centre: gradient is the intensity change across the full width / height.
  double gain = 1.0;
  double offset = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  // imnoise(I, 'gaussian', 0, var) on [0, 1] intensities, per channel, then clip.
  double noise_var = 0.0;
  // The camera's response after the noise, before 8-bit rounding: each clipped value v in
  // [0, 1] is written as v^(1/gamma) (1: linear; cameras encode with about 2.2).
  double gamma = 1.0;
  // JPEG quality 1..100 after quantisation; 0: no JPEG.
  int jpeg_quality = 0;

  bool IsValid(std::string* error) const;
  // Pixels of scene needed beyond the image border for exact blur at the border.
  int MarginPx() const;
};

// `r` grown by `by` pixels on every side, within `image`.
PixelRect GrowWithin(const PixelRect& r, int by, const ImageF& image);

// The optics blur the scene continuously and each pixel averages the result over its area.
// A Gaussian kernel sampled at integers (radius ceil(4σ)) on the pixel-averaged scene is within
// 0.42 of an 8-bit level of that on a full-contrast edge from σ = kMinSampledBlurSigma (1.2 at
// 2 px, 15 at 0.6); a sharper blur is applied on a grid s = BlurSubsampling(σ) =
// ceil(kMinSampledBlurSigma / σ) times finer (SubpixelGrid), at most kMaxBlurSubsampling, to a
// render of the scene on it, and averaged back over the pixels: within 0.45 of a level from
// σ = 0.3 px, 1.5 at 0.1 px (Degradations.BlurredEdgeIsTheContinuousModel).
inline constexpr double kMinSampledBlurSigma = 3.5;
inline constexpr int kMaxBlurSubsampling = 8;
int BlurSubsampling(double sigma_px);

// Blurs `image` in place with a kernel sampled at integers, recomputing only `roi` expanded by the
// kernel radius (the image is constant outside `roi`). Borders are clamped; RenderFrame renders a
// margin so the visible image never sees them. Returns the grown non-constant region.
PixelRect GaussianBlur(double sigma_px, const PixelRect& roi, ImageF* image);
// For `fine`, an image on `grid` (scale s): GaussianBlur's kernel of σ·s sub-pixels, then each
// pixel of the grid's region the mean of its s×s sub-pixels, written into `image`, whose pixel
// (0, 0) is canvas pixel `image_origin`. Computed at the pixels only: one pass along each axis
// with the kernel summed over a pixel's s sub-pixels, read every s-th sub-pixel (borders
// clamped).
void BlurOntoPixels(double sigma_px,
                    const SubpixelGrid& grid,
                    const ImageF& fine,
                    const Eigen::Vector2i& image_origin,
                    ImageF* image);
PixelRect MotionBlur(double length_px, double angle_deg, const PixelRect& roi, ImageF* image);
void ApplyLighting(const Degradations& degradations, ImageF* image);
// Adds noise (seeded) to `image` in place, clips it to [0, 1], and returns it encoded with
// `gamma` (Degradations::gamma) and quantised to 8 bits (interleaved channels). `image` keeps
// the clipped linear values.
Image8 AddNoiseAndQuantize(double noise_var, double gamma, uint64_t seed, ImageF* image);
// Encodes and decodes with OpenCV's JPEG codec at `quality`.
void JpegRoundTrip(int quality, Image8* image);

}  // namespace markerbench
