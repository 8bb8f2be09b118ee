#include "bench/run/sweep_runner.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>
#include <opencv2/core/utility.hpp>
#include <system_error>
#include <thread>

#include "bench/io/atomic_file.h"
#include "bench/io/line_reader.h"
#include "bench/io/output_folder.h"
#include "bench/io/progress.h"
#include "bench/plan/frame_plan.h"
#include "bench/plan/scenario.h"
#include "bench/run/frame_bound.h"
#include "bench/run/frames_csv.h"
#include "bench/run/manifest.h"
#include "bench/run/pose_overlay.h"
#include "bench/run/sweep_trackers.h"
#include "core/gamma_curve.h"
#include "core/yaml_reader.h"
#include "renderer/image_io.h"

namespace fs = std::filesystem;

namespace markerbench {
namespace {

// A planned frame, or a sequence's frames in order (run with the trackers' state kept), and
// the scenario trackers that can track its marker.
struct Job {
  std::vector<PlannedFrame> frames;
  std::vector<size_t> trackers;
};

size_t FrameCount(const std::vector<Job>& jobs, size_t first = 0) {
  size_t n = 0;
  for (size_t j = first; j < jobs.size(); ++j) n += jobs[j].frames.size();
  return n;
}

struct PreparedSweep {
  Scenario scenario;
  std::string dir;
  std::vector<std::string> input_hashes;  // SHA-256 of each of scenario.input_files
  std::string fingerprint;                // of the input hashes: a resumed run must match it
  std::vector<Job> jobs;
  std::vector<std::string> idle_markers;  // markers no tracker can track: they only constrain poses
  Shard shard;
  size_t done = 0;  // jobs already complete in frames.csv and timing.csv (resume)
  // The builds whose rows the files hold (BuildIdentity(), each with "from_frame", the frames
  // written before it): this one alone, but for a run resumed by another build.
  nlohmann::json builds = nlohmann::json::array();
  // A complete run (run.json says so, and the files hold every row): nothing left to do, and
  // its run.json and manifest entry stay as they are. `compressed`: its files are .zst.
  bool complete = false;
  bool compressed = false;
  uintmax_t frames_bytes = 0;
  uintmax_t timing_bytes = 0;
  std::unique_ptr<SweepTrackerContext> trackers;  // made once the run's folder is taken
};

// What a frames.csv or timing.csv of a killed run holds.
struct WrittenJobs {
  size_t complete = 0;  // jobs 0 .. complete-1 are whole
  // offsets[k]: the byte size of the header plus the rows of jobs 0 .. k-1, for k <= complete.
  std::vector<uintmax_t> offsets;
};

// Scans a file whose rows must follow `jobs`; `column_of_frame` and `column_of_tracker`
// locate the ids each row must match. A missing file holds nothing (offsets {0}).
WrittenJobs ScanWrittenJobs(const std::string& path,
                            const std::string& header,
                            const std::vector<Job>& jobs,
                            const std::vector<std::string>& tracker_names,
                            size_t column_of_frame,
                            size_t column_of_tracker) {
  WrittenJobs written;
  if (!fs::exists(path)) {
    written.offsets.push_back(0);
    return written;
  }
  // Streamed: a shard of millions of rows resumes in bounded memory.
  const uintmax_t size = fs::file_size(path);
  LineReader reader(path);
  std::string line;
  if (!reader.Next(&line) || line + '\n' != header) {
    throw ConfigError(path + ":1: expected the header '" + header.substr(0, header.size() - 1) +
                      "'; this folder was not written by markerbench sweep");
  }
  uintmax_t pos = header.size();
  written.offsets.push_back(pos);
  for (size_t j = 0; j < jobs.size(); ++j) {
    const Job& job = jobs[j];
    for (const PlannedFrame& frame : job.frames) {
      for (const size_t t : job.trackers) {
        // A last line without its '\n' is a torn row of a killed run.
        if (!reader.Next(&line) || pos + line.size() + 1 > size) return written;
        const std::vector<std::string> f = SplitCsvLine(line);
        if (f.size() <= std::max(column_of_frame, column_of_tracker) ||
            f[column_of_frame] != std::to_string(frame.index) ||
            f[column_of_tracker] != tracker_names[t]) {
          throw ConfigError(path + ":" + std::to_string(reader.line_number()) +
                            ": expected the row of frame " + std::to_string(frame.index) +
                            " and tracker " + tracker_names[t] +
                            "; the file does not follow this scenario's plan");
        }
        pos += line.size() + 1;
      }
    }
    written.offsets.push_back(pos);
    // A job without rows (an example image only) counts once a later job's rows are in.
    if (!job.trackers.empty()) written.complete = j + 1;
  }
  return written;
}

// Everything checked before anything is written.
PreparedSweep Prepare(const std::string& path, const SweepOptions& options) {
  PreparedSweep p;
  p.scenario = LoadScenario(path, options.overrides);
  const Scenario& s = p.scenario;
  if (s.trackers.empty()) {
    throw ConfigError(path + ": key 'trackers': missing; expected at least one tracker to sweep");
  }
  p.dir = (fs::path(options.out_dir) / s.name).string();
  p.input_hashes = InputHashes(s);
  p.fingerprint = Fingerprint(p.input_hashes);

  std::vector<std::vector<size_t>> trackers_of_marker(s.markers.size());
  for (size_t t = 0; t < s.trackers.size(); ++t) {
    for (const size_t m : s.trackers[t].markers) trackers_of_marker[m].push_back(t);
  }
  for (size_t m = 0; m < s.markers.size(); ++m) {
    if (trackers_of_marker[m].empty()) p.idle_markers.push_back(s.markers[m].name);
  }
  p.shard = options.shard;
  nlohmann::json build = BuildIdentity();
  build["from_frame"] = 0;
  p.builds.push_back(build);
  bool extending = false;  // the last job is a sequence to be tracked: it takes its frames
  for (PlannedFrame& f : PlanFrames(s)) {
    if (!InShard(f, s.trials, p.shard)) continue;
    if (f.sequence_frame > 0) {
      if (extending) p.jobs.back().frames.push_back(std::move(f));
      continue;
    }
    const auto& trackers = trackers_of_marker[static_cast<size_t>(f.marker_index)];
    extending = f.sequence_frame == 0 && !trackers.empty();
    // Markers without a tracker are still rendered for the example-image figure.
    if (!trackers.empty() || f.example) p.jobs.push_back({{std::move(f)}, trackers});
  }

  return p;
}

// The frames before `job`.
size_t FramesBefore(const std::vector<Job>& jobs, size_t job) {
  return FrameCount(jobs) - FrameCount(jobs, job);
}

// A resumed run's builds (run.json's "builds" at `run_json`; one written before they were kept
// names none, and its rows' build is unknown): those whose rows are kept, and this build after
// them if it is another and adds rows, with a warning: the rows agree only if the trackers did
// not change.
void KeepEarlierBuilds(PreparedSweep& p, const nlohmann::json& run, const std::string& run_json) {
  const size_t kept_frames = FramesBefore(p.jobs, p.done);
  if (kept_frames == 0) return;  // nothing of the earlier run is kept
  nlohmann::json builds = nlohmann::json::array();
  if (!run.contains("builds")) {
    builds.push_back({{"git_commit", "unknown"}, {"from_frame", 0}});
  } else {
    const nlohmann::json& earlier = run["builds"];
    const auto unreadable = [&] {
      return ConfigError(run_json + ": key 'builds': expected a list of the builds that wrote " +
                         "its rows, the first from frame 0, each with a 'from_frame' count, got " +
                         earlier.dump());
    };
    if (!earlier.is_array() || earlier.empty()) throw unreadable();
    for (const nlohmann::json& build : earlier) {
      if (!build.is_object() || !build.value("from_frame", nlohmann::json()).is_number_unsigned()) {
        throw unreadable();
      }
      if (build["from_frame"].get<size_t>() < kept_frames) builds.push_back(build);
    }
    if (earlier.front()["from_frame"].get<size_t>() != 0) throw unreadable();
  }
  nlohmann::json here = BuildIdentity();
  const nlohmann::json& last = builds.back();
  // A complete run gains no row, so no build.
  if (p.done < p.jobs.size() && !SameBuild(last, here)) {
    std::fprintf(stderr,
                 "%s: warning: resuming at frame %zu with %s; the frames before were written by "
                 "%s, and rows agree only if the trackers did not change between them\n",
                 p.scenario.name.c_str(),
                 kept_frames,
                 BuildText(here).c_str(),
                 BuildText(last).c_str());
    here["from_frame"] = kept_frames;
    builds.push_back(here);
  }
  p.builds = builds;
}

// What an earlier run left in the scenario's folder: refused, started again (--overwrite:
// every file of it removed) or continued (--resume). Called under the folder's lock.
void TakeOverEarlierRun(PreparedSweep& p, const SweepOptions& options) {
  const Scenario& s = p.scenario;
  const std::string& path = s.path;
  // Both forms exist only when a compression was killed before it removed the plain files.
  const std::string plain = p.dir + "/frames.csv";
  const bool compressed = !fs::exists(plain) && fs::exists(plain + ".zst");
  if (!compressed && !fs::exists(plain)) return;
  const std::string written = compressed ? plain + ".zst" : plain;
  if (!options.resume && !options.overwrite) {
    throw ConfigError(written +
                      ": exists; pass --resume to continue that run or --overwrite to "
                      "start again");
  }
  if (options.overwrite) {
    fs::remove_all(p.dir);  // stale example images and logs of another plan must not stay
    return;
  }
  const std::string run_json = p.dir + "/run.json";
  const nlohmann::json run = ReadManifest(run_json);
  const std::string fingerprint =
      ManifestValue(run, run_json, "fingerprint", std::string("missing"));
  if (fingerprint != p.fingerprint) {
    throw ConfigError(p.dir + ": was written by a different scenario or other overrides " +
                      "(run.json fingerprint " + fingerprint + ", " + path + " has " +
                      p.fingerprint + "); refusing to --resume into it");
  }
  // A run.json written before shards were kept is one whole run.
  const Shard shard = RunJsonShard(run, run_json).value_or(Shard{});
  if (shard.index != p.shard.index || shard.count != p.shard.count) {
    throw ConfigError(run_json + ": key 'shard': this folder holds shard " +
                      std::to_string(shard.index) + "/" + std::to_string(shard.count) +
                      "; refusing to --resume shard " + std::to_string(p.shard.index) + "/" +
                      std::to_string(p.shard.count) + " into it");
  }
  if (compressed) {
    // Compressed only once complete.
    p.done = p.jobs.size();
    p.complete = p.compressed = true;
    return;
  }
  fs::remove(p.dir + "/frames.csv.zst");
  fs::remove(p.dir + "/timing.csv.zst");
  std::vector<std::string> names;
  for (const TrackerEntry& t : s.trackers) names.push_back(t.name);
  const WrittenJobs in_frames = ScanWrittenJobs(written, FramesCsvHeader(), p.jobs, names, 4, 6);
  const WrittenJobs in_timing = ScanWrittenJobs(p.dir + "/timing.csv",
                                                TimingCsvHeader(),
                                                p.jobs,
                                                names,
                                                kTimingFrameColumn,
                                                kTimingTrackerColumn);
  // Continue after the jobs that both files hold whole.
  p.done = std::min(in_frames.complete, in_timing.complete);
  p.frames_bytes = in_frames.offsets[p.done];
  p.timing_bytes = in_timing.offsets[p.done];
  p.complete = p.done == p.jobs.size() && ManifestValue(run, run_json, "complete", false);
  KeepEarlierBuilds(p, run, run_json);
}

void WriteAll(int fd, const std::string& text, const std::string& path) {
  size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::system_error(errno, std::generic_category(), path + ": write failed");
    written += static_cast<size_t>(n);
  }
}

// An append-only file, written with one write() per frame. A killed run leaves at most a
// torn last frame, which --resume cuts off.
class AppendFile {
 public:
  AppendFile(const std::string& path, uintmax_t keep_bytes, const std::string& header)
      : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::system_error(errno, std::generic_category(), path + ": cannot open");
    if (::ftruncate(fd_, static_cast<off_t>(keep_bytes)) != 0) {
      throw std::system_error(errno, std::generic_category(), path + ": cannot truncate");
    }
    if (keep_bytes == 0) Append(header);
  }
  ~AppendFile() { ::close(fd_); }
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;

