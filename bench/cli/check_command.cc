#include "bench/cli/check_command.h"

#include <filesystem>
#include <set>

#include "bench/io/atomic_file.h"
#include "bench/io/output_folder.h"
#include "bench/report/check_output.h"
#include "bench/run/manifest.h"
#include "core/file_bytes.h"
#include "core/yaml_reader.h"

namespace fs = std::filesystem;

namespace markerbench {
namespace {

// The files of a scenario folder that make a reference (no images), plain or compressed.
const char* const kReferenceFiles[] = {
    "frames.csv", "frames.csv.zst", "timing.csv", "timing.csv.zst", "run.json"};

void Bless(const std::string& run_dir, const std::string& reference_dir, std::ostream& out) {
  CreateOutputFolder(reference_dir);
  std::set<std::string> scenarios;
  for (const ScenarioResults& s : ReadRunResults(run_dir)) {
    scenarios.insert(s.name);
    fs::create_directories(fs::path(reference_dir) / s.name);
    for (const char* file : kReferenceFiles) {
      const fs::path from = fs::path(run_dir) / s.name / file;
      const fs::path to = fs::path(reference_dir) / s.name / file;
      if (fs::exists(from)) {
        WriteFileAtomically(to.string(), ReadFileBytes(from.string()));
      } else {
        fs::remove(to);
      }
    }
  }
  const fs::path manifest = fs::path(run_dir) / "manifest.json";
  if (fs::exists(manifest)) {
    WriteFileAtomically((fs::path(reference_dir) / "manifest.json").string(),
                        ReadFileBytes(manifest.string()));
  }
  for (const auto& entry : fs::directory_iterator(reference_dir)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || scenarios.count(name) ||
        !(fs::exists(entry.path() / "frames.csv") || fs::exists(entry.path() / "frames.csv.zst"))) {
      continue;
    }
    for (const char* file : kReferenceFiles) fs::remove(entry.path() / file);
    if (fs::is_empty(entry.path())) fs::remove(entry.path());
    out << "bless: removed " << name << " from the reference (not in the run)\n";
  }
  out << "bless: " << reference_dir << " now holds the run's " << scenarios.size()
      << " scenarios\n";
}

}  // namespace

int RunCheckCommand(const CheckCommandOptions& options, std::ostream& out) {
  const std::vector<ScenarioResults> run = ReadRunResults(options.run_dir);
  if (options.bless && !fs::exists(options.reference_dir)) {
    out << "bless: no reference yet at " << options.reference_dir << "\n";
    Bless(options.run_dir, options.reference_dir, out);
    return 0;
  }
  CheckReport report;
  try {
    // A reference that cannot be compared (another ground truth, an older file format) is
    // bad input, except to --bless, which replaces it.
    report = CompareRuns(run, ReadRunResults(options.reference_dir), options.check);
  } catch (const ConfigError& e) {
    if (!options.bless) throw;
    out << "bless: " << e.what() << "\n";
    Bless(options.run_dir, options.reference_dir, out);
    return 0;
  }
  const auto built_from = [](const std::string& dir) {
    const nlohmann::json manifest = ReadManifest((fs::path(dir) / "manifest.json").string());
    const auto environment = manifest.find("environment");
    const bool known =
        manifest.is_object() && environment != manifest.end() && environment->is_object();
    return BuildText(known ? *environment : nlohmann::json::object());
  };
  report.run_build = built_from(options.run_dir);
  report.reference_build = built_from(options.reference_dir);
  out << CheckTable(report);
  if (!options.markdown_path.empty()) {
    WriteFileAtomically(options.markdown_path, CheckMarkdown(report, options.check));
  }
  if (!options.junit_path.empty()) WriteFileAtomically(options.junit_path, CheckJunit(report));
  if (options.bless) {
    Bless(options.run_dir, options.reference_dir, out);
    return 0;
  }
  return report.Regressed() ? 1 : 0;
}

}  // namespace markerbench
