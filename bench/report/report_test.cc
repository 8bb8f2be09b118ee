#include "bench/report/report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <openssl/evp.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench/run/frames_csv.h"
#include "core/config_error.h"
#include "core/file_bytes.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

// A frame of tracker `tracker` whose first hypothesis is `error_m` from the truth along x
// (NaN: not detected), at 1 m; its bound's median position error is (trial + 1) cm, and its
// camera-centre covariance has one axis of standard deviation 5 (trial + 1) cm (an efficient
// estimator is within 10 % of the distance with probability erf(√2 / (trial + 1))).
FrameRow Row(const std::string& scenario,
             const std::string& tracker,
             double value,
             int trial,
             double error_m) {
  FrameRow r;
  r.scenario = scenario;
  r.sweep_parameter = "noise_var";
  r.sweep_value = value;
  r.trial = trial;
  r.frame = trial;
  r.marker = "tag";
  r.tracker = tracker;
  r.seed = 1;
  r.apparent_size_px = 60.0;
  r.distance_m = 1.0;
  r.truth.translation = Eigen::Vector3d(0.0, 0.0, 1.0);
  r.bound.position_m = 0.012 * (trial + 1);
  r.bound.position_med_m = 0.01 * (trial + 1);
  r.bound.rotation_deg = 0.6;
  r.bound.rotation_med_deg = 0.5;
  r.bound.position_variances_m2 = Eigen::Vector3d(0.0, 0.0, std::pow(0.05 * (trial + 1), 2));
  if (std::isnan(error_m)) {
    r.status = TrackStatus::kNotDetected;
    r.errors = {NAN, NAN, NAN, NAN, false};
    r.message = "no \"tag\", sorry";  // quotes and a comma survive the round trip
  } else {
    r.status = TrackStatus::kOk;
    r.hypotheses = 1;
    Rigid3 estimate = r.truth;
    estimate.translation.x() -= error_m;  // camera centre moves by +error_m along x
    r.estimate = estimate;
    r.errors = {error_m, 0.0, error_m, 0.0, false};
  }
  return r;
}

TEST(FramesCsv, RowsRoundTrip) {
  FrameRow unobservable = Row("s", "x", 0.2, 1, NAN);
  unobservable.bound.position_m = unobservable.bound.position_med_m = INFINITY;
  unobservable.bound.position_variances_m2.setConstant(INFINITY);
  FrameRow without_bound = Row("s", "y", 0.2, 1, NAN);
  without_bound.bound.position_m = without_bound.bound.position_med_m = NAN;
  without_bound.bound.rotation_deg = without_bound.bound.rotation_med_deg = NAN;
  without_bound.bound.position_variances_m2.setConstant(NAN);
  for (const FrameRow& row : {Row("s", "apriltag", 0.1, 3, 0.02), unobservable, without_bound}) {
    std::string line = FormatFrameRow(row);
    ASSERT_EQ(line.back(), '\n');
    line.pop_back();
    const FrameRow back = ParseFrameRow(line);
    EXPECT_EQ(FormatFrameRow(back), FormatFrameRow(row));
    EXPECT_EQ(back.message, row.message);
    EXPECT_EQ(back.estimate.has_value(), row.estimate.has_value());
    EXPECT_EQ(std::isinf(back.bound.position_m), std::isinf(row.bound.position_m));
    EXPECT_EQ(std::isnan(back.bound.rotation_med_deg), std::isnan(row.bound.rotation_med_deg));
    for (int k = 0; k < 3; ++k) {
      const double v = row.bound.position_variances_m2[k];
      EXPECT_TRUE(std::isnan(v) ? std::isnan(back.bound.position_variances_m2[k])
                                : back.bound.position_variances_m2[k] == v);
    }
  }
  EXPECT_THROW(ParseFrameRow("a,b,c"), std::runtime_error);
}

