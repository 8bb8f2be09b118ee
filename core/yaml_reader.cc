#include "core/yaml_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include "core/joined.h"
#include "core/regular_file.h"

namespace markerbench {
namespace {

// A short list of plain values is shown as written, so that the message says which value is out
// of range; a longer or nested one by its length.
std::string Describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) {
    constexpr size_t kMaxShownItems = 8;
    const bool plain = node.size() <= kMaxShownItems &&
                       std::all_of(node.begin(), node.end(), [](const YAML::Node& item) {
                         return item.IsScalar();
                       });
    if (!plain) return "a list of " + std::to_string(node.size());
    std::vector<std::string> items;
    for (const YAML::Node& item : node) items.push_back(item.Scalar());
    return "[" + Joined(items) + "]";
  }
  return "a mapping";
}

template <typename T>
const char* TypeName();
template <>
const char* TypeName<double>() {
  return "a number";
}
template <>
const char* TypeName<int>() {
  return "an integer";
}
template <>
const char* TypeName<bool>() {
  return "true or false";
}
template <>
const char* TypeName<std::string>() {
  return "a string";
}

template <typename T>
bool Convert(const YAML::Node& node, T* out) {
  if (!node.IsDefined() || !node.IsScalar()) return false;
  try {
    *out = node.as<T>();
  } catch (const YAML::Exception&) {
    // An integer may be written as any whole number: 1e+05 is how NumberText writes 100000,
    // in the parameters a run records.
    if constexpr (std::is_same_v<T, int>) {
      double whole = 0.0;
      if (!Convert(node, &whole) || whole != std::floor(whole) ||
          !(std::abs(whole) <= std::numeric_limits<int>::max())) {
        return false;
      }
      *out = static_cast<int>(whole);
      return true;
    }
    return false;
  }
  if constexpr (std::is_same_v<T, double>) return std::isfinite(*out);
  return true;
}

std::string Line(const YAML::Node& node) { return std::to_string(node.Mark().line + 1); }

// Mappings anywhere in the file must have distinct plain keys: yaml-cpp keeps the first of
// two equal keys silently, and a complex key (`? [a, b]`) matches no getter. Aliases can make
// a small file expand to a huge tree, so at most kMaxValues nodes are visited.
void CheckKeys(const YAML::Node& node, const std::string& path, size_t* visited) {
  constexpr size_t kMaxValues = 1'000'000;
  if (++*visited > kMaxValues) {
    throw ConfigError(path + ": more than " + std::to_string(kMaxValues) +
                      " values (aliases expand to copies)");
  }
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) CheckKeys(item, path, visited);
  }
  if (!node.IsMap()) return;
  std::map<std::string, YAML::Node> keys;
  for (const auto& entry : node) {
    const YAML::Node& key = entry.first;
    if (!key.IsScalar()) {
      throw ConfigError(path + ":" + Line(key) + ": a key must be a plain name, got " +
                        Describe(key));
    }
    const auto [earlier, inserted] = keys.emplace(key.Scalar(), key);
    if (!inserted) {
      throw ConfigError(path + ":" + Line(key) + ": key '" + key.Scalar() +
                        "' is given twice, first on line " + Line(earlier->second));
    }
    CheckKeys(entry.second, path, visited);
  }
}

// One step of an override's key path: a key of a mapping or an index of a list.
struct KeyStep {
  std::string key;  // empty for an index
  size_t index = 0;
};

// "a.b[2].c" as steps; throws on an empty key or a malformed index.
std::vector<KeyStep> ParseKeyPath(const std::string& path, const std::string& setting) {
  std::vector<KeyStep> steps;
  size_t i = 0;
  const auto fail = [&](const std::string& what) {
    throw ConfigError(setting + ": " + what +
                      " (expected KEY=VALUE with KEY like render.noise_var or "
                      "trackers[0].options.threshold)");
  };
  while (true) {
    const size_t end = path.find_first_of(".[", i);
    const std::string key = path.substr(i, end == std::string::npos ? end : end - i);
    if (key.empty()) fail("an empty key");
    steps.push_back({key, 0});
    i = end == std::string::npos ? path.size() : end;
    while (i < path.size() && path[i] == '[') {
      const size_t close = path.find(']', i);
      const std::string digits = path.substr(i + 1, close == std::string::npos ? 0 : close - i - 1);
      if (close == std::string::npos || digits.empty() || digits.size() > 6 ||
          digits.find_first_not_of("0123456789") != std::string::npos) {
        fail("a list index [N]");
      }
      steps.push_back({"", static_cast<size_t>(std::stoul(digits))});
      i = close + 1;
    }
    if (i == path.size()) break;
    if (path[i] != '.') fail("'.' or '[' after a key");
    ++i;
  }
  return steps;
}

void CollectNodes(const YAML::Node& node,
                  const std::string& text,
                  std::vector<std::pair<YAML::Node, std::string>>* out) {
  out->emplace_back(node, text);
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) CollectNodes(item, text, out);
  } else if (node.IsMap()) {
    for (const auto& entry : node) CollectNodes(entry.second, text, out);
  }
}