  void Append(const std::string& text) { WriteAll(fd_, text, path_); }

 private:
  std::string path_;
  int fd_ = -1;
};

// Puts the rows of finished jobs into the files in plan order.
class OrderedWriter {
 public:
  OrderedWriter(AppendFile* frames,
                AppendFile* timing,
                const std::vector<Job>& jobs,
                size_t next,
                Progress* progress)
      : frames_(frames), timing_(timing), jobs_(jobs), next_(next), progress_(progress) {}

  void Submit(size_t job, std::string frame_rows, std::string timing_rows) {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.emplace(job, std::make_pair(std::move(frame_rows), std::move(timing_rows)));
    for (auto it = pending_.begin(); it != pending_.end() && it->first == next_;
         it = pending_.erase(it), ++next_) {
      frames_->Append(it->second.first);
      timing_->Append(it->second.second);
      progress_->Advance(jobs_[next_].frames.size());
    }
  }

 private:
  std::mutex mutex_;
  std::map<size_t, std::pair<std::string, std::string>> pending_;
  AppendFile* frames_;
  AppendFile* timing_;
  const std::vector<Job>& jobs_;
  size_t next_;
  Progress* progress_;
};

// Renders one frame and runs `trackers`; appends its frames.csv and timing.csv rows. A
// sequence's first frame resets them; its later frames find them as the last one left them.
void RunFrame(const PreparedSweep& p,
              const PlannedFrame& f,
              const std::vector<size_t>& tracker_indices,
              std::vector<std::unique_ptr<Tracker>>* trackers,
              PoseOverlay* video,
              std::string* frame_rows,
              std::string* timing_rows) {
  const Scenario& s = p.scenario;
  const MarkerSpec& marker = s.markers[static_cast<size_t>(f.marker_index)];
  const FrameRequest request = RequestFor(s, f);
  const RenderedFrame frame = RenderFrame(request);
  if (f.example) {
    WriteImage(p.dir + "/examples/" + marker.name + ".png", frame.image);
  }
  if (tracker_indices.empty()) return;
  std::vector<std::pair<std::string, TrackResult>> results;  // for the video
  FrameRow row;
  row.scenario = s.name;
  row.sweep_parameter = s.sweep_parameter;
  row.sweep_value = f.sweep_value;
  row.grid = f.grid;
  row.trial = f.trial;
  row.frame = f.index;
  row.marker = marker.name;
  row.seed = s.seed;
  row.apparent_size_px = frame.truth.apparent_size_px;
  row.distance_m = DistanceToMarker(f.cam_from_marker, marker);
  row.truth = f.cam_from_marker;
  row.bound = PlannedFrameBound(s, f, request);
  Image8 linear;  // the frame in linear values, for trackers told the camera's response
  const double gamma = request.degradations.gamma;
  for (const size_t t : tracker_indices) {
    Tracker* tracker = (*trackers)[t].get();
    const Image8* image = &frame.image;
    if (s.trackers[t].linear_input && gamma != 1.0) {
      if (linear.pixels.empty()) linear = Linearized(frame.image, gamma);
      image = &linear;
    }
    // Frames are independent, and sequences too: no state may leak between them.
    if (f.sequence_frame <= 0) tracker->Reset();
    const auto start = std::chrono::steady_clock::now();
    const TrackResult result =
        TrackCatchingExceptions(tracker, {image, &s.camera, &marker, f.index});
    const double round_trip_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    // The tracker's own time, when it runs in another process and reports it.
    const double time_ms = result.time_ms.value_or(round_trip_ms);
    row.tracker = s.trackers[t].name;
    SetTrackResult(result.status, result.hypotheses, &row);
    row.message = result.message;
    *frame_rows += FormatFrameRow(row);
    *timing_rows += FormatTimingRow(row, time_ms, round_trip_ms);
    if (video) results.emplace_back(row.tracker, result);
  }
  if (video) video->Add(frame.image, results, s.trajectory->fps);
}