// timing.csv names the scenario and says whether the row succeeded (10 % of the distance).
TEST(TimingCsv, RowsCarryScenarioAndSuccess) {
  EXPECT_EQ(TimingCsvHeader(), "frame,scenario,tracker,success,time_ms,round_trip_ms\n");
  EXPECT_EQ(FormatTimingRow(Row("fig6", "circle", 0.1, 2, 0.09), 1.25, 2.5),
            "2,fig6,circle,1,1.2500,2.5000\n");
  EXPECT_EQ(FormatTimingRow(Row("fig6", "circle", 0.1, 2, 0.11), 1.25, 2.5),
            "2,fig6,circle,0,1.2500,2.5000\n");
  EXPECT_EQ(FormatTimingRow(Row("fig6", "circle", 0.1, 2, NAN), 1.25, 2.5),
            "2,fig6,circle,0,1.2500,2.5000\n");
}

// Counts and the seed out of their types' range are errors, not wrapped or undefined casts
// (found by loaders_fuzz).
TEST(FramesCsv, CountsOutOfRangeAreErrors) {
  const std::string good = FormatFrameRow(Row("s", "t", 0.1, 3, 0.02));
  const std::vector<std::string> fields = SplitCsvLine(good.substr(0, good.size() - 1));
  const auto with = [&](size_t column, const std::string& value) {
    std::vector<std::string> f = fields;
    f[column] = value;
    std::string line;
    for (const std::string& v : f) line += (line.empty() ? "" : ",") + CsvField(v);
    return line;
  };
  EXPECT_NO_THROW(ParseFrameRow(with(3, "7")));
  // Not structured bindings: the lambda below uses them (C++17 cannot capture those).
  for (const auto& bad : std::vector<std::pair<size_t, std::string>>{
           {3, "8.65065e+13"}, {3, "-1"}, {4, "2.5"}, {11, "1e300"}, {7, "-3"}, {7, "1x"}}) {
    EXPECT_THAT([&] { ParseFrameRow(with(bad.first, bad.second)); },
                ::testing::ThrowsMessage<std::runtime_error>(HasSubstr("expected a whole number")))
        << bad.first << " " << bad.second;
  }
}

class ReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        (fs::temp_directory_path() / ("markerbench_report_" + std::to_string(::getpid()))).string();
    fs::remove_all(dir_);
    fs::create_directories(dir_ + "/fig6_noise");
    // apriltag: 5 trials at σ² = 0.1, 0.18, 0.2 with 5, 3 and 2 successes (error ≤ 0.1 m).
    const std::vector<std::pair<double, std::vector<double>>> cells = {
        {0.1, {0.01, 0.02, 0.03, 0.04, 0.05}},
        {0.18, {0.01, 0.05, 0.09, 0.2, NAN}},
        {0.2, {0.02, 0.08, 0.5, NAN, NAN}},
    };
    std::string frames = FramesCsvHeader(), timing = TimingCsvHeader();
    for (const auto& [value, errors] : cells) {
      for (size_t trial = 0; trial < errors.size(); ++trial) {
        const FrameRow row = Row("fig6_noise", "apriltag", value, trial, errors[trial]);
        frames += FormatFrameRow(row);
        timing += FormatTimingRow(row, 1.0 + trial, 1.5 + trial);
      }
    }
    std::ofstream(dir_ + "/fig6_noise/frames.csv") << frames;
    std::ofstream(dir_ + "/fig6_noise/timing.csv") << timing;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string dir_;
};

