#include "bench/report/summary.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "bench/run/frames_csv.h"
#include "core/config_error.h"
#include "core/number_text.h"
#include "renderer/pose_crlb.h"

namespace markerbench {

void SummaryBuilder::Add(const FrameRow& r, double time_ms) {
  if (!open_.empty() &&
      (open_.front().row.scenario != r.scenario || open_.front().row.grid != r.grid ||
       open_.front().row.sweep_value != r.sweep_value)) {
    CloseCell();
  }
  if (open_.empty()) {
    if (closed_cells_.count({r.scenario, r.grid, r.sweep_value})) {
      throw ConfigError("a row of " + r.scenario + " at " + r.sweep_parameter + " = " +
                        NumberText(r.sweep_value) + (r.grid.empty() ? "" : " (" + r.grid + ")") +
                        " after the rows of other values; frames.csv must keep each sweep "
                        "value's rows together, in plan order, as sweep and merge write them");
    }
  }
  auto group = std::find_if(open_.begin(), open_.end(), [&](const Group& g) {
    return g.row.tracker == r.tracker && g.row.marker == r.marker;
  });
  if (group == open_.end()) {
    group = open_.insert(open_.end(), Group{});
    group->row.scenario = r.scenario;
    group->row.sweep_parameter = r.sweep_parameter;
    group->row.sweep_value = r.sweep_value;
    group->row.grid = r.grid;
    group->row.tracker = r.tracker;
    group->row.marker = r.marker;
  }
  Group& g = *group;
  const bool has_pose = r.estimate.has_value();
  ++g.row.n;
  g.detected += r.status == TrackStatus::kOk || r.status == TrackStatus::kPoseFailed;
  g.successes +=
      IsSuccess(has_pose, r.errors.position_error_m, r.distance_m, options_.success_fraction);
  g.best_successes +=
      IsSuccess(has_pose, r.errors.best_position_error_m, r.distance_m, options_.success_fraction);
  g.sizes.push_back(r.apparent_size_px);
  g.times.push_back(time_ms);
  g.position_bound.push_back(r.bound.position_med_m);
  g.rotation_bound.push_back(r.bound.rotation_med_deg);
  g.success_at_bound_sum += ProbabilityNormWithin(options_.success_fraction * r.distance_m,
                                                  r.bound.position_variances_m2);
  if (!has_pose) return;
  g.posed_position_bound.push_back(r.bound.position_med_m);
  g.posed_rotation_bound.push_back(r.bound.rotation_med_deg);
  ++g.posed;
  g.flips += r.errors.flip;
  g.position.push_back(r.errors.position_error_m);
  g.rotation.push_back(r.errors.rotation_error_deg);
  g.best_position.push_back(r.errors.best_position_error_m);
}

void SummaryBuilder::CloseCell() {
  closed_cells_.emplace(
      open_.front().row.scenario, open_.front().row.grid, open_.front().row.sweep_value);
  for (Group& g : open_) {
    SummaryRow s = g.row;
    s.apparent_size_median_px = Median(g.sizes);
    s.detection_rate = static_cast<double>(g.detected) / s.n;
    s.success_rate = static_cast<double>(g.successes) / s.n;
    s.position_error_median_m = Median(g.position);
    s.position_error_mean_m = Mean(g.position);
    s.position_error_p90_m = Percentile(g.position, 90.0);
    s.rotation_error_median_deg = Median(g.rotation);
    s.best_position_error_median_m = Median(g.best_position);
    s.flip_rate = g.posed ? static_cast<double>(g.flips) / g.posed : NAN;
    s.best_success_rate = static_cast<double>(g.best_successes) / s.n;
    s.time_median_ms = Median(g.times);
    s.crlb_position_median_m = Median(g.position_bound);
    s.crlb_rotation_median_deg = Median(g.rotation_bound);
    s.efficiency = s.position_error_median_m / Median(g.posed_position_bound);
    s.rotation_efficiency = s.rotation_error_median_deg / Median(g.posed_rotation_bound);
    s.success_at_bound = g.success_at_bound_sum / s.n;
    s.detection_rate_ci = WilsonInterval(g.detected, s.n);
    s.success_rate_ci = WilsonInterval(g.successes, s.n);
    s.best_success_rate_ci = WilsonInterval(g.best_successes, s.n);
    s.position_error_median_ci_m = MedianInterval(g.position);
    s.rotation_error_median_ci_deg = MedianInterval(g.rotation);
    rows_.push_back(s);
  }
  open_.clear();
}

std::vector<SummaryRow> SummaryBuilder::Finish() {
  if (!open_.empty()) CloseCell();
  // Series (scenario, tracker, marker, grid) in order of appearance, values in order within
  // each.
  std::map<std::tuple<std::string, std::string, std::string, std::string>, size_t> series_rank;
  for (const SummaryRow& r : rows_) {
    series_rank.try_emplace({r.scenario, r.tracker, r.marker, r.grid}, series_rank.size());
  }
  std::vector<SummaryRow> summary = std::move(rows_);
  rows_.clear();
  std::stable_sort(summary.begin(), summary.end(), [&](const SummaryRow& a, const SummaryRow& b) {
    return series_rank.at({a.scenario, a.tracker, a.marker, a.grid}) <
           series_rank.at({b.scenario, b.tracker, b.marker, b.grid});
  });
  return summary;
}

std::vector<SeriesName> SeriesNames(const std::vector<SummaryRow>& rows,
                                    const std::string& scenario) {
  std::vector<SeriesName> names;
  for (const SummaryRow& r : rows) {
    const SeriesName name{r.tracker, r.marker, r.grid};
    if (r.scenario == scenario && std::find(names.begin(), names.end(), name) == names.end()) {
      names.push_back(name);
    }
  }
  return names;
}

std::optional<double> BreakdownValue(const std::vector<SummaryRow>& rows,
                                     const SummaryOptions& options) {
  for (const SummaryRow& r : rows) {
    if (r.success_rate < options.breakdown_rate) return r.sweep_value;
  }
  return std::nullopt;
}

std::vector<SummaryRow> SeriesOf(const std::vector<SummaryRow>& summary,
                                 const std::string& scenario,
                                 const std::string& tracker,
                                 const std::string& marker,
                                 const std::string& grid) {
  std::vector<SummaryRow> series;
  for (const SummaryRow& r : summary) {
    if (r.scenario == scenario && r.tracker == tracker && r.marker == marker && r.grid == grid) {
      series.push_back(r);
    }
  }
  return series;
}

std::string SummaryCsv(const std::vector<SummaryRow>& rows) {
  std::string csv =
      "scenario,sweep_parameter,sweep_value,grid,tracker,marker,n,apparent_size_median_px,"
      "detection_rate,success_rate,"
      "position_error_median_m,position_error_mean_m,position_error_p90_m,"
      "rotation_error_median_deg,best_position_error_median_m,flip_rate,time_median_ms,"
      "crlb_position_median_m,efficiency,crlb_rotation_median_deg,rotation_efficiency,"
      "detection_rate_lo,detection_rate_hi,success_rate_lo,success_rate_hi,"
      "position_error_median_lo_m,position_error_median_hi_m,"
      "rotation_error_median_lo_deg,rotation_error_median_hi_deg,success_at_bound,"
      "best_success_rate,best_success_rate_lo,best_success_rate_hi\n";
  for (const SummaryRow& r : rows) {
    csv += CsvField(r.scenario) + ',' + r.sweep_parameter + ',' + NumberText(r.sweep_value) + ',' +
           CsvField(r.grid) + ',' + CsvField(r.tracker) + ',' + CsvField(r.marker) + ',' +
           std::to_string(r.n) + ',' + NumberText(r.apparent_size_median_px) + ',' +
           NumberText(r.detection_rate) + ',' + NumberText(r.success_rate) + ',' +
           NumberTextOrEmpty(r.position_error_median_m) + ',' +
           NumberTextOrEmpty(r.position_error_mean_m) + ',' +
           NumberTextOrEmpty(r.position_error_p90_m) + ',' +
           NumberTextOrEmpty(r.rotation_error_median_deg) + ',' +
           NumberTextOrEmpty(r.best_position_error_median_m) + ',' +
           NumberTextOrEmpty(r.flip_rate) + ',' + NumberTextOrEmpty(r.time_median_ms) + ',' +
           NumberTextOrEmpty(r.crlb_position_median_m) + ',' + NumberTextOrEmpty(r.efficiency) +
           ',' + NumberTextOrEmpty(r.crlb_rotation_median_deg) + ',' +
           NumberTextOrEmpty(r.rotation_efficiency);
    for (const Interval& i : {r.detection_rate_ci,
                              r.success_rate_ci,
                              r.position_error_median_ci_m,
                              r.rotation_error_median_ci_deg}) {
      csv += ',' + NumberTextOrEmpty(i.lo) + ',' + NumberTextOrEmpty(i.hi);
    }
    csv += ',' + NumberTextOrEmpty(r.success_at_bound) + ',' + NumberText(r.best_success_rate) +
           ',' + NumberTextOrEmpty(r.best_success_rate_ci.lo) + ',' +
           NumberTextOrEmpty(r.best_success_rate_ci.hi) + '\n';
  }
  return csv;
}

std::string BreakdownsCsv(const std::vector<SummaryRow>& summary, const SummaryOptions& options) {
  std::string csv = "scenario,sweep_parameter,grid,tracker,marker,breakdown_value,last_value\n";
  std::vector<std::string> scenarios;
  for (const SummaryRow& r : summary) {
    if (std::find(scenarios.begin(), scenarios.end(), r.scenario) == scenarios.end()) {
      scenarios.push_back(r.scenario);
    }
  }
  for (const std::string& scenario : scenarios) {
    for (const SeriesName& name : SeriesNames(summary, scenario)) {
      const std::vector<SummaryRow> series =
          SeriesOf(summary, scenario, name.tracker, name.marker, name.grid);
      const std::optional<double> breakdown = BreakdownValue(series, options);
      csv += CsvField(scenario) + ',' + series.front().sweep_parameter + ',' + CsvField(name.grid) +
             ',' + CsvField(name.tracker) + ',' + CsvField(name.marker) + ',' +
             (breakdown ? NumberText(*breakdown) : "") + ',' +
             NumberText(series.back().sweep_value) + '\n';
    }
  }
  return csv;
}

}  // namespace markerbench
