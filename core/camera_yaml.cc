#include "core/camera_yaml.h"

#include <cmath>
#include <cstdint>

#include "core/yaml_reader.h"

namespace markerbench {
namespace {

// A {rows, cols, data} matrix block with the given shape.
std::vector<double> ReadMatrix(const YamlMap& parent, const std::string& key, int rows, int cols) {
  const YamlMap block = parent.GetMap(key);
  const int r = block.Get<int>("rows");
  const int c = block.Get<int>("cols");
  if (r != rows || c != cols) {
    block.Fail("rows", "a " + std::to_string(rows) + "x" + std::to_string(cols) + " matrix");
  }
  const std::vector<double> data = block.Get<std::vector<double>>("data");
  if (data.size() != static_cast<size_t>(rows * cols)) {
    block.Fail("data", std::to_string(rows * cols) + " numbers (rows x cols)");
  }
  block.RejectUnknownKeys();
  return data;
}

// Whether distortion maps the image one to one: at a grid of pixels over the whole image,
// undistorting and distorting again returns the pixel and the Jacobian keeps its sign.
bool DistortionIsMonotonic(const Camera& camera) {
  constexpr int kSteps = 16;
  constexpr double kRoundTripTolPx = 0.01;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j <= kSteps; ++j) {
      const double u = -0.5 + camera.width * i / static_cast<double>(kSteps);
      const double v = -0.5 + camera.height * j / static_cast<double>(kSteps);
      // The pixel's distorted normalized point: K⁻¹ of it, as if it were an ideal pixel.
      const Eigen::Vector2d distorted = camera.CamFromIdeal({u, v}).head<2>();
      const Eigen::Vector2d ray = camera.Undistort(distorted);
      const Eigen::Vector2d error = camera.Distort(ray) - distorted;
      if (!(std::abs(error.x()) * camera.fx < kRoundTripTolPx &&
            std::abs(error.y()) * camera.fy < kRoundTripTolPx &&
            camera.DistortJacobian(ray).determinant() > 0.0)) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace

Camera LoadCameraYaml(const std::string& path) {
  const YamlMap root = YamlMap::LoadFile(path);
  Camera camera;
  camera.width = root.GetInt("image_width", 1, kMaxImageSide);
  camera.height = root.GetInt("image_height", 1, kMaxImageSide);
  if (static_cast<int64_t>(camera.width) * camera.height > kMaxImagePixels) {
    root.Fail("image_height",
              "an image of at most " + std::to_string(kMaxImagePixels) +
                  " pixels (image_width x image_height)");
  }
  camera.name = root.GetOr<std::string>("camera_name", "camera");

  const std::vector<double> k = ReadMatrix(root, "camera_matrix", 3, 3);
  if (!(k[0] >= kMinFocalPx && k[0] <= kMaxFocalPx && k[4] >= kMinFocalPx && k[4] <= kMaxFocalPx)) {
    root.Fail("camera_matrix", "focal lengths data[0] (fx) and data[4] (fy) in [0.001, 1e7] px");
  }
  if (k[1] != 0.0 || k[3] != 0.0 || k[6] != 0.0 || k[7] != 0.0 || k[8] != 1.0) {
    root.Fail("camera_matrix", "[fx, 0, cx, 0, fy, cy, 0, 0, 1] (zero skew)");
  }
  camera.fx = k[0];
  camera.cx = k[2];
  camera.fy = k[4];
  camera.cy = k[5];
  if (!(camera.cx >= -0.5 && camera.cx <= camera.width - 0.5 && camera.cy >= -0.5 &&
        camera.cy <= camera.height - 0.5)) {
    root.Fail("camera_matrix", "a principal point data[2] (cx), data[5] (cy) inside the image");
  }

  const std::string model = root.Get<std::string>("distortion_model");
  if (model != "plumb_bob") root.Fail("distortion_model", "'plumb_bob' (k1 k2 p1 p2 k3)");
  const std::vector<double> d = ReadMatrix(root, "distortion_coefficients", 1, 5);
  std::copy(d.begin(), d.end(), camera.distortion.begin());
  const bool bounded =
      std::abs(d[0]) <= kMaxRadialCoefficient && std::abs(d[1]) <= kMaxRadialCoefficient &&
      std::abs(d[4]) <= kMaxRadialCoefficient && std::abs(d[2]) <= kMaxTangentialCoefficient &&
      std::abs(d[3]) <= kMaxTangentialCoefficient;
  if (!bounded) {
    root.Fail("distortion_coefficients", "|k1|, |k2|, |k3| <= 100 and |p1|, |p2| <= 1");
  }
  if (!DistortionIsMonotonic(camera)) {
    root.Fail("distortion_coefficients",
              "distortion that is one to one over the image (these fold it back on itself)");
  }

  // ROS writes these for stereo rectification; they are checked for shape and not used.
  if (root.Has("rectification_matrix")) ReadMatrix(root, "rectification_matrix", 3, 3);
  if (root.Has("projection_matrix")) ReadMatrix(root, "projection_matrix", 3, 4);
  root.RejectUnknownKeys();

  std::string error;
  if (!camera.IsValid(&error)) throw ConfigError(path + ": " + error);
  return camera;
}

}  // namespace markerbench
