#include "bench/plan/marker_files.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "bench/io/atomic_file.h"

namespace markerbench {

std::string WriteScaledMarkerFile(const std::string& source,
                                  double scale,
                                  const std::string& dir,
                                  const std::string& name) {
  YAML::Node marker = YAML::LoadFile(source);
  marker["scale"] = (marker["scale"] ? marker["scale"].as<double>() : 1.0) * scale;
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << marker;
  std::filesystem::create_directories(dir);
  const std::string path = std::filesystem::absolute(dir + "/" + name + ".yaml").string();
  WriteFileAtomically(path, std::string(out.c_str()) + "\n");
  return path;
}

std::map<std::string, std::string> WriteScaledMarkerFiles(const Scenario& scenario,
                                                          const std::string& dir) {
  std::map<std::string, std::string> files;
  for (size_t m = 0; m < scenario.markers.size(); ++m) {
    const std::string& name = scenario.markers[m].name;
    // input_files: the scenario, the camera, then the markers in order.
    files[name] =
        WriteScaledMarkerFile(scenario.input_files[2 + m], scenario.marker_scales[m], dir, name);
  }
  return files;
}

}  // namespace markerbench