// Runs one job's frames in order; returns their frames.csv and timing.csv rows.
std::pair<std::string, std::string> RunJob(const PreparedSweep& p,
                                           const Job& job,
                                           std::vector<std::unique_ptr<Tracker>>* trackers) {
  std::string frame_rows, timing_rows;
  // The example sequence is also a video with every tracker's pose drawn
  // (examples/<marker>.mp4), written beside and renamed once whole.
  std::unique_ptr<PoseOverlay> video;
  std::string video_path;
  const PlannedFrame& first = job.frames.front();
  if (first.example && first.sequence_frame == 0 && !job.trackers.empty()) {
    const MarkerSpec& marker = p.scenario.markers[static_cast<size_t>(first.marker_index)];
    video_path = p.dir + "/examples/" + marker.name + ".mp4";
    video = std::make_unique<PoseOverlay>(video_path + ".part.mp4", p.scenario.camera, marker);
  }
  for (const PlannedFrame& f : job.frames) {
    RunFrame(p, f, job.trackers, trackers, video.get(), &frame_rows, &timing_rows);
  }
  if (video) {
    video.reset();  // closes the file
    fs::rename(video_path + ".part.mp4", video_path);
  }
  return {frame_rows, timing_rows};
}

nlohmann::json ScenarioManifest(const PreparedSweep& p, int threads) {
  const Scenario& s = p.scenario;
  nlohmann::json entry;
  entry["file"] = s.path;
  entry["fingerprint"] = p.fingerprint;
  for (size_t i = 0; i < s.input_files.size(); ++i) {
    entry["input_files"].push_back({{"path", s.input_files[i]}, {"sha256", p.input_hashes[i]}});
  }
  if (!s.overrides.empty()) {
    entry["overrides"] = {{"set", s.overrides.set}, {"trackers", s.overrides.trackers}};
  }
  entry["seed"] = s.seed;
  entry["trials"] = s.trials;
  entry["crlb"] = s.crlb;
  entry["sweep"] = {{"parameter", s.sweep_parameter},
                    {"values", s.sweep_values},
                    {"example_value", s.example_value}};
  for (const SweepAxis& axis : s.grid_axes) {
    entry["sweep"]["grid"].push_back({{"parameter", axis.parameter}, {"values", axis.values}});
  }
  entry["equal_ink_area_m2"] =
      s.equal_ink_area_m2 ? nlohmann::json(*s.equal_ink_area_m2) : nlohmann::json();
  for (const MarkerSpec& m : s.markers) entry["markers"].push_back(m.name);
  entry["markers_without_tracker"] = p.idle_markers;
  for (const TrackerEntry& t : s.trackers) {
    nlohmann::json tracker;
    tracker["name"] = t.name;
    for (const size_t m : t.markers) tracker["markers"].push_back(s.markers[m].name);
    for (const auto& [key, value] : t.parameters) tracker["parameters"][key] = value;
    entry["trackers"].push_back(tracker);
  }
  if (const std::optional<TrajectoryOptions>& t = s.trajectory) {
    nlohmann::json occlusions = nlohmann::json::array();
    for (const FrameRange& r : t->occlusions) occlusions.push_back({r.first, r.last});
    entry["trajectory"] = {{"kind", TrajectoryKindName(t->kind)},
                           {"fps", t->fps},
                           {"frames", t->Frames()},
                           {"static_s", t->static_s},
                           {"exposure_s", t->exposure_s},
                           {"readout_s", t->readout_s},
                           {"occlusions", occlusions}};
  }
  entry["frames"] = FrameCount(p.jobs);
  entry["shard"] = {{"index", p.shard.index}, {"count", p.shard.count}};
  entry["resumed_at_frame"] = FramesBefore(p.jobs, p.done);
  entry["builds"] = p.builds;
  entry["threads"] = threads;
  return entry;
}

