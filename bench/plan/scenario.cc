#include "bench/plan/scenario.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "bench/plan/frame_plan.h"
#include "bench/plan/trajectory.h"
#include "core/camera_yaml.h"
#include "core/joined.h"
#include "core/marker_scaling.h"
#include "core/marker_yaml.h"
#include "core/number_text.h"
#include "core/sha256.h"
#include "core/yaml_reader.h"
#include "trackers/external/external_tracker.h"
#include "trackers/isolated/isolated_tracker.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

// Reads [lo, hi] ranges in degrees.
void ReadRange(
    const YamlMap& map, const std::string& key, double lo, double hi, double* min, double* max) {
  if (!map.Has(key)) return;
  const std::vector<double> range = map.Get<std::vector<double>>(key);
  if (range.size() != 2 || !(range[0] >= lo && range[1] <= hi && range[0] <= range[1])) {
    map.Fail(key, "[min, max] with " + NumberText(lo) + " <= min <= max <= " + NumberText(hi));
  }
  *min = range[0];
  *max = range[1];
}

PoseSamplerOptions ReadPoses(const YamlMap& map) {
  PoseSamplerOptions poses;
  const std::string sampler = map.Get<std::string>("sampler");
  if (sampler != "look_at") map.Fail("sampler", "'look_at' (the paper's protocol)");
  poses.distance_m = map.GetLength("distance_m");
  ReadRange(map, "tilt_deg", 0.0, 89.0, &poses.tilt_min_deg, &poses.tilt_max_deg);
  ReadRange(map, "azimuth_deg", -360.0, 720.0, &poses.azimuth_min_deg, &poses.azimuth_max_deg);
  ReadRange(map, "roll_deg", -360.0, 720.0, &poses.roll_min_deg, &poses.roll_max_deg);
  if (map.Has("max_offset_px")) poses.max_offset_px = map.GetDouble("max_offset_px", 0.0, 1e4);
  if (map.Has("border_px")) poses.border_px = map.GetDouble("border_px", 0.0, 1e4);
  map.RejectUnknownKeys();
  return poses;
}

// `trajectory: {kind, fps, duration_s, ...}` (bench/plan/trajectory.h).
TrajectoryOptions ReadTrajectory(const YamlMap& map) {
  TrajectoryOptions t;
  const std::string kind = map.Get<std::string>("kind");
  if (kind == "orbit") {
    t.kind = TrajectoryKind::kOrbit;
  } else if (kind == "approach") {
    t.kind = TrajectoryKind::kApproach;
  } else if (kind == "handheld") {
    t.kind = TrajectoryKind::kHandheld;
  } else {
    map.Fail("kind", "orbit, approach or handheld");
  }
  t.fps = map.GetDouble("fps", 0.1, 1000.0);
  t.duration_s = map.GetDouble("duration_s", 1e-3, 3600.0);
  constexpr int kMaxFrames = 100000;
  if (t.Frames() > kMaxFrames) map.Fail("duration_s", "at most 100000 frames (fps × duration_s)");
  if (map.Has("static_s")) t.static_s = map.GetDouble("static_s", 0.0, t.duration_s);
  if (map.Has("exposure_s")) t.exposure_s = map.GetDouble("exposure_s", 0.0, 1.0 / t.fps);
  if (map.Has("readout_s")) t.readout_s = map.GetDouble("readout_s", 0.0, 1.0 / t.fps);
  const auto only_for = [&](const std::string& key, TrajectoryKind k) {
    if (map.Has(key) && t.kind != k) {
      map.Fail(key, std::string("no such key for kind ") + TrajectoryKindName(t.kind));
    }
    return map.Has(key);
  };
  if (only_for("degrees_per_s", TrajectoryKind::kOrbit)) {
    t.degrees_per_s = map.GetDouble("degrees_per_s", -3600.0, 3600.0);
  }
  if (map.Has("from_m")) {
    map.Fail("from_m",
             "no such key: a trajectory starts at poses.distance_m, which a sweep may vary");
  }
  if (only_for("to_m", TrajectoryKind::kApproach)) t.to_m = map.GetLength("to_m");
  if (only_for("linear_speed_m_s", TrajectoryKind::kHandheld)) {
    t.linear_speed_m_s = map.GetDouble("linear_speed_m_s", 0.0, 10.0);
  }
  if (only_for("angular_speed_deg_s", TrajectoryKind::kHandheld)) {
    t.angular_speed_deg_s = map.GetDouble("angular_speed_deg_s", 0.0, 3600.0);
  }
  if (map.Has("occlusions")) {
    const std::string expected = "a list of [first, last] frame ranges with 0 <= first <= last < " +
                                 std::to_string(t.Frames()) + " (the frames of a sequence)";
    const YAML::Node ranges = map.GetNode("occlusions");
    if (!ranges.IsSequence()) map.Fail("occlusions", expected);
    for (const YAML::Node& range : ranges) {
      FrameRange r;
      try {
        if (!range.IsSequence() || range.size() != 2) map.Fail("occlusions", expected);
        r = {range[0].as<int>(), range[1].as<int>()};
      } catch (const YAML::Exception&) {
        map.Fail("occlusions", expected);
      }
      if (!(r.first >= 0 && r.first <= r.last && r.last < t.Frames())) {
        map.Fail("occlusions", expected);
      }
      t.occlusions.push_back(r);
    }
  }
  map.RejectUnknownKeys();
  return t;
}

