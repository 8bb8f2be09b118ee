// Strict YAML reading for every user-facing file (architecture.md, "Error handling" tier 2).
// A YamlMap tracks the keys it hands out; RejectUnknownKeys() reports the rest. Every error
// names the file, the line, the full key path and what was expected, as a ConfigError.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/config_error.h"

namespace markerbench {

class YamlMap {
 public:
  // Parses `path`, whose top level must be a mapping, then applies `overrides` in order:
  // "key.path=value" with the value in YAML flow form ("render.noise_var=0.05",
  // "sweep.values=[0.1, 0.2]", "trackers[1].options.threshold=90"); missing keys are created.
  // Errors about an overridden value name the override, not a line of the file.
  static YamlMap LoadFile(const std::string& path, const std::vector<std::string>& overrides = {});
  // A mapping made only of settings in the same "key.path=value" form, given on a command line
  // with `flag` (errors name "source (flag key=value)").
  static YamlMap FromSettings(const std::string& source,
                              const std::string& flag,
                              const std::vector<std::string>& settings);

  YamlMap(const YAML::Node& node, std::string file, std::string key_path);

  const std::string& file() const { return file_; }
  const std::string& key_path() const { return key_path_; }
  bool Has(const std::string& key) const;

  // Required values. T is double, int, bool, std::string, Eigen::Vector2d, Eigen::Vector3d,
  // std::vector<double>, std::vector<std::string> or std::vector<int>.
  template <typename T>
  T Get(const std::string& key) const;
  // Optional values with a documented default.
  template <typename T>
  T GetOr(const std::string& key, const T& default_value) const {
    return Has(key) ? Get<T>(key) : default_value;
  }

  // Required numbers with a closed range [lo, hi].
  double GetDouble(const std::string& key, double lo, double hi) const;
  int GetInt(const std::string& key, int lo, int hi) const;
  // Lengths and coordinates in metres: what the renderer can draw in doubles without
  // overflow at any camera (a length in [kMinLengthM, kMaxLengthM], a point with every
  // coordinate in [-kMaxLengthM, kMaxLengthM]).
  static constexpr double kMinLengthM = 1e-6;
  static constexpr double kMaxLengthM = 1e4;
  double GetLength(const std::string& key) const;
  Eigen::Vector2d GetPoint(const std::string& key) const;
  // Colour: three numbers in [0, 1].
  Eigen::Vector3d GetColor(const std::string& key) const;

  YamlMap GetMap(const std::string& key) const;
  std::vector<YamlMap> GetMapList(const std::string& key) const;
  // The raw node, for values whose form depends on context; the key counts as read.
  YAML::Node GetNode(const std::string& key) const;

  // Throws naming the first key that no getter asked for.
  void RejectUnknownKeys() const;

  // Throws a ConfigError located at `key` (or at this map when the key is absent).
  [[noreturn]] void Fail(const std::string& key, const std::string& expected) const;

 private:
  // Each node an override put in the tree, with the override's text.
  using Overridden = std::vector<std::pair<YAML::Node, std::string>>;

  // `root` with the settings applied, errors about them naming "source (flag key=value)".
  static YamlMap WithSettings(YAML::Node root,
                              const std::string& source,
                              const std::string& flag,
                              const std::vector<std::string>& settings);
  YAML::Node Lookup(const std::string& key) const;
  YamlMap Child(const YAML::Node& node, std::string key_path) const;
  std::string Where(const YAML::Node& node) const;
  std::string FullKey(const std::string& key) const;

  YAML::Node node_;
  std::string file_;
  std::string key_path_;
  mutable std::set<std::string> read_keys_;
  std::shared_ptr<const Overridden> overridden_;
};

// Ends reading an options map: unknown keys are errors, and so is the complaint of
// `options.IsValid`, which names its key first ("key=value must ...") and is located there.
template <typename Options>
void FinishOptions(const YamlMap& map, const Options& options) {
  map.RejectUnknownKeys();
  std::string error;
  if (!options.IsValid(&error)) map.Fail(error.substr(0, error.find('=')), error);
}

// Resolves a path written inside `yaml_file` relative to that file's folder.
std::string ResolveRelativeTo(const std::string& yaml_file, const std::string& path);

}  // namespace markerbench
