#include "bench/plan/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "bench/plan/frame_plan.h"
#include "core/file_bytes.h"
#include "core/test_files.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;

const std::string kRoot = std::filesystem::current_path().string();

std::string GoodScenario() {
  return "name: t\ncamera: " + kRoot + "/scenarios/cameras/default.yaml\nmarkers:\n  - " + kRoot +
         "/scenarios/markers/apriltag.yaml\ntrackers:\n  - {name: apriltag, options: "
         "{quad_decimate: 1.0}}\n"
         "poses:\n  sampler: look_at\n  distance_m: 0.6\n  tilt_deg: [0, 40]\n"
         "render:\n  noise_var: 0.02\n  channels: auto\n"
         "sweep:\n  parameter: blur_sigma_px\n  values: [0, 1, 2]\ntrials: 3\nseed: 5\n";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

std::string ErrorOf(const std::string& text) {
  const std::string path = WriteTestFile("scenario.yaml", text);
  try {
    LoadScenario(path);
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path));
    return e.what();
  }
  return "";
}

TEST(Scenario, LoadsEveryField) {
  const Scenario s = LoadScenario(WriteTestFile("scenario.yaml", GoodScenario()));
  EXPECT_EQ(s.name, "t");
  EXPECT_EQ(s.camera.width, 640);
  ASSERT_EQ(s.markers.size(), 1u);
  EXPECT_EQ(s.trackers.at(0).name, "apriltag");
  EXPECT_EQ(s.trackers.at(0).options["quad_decimate"].as<double>(), 1.0);
  EXPECT_EQ(s.poses.tilt_max_deg, 40.0);
  EXPECT_EQ(s.render.degradations.noise_var, 0.02);
  EXPECT_EQ(s.sweep_parameter, "blur_sigma_px");
  EXPECT_EQ(s.sweep_values.size(), 3u);
  EXPECT_EQ(s.trials, 3);
  EXPECT_EQ(s.seed, 5u);
  EXPECT_EQ(s.example_value, 2.0);  // default: the last value
  EXPECT_FALSE(s.equal_ink_area_m2.has_value());
  EXPECT_EQ(s.input_files.size(), 3u);
  EXPECT_TRUE(s.crlb);  // default: every frame gets its Cramér-Rao bound
}

// A grid runs the first axis for every combination of the others; its cells and their grid
// text follow the plan's order (the first axis fastest), each with its own poses.
TEST(Scenario, GridSweepsEveryCombination) {
  const Scenario s = LoadScenario(
      WriteTestFile("scenario.yaml",
                    Replace(GoodScenario(),
                            "sweep:\n  parameter: blur_sigma_px\n  values: [0, 1, 2]\n",
                            "sweep:\n  grid:\n    distance_m: [0.5, 1]\n    tilt_deg: [0, 30, 60]\n"
                            "    noise_var: [0, 0.1]\n  example_value: 0.5\n")));
  EXPECT_EQ(s.sweep_parameter, "distance_m");
  EXPECT_EQ(s.sweep_values, (std::vector<double>{0.5, 1.0}));
  ASSERT_EQ(s.grid_axes.size(), 2u);
  EXPECT_EQ(s.grid_axes[0].parameter, "tilt_deg");
  EXPECT_EQ(s.grid_axes[1].parameter, "noise_var");
  const std::vector<PlannedFrame> frames = PlanFrames(s);
  ASSERT_EQ(frames.size(), 2u * 3 * 2 * 3);  // cells x trials (one marker)
  EXPECT_EQ(frames[0].grid, "tilt_deg=0;noise_var=0");
  EXPECT_EQ(frames[3].sweep_value, 1.0);  // the first axis is the fastest
  EXPECT_EQ(frames[3].grid, "tilt_deg=0;noise_var=0");
  EXPECT_EQ(frames[6].grid, "tilt_deg=30;noise_var=0");
  EXPECT_EQ(frames[18].grid, "tilt_deg=0;noise_var=0.1");
  EXPECT_EQ(frames.back().grid, "tilt_deg=60;noise_var=0.1");
  int examples = 0;
  for (const PlannedFrame& f : frames) {
    EXPECT_EQ(f.cell, f.index / 3);
    examples += f.example;
    // The settings of the cell are applied: distance, tilt and noise.
    const double distance = f.cam_from_marker.translation.norm();
    EXPECT_NEAR(distance, f.sweep_value, 0.02 * f.sweep_value) << f.index;
    EXPECT_EQ(f.degradations.noise_var,
              f.grid.find("noise_var=0.1") != std::string::npos ? 0.1 : 0.0);
    // Tilt: between the marker's normal and the ray from the marker to the camera.
    const Eigen::Vector3d& t = f.cam_from_marker.translation;
    const double tilt =
        std::acos(std::min(1.0, std::fabs(f.cam_from_marker.rotation.col(2).dot(t)) / t.norm())) *
        180.0 / M_PI;
    EXPECT_NEAR(tilt, std::stod(f.grid.substr(f.grid.find('=') + 1)), 0.5) << f.grid;
  }
  EXPECT_EQ(examples, 1);
  EXPECT_TRUE(frames[0].example);
}