TEST_F(ReportTest, SummaryOfASyntheticSweep) {
  ReportOptions options;
  options.plots = false;
  WriteReport(dir_, options);
  std::istringstream summary(ReadFileBytes(dir_ + "/summary.csv"));
  std::string line;
  std::getline(summary, line);  // header
  // scenario .. marker, then n, median apparent size, detection, success, median / mean / p90
  // error, median rotation, oracle median, flip rate, median time (of every call: 1..5 ms),
  // median bound (1..5 cm over all trials: 3 cm), efficiency (median error / median bound of
  // the posed trials), median rotation bound, rotation efficiency (no rotation error: 0);
  // then the Wilson intervals of detection and success (5/5: 0.5655-1, 4/5: 0.3755-0.9638,
  // 3/5: 0.2307-0.8824, 2/5: 0.1176-0.7693).
  const std::vector<std::vector<double>> expected = {
      {5, 60, 1.0, 1.0, 0.03, 0.03, 0.046, 0, 0.03, 0, 3, 0.03, 1.0, 0.5, 0, 0.5655, 1, 0.5655, 1},
      // Posed errors 0.01, 0.05, 0.09, 0.2: median 0.07, mean 0.0875, p90 0.167; posed
      // bounds 1-4 cm: efficiency 0.07 / 0.025.
      {5,
       60,
       0.8,
       0.6,
       0.07,
       0.0875,
       0.167,
       0,
       0.07,
       0,
       3,
       0.03,
       2.8,
       0.5,
       0,
       0.3755,
       0.9638,
       0.2307,
       0.8824},
      // Posed errors 0.02, 0.08, 0.5: median 0.08, mean 0.2, p90 0.416; bounds 1-3 cm.
      {5,
       60,
       0.6,
       0.4,
       0.08,
       0.2,
       0.416,
       0,
       0.08,
       0,
       3,
       0.03,
       4.0,
       0.5,
       0,
       0.2307,
       0.8824,
       0.1176,
       0.7693}};
  for (const std::vector<double>& want : expected) {
    ASSERT_TRUE(std::getline(summary, line));
    const std::vector<std::string> fields = SplitCsvLine(line);
    ASSERT_EQ(fields.size(), 33u) << line;
    // Five or fewer posed frames: no median interval reaches 95 % (empty fields).
    for (size_t i = 25; i < 29; ++i) {
      EXPECT_EQ(fields[i], "") << line;
    }
    // scenario, grid (empty: one axis), tracker, marker
    EXPECT_EQ(fields[0] + "|" + fields[3] + "|" + fields[4] + fields[5], "fig6_noise||apriltagtag");
    // Success at the bound: the mean over the 5 trials of erf(√2 / (trial + 1)), whatever
    // the tracker found (0.95450, 0.68269, 0.49501, 0.38292, 0.31084).
    EXPECT_NEAR(std::stod(fields[29]), 0.5651945, 1e-6) << line;
    // The oracle's success and its interval: one hypothesis a frame, so the first's.
    EXPECT_EQ(fields[30], fields[9]) << line;
    EXPECT_EQ(fields[31] + "-" + fields[32], fields[23] + "-" + fields[24]) << line;
    for (size_t i = 0; i < want.size(); ++i) {
      EXPECT_NEAR(std::stod(fields[6 + i]), want[i], i < 15 ? 1e-12 : 5e-5)
          << line << " column " << 6 + i;
    }
  }
  EXPECT_FALSE(std::getline(summary, line));

  const std::string report = ReadFileBytes(dir_ + "/report.md");
  // Breakdown: the first value under 50% success is 0.2, the paper says "fails above 0.18".
  EXPECT_THAT(report, HasSubstr("| apriltag | tag | 0.2 |"));
  // The same for scripts: breakdowns.csv (the last value reached, 0.2).
  EXPECT_EQ(ReadFileBytes(dir_ + "/breakdowns.csv"),
            "scenario,sweep_parameter,grid,tracker,marker,breakdown_value,last_value\n"
            "fig6_noise,noise_var,,apriltag,tag,0.2,0.2\n");
  EXPECT_THAT(report,
              HasSubstr("| AprilTag noise breakdown | σ² > 0.18 | - | breaks down at noise_var = "
                        "0.2 | agrees | - |"));
  // The originals' measured breakdowns stand beside the paper's even when not run here.
  EXPECT_THAT(report,
              HasSubstr("| ARToolKitPlus noise breakdown | σ² > 0.1 | breaks down at noise_var = "
                        "0.12 | not run: no `artkplus` rows in `fig6_noise`"));
  EXPECT_THAT(report,
              HasSubstr("| 0.18 | apriltag | tag | 5 | 60 | 80% | 60% (23–88%) | 70 | 87.5 |"));
  EXPECT_THAT(report, HasSubstr("| 3 | 30 | 2.8 | 0 | 57% |\n"));  // ms, bound, × bound, at bound
  // The circle method's own claims, not run here.
  EXPECT_THAT(report, HasSubstr("| circle method blur | works up to σ = 10 | - | not run"));
  EXPECT_THAT(ReadFileBytes(dir_ + "/manifest.json"),
              HasSubstr("\"success_position_fraction_of_distance\": 0.1"));
}