// A render key that may also be swept: the sweep's range.
double GetSwept(const YamlMap& map, const std::string& key) {
  const ValueRange range = SweepRange(key);
  const double value = map.GetDouble(key, range.lo, range.hi);
  if (key == "jpeg_quality" && value != std::round(value)) map.Fail(key, "a whole number");
  return value;
}

RenderDefaults ReadRender(const YamlMap& map) {
  RenderDefaults render;
  Degradations& d = render.degradations;
  if (map.Has("noise_var")) d.noise_var = GetSwept(map, "noise_var");
  if (map.Has("blur_sigma_px")) d.blur_sigma_px = GetSwept(map, "blur_sigma_px");
  if (map.Has("motion_blur_px")) d.motion_blur_px = GetSwept(map, "motion_blur_px");
  if (map.Has("motion_blur_angle_deg")) {
    d.motion_blur_angle_deg = map.GetDouble("motion_blur_angle_deg", -360.0, 360.0);
  }
  if (map.Has("gain")) d.gain = GetSwept(map, "gain");
  if (map.Has("offset")) d.offset = map.GetDouble("offset", -1.0, 1.0);
  if (map.Has("gradient")) {
    d.gradient = map.Get<Eigen::Vector2d>("gradient");
    if (!(d.gradient.cwiseAbs().maxCoeff() <= 10.0)) map.Fail("gradient", "[gx, gy] in [-10, 10]");
  }
  if (map.Has("gamma")) d.gamma = GetSwept(map, "gamma");
  if (map.Has("jpeg_quality")) d.jpeg_quality = static_cast<int>(GetSwept(map, "jpeg_quality"));
  if (map.Has("channels")) {
    const std::string c = map.Get<std::string>("channels");
    if (c == "auto") {
      render.channels = Channels::kAuto;
    } else if (c == "grey" || c == "gray") {
      render.channels = Channels::kGrey;
    } else if (c == "rgb") {
      render.channels = Channels::kRgb;
    } else {
      map.Fail("channels", "auto, grey or rgb");
    }
  }
  if (map.Has("sheet_size_m")) {
    const Eigen::Vector2d size = map.Get<Eigen::Vector2d>("sheet_size_m");
    if (!(size.minCoeff() >= YamlMap::kMinLengthM && size.maxCoeff() <= YamlMap::kMaxLengthM)) {
      map.Fail("sheet_size_m", "[width, height] in metres, each in [1e-06, 10000]");
    }
    render.sheet_size_m = size;
  }
  if (map.Has("backdrop")) render.backdrop = map.GetColor("backdrop");
  map.RejectUnknownKeys();
  return render;
}

}  // namespace

const std::vector<std::string>& SweepParameters() {
  static const std::vector<std::string> kParameters = {"noise_var",
                                                       "blur_sigma_px",
                                                       "motion_blur_px",
                                                       "distance_m",
                                                       "tilt_deg",
                                                       "gain",
                                                       "gamma",
                                                       "jpeg_quality"};
  return kParameters;
}

int ChannelsFor(Channels channels, const MarkerSpec& marker) {
  switch (channels) {
    case Channels::kGrey:
      return 1;
    case Channels::kRgb:
      return 3;
    default:
      return marker.HasColor() ? 3 : 1;
  }
}

