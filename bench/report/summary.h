// summary.csv (architecture.md, "Summary"): one row per scenario × tracker × marker × cell
// (a sweep value, at one combination of a grid's other axes), and the breakdown value of each
// series.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "bench/metrics/intervals.h"
#include "bench/run/frames_csv.h"

namespace markerbench {

struct SummaryOptions {
  // Success: a pose with position error <= success_fraction × the true distance.
  double success_fraction = kSuccessFraction;
  // Breakdown: the first sweep value whose success rate is below this.
  double breakdown_rate = 0.5;
};

struct SummaryRow {
  std::string scenario;
  std::string sweep_parameter;
  double sweep_value = 0.0;
  std::string grid;  // frames.csv's grid: the other axes of a grid sweep; else empty
  std::string tracker;
  std::string marker;
  int n = 0;
  double apparent_size_median_px = 0.0;
  double detection_rate = 0.0;  // the marker was found: status ok or pose_failed
  double success_rate = 0.0;
  // Over the frames with a pose (status ok); NaN when there are none.
  double position_error_median_m = 0.0;
  double position_error_mean_m = 0.0;
  double position_error_p90_m = 0.0;
  double rotation_error_median_deg = 0.0;
  double best_position_error_median_m = 0.0;  // the oracle hypothesis
  double flip_rate = 0.0;
  // Success of the oracle hypothesis (over all frames): what a tracker that returns several
  // would reach if the right one were told apart, e.g. by the next frame.
  double best_success_rate = 0.0;
  double time_median_ms = 0.0;  // NaN when timing.csv is missing
  // The physical limit (frames.csv's crlb_*_med columns; NaN when the run has no bound):
  // the median over all the cell's frames of the error an efficient estimator would have,
  // and the efficiency: the median error over the frames with a pose divided by the median
  // bound over the same frames (1 at the limit; a success rate below 100 % is left out).
  double crlb_position_median_m = 0.0;
  double crlb_rotation_median_deg = 0.0;
  double efficiency = 0.0;
  double rotation_efficiency = 0.0;
  // The success rate an efficient estimator would have: the mean over the cell's frames of
  // P(|e| <= success_fraction × distance) for e ~ N(0, the bound's covariance of the camera
  // centre). What the frames allow, whatever the tracker; NaN when the run has no bound.
  double success_at_bound = 0.0;
  // 95 % intervals (bench/metrics/intervals.h): Wilson for the rates, order statistics for medians.
  Interval detection_rate_ci;
  Interval success_rate_ci;
  Interval best_success_rate_ci;
  Interval position_error_median_ci_m;
  Interval rotation_error_median_ci_deg;
};

// Builds the summary from frames.csv rows, one at a time, in memory bounded by one sweep cell
// (a scenario's rows at one sweep value) rather than by the file: a sweep writes its cells
// one after another, so a cell's groups are summarised and freed when the next cell begins.
class SummaryBuilder {
 public:
  explicit SummaryBuilder(const SummaryOptions& options) : options_(options) {}

  // `time_ms`: the row's time (NaN when unknown). Throws ConfigError when the row belongs to
  // a cell that ended earlier (the rows are not in plan order).
  void Add(const FrameRow& row, double time_ms);

  // Groups in the order in which they first appear: scenario, then tracker, marker and grid
  // combination (a series), then sweep value.
  std::vector<SummaryRow> Finish();

 private:
  // One (tracker, marker) group of the open cell.
  struct Group {
    SummaryRow row;  // names and counts so far
    int detected = 0, successes = 0, best_successes = 0, posed = 0, flips = 0;
    std::vector<double> sizes, times, position_bound, rotation_bound;  // every frame
    std::vector<double> position, rotation, best_position;             // frames with a pose
    std::vector<double> posed_position_bound, posed_rotation_bound;
    double success_at_bound_sum = 0.0;  // NaN once a frame has no bound
  };
  void CloseCell();

  SummaryOptions options_;
  std::set<std::tuple<std::string, std::string, double>> closed_cells_;  // scenario, grid, value
  std::vector<Group> open_;  // the open cell's groups, in order of appearance
  std::vector<SummaryRow> rows_;
};

// A series of one scenario: tracker, marker and grid combination.
struct SeriesName {
  std::string tracker, marker, grid;
  bool operator==(const SeriesName& o) const {
    return tracker == o.tracker && marker == o.marker && grid == o.grid;
  }
};

// The series of one scenario, in order of appearance.
std::vector<SeriesName> SeriesNames(const std::vector<SummaryRow>& rows,
                                    const std::string& scenario);

// The first sweep value of `rows` (one series, in sweep order) whose
// success rate is below the breakdown rate; nullopt when there is none.
std::optional<double> BreakdownValue(const std::vector<SummaryRow>& rows,
                                     const SummaryOptions& options);

// Rows of `summary` for one series: scenario, tracker, marker and grid combination, in sweep
// order.
std::vector<SummaryRow> SeriesOf(const std::vector<SummaryRow>& summary,
                                 const std::string& scenario,
                                 const std::string& tracker,
                                 const std::string& marker,
                                 const std::string& grid = "");

std::string SummaryCsv(const std::vector<SummaryRow>& rows);

// breakdowns.csv: per series, its breakdown value (BreakdownValue; empty for none) and the
// last sweep value it reached, so that scripts read the report's rule instead of repeating it.
std::string BreakdownsCsv(const std::vector<SummaryRow>& summary, const SummaryOptions& options);

}  // namespace markerbench
