#include "bench/manifest.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <thread>

#include "bench/atomic_file.h"
#include "bench/build_info.h"
#include "core/regular_file.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

// Standard output of a shell command, trailing newline removed; empty on failure.
std::string CommandOutput(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(command.c_str(), "r"), ::pclose);
  if (!pipe) return "";
  std::string out;
  char buffer[256];
  while (std::fgets(buffer, sizeof(buffer), pipe.get())) out += buffer;
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

}  // namespace

nlohmann::json EnvironmentManifest(int threads) {
  const std::string git = std::string("git -C '") + MARKERBENCH_SOURCE_DIR + "' ";
  nlohmann::json env;
  env["git_commit"] = CommandOutput(git + "rev-parse HEAD 2>/dev/null");
  // Changes to tracked files other than results/ (which a run itself rewrites).
  env["git_dirty"] =
      !CommandOutput(git + "status --porcelain --untracked-files=no -- . ':!results' 2>/dev/null")
           .empty();
  env["compiler"] = build_info::kCompiler;
  env["build_type"] = build_info::kBuildType;
  for (const auto& [library, version] : build_info::kLibraries) env["libraries"][library] = version;
  env["cpu_model"] = CpuModel();
  env["hardware_threads"] = std::thread::hardware_concurrency();
  env["threads"] = threads;
  return env;
}

std::string VersionText() {
  const std::string describe = CommandOutput(std::string("git -C '") + MARKERBENCH_SOURCE_DIR +
                                             "' describe --always --dirty 2>/dev/null");
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
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw ConfigError(path + ": expected a JSON manifest: " + e.what());
  }
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
