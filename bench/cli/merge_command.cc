#include "bench/cli/merge_command.h"

#include <sys/resource.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <queue>

#include "bench/io/atomic_file.h"
#include "bench/io/line_reader.h"
#include "bench/io/output_folder.h"
#include "bench/plan/shard.h"
#include "bench/run/frames_csv.h"
#include "bench/run/manifest.h"
#include "bench/run/run_results.h"
#include "core/config_error.h"
#include "core/number_text.h"

namespace fs = std::filesystem;

namespace markerbench {
namespace {

// One scenario folder of one shard.
struct ShardFolder {
  std::string dir;     // the shard's --out
  std::string folder;  // dir/<scenario>
  nlohmann::json run;  // its run.json
  Shard shard;
};

std::string ShardText(const Shard& shard) {
  return std::to_string(shard.index) + "/" + std::to_string(shard.count);
}

ShardFolder ReadShardFolder(const std::string& dir, const std::string& folder) {
  const std::string run_json = folder + "/run.json";
  if (!fs::exists(run_json)) {
    throw ConfigError(run_json + ": missing; expected the folder of a markerbench sweep");
  }
  ShardFolder s{dir, folder, ReadManifest(run_json), {}};
  const std::optional<Shard> shard = RunJsonShard(s.run, run_json);
  if (!shard) {
    throw ConfigError(run_json +
                      ": key 'shard': missing; written by a markerbench older than shards "
                      "or not by sweep");
  }
  s.shard = *shard;
  return s;
}

// Scenario name -> its folders in the shards, each checked to be a whole plan, in shard order.
std::map<std::string, std::vector<ShardFolder>> CollectPlans(const std::vector<std::string>& dirs) {
  std::map<std::string, std::vector<ShardFolder>> found;
  for (const std::string& dir : dirs) {
    for (const std::string& folder : ScenarioFolders(dir)) {
      found[fs::path(folder).filename().string()].push_back(ReadShardFolder(dir, folder));
    }
  }
  for (auto& [name, shards] : found) {
    const ShardFolder& first = shards.front();
    const auto fingerprint_of = [](const ShardFolder& s) {
      return ManifestValue(s.run, s.folder + "/run.json", "fingerprint", std::string("?"));
    };
    const std::string fingerprint = fingerprint_of(first);
    std::vector<const ShardFolder*> by_index(static_cast<size_t>(first.shard.count), nullptr);
    for (const ShardFolder& s : shards) {
      if (fingerprint_of(s) != fingerprint || s.shard.count != first.shard.count) {
        throw ConfigError(s.folder + ": shard " + ShardText(s.shard) + " of fingerprint " +
                          fingerprint_of(s) + ", but " + first.folder + " is shard " +
                          ShardText(first.shard) + " of fingerprint " + fingerprint +
                          ": the shards come from different scenarios (or a scenario or its "
                          "files changed between them)");
      }
      const ShardFolder*& slot = by_index[static_cast<size_t>(s.shard.index)];
      if (slot) {
        throw ConfigError(name + ": shard " + ShardText(s.shard) + " given twice: " + slot->folder +
                          " and " + s.folder);
      }
      slot = &s;
    }
    std::string missing;
    for (size_t i = 0; i < by_index.size(); ++i) {
      if (!by_index[i]) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    }
    if (!missing.empty()) {
      throw ConfigError(name + ": shards " + missing + " of " + std::to_string(by_index.size()) +
                        " are missing (found " + std::to_string(shards.size()) + ")");
    }
    for (const ShardFolder& s : shards) {
      if (!ManifestValue(s.run, s.folder + "/run.json", "complete", false)) {
        throw ConfigError(s.folder + "/run.json: shard " + ShardText(s.shard) +
                          " is incomplete; finish it with sweep --resume --shard " +
                          ShardText(s.shard));
      }
    }
    std::sort(shards.begin(), shards.end(), [](const ShardFolder& a, const ShardFolder& b) {
      return a.shard.index < b.shard.index;
    });
  }
  return found;
}

// A shard's frames.csv and timing.csv, read in step.
struct ShardCursor {
  const ShardFolder* source = nullptr;
  std::unique_ptr<LineReader> frames;
  std::unique_ptr<LineReader> timing;
  std::string line;  // the current frames.csv row
  int frame = -1;    // its frame; -1 at the end
  size_t rows = 0;   // rows taken so far
};

int FrameOf(const std::string& line, const LineReader& reader, size_t column) {
  const std::vector<std::string> f = SplitCsvLine(line);
  const std::optional<long long> frame =
      f.size() > column ? ParseWholeNumber(f[column], 0.0, std::numeric_limits<int>::max())
                        : std::nullopt;
  if (!frame) {
    throw ConfigError(reader.path() + ":" + std::to_string(reader.line_number()) +
                      ": expected a frame number in column " + std::to_string(column + 1));
  }
  return static_cast<int>(*frame);
}

void Advance(ShardCursor& c) {
  c.frame = c.frames->Next(&c.line) ? FrameOf(c.line, *c.frames, 4) : -1;
}

std::string RequireFile(const std::string& folder, const std::string& name) {
  const std::optional<std::string> path = FindTextFile(folder, name);
  if (!path) throw ConfigError(folder + ": no " + name);
  return *path;
}

// Interleaves the shards' rows by frame number: each shard holds its frames in plan order,
// and a frame's rows (one per tracker) stay together.
size_t MergeRows(const std::vector<ShardFolder>& shards,
                 const std::string& out_folder,
                 bool compress) {
  const std::string suffix = compress ? ".zst" : "";
  const Compression compression = compress ? Compression::kZstd : Compression::kNone;
  AtomicFileWriter frames_out(out_folder + "/frames.csv" + suffix, compression);
  AtomicFileWriter timing_out(out_folder + "/timing.csv" + suffix, compression);
  frames_out.Write(FramesCsvHeader());
  timing_out.Write(TimingCsvHeader());
  std::vector<ShardCursor> cursors(shards.size());
  using Entry = std::pair<int, size_t>;  // (frame, cursor)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> next;
  for (size_t i = 0; i < shards.size(); ++i) {
    ShardCursor& c = cursors[i];
    c.source = &shards[i];
    c.frames = std::make_unique<LineReader>(RequireFile(shards[i].folder, "frames.csv"));
    c.timing = std::make_unique<LineReader>(RequireFile(shards[i].folder, "timing.csv"));
    ExpectHeader(*c.frames, FramesCsvHeader());
    ExpectHeader(*c.timing, TimingCsvHeader());
    Advance(c);
    if (c.frame >= 0) next.push({c.frame, i});
  }
  size_t rows = 0;
  int last_frame = -1;
  std::string timing_line;
  while (!next.empty()) {
    const auto [frame, i] = next.top();
    next.pop();
    ShardCursor& c = cursors[i];
    if (frame <= last_frame) {
      throw ConfigError(c.frames->path() + ":" + std::to_string(c.frames->line_number()) +
                        ": frame " + std::to_string(frame) +
                        " is out of plan order or also in another shard");
    }
    while (c.frame == frame) {
      if (!c.timing->Next(&timing_line) || FrameOf(timing_line, *c.timing, 0) != frame) {
        throw ConfigError(c.timing->path() + ":" + std::to_string(c.timing->line_number()) +
                          ": expected the timing of frame " + std::to_string(frame));
      }
      c.line += '\n';
      timing_line += '\n';
      frames_out.Write(c.line);
      timing_out.Write(timing_line);
      ++c.rows;
      ++rows;
      Advance(c);
    }
    last_frame = frame;
    if (c.frame >= 0) next.push({c.frame, i});
  }
  for (const ShardCursor& c : cursors) {
    const size_t expected =
        ManifestValue(c.source->run, c.source->folder + "/run.json", "rows", size_t{0});
    if (c.rows != expected || c.timing->Next(&timing_line)) {
      throw ConfigError(c.frames->path() + ": holds " + std::to_string(c.rows) +
                        " rows, but run.json says the shard has " + std::to_string(expected) +
                        " (or timing.csv has more); the shard is damaged: run it again");
    }
  }
  frames_out.Commit();
  timing_out.Commit();
  return rows;
}

// Each marker's example image comes from the one shard that rendered it.
void CopyExamples(const std::vector<ShardFolder>& shards, const std::string& out_folder) {
  fs::create_directories(out_folder + "/examples");
  for (const ShardFolder& s : shards) {
    const fs::path examples = fs::path(s.folder) / "examples";
    if (!fs::is_directory(examples)) continue;
    for (const auto& entry : fs::directory_iterator(examples)) {
      if (entry.path().extension() != ".png") continue;
      fs::copy_file(entry.path(),
                    fs::path(out_folder) / "examples" / entry.path().filename(),
                    fs::copy_options::overwrite_existing);
    }
  }
}

// The merged run.json: shard 0's, one whole complete run of `rows` rows merged from `shards`.
nlohmann::json MergedRunJson(const std::vector<ShardFolder>& shards, size_t rows) {
  nlohmann::json run = shards.front().run;
  // One build wrote the merged rows where one wrote every shard's whole; otherwise none is
  // named here (a shard's "from_frame" counts its own frames), and the manifest's "shards"
  // list each shard's builds.
  const nlohmann::json first_builds = run.value("builds", nlohmann::json());
  const auto one_build = [&](const ShardFolder& s) {
    const nlohmann::json builds = s.run.value("builds", nlohmann::json());
    return builds.is_array() && builds.size() == 1 && builds == first_builds;
  };
  if (!std::all_of(shards.begin(), shards.end(), one_build)) run.erase("builds");
  run["shard"] = {{"index", 0}, {"count", 1}};
  run["rows"] = rows;
  run["complete"] = true;
  run["merged_from"] = nlohmann::json::array();
  for (const ShardFolder& s : shards) run["merged_from"].push_back(s.folder);
  return run;
}

// The manifest entry of a merged scenario: the first shard's, with the shards' costs.
nlohmann::json MergedEntry(const std::vector<ShardFolder>& shards,
                           const std::string& name,
                           std::ostream& log) {
  nlohmann::json entry;
  nlohmann::json list = nlohmann::json::array();
  double frames = 0.0, core_s = 0.0, wall_s = 0.0;
  int threads = 0;
  std::string first_builds;
  for (const ShardFolder& s : shards) {
    const nlohmann::json manifest = ReadManifest(s.dir + "/manifest.json");
    const nlohmann::json e = manifest.value("/scenarios"_json_pointer, nlohmann::json::object())
                                 .value(name, nlohmann::json::object());
    if (entry.is_null()) entry = e;
    const nlohmann::json environment = manifest.value("environment", nlohmann::json::object());
    const std::string shard_commit = environment.value("git_commit", std::string("?"));
    // The builds that wrote the shard's rows (one but for a resumed run; a manifest written
    // before they were kept names the environment's).
    nlohmann::json builds = e.value("builds", nlohmann::json::array());
    if (!builds.is_array() || builds.empty()) builds = nlohmann::json::array({environment});
    std::string builds_text;
    for (const nlohmann::json& build : builds) {
      builds_text += (builds_text.empty() ? "" : ", then ") + BuildText(build);
    }
    if (first_builds.empty()) first_builds = builds_text;
    if (builds_text != first_builds) {
      log << "merge: warning: " << name << " shard " << ShardText(s.shard) << " was built from "
          << builds_text << ", shard 0 from " << first_builds
          << "; rows agree only if the trackers did not change between them\n";
    }
    const double shard_wall_s = e.value("wall_s", 0.0);
    const int shard_threads = e.value("threads", 0);
    frames += e.value("frames", 0.0);
    core_s += shard_wall_s * shard_threads;
    wall_s = std::max(wall_s, shard_wall_s);
    threads += shard_threads;
    list.push_back(
        {{"index", s.shard.index},
         {"folder", s.folder},
         {"git_commit", shard_commit},
         {"builds", builds},
         {"cpu_model", manifest.value("/environment/cpu_model"_json_pointer, std::string("?"))},
         {"frames", e.value("frames", 0)},
         {"wall_s", shard_wall_s},
         {"threads", shard_threads}});
  }
  entry.erase("resumed_at_frame");
  entry.erase("builds");  // each shard's are in "shards"
  entry["frames"] = frames;
  entry["shard"] = {{"index", 0}, {"count", 1}};
  entry["shards"] = list;
  // As if the shards ran side by side: the longest shard's time, every shard's threads.
  entry["wall_s"] = wall_s;
  entry["threads"] = threads;
  entry["frames_per_s"] = wall_s > 0.0 ? frames / wall_s : 0.0;
  entry["core_s"] = core_s;
  entry["frames_per_core_s"] = core_s > 0.0 ? frames / core_s : 0.0;
  return entry;
}

// A merge may open two files per shard at once.
void RaiseOpenFileLimit() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_NOFILE, &limit) == 0 && limit.rlim_cur < limit.rlim_max) {
    limit.rlim_cur = limit.rlim_max;
    ::setrlimit(RLIMIT_NOFILE, &limit);
  }
}

}  // namespace

