#include "bench/summary.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "bench/frames_csv.h"
#include "core/number_text.h"

namespace markerbench {
namespace {

using GroupKey = std::tuple<std::string, std::string, std::string, double>;

}  // namespace

std::vector<SummaryRow> Summarize(const std::vector<FrameRow>& rows,
                                  const std::vector<double>& time_ms,
                                  const SummaryOptions& options) {
  std::vector<GroupKey> order;
  std::map<GroupKey, std::vector<size_t>> members;
  for (size_t i = 0; i < rows.size(); ++i) {
    const FrameRow& r = rows[i];
    const GroupKey key{r.scenario, r.tracker, r.marker, r.sweep_value};
    auto [it, inserted] = members.try_emplace(key);
    if (inserted) order.push_back(key);
    it->second.push_back(i);
  }
  // Series (scenario, tracker, marker) in order of appearance, values in order within each.
  std::map<std::tuple<std::string, std::string, std::string>, size_t> series_rank;
  for (const GroupKey& key : order) {
    series_rank.try_emplace({std::get<0>(key), std::get<1>(key), std::get<2>(key)},
                            series_rank.size());
  }
  std::stable_sort(order.begin(), order.end(), [&](const GroupKey& a, const GroupKey& b) {
    return series_rank.at({std::get<0>(a), std::get<1>(a), std::get<2>(a)}) <
           series_rank.at({std::get<0>(b), std::get<1>(b), std::get<2>(b)});
  });

  std::vector<SummaryRow> summary;
  for (const GroupKey& key : order) {
    const std::vector<size_t>& group = members[key];
    const FrameRow& first = rows[group.front()];
    SummaryRow s;
    s.scenario = first.scenario;
    s.sweep_parameter = first.sweep_parameter;
    s.sweep_value = first.sweep_value;
    s.tracker = first.tracker;
    s.marker = first.marker;
    s.n = static_cast<int>(group.size());
    int detected = 0, successes = 0, posed = 0, flips = 0;
    std::vector<double> sizes, position, rotation, best_position, times;
    std::vector<double> position_bound, rotation_bound;              // every frame
    std::vector<double> posed_position_bound, posed_rotation_bound;  // frames with a pose
    for (const size_t i : group) {
      const FrameRow& r = rows[i];
      const bool has_pose = r.estimate.has_value();
      detected += r.status == TrackStatus::kOk || r.status == TrackStatus::kPoseFailed;
      successes +=
          IsSuccess(has_pose, r.errors.position_error_m, r.distance_m, options.success_fraction);
      sizes.push_back(r.apparent_size_px);
      times.push_back(i < time_ms.size() ? time_ms[i] : NAN);
      position_bound.push_back(r.crlb_position_med_m);
      rotation_bound.push_back(r.crlb_rotation_med_deg);
      if (!has_pose) continue;
      posed_position_bound.push_back(r.crlb_position_med_m);
      posed_rotation_bound.push_back(r.crlb_rotation_med_deg);
      ++posed;
      flips += r.errors.flip;
      position.push_back(r.errors.position_error_m);
      rotation.push_back(r.errors.rotation_error_deg);
      best_position.push_back(r.errors.best_position_error_m);
    }
    s.apparent_size_median_px = Median(sizes);
    s.detection_rate = static_cast<double>(detected) / s.n;
    s.success_rate = static_cast<double>(successes) / s.n;
    s.position_error_median_m = Median(position);
    s.position_error_mean_m = Mean(position);
    s.position_error_p90_m = Percentile(position, 90.0);
    s.rotation_error_median_deg = Median(rotation);
    s.best_position_error_median_m = Median(best_position);
    s.flip_rate = posed ? static_cast<double>(flips) / posed : NAN;
    s.time_median_ms = Median(times);
    s.crlb_position_median_m = Median(position_bound);
    s.crlb_rotation_median_deg = Median(rotation_bound);
    s.efficiency = s.position_error_median_m / Median(posed_position_bound);
    s.rotation_efficiency = s.rotation_error_median_deg / Median(posed_rotation_bound);
    summary.push_back(s);
  }
  return summary;
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
                                 const std::string& marker) {
  std::vector<SummaryRow> series;
  for (const SummaryRow& r : summary) {
    if (r.scenario == scenario && r.tracker == tracker && r.marker == marker) series.push_back(r);
  }
  return series;
}

std::string SummaryCsv(const std::vector<SummaryRow>& rows) {
  std::string csv =
      "scenario,sweep_parameter,sweep_value,tracker,marker,n,apparent_size_median_px,"
      "detection_rate,success_rate,"
      "position_error_median_m,position_error_mean_m,position_error_p90_m,"
      "rotation_error_median_deg,best_position_error_median_m,flip_rate,time_median_ms,"
      "crlb_position_median_m,efficiency,crlb_rotation_median_deg,rotation_efficiency\n";
  for (const SummaryRow& r : rows) {
    csv += CsvField(r.scenario) + ',' + r.sweep_parameter + ',' + NumberText(r.sweep_value) + ',' +
           CsvField(r.tracker) + ',' + CsvField(r.marker) + ',' + std::to_string(r.n) + ',' +
           NumberText(r.apparent_size_median_px) + ',' + NumberText(r.detection_rate) + ',' +
           NumberText(r.success_rate) + ',' + NumberTextOrEmpty(r.position_error_median_m) + ',' +
           NumberTextOrEmpty(r.position_error_mean_m) + ',' +
           NumberTextOrEmpty(r.position_error_p90_m) + ',' +
           NumberTextOrEmpty(r.rotation_error_median_deg) + ',' +
           NumberTextOrEmpty(r.best_position_error_median_m) + ',' +
           NumberTextOrEmpty(r.flip_rate) + ',' + NumberTextOrEmpty(r.time_median_ms) + ',' +
           NumberTextOrEmpty(r.crlb_position_median_m) + ',' + NumberTextOrEmpty(r.efficiency) +
           ',' + NumberTextOrEmpty(r.crlb_rotation_median_deg) + ',' +
           NumberTextOrEmpty(r.rotation_efficiency) + '\n';
  }
  return csv;
}

}  // namespace markerbench
