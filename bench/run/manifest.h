// manifest.json beside the results (architecture.md, "Manifest"): git commit, compiler,
// build type, library versions, CPU model, threads, and one entry per scenario with its file
// hashes, every tracker parameter and the measured wall time.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace markerbench {

// What built and ran this program.
nlohmann::json EnvironmentManifest(int threads);

// The build of this program as a manifest and run.json name it: {"git_commit", "git_diff_sha256"}
// (cmake/git_info.cmake; the hash empty for a tree without local changes).
nlohmann::json BuildIdentity();
// Whether two of them name the same commit and the same local changes (other keys aside).
bool SameBuild(const nlohmann::json& a, const nlohmann::json& b);
// A build for messages: "commit C" or "commit C with local changes (SHA-256 H…)", H's first 12
// digits (or none, from a manifest that has only git_dirty); "?" for what it does not say.
std::string BuildText(const nlohmann::json& build);

// `markerbench --version`: the source's git describe, the build and the libraries' versions.
std::string VersionText();

// Reads `path` (if any), sets "environment", puts `entry` at scenarios[scenario_name] and
// writes it back atomically (temporary file, then rename).
void UpdateManifest(const std::string& path,
                    const std::string& scenario_name,
                    const nlohmann::json& environment,
                    const nlohmann::json& entry);

// Reads a manifest; an empty object when the file does not exist.
nlohmann::json ReadManifest(const std::string& path);
// Writes `manifest` atomically.
void WriteManifest(const std::string& path, const nlohmann::json& manifest);

}  // namespace markerbench
