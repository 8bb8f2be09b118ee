// A scenario file (architecture.md, "Scenario"): camera, markers, trackers, pose sampler,
// render defaults, one sweep axis, trials and seed. Paths inside it are relative to it.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/plan/trajectory_options.h"
#include "core/camera.h"
#include "core/marker_spec.h"
#include "renderer/degradations.h"
#include "trackers/tracker.h"

namespace markerbench {

// The paper's protocol (experiments.md): the camera looks at the marker centre from
// distance_m; tilt, azimuth and roll are uniform in their ranges; the marker centre lands
// uniformly in a disk of max_offset_px around the image centre.
struct PoseSamplerOptions {
  double distance_m = 0.6;
  double tilt_min_deg = 0.0;
  double tilt_max_deg = 40.0;
  double azimuth_min_deg = 0.0;
  double azimuth_max_deg = 360.0;
  double roll_min_deg = 0.0;
  double roll_max_deg = 360.0;
  double max_offset_px = 60.0;
  // Every marker's ink bounds must stay this far inside the image; else resample.
  double border_px = 2.0;
};

enum class Channels { kAuto, kGrey, kRgb };

struct RenderDefaults {
  Degradations degradations;
  Channels channels = Channels::kAuto;  // auto: RGB for markers with colour, else grey
  std::optional<Eigen::Vector2d> sheet_size_m;
  Rgb backdrop = Rgb::Constant(0.5);
};

struct TrackerEntry {
  std::string name;
  YAML::Node options;       // validated by the tracker factory when the scenario loads
  std::string options_key;  // "trackers[i].options", for errors
  // Run in a worker process, so that a crash or hang is an error row (default: for trackers
  // that run third-party C code), with `timeout_s` per frame.
  bool isolated = false;
  double timeout_s = 60.0;
  // The tracker is told the camera's response: it gets each frame taken back to linear values
  // (render.gamma undone, core/gamma_curve.h), as `track --gamma` does for a real camera.
  bool linear_input = false;
  // An external tracker (README, "Benchmark your own tracker"): the command, run in
  // `working_dir` (the scenario file's folder). Empty for built-in trackers.
  std::vector<std::string> exec;
  std::string working_dir;
  // Found at load by building the tracker once: the indices of the scenario's markers it can
  // track (never empty), and every parameter in effect (Tracker::Parameters).
  std::vector<size_t> markers;
  std::vector<std::pair<std::string, std::string>> parameters;
};

// Command-line changes to a scenario for quick studies (sweep --set, --trials, --trackers).
// They are applied before the scenario is read, so they are checked as the file's own keys
// are; they enter the fingerprint, and an isolated tracker's worker gets them too.
struct ScenarioOverrides {
  // "key.path=value" in order (YamlMap::LoadFile); --trials N is "trials=N".
  std::vector<std::string> set;
  // Keep only the trackers of these names (in the file's order); empty keeps every tracker.
  std::vector<std::string> trackers;

  bool empty() const { return set.empty() && trackers.empty(); }
  // As command-line arguments: --set X ... --trackers a,b.
  std::vector<std::string> Arguments() const;
};

// One axis of a sweep: a parameter of SweepParameters() and its values.
struct SweepAxis {
  std::string parameter;
  std::vector<double> values;
};

// The sweep parameters a scenario may vary.
const std::vector<std::string>& SweepParameters();

struct Scenario {
  std::string path;
  ScenarioOverrides overrides;
  // The scenario, camera and marker files: what a run's fingerprint hashes.
  std::vector<std::string> input_files;
  std::string name;
  Camera camera;
  std::vector<MarkerSpec> markers;    // after equal-area scaling, when asked for
  std::vector<double> marker_scales;  // each marker's equal-area factor (1 without scaling)
  std::optional<double> equal_ink_area_m2;
  std::vector<TrackerEntry> trackers;
  PoseSamplerOptions poses;
  // A sequence scenario (bench/plan/trajectory.h): every trial is a video along it, run by
  // each tracker with its state kept from frame to frame.
  std::optional<TrajectoryOptions> trajectory;
  RenderDefaults render;
  // The first (or only) axis: frames.csv's sweep_parameter and sweep_value.
  std::string sweep_parameter;
  std::vector<double> sweep_values;
  // A grid's other axes (`sweep: {grid: {...}}`, in file order); empty for a one-axis sweep.
  // Every combination of their values runs the whole first axis (frames.csv's grid column).
  std::vector<SweepAxis> grid_axes;
  // The first axis's value whose example images the report shows (at the grid's first
  // combination).
  double example_value = 0.0;
  int trials = 1;
  uint64_t seed = 0;
  // Compute every frame's Cramér-Rao bound (frames.csv's crlb_* columns); `crlb: false`
  // saves its cost (a few ms a frame).
  bool crlb = true;
};

// Throws ConfigError naming the file, line and key. Also checks what can only be checked by
// trying: every tracker's options, that each tracker can track one of the markers, and that
// the pose sampler can put every marker in view at every sweep value.
Scenario LoadScenario(const std::string& path, const ScenarioOverrides& overrides = {});

// SHA-256 of each of scenario.input_files (and of the overrides' arguments, when there are
// any), and of those hashes: the fingerprint that a resumed run and an isolated tracker's
// worker process must find again.
std::vector<std::string> InputHashes(const Scenario& scenario);
std::string Fingerprint(const std::vector<std::string>& input_hashes);

// A fresh tracker for `entry` (options checked again; they were valid at load).
std::unique_ptr<Tracker> MakeScenarioTracker(const Scenario& scenario, const TrackerEntry& entry);

// The channel count for `marker` under `channels`.
int ChannelsFor(Channels channels, const MarkerSpec& marker);

}  // namespace markerbench
