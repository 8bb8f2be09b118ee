#include "core/camera_yaml.h"

#include <cmath>

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

}  // namespace

Camera LoadCameraYaml(const std::string& path) {
  const YamlMap root = YamlMap::LoadFile(path);
  Camera camera;
  camera.width = root.GetInt("image_width", 1, 100000);
  camera.height = root.GetInt("image_height", 1, 100000);
  camera.name = root.GetOr<std::string>("camera_name", "camera");

  const std::vector<double> k = ReadMatrix(root, "camera_matrix", 3, 3);
  if (!(k[0] > 0.0 && k[4] > 0.0)) {
    root.Fail("camera_matrix", "positive focal lengths data[0] (fx) and data[4] (fy)");
  }
  if (k[1] != 0.0 || k[3] != 0.0 || k[6] != 0.0 || k[7] != 0.0 || k[8] != 1.0) {
    root.Fail("camera_matrix", "[fx, 0, cx, 0, fy, cy, 0, 0, 1] (zero skew)");
  }
  camera.fx = k[0];
  camera.cx = k[2];
  camera.fy = k[4];
  camera.cy = k[5];

  const std::string model = root.Get<std::string>("distortion_model");
  if (model != "plumb_bob") root.Fail("distortion_model", "'plumb_bob' (k1 k2 p1 p2 k3)");
  const std::vector<double> d = ReadMatrix(root, "distortion_coefficients", 1, 5);
  std::copy(d.begin(), d.end(), camera.distortion.begin());

  // ROS writes these for stereo rectification; they are checked for shape and not used.
  if (root.Has("rectification_matrix")) ReadMatrix(root, "rectification_matrix", 3, 3);
  if (root.Has("projection_matrix")) ReadMatrix(root, "projection_matrix", 3, 4);
  root.RejectUnknownKeys();

  std::string error;
  if (!camera.IsValid(&error)) throw ConfigError(path + ": " + error);
  return camera;
}

}  // namespace markerbench
