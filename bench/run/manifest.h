// manifest.json beside the results (architecture.md, "Manifest"): git commit, compiler,
// build type, library versions, CPU model, threads, and one entry per scenario with its file
// hashes, every tracker parameter and the measured wall time.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>

#include "bench/plan/shard.h"
#include "core/config_error.h"

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

// Reads a manifest (or run.json); an empty object when the file does not exist. One that is not
// a JSON object, or where a key that report, merge, check or sweep read has another type (the
// environment's strings and threads; each scenario's file, trials, seed, frames, wall_s,
// frames_per_s, threads, builds, shards and trajectory), is a ConfigError naming the file and
// the key.
nlohmann::json ReadManifest(const std::string& path);

// Writes `manifest` atomically.
void WriteManifest(const std::string& path, const nlohmann::json& manifest);

// Key `key` of `manifest`, read from `path`, as a bool, a string or an integer; `fallback` where
// it is absent. A value of another type is a ConfigError naming the file and the key.
template <class T>
T ManifestValue(const nlohmann::json& manifest,
                const std::string& path,
                const std::string& key,
                const T& fallback) {
  const auto found = manifest.find(key);
  if (found == manifest.end()) return fallback;
  std::string expected;
  if constexpr (std::is_same_v<T, bool>) {
    if (found->is_boolean()) return found->template get<bool>();
    expected = "true or false";
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (found->is_string()) return found->template get<std::string>();
    expected = "a string";
  } else {
    static_assert(std::is_integral_v<T>, "a bool, a string or an integer");
    const bool fits =
        std::is_unsigned_v<T> ? found->is_number_unsigned() : found->is_number_integer();
    if (fits) return found->template get<T>();
    expected = std::is_unsigned_v<T> ? "a count" : "an integer";
  }
  throw ConfigError(path + ": key '" + key + "': expected " + expected + ", got " + found->dump());
}

// run.json's shard ({"index", "count"}), read from `path`; nullopt where the key is absent. One
// of another type, or naming no shard of its count, is a ConfigError naming the file and the key.
std::optional<Shard> RunJsonShard(const nlohmann::json& run, const std::string& path);

}  // namespace markerbench