// A user's own scenario gets its sections, not nine "not run" claims of the paper.
TEST_F(ReportTest, AUsersScenarioMakesNoClaimsOfThePaper) {
  fs::create_directories(dir_ + "/mine");
  std::string frames = FramesCsvHeader();
  for (int trial = 0; trial < 3; ++trial)
    frames += FormatFrameRow(Row("mine", "circle", 0.1, trial, 0.01));
  std::ofstream(dir_ + "/mine/frames.csv") << frames;
  fs::remove_all(dir_ + "/fig6_noise");
  ReportOptions options;
  options.plots = false;
  WriteReport(dir_, options);
  const std::string report = ReadFileBytes(dir_ + "/report.md");
  EXPECT_THAT(report, ::testing::Not(HasSubstr("The paper's claims")));
  EXPECT_THAT(report, HasSubstr("## mine (sweep of `noise_var`)"));
  EXPECT_THAT(report, HasSubstr("| 0.1 | circle | tag | 3 |"));
  // Every frame succeeds: no breakdown (an empty field).
  EXPECT_THAT(ReadFileBytes(dir_ + "/breakdowns.csv"),
              HasSubstr("\nmine,noise_var,,circle,tag,,0.1\n"));
}

TEST_F(ReportTest, StricterSuccessMovesTheBreakdown) {
  ReportOptions options;
  options.plots = false;
  options.summary.success_fraction = 0.045;  // 0.1: 4 of 5 succeed; 0.18: 1 of 5
  WriteReport(dir_, options);
  EXPECT_THAT(ReadFileBytes(dir_ + "/report.md"), HasSubstr("| apriltag | tag | 0.18 |"));
  EXPECT_THAT(ReadFileBytes(dir_ + "/breakdowns.csv"), HasSubstr(",apriltag,tag,0.18,0.2\n"));
}

// report.html stands alone: its plots are inside it (the same bytes as the PNG) and its tables
// are HTML tables with the sorting script.
TEST_F(ReportTest, HtmlEmbedsPlotsAndSortableTables) {
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + "not really an image \xff\x00";
  std::ofstream(dir_ + "/fig6_noise.png", std::ios::binary) << png;
  ReportOptions options;
  options.plots = false;
  WriteReport(dir_, options);
  const std::string html = ReadFileBytes(dir_ + "/report.html");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_THAT(html, HasSubstr("<title>markerbench report</title>"));
  EXPECT_THAT(html, HasSubstr("<th>tracker</th>"));
  EXPECT_THAT(html, HasSubstr("<td>apriltag</td>"));
  EXPECT_THAT(html, HasSubstr("addEventListener(\"click\""));
  EXPECT_THAT(html, Not(HasSubstr("src=\"fig6_noise.png\"")));
  const std::string prefix = "src=\"data:image/png;base64,";
  const size_t start = html.find(prefix);
  ASSERT_NE(start, std::string::npos);
  const size_t begin = start + prefix.size();
  const std::string encoded = html.substr(begin, html.find('"', begin) - begin);
  std::string decoded(encoded.size(), '\0');
  const int n = EVP_DecodeBlock(reinterpret_cast<unsigned char*>(decoded.data()),
                                reinterpret_cast<const unsigned char*>(encoded.data()),
                                static_cast<int>(encoded.size()));
  ASSERT_GE(n, 0);
  // EVP_DecodeBlock keeps the padding's zero bytes.
  const size_t padding = std::count(encoded.end() - 2, encoded.end(), '=');
  EXPECT_EQ(decoded.substr(0, static_cast<size_t>(n) - padding), png);
}

