// markerbench check: a run compared with an accepted reference, cell by cell, with paired
// one-sided tests in the direction of "worse" (README, "Use markerbench as a regression gate").
// Frames pair by (scenario, sweep value, trial, marker, tracker); frames.csv's status,
// position_error_m and rotation_error_deg are read as written, never re-derived.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "bench/run/run_results.h"

namespace markerbench {

struct CheckOptions {
  // Family-wise error rate of each family of tests (accuracy, speed), Holm-corrected.
  double alpha = 0.01;
  // Smallest changes that count, so that a clear but negligible change passes: the median
  // error ratio must pass 1 + min_error_change, the success rate move by min_success_change.
  double min_error_change = 0.10;
  double min_success_change = 0.03;
  // Success: a pose with position error <= success_fraction × the true distance (as report).
  double success_fraction = 0.1;
  // Speed: each tracker's time as a ratio to this tracker's on the same frames of the same
  // run, against the same ratio in the reference; empty = no speed check.
  std::string speed_tracker;
  double speed_tolerance = 0.25;
};

enum class Verdict { kSame, kWithinTolerance, kImproved, kRegressed };

const char* ToString(Verdict verdict);

struct MetricCheck {
  std::string metric;  // "success", "position error", "rotation error" or "time ratio"
  std::string unit;    // "", "m", "deg"
  // Success rates over the paired frames; median errors over the frames that succeed in
  // both; median time ratios. NaN when there is nothing to compare.
  double reference = NAN;
  double now = NAN;
  int n = 0;  // frames behind the test
  // One-sided p-values, Holm-adjusted over their family: towards worse and towards better.
  double p_worse = 1.0;
  double p_better = 1.0;
  Verdict verdict = Verdict::kSame;
};

struct CellCheck {
  std::string scenario;
  std::string tracker;
  std::string marker;
  std::string sweep_parameter;  // empty for a speed check (all of a scenario's frames)
  double sweep_value = NAN;
  std::string grid;  // a grid sweep's other axes; else empty
  int paired = 0;
  bool vanished = false;  // in the reference, no frame of it in the run: a regression
  bool added = false;     // in the run only: listed, not judged
  std::vector<MetricCheck> metrics;

  Verdict Overall() const;  // the worst of the metrics (vanished: regressed)
};

struct CheckReport {
  std::vector<CellCheck> cells;  // accuracy, reference order, then the run's new cells
  std::vector<CellCheck> speed;  // one per scenario, tracker and marker
  // Rows present on one side only, as "scenario value trial marker tracker".
  std::vector<std::string> reference_only;
  std::vector<std::string> run_only;
  // What built each side (BuildText of its manifest's environment), where the caller read it.
  std::string run_build, reference_build;

  bool Regressed() const;
};

// Throws ConfigError naming the scenario when paired frames carry different ground truth
// (another scenario, seed or pose protocol), or when the speed check lacks its data.
CheckReport CompareRuns(const std::vector<ScenarioResults>& run,
                        const std::vector<ScenarioResults>& reference,
                        const CheckOptions& options);

}  // namespace markerbench