// Applies "key.path=value" (given with `flag`) to `root`; appends the nodes it put there to
// `overridden`.
void ApplyOverride(YAML::Node root,
                   const std::string& flag,
                   const std::string& override_text,
                   std::vector<std::pair<YAML::Node, std::string>>* overridden) {
  const std::string setting = flag + " " + override_text;
  const size_t equals = override_text.find('=');
  if (equals == std::string::npos) throw ConfigError(setting + ": expected KEY=VALUE");
  const std::vector<KeyStep> steps = ParseKeyPath(override_text.substr(0, equals), setting);
  YAML::Node value;
  try {
    value = YAML::Load(override_text.substr(equals + 1));
  } catch (const YAML::Exception& e) {
    throw ConfigError(setting + ": the value is not valid YAML: " + e.msg);
  }
  if (!value.IsDefined() || value.IsNull()) {
    throw ConfigError(setting + ": expected a value after '='");
  }
  YAML::Node node = root;
  std::string walked;
  for (size_t s = 0; s < steps.size(); ++s) {
    const KeyStep& step = steps[s];
    const bool last = s + 1 == steps.size();
    if (!step.key.empty()) {
      if (!node.IsMap()) {
        throw ConfigError(setting + ": '" + walked + "' is not a mapping");
      }
      if (last) {
        node[step.key] = value;
      } else if (!node[step.key].IsDefined()) {
        node[step.key] = YAML::Node(YAML::NodeType::Map);
      }
      node.reset(node[step.key]);
      walked += (walked.empty() ? "" : ".") + step.key;
    } else {
      if (!node.IsSequence() || step.index >= node.size()) {
        throw ConfigError(setting + ": '" + walked + "' has no item " + std::to_string(step.index));
      }
      if (last) node[step.index] = value;
      node.reset(node[step.index]);
      walked += "[" + std::to_string(step.index) + "]";
    }
  }
  CollectNodes(node, setting, overridden);
}

}  // namespace

YamlMap YamlMap::LoadFile(const std::string& path, const std::vector<std::string>& overrides) {
  RequireRegularFile(path);
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(path + ": cannot open the file");
  } catch (const YAML::Exception& e) {
    const std::string line = e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1);
    throw ConfigError(path + line + ": not valid YAML: " + e.msg);
  }
  if (!root.IsMap()) {
    throw ConfigError(path + ": expected a YAML mapping at the top level, got " + Describe(root));
  }
  YamlMap map = WithSettings(root, path, "--set", overrides);
  size_t visited = 0;
  CheckKeys(root, path, &visited);
  return map;
}

YamlMap YamlMap::FromSettings(const std::string& source,
                              const std::string& flag,
                              const std::vector<std::string>& settings) {
  return WithSettings(YAML::Node(YAML::NodeType::Map), source, flag, settings);
}

YamlMap YamlMap::WithSettings(YAML::Node root,
                              const std::string& source,
                              const std::string& flag,
                              const std::vector<std::string>& settings) {
  auto overridden = std::make_shared<Overridden>();
  for (const std::string& text : settings) ApplyOverride(root, flag, text, overridden.get());
  YamlMap map(root, source, "");
  map.overridden_ = std::move(overridden);
  return map;
}

YamlMap YamlMap::Child(const YAML::Node& node, std::string key_path) const {
  YamlMap child(node, file_, std::move(key_path));
  child.overridden_ = overridden_;
  return child;
}

YamlMap::YamlMap(const YAML::Node& node, std::string file, std::string key_path)
    : node_(node), file_(std::move(file)), key_path_(std::move(key_path)) {}

bool YamlMap::Has(const std::string& key) const { return node_[key].IsDefined(); }

std::string YamlMap::FullKey(const std::string& key) const {
  return key_path_.empty() ? key : key_path_ + "." + key;
}

std::string YamlMap::Where(const YAML::Node& node) const {
  if (overridden_) {
    for (const auto& [overridden, text] : *overridden_) {
      if (overridden.is(node)) return file_ + " (" + text + ")";
    }
  }
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return file_;
  return file_ + ":" + std::to_string(mark.line + 1);
}

void YamlMap::Fail(const std::string& key, const std::string& expected) const {
  const YAML::Node value = node_[key];
  const bool present = value.IsDefined();
  std::ostringstream msg;
  msg << Where(present ? value : node_) << ": key '" << FullKey(key) << "': ";
  if (present) {
    msg << "expected " << expected << ", got " << Describe(value);
  } else {
    msg << "missing; expected " << expected;
  }
  throw ConfigError(msg.str());
}

YAML::Node YamlMap::Lookup(const std::string& key) const {
  read_keys_.insert(key);
  return node_[key];
}