std::vector<std::string> ScenarioOverrides::Arguments() const {
  std::vector<std::string> arguments;
  for (const std::string& s : set) arguments.insert(arguments.end(), {"--set", s});
  if (!trackers.empty()) arguments.insert(arguments.end(), {"--trackers", Joined(trackers, ",")});
  return arguments;
}

std::vector<std::string> InputHashes(const Scenario& scenario) {
  std::vector<std::string> hashes;
  for (const std::string& file : scenario.input_files) hashes.push_back(Sha256OfFile(file));
  if (!scenario.overrides.empty()) {
    Sha256 overrides;
    for (const std::string& argument : scenario.overrides.Arguments()) {
      overrides.Update(argument + '\0');
    }
    hashes.push_back(overrides.HexDigest());
  }
  return hashes;
}

std::string Fingerprint(const std::vector<std::string>& input_hashes) {
  Sha256 fingerprint;
  for (const std::string& hash : input_hashes) fingerprint.Update(hash);
  return fingerprint.HexDigest();
}

std::unique_ptr<Tracker> MakeScenarioTracker(const Scenario& scenario, const TrackerEntry& entry) {
  if (!entry.options.IsDefined()) return MakeTracker(entry.name, nullptr);
  const YamlMap options(entry.options, scenario.path, entry.options_key);
  return MakeTracker(entry.name, &options);
}

namespace {

constexpr const char* kFolderNameRule = "letters, digits, '_', '-' or '.' (it names a file)";

// One path component of safe characters that is not "." or "..".
bool IsFolderName(const std::string& name) {
  return name != "." && name != ".." && !name.empty() &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
         });
}

TrackerEntry ReadBuiltInTracker(const YamlMap& t, const Scenario& s) {
  TrackerEntry entry;
  entry.name = t.Get<std::string>("name");
  entry.options_key = t.key_path() + ".options";
  if (t.Has("options")) {
    entry.options = t.GetNode("options");
    if (!entry.options.IsMap()) t.Fail("options", "a mapping of tracker options");
  }
  entry.isolated = t.GetOr<bool>("isolated", RunsThirdPartyCCode(entry.name));
  if (t.Has("timeout_s")) entry.timeout_s = t.GetDouble("timeout_s", 1e-3, 86400.0);
  entry.linear_input = t.GetOr<bool>("linear_input", false);
  t.RejectUnknownKeys();
  const std::vector<std::string> names = TrackerNames();
  if (std::find(names.begin(), names.end(), entry.name) == names.end()) {
    t.Fail("name",
           "one of the available trackers: " + Joined(names) + " (or give exec: a command)");
  }
  const std::unique_ptr<Tracker> tracker = MakeScenarioTracker(s, entry);
  for (size_t m = 0; m < s.markers.size(); ++m) {
    if (tracker->CanTrack(s.markers[m])) entry.markers.push_back(m);
  }
  if (entry.markers.empty()) t.Fail("name", "a tracker for one of the scenario's markers");
  entry.parameters = tracker->Parameters();
  if (entry.isolated) {
    for (auto& parameter : IsolationParameters(entry.timeout_s))
      entry.parameters.push_back(parameter);
  }
  if (entry.linear_input) entry.parameters.emplace_back("linear_input", "true");
  return entry;
}

