// A rendered dataset is self-contained, and score turns a tracker's estimates for it into a
// run folder that report reads, with a located error for every kind of bad estimate.
#include "bench/cli/score_command.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench/cli/render_command.h"
#include "bench/plan/frame_plan.h"
#include "bench/report/report.h"
#include "bench/run/dataset.h"
#include "bench/run/frame_bound.h"
#include "bench/run/pose_columns.h"
#include "bench/run/run_results.h"
#include "core/config_error.h"
#include "core/marker_yaml.h"
#include "core/test_files.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

constexpr int kFrames = 6;

// The smoke scenario's first frames, rendered once for every test.
const std::string& DatasetDir() {
  static const std::string dir = [] {
    const std::string out = fs::path(WriteTestFile("unused", "")).parent_path() / "dataset";
    fs::remove_all(out);
    RenderScenario("scenarios/smoke.yaml", out, kFrames, false, false);
    return out;
  }();
  return dir;
}

std::string EstimatesHeader() {
  std::string header = "frame,status";
  for (const char* c : kPoseColumns) header += std::string(",") + c;
  return header;
}

std::string PoseText(const Rigid3& pose) {
  std::string text;
  for (int k = 0; k < 9; ++k) text += "," + NumberText(pose.rotation(k / 3, k % 3));
  for (int k = 0; k < 3; ++k) text += "," + NumberText(pose.translation[k]);
  return text;
}

TEST(Dataset, RenderWritesASelfContainedDataset) {
  const Scenario scenario = LoadScenario("scenarios/smoke.yaml");
  const Dataset dataset = ReadDataset(DatasetDir());
  EXPECT_EQ(dataset.scenario, "smoke");
  EXPECT_TRUE(fs::exists(DatasetDir() + "/README.txt"));
  EXPECT_EQ(dataset.camera.fx, scenario.camera.fx);
  // The marker files give the markers as the frames show them, equal-area scale included.
  ASSERT_EQ(dataset.markers.size(), scenario.markers.size());
  for (const MarkerSpec& m : scenario.markers) {
    const MarkerSpec from_file = LoadMarkerYaml(DatasetDir() + "/markers/" + m.name + ".yaml");
    EXPECT_TRUE(from_file.InkBounds().isApprox(m.InkBounds(), 1e-12)) << m.name;
    ASSERT_EQ(from_file.keypoints.size(), m.keypoints.size());
    for (size_t k = 0; k < m.keypoints.size(); ++k) {
      EXPECT_TRUE(from_file.keypoints[k].isApprox(m.keypoints[k], 1e-12)) << m.name << k;
    }
  }
  // The ground truth reads back exactly.
  const std::vector<PlannedFrame> plan = PlanFrames(scenario, kFrames);
  ASSERT_EQ(dataset.frames.size(), plan.size());
  for (size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(dataset.frames[i].truth.rotation, plan[i].cam_from_marker.rotation) << i;
    EXPECT_EQ(dataset.frames[i].truth.translation, plan[i].cam_from_marker.translation) << i;
    EXPECT_EQ(dataset.frames[i].sweep_value, plan[i].sweep_value) << i;
    // The frame's Cramér-Rao bound, to the bit what a sweep of the scenario writes.
    const FrameBound bound = PlannedFrameBound(scenario, plan[i], RequestFor(scenario, plan[i]));
    const FrameBound& read = dataset.frames[i].bound;
    EXPECT_GT(read.position_med_m, 0.0) << i;
    EXPECT_EQ(read.position_m, bound.position_m) << i;
    EXPECT_EQ(read.position_med_m, bound.position_med_m) << i;
    EXPECT_EQ(read.rotation_deg, bound.rotation_deg) << i;
    EXPECT_EQ(read.rotation_med_deg, bound.rotation_med_deg) << i;
    EXPECT_EQ(read.position_variances_m2, bound.position_variances_m2) << i;
  }
}