// run.json: what `--resume` and `merge` check the folder against.
nlohmann::json RunJson(const PreparedSweep& p, bool complete) {
  size_t rows = 0;
  for (const Job& job : p.jobs) rows += job.frames.size() * job.trackers.size();
  return {{"scenario", p.scenario.path},
          {"fingerprint", p.fingerprint},
          {"shard", {{"index", p.shard.index}, {"count", p.shard.count}}},
          {"complete", complete},
          {"rows", rows},
          {"builds", p.builds}};
}

// Replaces a complete CSV file by its .zst (after run.json says complete): the compressed file
// is in place before the plain one goes, and --resume removes a .zst left beside its plain
// file.
void CompressCsv(const std::string& path) {
  LineReader reader(path);
  AtomicFileWriter writer(path + ".zst", Compression::kZstd);
  std::string line;
  while (reader.Next(&line)) {
    line += '\n';
    writer.Write(line);
  }
  writer.Commit();
  fs::remove(path);
}

// A complete run's frames.csv and timing.csv, each replaced by its .zst.
void CompressRun(const PreparedSweep& p) {
  CompressCsv(p.dir + "/frames.csv");
  CompressCsv(p.dir + "/timing.csv");
}

void Run(PreparedSweep& p, int threads, bool compress, const std::string& manifest_path) {
  fs::create_directories(p.dir + "/examples");
  WriteManifest(p.dir + "/run.json", RunJson(p, false));
  AppendFile frames(p.dir + "/frames.csv", p.frames_bytes, FramesCsvHeader());
  AppendFile timing(p.dir + "/timing.csv", p.timing_bytes, TimingCsvHeader());
  for (const std::string& m : p.idle_markers) {
    std::fprintf(stderr,
                 "%s: no tracker for marker %s; it only constrains the poses and the examples\n",
                 p.scenario.name.c_str(),
                 m.c_str());
  }
  const size_t frames_total = FrameCount(p.jobs);
  Progress progress(p.scenario.name, frames_total, frames_total - FrameCount(p.jobs, p.done));
  OrderedWriter writer(&frames, &timing, p.jobs, p.done, &progress);
  std::atomic<size_t> next{p.done};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) {
    pool.emplace_back([&] {
      try {
        std::vector<std::unique_ptr<Tracker>> trackers;
        for (size_t t = 0; t < p.scenario.trackers.size(); ++t) {
          trackers.push_back(p.trackers->MakeTracker(t));
        }
        for (size_t j = next++; j < p.jobs.size() && !failed; j = next++) {
          auto [frame_rows, timing_rows] = RunJob(p, p.jobs[j], &trackers);
          writer.Submit(j, std::move(frame_rows), std::move(timing_rows));
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
      }
    });
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  progress.Finish();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  WriteManifest(p.dir + "/run.json", RunJson(p, true));
  if (compress) CompressRun(p);
  nlohmann::json entry = ScenarioManifest(p, threads);
  const double frames_run = static_cast<double>(FrameCount(p.jobs, p.done));
  entry["wall_s"] = wall_s;
  entry["frames_per_s"] = wall_s > 0.0 ? frames_run / wall_s : 0.0;
  entry["frames_per_core_s"] = wall_s > 0.0 ? frames_run / (wall_s * threads) : 0.0;
  UpdateManifest(manifest_path, p.scenario.name, EnvironmentManifest(threads), entry);
}

}  // namespace