TEST_F(ReportTest, MisalignedTimingIsAnError) {
  std::ofstream(dir_ + "/fig6_noise/timing.csv")
      << TimingCsvHeader() << "7,fig6_noise,apriltag,1,1.0,1.0\n";
  ReportOptions options;
  options.plots = false;
  EXPECT_THROW(WriteReport(dir_, options), ConfigError);
}

// A manifest.json whose keys have other types (edited by hand, or by another tool) is bad
// input naming the file and the key, not the JSON library's message.
TEST_F(ReportTest, ADamagedManifestNamesTheFileAndTheKey) {
  const nlohmann::json valid = {{"environment",
                                 {{"git_commit", "abc"},
                                  {"compiler", "g++"},
                                  {"build_type", "Release"},
                                  {"cpu_model", "cpu"},
                                  {"threads", 2}}},
                                {"scenarios",
                                 {{"fig6_noise",
                                   {{"file", "fig6.yaml"},
                                    {"trials", 5},
                                    {"seed", 1},
                                    {"frames", 15},
                                    {"wall_s", 1.5},
                                    {"frames_per_s", 10.0},
                                    {"threads", 2},
                                    {"builds", {{{"git_commit", "abc"}, {"from_frame", 0}}}},
                                    {"shards", {{{"builds", {{{"git_commit", "abc"}}}}}}}}}}}};
  const std::string manifest_path = dir_ + "/manifest.json";
  ReportOptions options;
  options.plots = false;
  std::ofstream(manifest_path) << valid.dump();
  WriteReport(dir_, options);
  EXPECT_THAT(ReadFileBytes(dir_ + "/report.md"), HasSubstr("Ran 15 frames"));
  const nlohmann::json trajectory = {{"fps", 30.0},
                                     {"frames", 10},
                                     {"static_s", 0.0},
                                     {"exposure_s", 0.01},
                                     {"readout_s", 0.0},
                                     {"occlusions", {{1, 2}}}};
  struct Damage {
    std::string pointer;
    nlohmann::json value;
    std::string message;
  };
  const std::string entry = "/scenarios/fig6_noise";
  const std::vector<Damage> damages = {
      {"/environment", "x", "key 'environment': expected an object, got \"x\""},
      {"/environment/threads", "two", "key 'environment/threads': expected a number"},
      {"/environment/git_commit", 5, "key 'environment/git_commit': expected a string, got 5"},
      {entry, 5, "key 'scenarios/fig6_noise': expected an object, got 5"},
      {entry + "/wall_s", "1 s", "key 'scenarios/fig6_noise/wall_s': expected a number"},
      {entry + "/file", 3, "key 'scenarios/fig6_noise/file': expected a string"},
      {entry + "/builds",
       nlohmann::json::object(),
       "key 'scenarios/fig6_noise/builds': expected a list, got {}"},
      {entry + "/builds/0", "abc", "key 'scenarios/fig6_noise/builds/0': expected an object"},
      {entry + "/shards/0/builds/0/git_commit",
       5,
       "key 'scenarios/fig6_noise/shards/0/builds/0/git_commit': expected a string"},
      {entry + "/trajectory", "orbit", "key 'scenarios/fig6_noise/trajectory': expected an object"},
      {entry + "/trajectory/fps", nullptr, "key 'scenarios/fig6_noise/trajectory/fps': missing"},
      {entry + "/trajectory/frames",
       "10",
       "key 'scenarios/fig6_noise/trajectory/frames': expected a number, got \"10\""},
      {entry + "/trajectory/occlusions/0",
       nlohmann::json::array({1}),
       "key 'scenarios/fig6_noise/trajectory/occlusions/0': expected [first, last] frames"},
  };
  for (const Damage& damage : damages) {
    SCOPED_TRACE(damage.pointer);
    nlohmann::json damaged = valid;
    if (damage.pointer.rfind(entry + "/trajectory/", 0) == 0) {
      damaged[nlohmann::json::json_pointer(entry + "/trajectory")] = trajectory;
    }
    const nlohmann::json::json_pointer at(damage.pointer);
    if (damage.value.is_null()) {
      damaged[at.parent_pointer()].erase(at.back());
    } else {
      damaged[at] = damage.value;
    }
    std::ofstream(manifest_path) << damaged.dump();
    EXPECT_THAT(
        [&] { WriteReport(dir_, options); },
        ::testing::ThrowsMessage<ConfigError>(HasSubstr(manifest_path + ": " + damage.message)));
  }
}