// groundtruth.csv with one field replaced: (column, value) on its first row.
std::string DamagedDataset(const std::string& column, const std::string& value) {
  const std::string copy = fs::path(WriteTestFile("unused", "")).parent_path() / "damaged";
  fs::remove_all(copy);
  fs::copy(DatasetDir(), copy, fs::copy_options::recursive);
  std::ifstream in(copy + "/groundtruth.csv");
  std::string header, row, rest;
  std::getline(in, header);
  std::getline(in, row);
  for (std::string line; std::getline(in, line);) rest += line + "\n";
  in.close();
  std::vector<std::string> names = SplitCsvLine(header), fields = SplitCsvLine(row);
  const size_t at = std::find(names.begin(), names.end(), column) - names.begin();
  EXPECT_LT(at, names.size()) << column;
  if (at < names.size()) fields[at] = value;
  std::string line;
  for (const std::string& f : fields) line += (line.empty() ? "" : ",") + CsvField(f);
  std::ofstream(copy + "/groundtruth.csv") << header << "\n" << line << "\n" << rest;
  return copy;
}

// A damaged groundtruth.csv: frame numbers and seeds out of range are located errors.
TEST(Dataset, CountsOutOfRangeAreErrors) {
  for (const auto& [column, value] : std::vector<std::pair<std::string, std::string>>{
           {"frame", "1e300"}, {"frame", "-1"}, {"seed", "-3"}, {"seed", "1.5"}}) {
    const std::string copy = DamagedDataset(column, value);
    EXPECT_THAT([&] { ReadDataset(copy); },
                ::testing::ThrowsMessage<ConfigError>(HasSubstr(
                    "groundtruth.csv:2: column '" + column + "': expected a whole number")))
        << column << " " << value;
  }
}

// The bound's fields: empty (not computed) and inf (nothing to see) read back as such, a
// negative or unreadable one is a located error.
TEST(Dataset, BoundFieldsReadBackOrNameTheirLine) {
  EXPECT_TRUE(
      std::isnan(ReadDataset(DamagedDataset("crlb_position_m", "")).frames[0].bound.position_m));
  EXPECT_EQ(ReadDataset(DamagedDataset("crlb_rotation_deg", "inf")).frames[0].bound.rotation_deg,
            INFINITY);
  // A file with CRLF line ends (edited on Windows) reads the same.
  const std::string crlf = DamagedDataset("crlb_position_m", "");
  std::ifstream in(crlf + "/groundtruth.csv");
  std::string text;
  for (std::string line; std::getline(in, line);) text += line + "\r\n";
  in.close();
  std::ofstream(crlf + "/groundtruth.csv") << text;
  const Dataset read = ReadDataset(crlf);
  EXPECT_EQ(read.frames.back().bound.position_variances_m2,
            ReadDataset(DatasetDir()).frames.back().bound.position_variances_m2);
  for (const char* value : {"-1", "x"}) {
    const std::string copy = DamagedDataset("crlb_position_var2_m2", value);
    EXPECT_THAT([&] { ReadDataset(copy); },
                ::testing::ThrowsMessage<ConfigError>(
                    HasSubstr("groundtruth.csv:2: column 'crlb_position_var2_m2': expected a")))
        << value;
  }
}