void RunSweeps(const std::vector<std::string>& scenario_paths, const SweepOptions& options) {
  if (scenario_paths.empty()) throw ConfigError("sweep: expected at least one scenario file");
  std::vector<PreparedSweep> sweeps;
  for (const std::string& path : scenario_paths) {
    sweeps.push_back(Prepare(path, options));
    for (size_t i = 0; i + 1 < sweeps.size(); ++i) {
      if (sweeps[i].scenario.name == sweeps.back().scenario.name) {
        throw ConfigError(path + ": key 'name': '" + sweeps.back().scenario.name +
                          "' is also the name of " + sweeps[i].scenario.path +
                          "; each scenario writes to DIR/<name>");
      }
    }
  }
  if (options.threads < 0 || options.threads > kMaxThreads) {
    throw ConfigError("--threads: expected a number in [1, " + std::to_string(kMaxThreads) +
                      "], got " + std::to_string(options.threads));
  }
  const int requested = options.threads > 0
                            ? options.threads
                            : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  LockOutputFolder(options.out_dir);
  for (PreparedSweep& p : sweeps) TakeOverEarlierRun(p, options);
  // Only for runs that have frames left: a complete one runs no tracker (an external one's
  // handshake and its scaled marker files would be work for nothing).
  for (PreparedSweep& p : sweeps) {
    if (!p.complete) {
      p.trackers = std::make_unique<SweepTrackerContext>(p.scenario, p.fingerprint, p.dir);
    }
  }
  // Parallelism comes from the pool; OpenCV's own threads would oversubscribe the cores and
  // make time_ms depend on what the other workers do.
  cv::setNumThreads(1);
  for (PreparedSweep& p : sweeps) {
    if (p.complete) {
      // Run again, it would replace the manifest entry's cost of the run (and a merged run's
      // list of shards) by a run of nothing.
      if (options.compress && !p.compressed) {
        CompressRun(p);
        p.compressed = true;
      }
      std::fprintf(stderr,
                   "%s: complete (%s); nothing to resume\n",
                   p.scenario.name.c_str(),
                   p.compressed ? "frames.csv.zst" : "frames.csv");
      continue;
    }
    // No more workers than frames left to run.
    const int threads = static_cast<int>(
        std::clamp<size_t>(p.jobs.size() - p.done, 1, static_cast<size_t>(requested)));
    Run(p, threads, options.compress, options.out_dir + "/manifest.json");
  }
}

}  // namespace markerbench