// An approach starts at poses.distance_m, so a distance sweep varies where each video
// starts; every video ends at to_m.
TEST(Scenario, AnApproachStartsAtTheSweptDistance) {
  const Scenario s = LoadScenario(
      WriteTestFile("scenario.yaml",
                    Replace(GoodScenario(),
                            "sweep:\n  parameter: blur_sigma_px\n  values: [0, 1, 2]\n",
                            "trajectory: {kind: approach, fps: 10, duration_s: 1, to_m: 0.4}\n"
                            "sweep:\n  parameter: distance_m\n  values: [0.8, 1.5]\n")));
  const std::vector<PlannedFrame> frames = PlanFrames(s);
  ASSERT_EQ(frames.size(), 2u * 3 * 10);  // values x trials x frames
  for (const PlannedFrame& f : frames) {
    const double distance = f.cam_from_marker.translation.norm();
    const double expected = f.sweep_value + (0.4 - f.sweep_value) * f.sequence_frame / 10.0;
    // Within the look-at's offset of the marker centre from the image centre.
    EXPECT_NEAR(distance, expected, 0.02 * expected) << f.index;
  }
}

TEST(Scenario, GridErrorsNameTheirKey) {
  const std::string one_axis = "sweep:\n  parameter: blur_sigma_px\n  values: [0, 1, 2]\n";
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), one_axis, "sweep:\n  grid: {tilt_deg: [0, 1]}\n")),
              HasSubstr("key 'sweep.grid': expected a mapping of two or more sweep parameters"));
  EXPECT_THAT(
      ErrorOf(Replace(GoodScenario(), one_axis, "sweep:\n  grid: {tilt_deg: [0], focus: [1]}\n")),
      HasSubstr("key 'sweep.grid.focus': expected one of noise_var"));
  EXPECT_THAT(ErrorOf(Replace(
                  GoodScenario(), one_axis, "sweep:\n  grid: {tilt_deg: [0, 95], gain: [1]}\n")),
              HasSubstr("key 'sweep.grid.tilt_deg': expected values valid for tilt_deg"));
  EXPECT_THAT(
      ErrorOf(Replace(GoodScenario(), one_axis, "sweep:\n  grid: {tilt_deg: [], gain: [1]}\n")),
      HasSubstr("key 'sweep.grid.tilt_deg': expected a non-empty list"));
  EXPECT_THAT(
      ErrorOf(Replace(GoodScenario(), one_axis, one_axis + "  grid: {tilt_deg: [0], gain: [1]}\n")),
      HasSubstr("key 'sweep.grid': expected either parameter and values, or a grid"));
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(),
                              one_axis,
                              "sweep:\n  grid: {tilt_deg: [0], gain: [1]}\n  example_value: 3\n")),
              HasSubstr("key 'sweep.example_value': expected one of the sweep values (of "
                        "a grid's first axis)"));
}

TEST(Scenario, ARangeErrorShowsItsBoundsAndTheValuesGiven) {
  EXPECT_THAT(
      ErrorOf(Replace(GoodScenario(), "tilt_deg: [0, 40]", "tilt_deg: [0, 89.5]")),
      HasSubstr(":10: key 'poses.tilt_deg': expected [min, max] with 0 <= min <= max <= 89, "
                "got [0, 89.5]"));
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "tilt_deg: [0, 40]", "tilt_deg: [0, 10, 40]")),
              HasSubstr("got [0, 10, 40]"));
  // An empty item keeps its place.
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "tilt_deg: [0, 40]", "tilt_deg: ['', 40]")),
              HasSubstr("got [, 40]"));
}

TEST(Scenario, TheBoundCanBeTurnedOff) {
  EXPECT_FALSE(LoadScenario(WriteTestFile("scenario.yaml", GoodScenario() + "crlb: false\n")).crlb);
  EXPECT_THAT(ErrorOf(GoodScenario() + "crlb: sometimes\n"), HasSubstr("key 'crlb'"));
}