TEST(Score, EstimatesBecomeARunThatReportReads) {
  const Dataset dataset = ReadDataset(DatasetDir());
  Rigid3 shifted = dataset.frames[0].truth;
  shifted.translation.x() += 0.001;  // moves the camera centre by exactly 1 mm
  const std::string estimates =
      WriteTestFile("estimates.csv",
                    EstimatesHeader() + ",time_ms\n0,ok" + PoseText(shifted) + ",2.5\n" + "1,ok" +
                        PoseText(dataset.frames[1].truth) + ",3\n1,ok" + PoseText(shifted) + ",\n" +
                        "2,not_detected" + std::string(12, ',') + ",1\n");
  ScoreOptions options;
  options.dataset_dir = DatasetDir();
  options.estimates_path = estimates;
  options.tracker = "mine";
  options.out_dir = fs::path(estimates).parent_path() / "scored";
  fs::remove_all(options.out_dir);
  std::ostringstream said;
  RunScoreCommand(options, said);
  EXPECT_THAT(said.str(), HasSubstr("3 had no estimate"));

  const std::vector<ScenarioResults> run = ReadRunResults(options.out_dir);
  ASSERT_EQ(run.size(), 1u);
  const std::vector<FrameRow>& rows = run[0].rows;
  ASSERT_EQ(rows.size(), static_cast<size_t>(kFrames));
  EXPECT_EQ(rows[0].status, TrackStatus::kOk);
  EXPECT_NEAR(rows[0].errors.position_error_m, 0.001, 1e-12);
  EXPECT_EQ(rows[1].hypotheses, 2);
  EXPECT_NEAR(rows[1].errors.position_error_m, 0.0, 1e-12);
  EXPECT_EQ(rows[2].status, TrackStatus::kNotDetected);
  for (int i = 3; i < kFrames; ++i) {
    EXPECT_EQ(rows[static_cast<size_t>(i)].status, TrackStatus::kNotDetected);
    EXPECT_EQ(rows[static_cast<size_t>(i)].message, "no estimate");
  }
  EXPECT_EQ(rows[0].tracker, "mine");
  // Every frame, estimated or not, keeps its bound from the dataset.
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].bound.position_med_m, dataset.frames[i].bound.position_med_m) << i;
    EXPECT_EQ(rows[i].bound.position_variances_m2, dataset.frames[i].bound.position_variances_m2)
        << i;
  }
  EXPECT_FALSE(fs::exists(options.out_dir + "/smoke/timing.csv")) << "frames 3-5 have no time";
  ReportOptions report;
  report.plots = false;
  WriteReport(options.out_dir, report);
  EXPECT_TRUE(fs::exists(options.out_dir + "/summary.csv"));
  // A second score into the same folder would mix two runs.
  EXPECT_THROW(RunScoreCommand(options, said), ConfigError);
}

TEST(Score, BadEstimatesNameTheirLine) {
  const Dataset dataset = ReadDataset(DatasetDir());
  const std::string good = PoseText(dataset.frames[0].truth);
  Rigid3 reflected = dataset.frames[0].truth;
  reflected.rotation.col(0) *= -1.0;
  for (const auto& [text, complaint] : std::vector<std::pair<std::string, std::string>>{
           {"frame,status\n", ":1: expected the header"},
           {EstimatesHeader() + "\n0,ok" + good + "\n99,ok" + good + "\n",
            ":3: column 'frame': '99' is not a frame of the dataset"},
           {EstimatesHeader() + "\n1e300,ok" + good + "\n",
            ":2: column 'frame': '1e300' is not a frame of the dataset"},
           {EstimatesHeader() + "\n0,fine" + good + "\n", ":2: column 'status'"},
           {EstimatesHeader() + "\n0,ok,x" + good.substr(good.find(',', 1)) + "\n",
            ":2: column 'r11': expected a number, got 'x'"},
           {EstimatesHeader() + "\n0,ok" + PoseText(reflected) + "\n",
            ":2: columns 'r11'..'r33': expected a rotation"},
           {EstimatesHeader() + "\n0,ok" + good + "\n0,error" + std::string(12, ',') + "\n",
            ":3: frame 0 is 'error' here but 'ok' on line 2"},
           {EstimatesHeader() + "\n0,ok\n", ":2: expected 14 fields, got 2"}}) {
    ScoreOptions options;
    options.dataset_dir = DatasetDir();
    options.estimates_path = WriteTestFile("bad_estimates.csv", text);
    options.tracker = "mine";
    options.out_dir = fs::path(options.estimates_path).parent_path() / "never";
    std::ostringstream said;
    try {
      RunScoreCommand(options, said);
      ADD_FAILURE() << text;
    } catch (const ConfigError& e) {
      EXPECT_THAT(e.what(), HasSubstr("bad_estimates.csv" + complaint)) << text;
    }
    EXPECT_FALSE(fs::exists(options.out_dir)) << "nothing is written for bad estimates";
  }
}

}  // namespace
}  // namespace markerbench