// An external tracker (trackers/external): a command, the markers it tracks and a timeout.
// Nothing is started at load; the sweep shakes hands with it before its first frame.
TrackerEntry ReadExecTracker(const YamlMap& t, const Scenario& s) {
  TrackerEntry entry;
  entry.name = t.Get<std::string>("name");
  if (!IsFolderName(entry.name)) t.Fail("name", kFolderNameRule);
  const std::vector<std::string> names = TrackerNames();
  if (std::find(names.begin(), names.end(), entry.name) != names.end()) {
    t.Fail("name", "a name that is not a built-in tracker's");
  }
  if (entry.name == "truth")
    t.Fail("name", "a name other than 'truth' (the TUM files' ground truth)");
  entry.exec = t.Get<std::vector<std::string>>("exec");
  if (entry.exec.empty() || entry.exec[0].empty()) t.Fail("exec", "a command: [program, args...]");
  entry.working_dir = std::filesystem::absolute(s.path).parent_path().string();
  entry.timeout_s = t.Has("timeout_s") ? t.GetDouble("timeout_s", 1e-3, 86400.0) : 10.0;
  entry.linear_input = t.GetOr<bool>("linear_input", false);
  const std::vector<std::string> markers = t.GetOr<std::vector<std::string>>("markers", {});
  for (size_t m = 0; m < s.markers.size(); ++m) {
    if (markers.empty() ||
        std::find(markers.begin(), markers.end(), s.markers[m].name) != markers.end()) {
      entry.markers.push_back(m);
    }
  }
  for (const std::string& name : markers) {
    const bool known = std::any_of(
        s.markers.begin(), s.markers.end(), [&](const MarkerSpec& m) { return m.name == name; });
    if (!known) t.Fail("markers", "names of the scenario's markers ('" + name + "' is none)");
  }
  t.RejectUnknownKeys();
  ExternalTrackerOptions options;
  options.command = entry.exec;
  options.timeout_s = entry.timeout_s;
  entry.parameters = ExternalTrackerParameters(options);
  if (entry.linear_input) entry.parameters.emplace_back("linear_input", "true");
  return entry;
}

// One sweep axis: `parameter` (read from `parameter_key`, for errors) and the values at
// `values_key` of `map`, each valid for the parameter.
SweepAxis ReadSweepAxis(const YamlMap& map,
                        const std::string& parameter_key,
                        const std::string& parameter,
                        const std::string& values_key) {
  const auto& names = SweepParameters();
  if (std::find(names.begin(), names.end(), parameter) == names.end()) {
    map.Fail(parameter_key,
             "one of noise_var, blur_sigma_px, motion_blur_px, distance_m, tilt_deg, gain, "
             "gamma, jpeg_quality");
  }
  SweepAxis axis{parameter, map.Get<std::vector<double>>(values_key)};
  if (axis.values.empty()) map.Fail(values_key, "a non-empty list of numbers");
  for (const double value : axis.values) {
    PoseSamplerOptions poses;
    Degradations degradations;
    try {
      ApplySweepValue(parameter, value, &poses, &degradations);
    } catch (const std::invalid_argument& e) {
      map.Fail(values_key, "values valid for " + parameter + " (" + e.what() + ")");
    }
  }
  return axis;
}

// `sweep: {grid: {p1: [...], p2: [...], ...}}`: two or more distinct axes, in file order.
std::vector<SweepAxis> ReadGrid(const YamlMap& sweep) {
  const YAML::Node node = sweep.GetNode("grid");
  const YamlMap grid = sweep.GetMap("grid");
  if (node.size() < 2) {
    sweep.Fail("grid", "a mapping of two or more sweep parameters to their values");
  }
  std::vector<SweepAxis> axes;
  for (const auto& entry : node) {
    const std::string parameter = entry.first.as<std::string>();
    axes.push_back(ReadSweepAxis(grid, parameter, parameter, parameter));
  }
  grid.RejectUnknownKeys();
  return axes;
}

// Keeps the trackers that --trackers names; each name must be one of the scenario's.
void KeepTrackers(const std::vector<std::string>& names, Scenario* s) {
  if (names.empty()) return;
  std::vector<std::string> all;
  for (const TrackerEntry& t : s->trackers) all.push_back(t.name);
  for (const std::string& name : names) {
    const auto named = [&](const TrackerEntry& t) { return t.name == name; };
    if (std::none_of(s->trackers.begin(), s->trackers.end(), named)) {
      throw ConfigError("--trackers: " + s->path + " has no tracker '" + name +
                        "' (its trackers: " + (all.empty() ? "none" : Joined(all)) + ")");
    }
  }
  const auto unnamed = [&](const TrackerEntry& t) {
    return std::find(names.begin(), names.end(), t.name) == names.end();
  };
  s->trackers.erase(std::remove_if(s->trackers.begin(), s->trackers.end(), unnamed),
                    s->trackers.end());
}

}  // namespace

