#include "bench/report/regression_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "bench/report/check_output.h"
#include "core/number_text.h"
#include "core/random.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;

constexpr int kTrials = 200;

// A synthetic run: two trackers on their markers over a two-value noise sweep, kTrials
// paired frames per cell, 95 % found, log-normal errors and times.
ScenarioResults SyntheticRun() {
  ScenarioResults run;
  run.name = "noise";
  Rng rng(42);
  for (const double value : {0.02, 0.1}) {
    for (int trial = 0; trial < kTrials; ++trial) {
      for (const auto& [tracker, marker] :
           {std::pair<std::string, std::string>{"circle", "circles_a"}, {"apriltag", "apriltag"}}) {
        FrameRow r;
        r.scenario = run.name;
        r.sweep_parameter = "noise_var";
        r.sweep_value = value;
        r.trial = trial;
        r.frame = static_cast<int>(run.rows.size());
        r.marker = marker;
        r.tracker = tracker;
        r.distance_m = 0.6;
        r.truth =
            Rigid3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.6 + 1e-3 * trial));
        r.status = rng.Uniform() < 0.95 ? TrackStatus::kOk : TrackStatus::kNotDetected;
        const double scale = std::exp(0.5 * rng.Gaussian());
        r.errors = r.status == TrackStatus::kOk
                       ? PoseErrors{1e-3 * scale, 0.1 * scale, 1e-3 * scale, 0.1 * scale}
                       : PoseErrors{NAN, NAN, NAN, NAN};
        run.rows.push_back(r);
        run.time_ms.push_back((tracker == "circle" ? 3.0 : 1.0) * std::exp(0.2 * rng.Gaussian()));
      }
    }
  }
  return run;
}

CheckReport Compare(const ScenarioResults& run, const CheckOptions& options = {}) {
  return CompareRuns({run}, {SyntheticRun()}, options);
}

// "tracker value" of the cells with the verdict, with the metrics that have it.
std::vector<std::string> CellsWith(const CheckReport& report, Verdict verdict) {
  std::vector<std::string> found;
  for (const std::vector<CellCheck>* cells : {&report.cells, &report.speed}) {
    for (const CellCheck& c : *cells) {
      if (c.Overall() != verdict) continue;
      std::string text =
          c.tracker + " " + (c.sweep_parameter.empty() ? "all" : NumberText(c.sweep_value));
      for (const MetricCheck& m : c.metrics) {
        if (m.verdict == verdict) text += ", " + m.metric;
      }
      found.push_back(text);
    }
  }
  return found;
}

void ScaleErrors(ScenarioResults* run, const std::string& tracker, double factor) {
  for (FrameRow& r : run->rows) {
    if (r.tracker != tracker) continue;
    r.errors.position_error_m *= factor;
    r.errors.rotation_error_deg *= factor;
  }
}

TEST(RegressionCheck, AnIdenticalRunIsTheSameEverywhere) {
  const CheckReport report = Compare(SyntheticRun());
  EXPECT_FALSE(report.Regressed());
  EXPECT_EQ(report.cells.size(), 4u);
  EXPECT_EQ(CellsWith(report, Verdict::kSame).size(), 4u);
  EXPECT_TRUE(report.reference_only.empty());
  EXPECT_TRUE(report.run_only.empty());
  EXPECT_THAT(CheckTable(report), HasSubstr("no regression: 4 cells, 0 regressed"));
}

TEST(RegressionCheck, AReorderedFileIsTheSameRun) {
  ScenarioResults run = SyntheticRun();
  std::reverse(run.rows.begin(), run.rows.end());
  std::reverse(run.time_ms.begin(), run.time_ms.end());
  EXPECT_EQ(CellsWith(Compare(run), Verdict::kSame).size(), 4u);
}

TEST(RegressionCheck, RandomTwoPercentNoiseOnTheErrorsPasses) {
  ScenarioResults run = SyntheticRun();
  Rng rng(7);
  for (FrameRow& r : run.rows) {
    r.errors.position_error_m *= rng.Uniform(0.98, 1.02);
    r.errors.rotation_error_deg *= rng.Uniform(0.98, 1.02);
  }
  const CheckReport report = Compare(run);
  EXPECT_FALSE(report.Regressed());
  EXPECT_EQ(CellsWith(report, Verdict::kWithinTolerance).size(), 4u);
}

TEST(RegressionCheck, ErrorsThirtyPercentLargerAreCaughtAndNamed) {
  ScenarioResults run = SyntheticRun();
  ScaleErrors(&run, "apriltag", 1.3);
  const CheckReport report = Compare(run);
  EXPECT_TRUE(report.Regressed());
  EXPECT_THAT(CellsWith(report, Verdict::kRegressed),
              ::testing::ElementsAre("apriltag 0.02, position error, rotation error",
                                     "apriltag 0.1, position error, rotation error"));
  EXPECT_THAT(CheckTable(report), HasSubstr("×1.30"));
}