TEST(Scenario, EqualAreaScalesEveryMarker) {
  const Scenario s = LoadScenario(
      WriteTestFile("scenario.yaml",
                    Replace(GoodScenario(), "trials: 3", "equal_ink_area_m2: 0.0225\ntrials: 3")));
  EXPECT_NEAR(s.markers[0].InkBounds().volume(), 0.0225, 1e-12);
  EXPECT_NEAR(s.markers[0].size_m, 0.15, 1e-12);  // the tag's ink is its black square
}

TEST(Scenario, ExampleValueMustBeASweepValue) {
  EXPECT_EQ(LoadScenario(WriteTestFile("scenario.yaml",
                                       Replace(GoodScenario(),
                                               "values: [0, 1, 2]",
                                               "values: [0, 1, 2]\n  example_value: 1")))
                .example_value,
            1.0);
  EXPECT_THAT(ErrorOf(Replace(
                  GoodScenario(), "values: [0, 1, 2]", "values: [0, 1, 2]\n  example_value: 7")),
              HasSubstr("key 'sweep.example_value': expected one of the sweep values"));
}

TEST(Scenario, UnknownTrackerListsTheAvailableOnes) {
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "name: apriltag,", "name: nosuch,")),
              HasSubstr("key 'trackers[0].name': expected one of the available trackers: "
                        "apriltag, apriltag-ippe, artkplus, artkplus-improved, aruco"));
}

TEST(Scenario, TrackerOptionsAreCheckedWithTheirKey) {
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "quad_decimate: 1.0", "quad_decimat: 1.0")),
              HasSubstr("key 'trackers[0].options.quad_decimat': unknown key"));
}

// Trackers that run third-party C code run in worker processes unless told otherwise.
TEST(Scenario, TrackersOfThirdPartyCCodeAreIsolated) {
  auto with_second = [](const std::string& entry) {
    return Replace(GoodScenario(), "poses:", "  - {name: apriltag-ippe" + entry + "}\nposes:");
  };
  const Scenario s = LoadScenario(WriteTestFile("scenario.yaml", with_second("")));
  ASSERT_EQ(s.trackers.size(), 2u);
  EXPECT_TRUE(s.trackers[0].isolated);
  EXPECT_EQ(s.trackers[0].timeout_s, 60.0);
  EXPECT_THAT(s.trackers[0].parameters, testing::Contains(testing::Pair("isolated", "true")));
  const Scenario chosen =
      LoadScenario(WriteTestFile("scenario.yaml", with_second(", isolated: false")));
  EXPECT_FALSE(chosen.trackers[1].isolated);
  EXPECT_THAT(chosen.trackers[1].parameters,
              testing::Not(testing::Contains(testing::Pair("isolated", "true"))));
  EXPECT_EQ(LoadScenario(WriteTestFile("scenario.yaml", with_second(", timeout_s: 2.5")))
                .trackers[1]
                .timeout_s,
            2.5);
  EXPECT_THAT(ErrorOf(with_second(", timeout_s: 0")), HasSubstr("key 'trackers[1].timeout_s'"));
  EXPECT_THAT(ErrorOf(with_second(", isolated: maybe")), HasSubstr("key 'trackers[1].isolated'"));
}

TEST(Scenario, ExecTrackersAreCheckedAtLoad) {
  auto with_exec = [](const std::string& entry) {
    return Replace(GoodScenario(), "poses:", "  - {" + entry + "}\nposes:");
  };
  const Scenario s = LoadScenario(WriteTestFile(
      "scenario.yaml", with_exec("name: mine, exec: [python3, mine.py, -v], markers: [apriltag]")));
  ASSERT_EQ(s.trackers.size(), 2u);
  EXPECT_EQ(s.trackers[1].exec, (std::vector<std::string>{"python3", "mine.py", "-v"}));
  EXPECT_EQ(s.trackers[1].markers, std::vector<size_t>{0});
  EXPECT_EQ(s.trackers[1].timeout_s, 10.0);
  EXPECT_EQ(s.trackers[1].working_dir, std::filesystem::path(WriteTestFile("x", "")).parent_path());
  EXPECT_THAT(s.trackers[1].parameters,
              testing::Contains(testing::Pair("exec", "python3 mine.py -v")));
  EXPECT_THAT(ErrorOf(with_exec("name: apriltag-ippe, exec: [x]")),
              HasSubstr("key 'trackers[1].name': expected a name that is not a built-in"));
  EXPECT_THAT(ErrorOf(with_exec("name: mine, exec: [x], markers: [circles_a]")),
              HasSubstr("key 'trackers[1].markers'"));
  EXPECT_THAT(ErrorOf(with_exec("name: mine, exec: []")), HasSubstr("key 'trackers[1].exec'"));
  EXPECT_THAT(ErrorOf(with_exec("name: mine, exec: [x], options: {a: 1}")),
              HasSubstr("key 'trackers[1].options': unknown key"));
  EXPECT_THAT(ErrorOf(with_exec("name: apriltag")),
              HasSubstr("key 'trackers[1].name': expected a name no other tracker"));
}

