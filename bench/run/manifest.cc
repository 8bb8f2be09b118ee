#include "bench/run/manifest.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

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
  return manifest;
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
