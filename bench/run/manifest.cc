#include "bench/run/manifest.h"

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <stdexcept>
#include <thread>
#include <utility>

#include "bench/io/atomic_file.h"
#include "bench/run/build_info.h"
#include "bench/run/git_info.h"
#include "core/regular_file.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

}  // namespace

nlohmann::json BuildIdentity() {
  return {{"git_commit", git_info::kCommit}, {"git_diff_sha256", git_info::kDiffSha256}};
}

bool SameBuild(const nlohmann::json& a, const nlohmann::json& b) {
  for (const char* key : {"git_commit", "git_diff_sha256"}) {
    if (a.value(key, std::string()) != b.value(key, std::string())) return false;
  }
  return true;
}

std::string BuildText(const nlohmann::json& build) {
  const std::string commit = "commit " + build.value("git_commit", std::string("?"));
  const std::string diff = build.value("git_diff_sha256", std::string());
  if (!diff.empty()) return commit + " with local changes (SHA-256 " + diff.substr(0, 12) + "…)";
  // A manifest written before the hash was kept says only whether there were changes.
  return build.value("git_dirty", false) ? commit + " with local changes" : commit;
}

nlohmann::json EnvironmentManifest(int threads) {
  nlohmann::json env = BuildIdentity();
  // Changes to tracked files other than results/ (which a run itself rewrites) at build time;
  // git_diff_sha256 tells two such builds apart.
  env["git_dirty"] = git_info::kDirty;
  env["compiler"] = build_info::kCompiler;
  env["build_type"] = build_info::kBuildType;
  for (const auto& [library, version] : build_info::kLibraries) env["libraries"][library] = version;
  env["cpu_model"] = CpuModel();
  env["hardware_threads"] = std::thread::hardware_concurrency();
  env["threads"] = threads;
  return env;
}

std::string VersionText() {
  const std::string describe = git_info::kDescribe;
  std::string text = "markerbench " + (describe.empty() ? std::string("(no git)") : describe) +
                     " (" + build_info::kBuildType + ", " + build_info::kCompiler + ")\n";
  for (const auto& [library, version] : build_info::kLibraries) {
    text += std::string(library) + " " + version + "\n";
  }
  return text;
}