// Any tracker entry, built-in or a command, can be told the camera's response; it is off
// unless asked for, recorded among the run's parameters, and must be a boolean.
TEST(Scenario, LinearInputIsAnEntrysChoiceAndRecorded) {
  EXPECT_FALSE(
      LoadScenario(WriteTestFile("scenario.yaml", GoodScenario())).trackers[0].linear_input);
  const Scenario s = LoadScenario(WriteTestFile(
      "scenario.yaml",
      Replace(Replace(GoodScenario(), "options: {quad_decimate: 1.0}}", "linear_input: true}"),
              "poses:",
              "  - {name: mine, exec: [x], linear_input: true}\nposes:")));
  for (const TrackerEntry& entry : s.trackers) {
    EXPECT_TRUE(entry.linear_input) << entry.name;
    EXPECT_THAT(entry.parameters, testing::Contains(testing::Pair("linear_input", "true")));
  }
  EXPECT_THAT(
      ErrorOf(Replace(GoodScenario(), "options: {quad_decimate: 1.0}}", "linear_input: 2}")),
      HasSubstr("key 'trackers[0].linear_input'"));
}

TEST(Scenario, TrackerMustTrackOneOfTheMarkers) {
  EXPECT_THAT(
      ErrorOf(Replace(
          GoodScenario(), "{name: apriltag, options: {quad_decimate: 1.0}}", "{name: aruco}")),
      HasSubstr("key 'trackers[0].name': expected a tracker for one of the scenario's "
                "markers"));
}

TEST(Scenario, MarkerThatCanNeverBeInView) {
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "distance_m: 0.6", "distance_m: 0.05")),
              HasSubstr("key 'poses.distance_m': expected markers in view"));
  EXPECT_THAT(
      ErrorOf(Replace(Replace(GoodScenario(), "parameter: blur_sigma_px", "parameter: distance_m"),
                      "values: [0, 1, 2]",
                      "values: [0.6, 0.05]")),
      HasSubstr("key 'sweep.values': expected markers in view"));
}

TEST(Scenario, NameMustBeAFolderName) {
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "name: t", "name: a/b")),
              HasSubstr("key 'name': expected letters, digits"));
  // `..` and `.` are made of allowed letters but name no folder of their own (out/..).
  for (const char* name : {"name: ..", "name: ."}) {
    EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "name: t", name)),
                HasSubstr("key 'name': expected letters, digits"))
        << name;
  }
}

// Two marker files with one stem once shared an example image path and aborted at 2 threads.
TEST(Scenario, MarkersNeedDistinctNames) {
  std::filesystem::create_directories(
      std::filesystem::path(WriteTestFile("placeholder", "")).parent_path() / "other");
  const std::string copy =
      WriteTestFile("other/apriltag.yaml", ReadFileBytes("scenarios/markers/apriltag.yaml"));
  const std::string error =
      ErrorOf(Replace(GoodScenario(),
                      "/scenarios/markers/apriltag.yaml\n",
                      "/scenarios/markers/apriltag.yaml\n  - " + copy + "\n"));
  EXPECT_THAT(error, HasSubstr("key 'markers': expected markers with distinct file names ("));
  EXPECT_THAT(error, HasSubstr("scenarios/markers/apriltag.yaml and " + copy));
}

TEST(Scenario, ShippedScenariosLoad) {
  for (const char* path : {"scenarios/smoke.yaml",
                           "scenarios/paper/fig6_noise.yaml",
                           "scenarios/paper/fig7_blur.yaml",
                           "scenarios/paper/fig8_distance.yaml",
                           "scenarios/examples/all_markers.yaml",
                           "scenarios/camera_response/gamma.yaml",
                           "scenarios/camera_response/gamma_linear_input.yaml",
                           "scenarios/render_only/bit_grid.yaml"}) {
    EXPECT_NO_THROW(LoadScenario(path)) << path;
  }
}