TEST(Report, EmptyFolderIsAnError) {
  ReportOptions options;
  options.plots = false;
  EXPECT_THROW(WriteReport(fs::temp_directory_path().string() + "/no_such_results", options),
               ConfigError);
}

}  // namespace
}  // namespace markerbench

namespace markerbench {
namespace {

// The summary is built one sweep cell at a time: trackers may interleave within a cell, but
// a cell that comes back after another is refused (its groups were already summarised).
// The oracle's success counts a frame whose first hypothesis is the circle's other tilt and whose
// second is right; its flip counts too, and the first hypothesis's success does not.
TEST(SummaryBuilderTest, TheOraclesSuccessCountsTheRightHypothesisOfAFlippedFrame) {
  SummaryBuilder builder({});
  for (int trial = 0; trial < 4; ++trial) {
    FrameRow row = Row("s", "a", 0.0, trial, trial < 3 ? 0.5 : 0.01);
    if (trial < 2) {  // the second hypothesis 1 cm off
      row.hypotheses = 2;
      row.errors.best_position_error_m = 0.01;
      row.errors.flip = true;
    }
    builder.Add(row, 1.0);
  }
  builder.Add(Row("s", "a", 0.0, 4, NAN), 1.0);
  const std::vector<SummaryRow> summary = builder.Finish();
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_DOUBLE_EQ(summary[0].success_rate, 1.0 / 5.0);
  EXPECT_DOUBLE_EQ(summary[0].best_success_rate, 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(summary[0].flip_rate, 2.0 / 4.0);
  // Wilson, 3 of 5.
  EXPECT_NEAR(summary[0].best_success_rate_ci.lo, 0.2307, 5e-5);
  EXPECT_NEAR(summary[0].best_success_rate_ci.hi, 0.8824, 5e-5);
}

TEST(SummaryBuilderTest, SummarisesCellByCellAndRefusesACellThatComesBack) {
  SummaryBuilder builder({});
  builder.Add(Row("s", "a", 0.0, 0, 0.001), 1.0);
  builder.Add(Row("s", "b", 0.0, 0, NAN), 2.0);
  builder.Add(Row("s", "a", 0.0, 1, 0.003), 3.0);
  builder.Add(Row("s", "a", 0.1, 0, 0.002), 4.0);
  const std::vector<SummaryRow> summary = builder.Finish();
  // Series in order of appearance (a, then b), values in order within each.
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[0].tracker, "a");
  EXPECT_EQ(summary[0].n, 2);
  EXPECT_DOUBLE_EQ(summary[0].position_error_median_m, 0.002);
  EXPECT_EQ(summary[1].tracker, "a");
  EXPECT_EQ(summary[1].sweep_value, 0.1);
  EXPECT_EQ(summary[2].tracker, "b");
  EXPECT_EQ(summary[2].detection_rate, 0.0);

  SummaryBuilder out_of_order({});
  out_of_order.Add(Row("s", "a", 0.0, 0, 0.001), 1.0);
  out_of_order.Add(Row("s", "a", 0.1, 0, 0.001), 1.0);
  EXPECT_THAT([&] { out_of_order.Add(Row("s", "a", 0.0, 1, 0.001), 1.0); },
              ::testing::ThrowsMessage<ConfigError>(HasSubstr("after the rows of other values")));
}

}  // namespace
}  // namespace markerbench