void MergeShards(const MergeOptions& options, std::ostream& log) {
  if (options.shard_dirs.empty()) throw ConfigError("merge: expected the shards' folders");
  for (const std::string& dir : options.shard_dirs) {
    std::error_code error;
    if (fs::equivalent(dir, options.out_dir, error)) {
      throw ConfigError("--out " + options.out_dir + ": is the shard folder " + dir +
                        "; merge into a folder of its own");
    }
  }
  const std::map<std::string, std::vector<ShardFolder>> plans = CollectPlans(options.shard_dirs);
  LockOutputFolder(options.out_dir);
  for (const auto& [name, shards] : plans) {
    const std::string folder = options.out_dir + "/" + name;
    if (fs::exists(folder) && !options.overwrite) {
      throw ConfigError(folder + ": exists; pass --overwrite to replace it");
    }
  }
  RaiseOpenFileLimit();
  const nlohmann::json environment =
      ReadManifest(plans.begin()->second.front().dir + "/manifest.json")
          .value("environment", nlohmann::json::object());
  for (const auto& [name, shards] : plans) {
    // Merged beside the folder and moved in whole: a merge that fails (a shard's rows or
    // manifest damaged) leaves no folder, or the one it was to replace as it was.
    const std::string folder = options.out_dir + "/" + name;
    const std::string staging = folder + ".merging";
    fs::remove_all(staging);
    fs::create_directories(staging);
    size_t rows = 0;
    nlohmann::json entry;
    try {
      rows = MergeRows(shards, staging, options.compress);
      CopyExamples(shards, staging);
      WriteManifest(staging + "/run.json", MergedRunJson(shards, rows));
      entry = MergedEntry(shards, name, log);
    } catch (...) {
      std::error_code ignored;
      fs::remove_all(staging, ignored);
      throw;
    }
    fs::remove_all(folder);
    fs::rename(staging, folder);
    UpdateManifest(options.out_dir + "/manifest.json", name, environment, entry);
    log << "merge: " << name << ": " << shards.size() << " shards, " << rows << " rows\n";
  }
}

}  // namespace markerbench