// Every example can be swept: it loads and names at least one tracker (sweep's only further
// requirement); markers no tracker reads live in scenarios/render_only/.
TEST(Scenario, EveryExampleCanBeSwept) {
  int examples = 0;
  for (const auto& entry : std::filesystem::directory_iterator("scenarios/examples")) {
    if (entry.path().extension() != ".yaml") continue;
    ++examples;
    const Scenario s = LoadScenario(entry.path().string());
    EXPECT_FALSE(s.trackers.empty()) << entry.path();
  }
  EXPECT_GE(examples, 8);
}

TEST(Scenario, UnknownKey) {
  EXPECT_THAT(ErrorOf(GoodScenario() + "threads: 4\n"), HasSubstr("key 'threads': unknown key"));
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "  distance_m: 0.6", "  distance_m: 0.6\n  dist: 1")),
              HasSubstr("key 'poses.dist': unknown key"));
}

TEST(Scenario, MissingKey) {
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "trials: 3\n", "")),
              HasSubstr("key 'trials': missing"));
}

TEST(Scenario, WrongType) {
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "seed: 5", "seed: five")),
              HasSubstr("key 'seed': expected an integer"));
}

TEST(Scenario, OutOfRange) {
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "noise_var: 0.02", "noise_var: -1")),
              HasSubstr("key 'render.noise_var': expected a number in [0, 10]"));
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "values: [0, 1, 2]", "values: [0, -1]")),
              HasSubstr("key 'sweep.values'"));
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "values: [0, 1, 2]", "values: []")),
              HasSubstr("key 'sweep.values': expected a non-empty list"));
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "tilt_deg: [0, 40]", "tilt_deg: [0, 95]")),
              HasSubstr("key 'poses.tilt_deg'"));
  // Values the renderer cannot draw are refused at load, never rendered.
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "distance_m: 0.6", "distance_m: 1e6")),
              HasSubstr("key 'poses.distance_m': expected a number in [1e-06, 10000]"));
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "values: [0, 1, 2]", "values: [0, 1e300]")),
              HasSubstr("key 'sweep.values': expected values valid for blur_sigma_px "
                        "(blur_sigma_px values must be in [0, 100])"));
  EXPECT_THAT(ErrorOf(Replace(Replace(GoodScenario(),
                                      "parameter: blur_sigma_px",
                                      "parameter: "
                                      "noise_var"),
                              "values: [0, 1, 2]",
                              "values: [0, .nan]")),
              HasSubstr("key 'sweep.values'"));
}

// The camera's response: a render key, refused out of range, and a sweep parameter that
// reaches every planned frame.
TEST(Scenario, GammaIsARenderKeyAndASweepParameter) {
  const std::string render = "  noise_var: 0.02\n";
  EXPECT_EQ(LoadScenario(WriteTestFile("scenario.yaml",
                                       Replace(GoodScenario(), render, render + "  gamma: 2.2\n")))
                .render.degradations.gamma,
            2.2);
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), render, render + "  gamma: 0\n")),
              HasSubstr("key 'render.gamma': expected a number in [0.1, 10]"));
  const Scenario s = LoadScenario(
      WriteTestFile("scenario.yaml",
                    Replace(Replace(GoodScenario(), "parameter: blur_sigma_px", "parameter: gamma"),
                            "values: [0, 1, 2]",
                            "values: [1, 2.2]")));
  const std::vector<PlannedFrame> frames = PlanFrames(s);
  ASSERT_EQ(frames.size(), 2u * 3);
  for (const PlannedFrame& f : frames) EXPECT_EQ(f.degradations.gamma, f.sweep_value);
  EXPECT_THAT(
      ErrorOf(Replace(Replace(GoodScenario(), "parameter: blur_sigma_px", "parameter: gamma"),
                      "values: [0, 1, 2]",
                      "values: [1, 0]")),
      HasSubstr("key 'sweep.values': expected values valid for gamma"));
}

TEST(Scenario, UnknownSweepParameter) {
  EXPECT_THAT(ErrorOf(Replace(GoodScenario(), "parameter: blur_sigma_px", "parameter: fog")),
              HasSubstr("key 'sweep.parameter': expected one of noise_var"));
}

TEST(Scenario, BadReferencedFileNamesThatFile) {
  const std::string marker = WriteTestFile("bad_marker.yaml", "kind: circles_a\n");
  try {
    LoadScenario(
        WriteTestFile("scenario.yaml",
                      Replace(GoodScenario(), kRoot + "/scenarios/markers/apriltag.yaml", marker)));
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(marker));
    EXPECT_THAT(e.what(), HasSubstr("key 'disks': missing"));
  }
}

}  // namespace
}  // namespace markerbench