Scenario LoadScenario(const std::string& path, const ScenarioOverrides& overrides) {
  const YamlMap root = YamlMap::LoadFile(path, overrides.set);
  Scenario s;
  s.path = path;
  s.overrides = overrides;
  s.input_files.push_back(path);
  s.name = root.GetOr<std::string>("name", std::filesystem::path(path).stem().string());
  if (!IsFolderName(s.name)) root.Fail("name", kFolderNameRule);
  s.input_files.push_back(ResolveRelativeTo(path, root.Get<std::string>("camera")));
  s.camera = LoadCameraYaml(s.input_files.back());
  const std::vector<std::string> markers = root.Get<std::vector<std::string>>("markers");
  if (markers.empty()) root.Fail("markers", "a list of at least one marker file");
  for (const std::string& m : markers) {
    s.input_files.push_back(ResolveRelativeTo(path, m));
    s.markers.push_back(LoadMarkerYaml(s.input_files.back()));
    // A marker's name (its file stem) names its rows and its example image.
    for (size_t i = 0; i + 1 < s.markers.size(); ++i) {
      if (s.markers[i].name == s.markers.back().name) {
        root.Fail("markers",
                  "markers with distinct file names (" + s.input_files[i + 2] + " and " +
                      s.input_files.back() + " are both '" + s.markers[i].name + "')");
      }
    }
  }
  if (root.Has("equal_ink_area_m2")) {
    s.equal_ink_area_m2 = root.GetDouble("equal_ink_area_m2", 1e-6, 100.0);
    for (MarkerSpec& m : s.markers) {
      s.marker_scales.push_back(EqualAreaFactor(m, *s.equal_ink_area_m2));
      m = ScaledMarker(m, s.marker_scales.back());
    }
  } else {
    s.marker_scales.assign(s.markers.size(), 1.0);
  }
  if (root.Has("trackers")) {
    for (const YamlMap& t : root.GetMapList("trackers")) {
      s.trackers.push_back(t.Has("exec") ? ReadExecTracker(t, s) : ReadBuiltInTracker(t, s));
      for (size_t i = 0; i + 1 < s.trackers.size(); ++i) {
        if (s.trackers[i].name == s.trackers.back().name) {
          t.Fail("name", "a name no other tracker of the scenario has (it names their rows)");
        }
      }
    }
  }
  KeepTrackers(overrides.trackers, &s);
  const YamlMap poses = root.GetMap("poses");
  s.poses = ReadPoses(poses);
  if (root.Has("trajectory")) s.trajectory = ReadTrajectory(root.GetMap("trajectory"));
  s.render = root.Has("render") ? ReadRender(root.GetMap("render")) : RenderDefaults{};
  const YamlMap sweep = root.GetMap("sweep");
  if (sweep.Has("grid")) {
    if (sweep.Has("parameter") || sweep.Has("values")) {
      sweep.Fail("grid", "either parameter and values, or a grid, not both");
    }
    const std::vector<SweepAxis> axes = ReadGrid(sweep);
    s.sweep_parameter = axes.front().parameter;
    s.sweep_values = axes.front().values;
    s.grid_axes.assign(axes.begin() + 1, axes.end());
  } else {
    const SweepAxis axis =
        ReadSweepAxis(sweep, "parameter", sweep.Get<std::string>("parameter"), "values");
    s.sweep_parameter = axis.parameter;
    s.sweep_values = axis.values;
  }
  s.example_value = sweep.GetOr<double>("example_value", s.sweep_values.back());
  if (std::find(s.sweep_values.begin(), s.sweep_values.end(), s.example_value) ==
      s.sweep_values.end()) {
    sweep.Fail("example_value", "one of the sweep values (of a grid's first axis)");
  }
  sweep.RejectUnknownKeys();
  s.trials = root.GetInt("trials", 1, 1000000);
  s.seed = static_cast<uint64_t>(root.GetInt("seed", 0, 2147483647));
  s.crlb = root.GetOr<bool>("crlb", true);
  root.RejectUnknownKeys();
  try {
    PlanFrames(s);
  } catch (const std::runtime_error& e) {
    const auto pose_axis = [](const std::string& p) {
      return p == "distance_m" || p == "tilt_deg";
    };
    bool swept = pose_axis(s.sweep_parameter);
    for (const SweepAxis& axis : s.grid_axes) swept = swept || pose_axis(axis.parameter);
    const std::string key = s.grid_axes.empty() ? "values" : "grid";
    if (s.trajectory) root.Fail("trajectory", std::string("markers in view: ") + e.what());
    (swept ? sweep : poses)
        .Fail(swept ? key : "distance_m", std::string("markers in view: ") + e.what());
  }
  return s;
}

}  // namespace markerbench
