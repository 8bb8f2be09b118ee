#include "renderer/render_frame.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/subpixel_grid.h"

namespace markerbench {
namespace {

Eigen::Vector2d Project(const Camera& camera,
                        const Rigid3& cam_from_marker,
                        const Eigen::Vector2d& x) {
  return camera.ImgFromCam(cam_from_marker * Eigen::Vector3d(x.x(), x.y(), 0.0));
}

// Keeps the centre width x height of `canvas`, in place.
void CropInPlace(int margin, int width, int height, ImageF* canvas) {
  if (margin == 0) return;
  float* dst = canvas->data.data();
  for (int c = 0; c < canvas->channels; ++c) {
    for (int y = 0; y < height; ++y) {
      const float* src =
          canvas->plane(c) + static_cast<size_t>(y + margin) * canvas->width + margin;
      dst = std::copy(src, src + width, dst);  // never overtakes src: dst <= src
    }
  }
  canvas->width = width;
  canvas->height = height;
  canvas->data.resize(static_cast<size_t>(width) * height * canvas->channels);
}

// dst += weight × src over every pixel.
void AddScaled(const ImageF& src, float weight, ImageF* dst) {
  for (size_t i = 0; i < dst->data.size(); ++i) dst->data[i] += weight * src.data[i];
}

PixelRect Union(const PixelRect& a, const PixelRect& b) {
  if (a.Empty()) return b;
  if (b.Empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

// The scene integrated over the exposure by the trapezoidal rule: n intervals, then 2n
// (reusing the n + 1 sub-frames already rendered) until no pixel changes by half an 8-bit
// level or kMaxExposureSubframes is reached. pose_at(u), u in [0, 1] over the exposure.
RasterResult RasterizeExposure(const Scene& scene,
                               int channels,
                               const std::function<Rigid3(double)>& pose_at) {
  Scene sub = scene;
  const auto render_at = [&](double u) {
    sub.cam_from_marker = pose_at(u);
    return Rasterize(sub, channels);
  };
  RasterResult first = render_at(0.0);
  const RasterResult last = render_at(1.0);
  ImageF sum = first.image;  // Σ f(u_i), the ends weighted 1/2
  for (float& v : sum.data) v *= 0.5f;
  AddScaled(last.image, 0.5f, &sum);
  PixelRect nonuniform = Union(first.nonuniform, last.nonuniform);
  int n = 1;
  ImageF previous;
  constexpr float kHalfLevel = 0.5f / 255.0f;
  while (true) {
    for (int i = 1; i < 2 * n; i += 2) {
      const RasterResult r = render_at(static_cast<double>(i) / (2 * n));
      AddScaled(r.image, 1.0f, &sum);
      nonuniform = Union(nonuniform, r.nonuniform);
    }
    n *= 2;
    ImageF mean = sum;
    for (float& v : mean.data) v /= static_cast<float>(n);
    bool settled = n >= kMinExposureSubframes && !previous.data.empty();
    for (size_t i = 0; settled && i < mean.data.size(); ++i) {
      settled = std::abs(mean.data[i] - previous.data[i]) < kHalfLevel;
    }
    if (settled || n >= kMaxExposureSubframes) return {std::move(mean), nonuniform};
    previous = std::move(mean);
  }
}

// The scene (or a band of its rows) seen from the moving camera, every row starting its
// exposure at start_s: the exposure integral of RasterizeExposure, or a still render without
// exposure.
RasterResult RasterizeRows(const Scene& scene,
                           int channels,
                           const FrameRequest& request,
                           double start_s) {
  const auto& pose_at = request.cam_from_marker_at;
  if (request.exposure_s <= 0.0) {
    Scene still = scene;
    still.cam_from_marker = pose_at(start_s);
    return Rasterize(still, channels);
  }
  return RasterizeExposure(
      scene, channels, [&](double u) { return pose_at(start_s + u * request.exposure_s); });
}

// A moving camera's canvas, or the part of it on `grid` (`scene` seen through the grid's
// camera): one exposure for a global shutter; with a rolling shutter, bands of rows, each
// rendered through a camera cropped to it at its rows' time.
RasterResult RasterizeMoving(const Scene& scene,
                             int channels,
                             const FrameRequest& request,
                             int margin,
                             const SubpixelGrid& grid) {
  if (request.readout_s <= 0.0) return RasterizeRows(scene, channels, request, 0.0);
  const int rows = scene.camera.height;
  const int image_rows = request.scene.camera.height;
  const auto row_start_s = [&](double v) {  // row v of the grid; margin rows extrapolate
    return request.readout_s * (grid.CanvasRow(v) - margin) / std::max(1, image_rows - 1);
  };
  // Bands short enough that the motion within one's readout is under 1/8 px.
  constexpr double kBandMotionPx = 0.125;
  const double motion =
      ImageMotionPx(scene, request.cam_from_marker_at, row_start_s(0), row_start_s(rows - 1));
  // Clamped as a double: a point near the camera plane can move by any amount (or NaN).
  const double wanted = std::ceil(motion / kBandMotionPx);
  const int bands =
      std::isnan(wanted) ? rows : static_cast<int>(std::clamp(wanted, 1.0, double(rows)));
  RasterResult canvas{ImageF(scene.camera.width, rows, channels), PixelRect{}};
  for (int b = 0; b < bands; ++b) {
    const int v0 = b * rows / bands, v1 = (b + 1) * rows / bands;
    Scene band = scene;
    band.camera.height = v1 - v0;
    band.camera.cy -= v0;
    const RasterResult r = RasterizeRows(band, channels, request, row_start_s(0.5 * (v0 + v1 - 1)));
    for (int c = 0; c < channels; ++c) {
      std::copy(r.image.plane(c),
                r.image.plane(c) + r.image.plane_size(),
                canvas.image.plane(c) + static_cast<size_t>(v0) * scene.camera.width);
    }
    // A band is uniform outside its non-uniform box, but not every band in the same colour
    // (the horizon may cross them): the whole band counts.
    canvas.nonuniform = Union(canvas.nonuniform, PixelRect{0, v0, scene.camera.width, v1});
  }
  return canvas;
}

// The canvas, or its part on `grid`: the scene from a still or a moving camera.
RasterResult RasterizeOnGrid(const Scene& canvas_scene,
                             const FrameRequest& request,
                             int margin,
                             const SubpixelGrid& grid) {
  Scene scene = canvas_scene;
  scene.camera = grid.FineCamera(canvas_scene.camera);
  return request.cam_from_marker_at
             ? RasterizeMoving(scene, request.channels, request, margin, grid)
             : Rasterize(scene, request.channels);
}

// The optics' blur of the canvas `raster` (degradations.h, BlurSubsampling). Returns the region
// it may have changed.
PixelRect BlurOptics(const Scene& canvas_scene,
                     const FrameRequest& request,
                     int margin,
                     RasterResult* raster) {
  const double sigma = request.degradations.blur_sigma_px;
  const int scale = BlurSubsampling(sigma);
  const PixelRect& ink = raster->nonuniform;
  if (scale == 1 || ink.Empty()) return GaussianBlur(sigma, ink, &raster->image);
  const SubpixelGrid grid{scale,
                          GrowWithin(ink, static_cast<int>(std::ceil(4.0 * sigma)), raster->image)};
  const RasterResult fine = RasterizeOnGrid(canvas_scene, request, margin, grid);
  BlurOntoPixels(sigma, grid, fine.image, Eigen::Vector2i::Zero(), &raster->image);
  return grid.region;
}

}  // namespace

double ImageMotionPx(const Scene& scene,
                     const std::function<Rigid3(double)>& pose_at,
                     double a,
                     double b) {
  Eigen::AlignedBox2d outline = scene.marker->InkBounds();
  if (scene.sheet_size_m) {
    const Eigen::Vector2d center = outline.center(), half = 0.5 * *scene.sheet_size_m;
    outline.extend(center - half);
    outline.extend(center + half);
  }
  double largest = 0.0;
  const Rigid3 pose_a = pose_at(a), pose_b = pose_at(b);
  for (const Eigen::Vector2d& p : BoxOutline(outline, 4)) {
    const Eigen::Vector3d x(p.x(), p.y(), 0.0);
    const Eigen::Vector3d in_a = pose_a * x, in_b = pose_b * x;
    if (!(in_a.z() > 0.0 && in_b.z() > 0.0)) continue;
    largest =
        std::max(largest, (scene.camera.ImgFromCam(in_a) - scene.camera.ImgFromCam(in_b)).norm());
  }
  return largest;
}

GroundTruth ComputeGroundTruth(const MarkerSpec& marker,
                               const Camera& camera,
                               const Rigid3& cam_from_marker) {
  GroundTruth truth;
  truth.cam_from_marker = cam_from_marker;
  for (const Eigen::Vector2d& k : marker.keypoints) {
    truth.keypoints_px.push_back(Project(camera, cam_from_marker, k));
  }
  std::vector<Eigen::Vector2d> q = BoxOutline(marker.InkBounds(), 1);
  for (Eigen::Vector2d& corner : q) corner = Project(camera, cam_from_marker, corner);
  double twice_area = 0.0;  // shoelace
  for (size_t i = 0; i < q.size(); ++i) {
    const Eigen::Vector2d& a = q[i];
    const Eigen::Vector2d& b = q[(i + 1) % q.size()];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  truth.apparent_size_px = std::sqrt(0.5 * std::abs(twice_area));
  return truth;
}

RenderedFrame RenderFrame(const FrameRequest& request) {
  std::string error;
  if (!request.degradations.IsValid(&error)) throw std::invalid_argument(error);
  if (request.channels != 1 && request.channels != 3) {
    throw std::invalid_argument("channels must be 1 or 3");
  }
  const Camera& camera = request.scene.camera;
  // Render a margin so that blur at the image border sees the scene beyond it.
  const int margin = request.degradations.MarginPx();
  Scene canvas_scene = request.scene;
  canvas_scene.camera.width += 2 * margin;
  canvas_scene.camera.height += 2 * margin;
  canvas_scene.camera.cx += margin;
  canvas_scene.camera.cy += margin;

  const SubpixelGrid canvas_grid{1, {0, 0, canvas_scene.camera.width, canvas_scene.camera.height}};
  RasterResult raster = RasterizeOnGrid(canvas_scene, request, margin, canvas_grid);
  const Degradations& d = request.degradations;
  const PixelRect changed = BlurOptics(canvas_scene, request, margin, &raster);
  MotionBlur(d.motion_blur_px, d.motion_blur_angle_deg, changed, &raster.image);
  ImageF& image = raster.image;
  CropInPlace(margin, camera.width, camera.height, &image);
  ApplyLighting(d, &image);

  RenderedFrame frame;
  frame.image = AddNoiseAndQuantize(d.noise_var, d.gamma, request.noise_seed, &image);
  if (request.keep_linear) frame.linear = std::move(image);
  JpegRoundTrip(d.jpeg_quality, &frame.image);
  frame.truth = ComputeGroundTruth(*request.scene.marker, camera, request.scene.cam_from_marker);
  return frame;
}

}  // namespace markerbench