template <typename T>
T YamlMap::Get(const std::string& key) const {
  const YAML::Node value = Lookup(key);
  if constexpr (std::is_same_v<T, Eigen::Vector2d> || std::is_same_v<T, Eigen::Vector3d>) {
    const std::string expected = "a list of " + std::to_string(T::RowsAtCompileTime) + " numbers";
    if (!value.IsDefined() || !value.IsSequence() ||
        value.size() != static_cast<size_t>(T::RowsAtCompileTime)) {
      Fail(key, expected);
    }
    T out;
    for (int i = 0; i < T::RowsAtCompileTime; ++i) {
      if (!Convert(value[i], &out[i])) Fail(key, expected);
    }
    return out;
  } else if constexpr (std::is_same_v<T, std::vector<double>> ||
                       std::is_same_v<T, std::vector<int>> ||
                       std::is_same_v<T, std::vector<std::string>>) {
    using E = typename T::value_type;
    const std::string expected = std::string("a list of ") + TypeName<E>() + " values";
    if (!value.IsDefined() || !value.IsSequence()) Fail(key, expected);
    T out(value.size());
    for (size_t i = 0; i < value.size(); ++i) {
      E element;
      if (!Convert(value[i], &element)) Fail(key, expected);
      out[i] = element;
    }
    return out;
  } else {
    T out;
    if (!Convert(value, &out)) Fail(key, TypeName<T>());
    return out;
  }
}

template double YamlMap::Get<double>(const std::string&) const;
template int YamlMap::Get<int>(const std::string&) const;
template bool YamlMap::Get<bool>(const std::string&) const;
template std::string YamlMap::Get<std::string>(const std::string&) const;
template Eigen::Vector2d YamlMap::Get<Eigen::Vector2d>(const std::string&) const;
template Eigen::Vector3d YamlMap::Get<Eigen::Vector3d>(const std::string&) const;
template std::vector<double> YamlMap::Get<std::vector<double>>(const std::string&) const;
template std::vector<int> YamlMap::Get<std::vector<int>>(const std::string&) const;
template std::vector<std::string> YamlMap::Get<std::vector<std::string>>(const std::string&) const;

double YamlMap::GetDouble(const std::string& key, double lo, double hi) const {
  const double value = Get<double>(key);
  if (!(value >= lo && value <= hi)) {
    std::ostringstream expected;
    expected << "a number in [" << lo << ", " << hi << "]";
    Fail(key, expected.str());
  }
  return value;
}

int YamlMap::GetInt(const std::string& key, int lo, int hi) const {
  const int value = Get<int>(key);
  if (value < lo || value > hi) {
    Fail(key, "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return value;
}

double YamlMap::GetLength(const std::string& key) const {
  return GetDouble(key, kMinLengthM, kMaxLengthM);
}

Eigen::Vector2d YamlMap::GetPoint(const std::string& key) const {
  const Eigen::Vector2d point = Get<Eigen::Vector2d>(key);
  if (!(point.cwiseAbs().maxCoeff() <= kMaxLengthM)) {
    std::ostringstream expected;
    expected << "[x, y] in metres, each in [" << -kMaxLengthM << ", " << kMaxLengthM << "]";
    Fail(key, expected.str());
  }
  return point;
}

Eigen::Vector3d YamlMap::GetColor(const std::string& key) const {
  const Eigen::Vector3d color = Get<Eigen::Vector3d>(key);
  if (!(color.minCoeff() >= 0.0 && color.maxCoeff() <= 1.0)) {
    Fail(key, "an RGB colour [r, g, b] with each value in [0, 1]");
  }
  return color;
}

YamlMap YamlMap::GetMap(const std::string& key) const {
  const YAML::Node value = Lookup(key);
  if (!value.IsDefined() || !value.IsMap()) Fail(key, "a mapping");
  return Child(value, FullKey(key));
}

std::vector<YamlMap> YamlMap::GetMapList(const std::string& key) const {
  const YAML::Node value = Lookup(key);
  if (!value.IsDefined() || !value.IsSequence()) Fail(key, "a list of mappings");
  std::vector<YamlMap> out;
  for (size_t i = 0; i < value.size(); ++i) {
    const std::string element_key = FullKey(key) + "[" + std::to_string(i) + "]";
    if (!value[i].IsMap()) {
      throw ConfigError(Where(value[i]) + ": key '" + element_key + "': expected a mapping, got " +
                        Describe(value[i]));
    }
    out.push_back(Child(value[i], element_key));
  }
  return out;
}

YAML::Node YamlMap::GetNode(const std::string& key) const { return Lookup(key); }

void YamlMap::RejectUnknownKeys() const {
  for (const auto& entry : node_) {
    const std::string key = entry.first.as<std::string>();
    if (read_keys_.count(key) == 0) {
      // A key an override added has no line; its value names the override.
      const bool added = entry.first.Mark().is_null();
      throw ConfigError(Where(added ? entry.second : entry.first) + ": key '" + FullKey(key) +
                        "': unknown key (check its spelling and the format in README.md)");
    }
  }
}

std::string ResolveRelativeTo(const std::string& yaml_file, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(yaml_file).parent_path() / p).lexically_normal().string();
}

}  // namespace markerbench