namespace {

// A JSON type a manifest's key must have, and its name for messages.
struct JsonKind {
  bool (nlohmann::json::*is)() const noexcept;
  const char* expected;
};
constexpr JsonKind kString{&nlohmann::json::is_string, "a string"};
constexpr JsonKind kNumber{&nlohmann::json::is_number, "a number"};
constexpr JsonKind kBool{&nlohmann::json::is_boolean, "true or false"};
constexpr JsonKind kObject{&nlohmann::json::is_object, "an object"};
constexpr JsonKind kArray{&nlohmann::json::is_array, "a list"};

[[noreturn]] void FailKey(const std::string& path,
                          const std::string& key,
                          const char* expected,
                          const nlohmann::json& got) {
  throw ConfigError(path + ": key '" + key + "': expected " + expected + ", got " + got.dump());
}

// Each of `keys` of `object`, named `prefix` + key in messages, of its kind where present (or
// `required`).
void CheckKeys(const nlohmann::json& object,
               const std::string& path,
               const std::string& prefix,
               std::initializer_list<std::pair<const char*, JsonKind>> keys,
               bool required = false) {
  for (const auto& [key, kind] : keys) {
    const auto found = object.find(key);
    if (found == object.end()) {
      if (required) throw ConfigError(path + ": key '" + prefix + key + "': missing");
    } else if (!((*found).*kind.is)()) {
      FailKey(path, prefix + key, kind.expected, *found);
    }
  }
}

// The builds of `object` (an entry's or a shard's, named `prefix` in messages), each an object
// whose keys BuildText reads are strings.
void CheckBuilds(const nlohmann::json& object, const std::string& path, const std::string& prefix) {
  const auto builds = object.find("builds");
  if (builds == object.end()) return;
  for (size_t i = 0; i < builds->size(); ++i) {
    const std::string at = prefix + "builds/" + std::to_string(i);
    if (!(*builds)[i].is_object()) FailKey(path, at, "an object", (*builds)[i]);
    CheckKeys((*builds)[i],
              path,
              at + "/",
              {{"git_commit", kString}, {"git_diff_sha256", kString}, {"git_dirty", kBool}});
  }
}

// The keys of a manifest that report, merge, check and sweep read, each of its type (a run.json
// has none of them).
void CheckManifestKeys(const nlohmann::json& manifest, const std::string& path) {
  CheckKeys(manifest, path, "", {{"environment", kObject}, {"scenarios", kObject}});
  if (const auto environment = manifest.find("environment"); environment != manifest.end()) {
    CheckKeys(*environment,
              path,
              "environment/",
              {{"git_commit", kString},
               {"git_diff_sha256", kString},
               {"git_dirty", kBool},
               {"compiler", kString},
               {"build_type", kString},
               {"cpu_model", kString},
               {"threads", kNumber}});
  }
  const auto scenarios = manifest.find("scenarios");
  if (scenarios == manifest.end()) return;
  for (const auto& [name, entry] : scenarios->items()) {
    const std::string key = "scenarios/" + name + "/";
    if (!entry.is_object()) FailKey(path, "scenarios/" + name, "an object", entry);
    CheckKeys(entry,
              path,
              key,
              {{"file", kString},
               {"trials", kNumber},
               {"seed", kNumber},
               {"frames", kNumber},
               {"wall_s", kNumber},
               {"frames_per_s", kNumber},
               {"threads", kNumber},
               {"builds", kArray},
               {"shards", kArray},
               {"trajectory", kObject}});
    CheckBuilds(entry, path, key);
    if (const auto shards = entry.find("shards"); shards != entry.end()) {
      for (size_t i = 0; i < shards->size(); ++i) {
        const std::string at = key + "shards/" + std::to_string(i);
        if (!(*shards)[i].is_object()) FailKey(path, at, "an object", (*shards)[i]);
        CheckKeys((*shards)[i], path, at + "/", {{"builds", kArray}});
        CheckBuilds((*shards)[i], path, at + "/");
      }
    }
    if (const auto trajectory = entry.find("trajectory"); trajectory != entry.end()) {
      const std::string at = key + "trajectory/";
      CheckKeys(*trajectory,
                path,
                at,
                {{"fps", kNumber},
                 {"frames", kNumber},
                 {"static_s", kNumber},
                 {"exposure_s", kNumber},
                 {"readout_s", kNumber},
                 {"occlusions", kArray}},
                true);
      const nlohmann::json& occlusions = (*trajectory)["occlusions"];
      for (size_t i = 0; i < occlusions.size(); ++i) {
        const nlohmann::json& range = occlusions[i];
        if (!range.is_array() || range.size() != 2 || !range[0].is_number_integer() ||
            !range[1].is_number_integer()) {
          FailKey(path, at + "occlusions/" + std::to_string(i), "[first, last] frames", range);
        }
      }
    }
  }
}

}  // namespace

nlohmann::json ReadManifest(const std::string& path) {
  if (!std::filesystem::exists(path)) return nlohmann::json::object();
  RequireRegularFile(path);
  std::ifstream in(path);
  nlohmann::json manifest;
  try {
    manifest = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw ConfigError(path + ": expected a JSON manifest: " + e.what());
  }
  if (!manifest.is_object()) {
    throw ConfigError(path + ": expected a JSON object, got " + manifest.type_name());
  }
  CheckManifestKeys(manifest, path);
  return manifest;
}

std::optional<Shard> RunJsonShard(const nlohmann::json& run, const std::string& path) {
  const auto shard = run.find("shard");
  if (shard == run.end()) return std::nullopt;
  if (!shard->is_object()) {
    throw ConfigError(path + ": key 'shard': expected {index, count}, got " + shard->dump());
  }
  const std::string key = path + ": key 'shard'";
  return ParseShard(std::to_string(ManifestValue(*shard, key, "index", 0)) + "/" +
                        std::to_string(ManifestValue(*shard, key, "count", 1)),
                    key);
}

void WriteManifest(const std::string& path, const nlohmann::json& manifest) {
  WriteFileAtomically(path, manifest.dump(2) + "\n");
}

void UpdateManifest(const std::string& path,
                    const std::string& scenario_name,
                    const nlohmann::json& environment,
                    const nlohmann::json& entry) {
  nlohmann::json manifest = ReadManifest(path);
  manifest["environment"] = environment;
  manifest["scenarios"][scenario_name] = entry;
  WriteManifest(path, manifest);
}

}  // namespace markerbench