TEST(RegressionCheck, AClearButNegligibleChangePasses) {
  ScenarioResults run = SyntheticRun();
  ScaleErrors(&run, "apriltag", 1.01);
  const CheckReport report = Compare(run);
  EXPECT_FALSE(report.Regressed());
  for (const CellCheck& c : report.cells) {
    if (c.tracker != "apriltag") continue;
    EXPECT_LT(c.metrics[1].p_worse, 1e-10);  // every frame 1 % worse: clear, but below 10 %
    EXPECT_EQ(c.metrics[1].verdict, Verdict::kWithinTolerance);
  }
}

TEST(RegressionCheck, ErrorsThirtyPercentSmallerAreAnImprovement) {
  ScenarioResults run = SyntheticRun();
  ScaleErrors(&run, "circle", 0.7);
  const CheckReport report = Compare(run);
  EXPECT_FALSE(report.Regressed());
  EXPECT_EQ(CellsWith(report, Verdict::kImproved).size(), 2u);
}

TEST(RegressionCheck, FifteenPercentFewerSuccessesInOneCellAreCaughtThere) {
  ScenarioResults run = SyntheticRun();
  int dropped = 0;
  for (FrameRow& r : run.rows) {
    if (r.tracker == "circle" && r.sweep_value == 0.1 && r.status == TrackStatus::kOk &&
        r.trial % 7 == 3) {  // 1 in 7 of the successes: about 15 %
      r.status = TrackStatus::kNotDetected;
      ++dropped;
    }
  }
  ASSERT_GT(dropped, 25);
  const CheckReport report = Compare(run);
  EXPECT_THAT(CellsWith(report, Verdict::kRegressed),
              ::testing::ElementsAre("circle 0.1, success"));
  EXPECT_THAT(CheckJunit(report), HasSubstr("<failure message=\"success 9"));
}

TEST(RegressionCheck, AVanishedCellIsARegressionAndANewOneIsNot) {
  ScenarioResults run = SyntheticRun();
  for (FrameRow& r : run.rows) {
    if (r.tracker == "apriltag" && r.sweep_value == 0.1) r.tracker = "aruco";
  }
  const CheckReport report = Compare(run);
  EXPECT_TRUE(report.Regressed());
  EXPECT_THAT(CellsWith(report, Verdict::kRegressed), ::testing::ElementsAre("apriltag 0.1"));
  EXPECT_EQ(report.reference_only.size(), static_cast<size_t>(kTrials));
  EXPECT_EQ(report.run_only.size(), static_cast<size_t>(kTrials));
  int added = 0;
  for (const CellCheck& c : report.cells) added += c.added;
  EXPECT_EQ(added, 1);
  EXPECT_THAT(CheckTable(report), HasSubstr("REGRESSED (vanished)"));
}

TEST(RegressionCheck, AnotherGroundTruthIsBadInputNamingTheScenario) {
  ScenarioResults run = SyntheticRun();
  run.rows[5].truth.translation.x() += 1e-3;
  try {
    Compare(run);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("noise: the ground truth of noise noise_var=0.02 trial 2"));
  }
}

TEST(RegressionCheck, SpeedIsComparedAsARatioToANamedTracker) {
  CheckOptions options;
  options.speed_tracker = "circle";
  ScenarioResults run = SyntheticRun();
  for (size_t i = 0; i < run.rows.size(); ++i) run.time_ms[i] *= 2.0;  // a slower machine
  EXPECT_FALSE(Compare(run, options).Regressed());
  for (size_t i = 0; i < run.rows.size(); ++i) {
    if (run.rows[i].tracker == "apriltag") run.time_ms[i] *= 1.5;
  }
  const CheckReport report = Compare(run, options);
  EXPECT_THAT(CellsWith(report, Verdict::kRegressed),
              ::testing::ElementsAre("apriltag all, time ratio"));
  run = SyntheticRun();
  for (size_t i = 0; i < run.rows.size(); ++i) {
    if (run.rows[i].tracker == "apriltag") run.time_ms[i] *= 1.1;  // within the 25 %
  }
  EXPECT_FALSE(Compare(run, options).Regressed());
}

TEST(RegressionCheck, SpeedNeedsTheNamedTracker) {
  CheckOptions options;
  options.speed_tracker = "runetag";
  EXPECT_THROW(Compare(SyntheticRun(), options), ConfigError);
}

}  // namespace
}  // namespace markerbench
