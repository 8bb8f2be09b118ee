#include "bench/report/regression_check.h"

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <tuple>

#include "bench/metrics/metrics.h"
#include "bench/metrics/paired_tests.h"
#include "core/number_text.h"
#include "core/yaml_reader.h"

namespace markerbench {
namespace {

// Truth poses of one frame written by two runs agree to the last digits of the CSV text.
constexpr double kTruthTolerance = 1e-9;
// Errors below this (a pose exact to the last bit) are compared as this.
constexpr double kSmallestError = 1e-15;

// (scenario, tracker, marker, sweep parameter, grid, sweep value)
using CellId = std::tuple<std::string, std::string, std::string, std::string, std::string, double>;
// (scenario, sweep parameter, grid, sweep value, trial, marker, tracker)
using FrameId =
    std::tuple<std::string, std::string, std::string, double, int, std::string, std::string>;

CellId CellOf(const std::string& scenario, const FrameRow& r) {
  return {scenario, r.tracker, r.marker, r.sweep_parameter, r.grid, r.sweep_value};
}

FrameId FrameOf(const std::string& scenario, const FrameRow& r) {
  return {scenario, r.sweep_parameter, r.grid, r.sweep_value, r.trial, r.marker, r.tracker};
}

std::string FrameText(const std::string& scenario, const FrameRow& r) {
  return scenario + " " + r.sweep_parameter + "=" + NumberText(r.sweep_value) +
         (r.grid.empty() ? "" : ";" + r.grid) + " trial " + std::to_string(r.trial) + " " +
         r.marker + " " + r.tracker;
}

bool SameTruth(const Rigid3& a, const Rigid3& b) {
  return (a.rotation - b.rotation).cwiseAbs().maxCoeff() <= kTruthTolerance &&
         (a.translation - b.translation).cwiseAbs().maxCoeff() <=
             kTruthTolerance * std::max(1.0, a.translation.norm());
}

struct Pair {
  const FrameRow* reference;
  const FrameRow* now;
};

struct Cell {
  CellCheck check;
  std::vector<Pair> pairs;
  bool in_reference = false;
};

// The pairs of every cell, in the reference's order, then the run's new cells.
std::vector<Cell> PairFrames(const std::vector<ScenarioResults>& run,
                             const std::vector<ScenarioResults>& reference,
                             CheckReport* report) {
  std::map<FrameId, const FrameRow*> run_frames;
  for (const ScenarioResults& s : run) {
    for (const FrameRow& r : s.rows) run_frames[FrameOf(s.name, r)] = &r;
  }
  std::vector<Cell> cells;
  std::map<CellId, size_t> index;
  const auto cell_of = [&](const std::string& scenario, const FrameRow& r) -> Cell& {
    const auto [it, inserted] = index.emplace(CellOf(scenario, r), cells.size());
    if (inserted) {
      Cell cell;
      cell.check.scenario = scenario;
      cell.check.tracker = r.tracker;
      cell.check.marker = r.marker;
      cell.check.sweep_parameter = r.sweep_parameter;
      cell.check.sweep_value = r.sweep_value;
      cell.check.grid = r.grid;
      cells.push_back(std::move(cell));
    }
    return cells[it->second];
  };
  std::set<FrameId> paired;
  for (const ScenarioResults& s : reference) {
    for (const FrameRow& r : s.rows) {
      Cell& cell = cell_of(s.name, r);
      cell.in_reference = true;
      const auto found = run_frames.find(FrameOf(s.name, r));
      if (found == run_frames.end()) {
        report->reference_only.push_back(FrameText(s.name, r));
        continue;
      }
      const FrameRow& now = *found->second;
      if (!SameTruth(r.truth, now.truth)) {
        throw ConfigError(s.name + ": the ground truth of " + FrameText(s.name, r) +
                          " differs from the reference's (another scenario, seed or pose "
                          "protocol); bless a new reference if the protocol changed on purpose");
      }
      cell.pairs.push_back({&r, &now});
      paired.insert(found->first);
    }
  }
  for (const ScenarioResults& s : run) {
    for (const FrameRow& r : s.rows) {
      cell_of(s.name, r);
      if (!paired.count(FrameOf(s.name, r))) report->run_only.push_back(FrameText(s.name, r));
    }
  }
  return cells;
}

bool Succeeded(const FrameRow& r, double fraction) {
  return IsSuccess(r.status == TrackStatus::kOk, r.errors.position_error_m, r.distance_m, fraction);
}

MetricCheck SuccessCheck(const std::vector<Pair>& pairs, double fraction) {
  MetricCheck m{"success", ""};
  int lost = 0, gained = 0, reference_ok = 0, now_ok = 0;
  for (const Pair& p : pairs) {
    const bool before = Succeeded(*p.reference, fraction);
    const bool after = Succeeded(*p.now, fraction);
    reference_ok += before;
    now_ok += after;
    lost += before && !after;
    gained += after && !before;
  }
  m.n = static_cast<int>(pairs.size());
  if (m.n > 0) {
    m.reference = static_cast<double>(reference_ok) / m.n;
    m.now = static_cast<double>(now_ok) / m.n;
  }
  m.p_worse = McNemarPValue(lost, gained);
  m.p_better = McNemarPValue(gained, lost);
  m.verdict = lost + gained == 0 ? Verdict::kSame : Verdict::kWithinTolerance;
  return m;
}

// Paired errors of the frames that succeed in both runs, compared as log ratios (a
// scale-free test: a 30 % worse tracker moves every frame by the same log step).
MetricCheck ErrorCheck(const std::vector<Pair>& pairs,
                       double fraction,
                       const std::string& metric,
                       const std::string& unit,
                       double PoseErrors::*error) {
  MetricCheck m{metric, unit};
  std::vector<double> before, after, log_ratios;
  for (const Pair& p : pairs) {
    if (!Succeeded(*p.reference, fraction) || !Succeeded(*p.now, fraction)) continue;
    before.push_back(p.reference->errors.*error);
    after.push_back(p.now->errors.*error);
    log_ratios.push_back(std::log(std::max(after.back(), kSmallestError)) -
                         std::log(std::max(before.back(), kSmallestError)));
  }
  m.n = static_cast<int>(log_ratios.size());
  m.reference = Median(before);
  m.now = Median(after);
  std::vector<double> negated(log_ratios.size());
  std::transform(
      log_ratios.begin(), log_ratios.end(), negated.begin(), [](double d) { return -d; });
  m.p_worse = WilcoxonSignedRankPValue(log_ratios);
  m.p_better = WilcoxonSignedRankPValue(negated);
  const bool same =
      std::all_of(log_ratios.begin(), log_ratios.end(), [](double d) { return d == 0.0; });
  m.verdict = same ? Verdict::kSame : Verdict::kWithinTolerance;
  return m;
}

// Holm over every metric of `cells` (one family), then the verdicts.
void Judge(std::vector<CellCheck>* cells,
           double alpha,
           const std::function<bool(const MetricCheck&, bool worse)>& large_enough) {
  std::vector<MetricCheck*> tests;
  for (CellCheck& c : *cells) {
    for (MetricCheck& m : c.metrics) tests.push_back(&m);
  }
  std::vector<double> worse, better;
  for (const MetricCheck* m : tests) {
    worse.push_back(m->p_worse);
    better.push_back(m->p_better);
  }
  worse = HolmAdjusted(worse);
  better = HolmAdjusted(better);
  for (size_t i = 0; i < tests.size(); ++i) {
    MetricCheck& m = *tests[i];
    m.p_worse = worse[i];
    m.p_better = better[i];
    if (m.verdict == Verdict::kSame) continue;
    if (m.p_worse < alpha && large_enough(m, true)) {
      m.verdict = Verdict::kRegressed;
    } else if (m.p_better < alpha && large_enough(m, false)) {
      m.verdict = Verdict::kImproved;
    }
  }
}

}  // namespace

namespace {

// Per-frame time ratios of each (tracker, marker) of one scenario to the speed tracker's time
// on the same pose (cell and trial; the median when it tracks several markers).
std::map<std::pair<std::string, std::string>, std::vector<double>> TimeRatios(
    const ScenarioResults& s, const std::string& speed_tracker, const std::string& side) {
  std::map<std::tuple<std::string, double, int>, std::vector<double>> base_times;
  for (size_t i = 0; i < s.rows.size(); ++i) {
    if (s.rows[i].tracker != speed_tracker) continue;
    if (!std::isfinite(s.time_ms[i])) {
      throw ConfigError(side + " " + s.name + "/timing.csv: the speed check needs the time of " +
                        "every frame");
    }
    base_times[{s.rows[i].grid, s.rows[i].sweep_value, s.rows[i].trial}].push_back(s.time_ms[i]);
  }
  if (base_times.empty()) {
    throw ConfigError(side + " " + s.name + ": no frames of the speed tracker '" + speed_tracker +
                      "'");
  }
  std::map<std::pair<std::string, std::string>, std::vector<double>> ratios;
  for (size_t i = 0; i < s.rows.size(); ++i) {
    const FrameRow& r = s.rows[i];
    const auto base = base_times.find({r.grid, r.sweep_value, r.trial});
    if (r.tracker == speed_tracker || base == base_times.end()) continue;
    const double base_ms = Median(base->second);
    if (std::isfinite(s.time_ms[i]) && base_ms > 0.0) {
      ratios[{r.tracker, r.marker}].push_back(s.time_ms[i] / base_ms);
    }
  }
  return ratios;
}

std::vector<CellCheck> SpeedChecks(const std::vector<ScenarioResults>& run,
                                   const std::vector<ScenarioResults>& reference,
                                   const std::string& speed_tracker) {
  std::vector<CellCheck> checks;
  for (const ScenarioResults& before : reference) {
    const auto after = std::find_if(
        run.begin(), run.end(), [&](const ScenarioResults& s) { return s.name == before.name; });
    if (after == run.end()) continue;  // a vanished scenario is judged by accuracy
    const auto before_ratios = TimeRatios(before, speed_tracker, "reference");
    const auto after_ratios = TimeRatios(*after, speed_tracker, "run");
    for (const auto& [series, ratios] : before_ratios) {
      const auto now = after_ratios.find(series);
      if (now == after_ratios.end()) continue;
      CellCheck c;
      c.scenario = before.name;
      c.tracker = series.first;
      c.marker = series.second;
      MetricCheck m{"time ratio", "× " + speed_tracker};
      m.reference = Median(ratios);
      m.now = Median(now->second);
      m.n = static_cast<int>(std::min(ratios.size(), now->second.size()));
      m.p_worse = MannWhitneyPValue(now->second, ratios);
      m.p_better = MannWhitneyPValue(ratios, now->second);
      m.verdict = ratios == now->second ? Verdict::kSame : Verdict::kWithinTolerance;
      c.metrics.push_back(m);
      checks.push_back(std::move(c));
    }
  }
  return checks;
}

}  // namespace

const char* ToString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kSame:
      return "same";
    case Verdict::kWithinTolerance:
      return "pass";
    case Verdict::kImproved:
      return "improved";
    case Verdict::kRegressed:
      return "REGRESSED";
  }
  return "?";
}

Verdict CellCheck::Overall() const {
  if (vanished) return Verdict::kRegressed;
  Verdict worst = Verdict::kSame;
  for (const MetricCheck& m : metrics) {
    if (m.verdict == Verdict::kRegressed) return Verdict::kRegressed;
    worst = std::max(worst, m.verdict);
  }
  return worst;
}

bool CheckReport::Regressed() const {
  const auto regressed = [](const CellCheck& c) { return c.Overall() == Verdict::kRegressed; };
  return std::any_of(cells.begin(), cells.end(), regressed) ||
         std::any_of(speed.begin(), speed.end(), regressed);
}

CheckReport CompareRuns(const std::vector<ScenarioResults>& run,
                        const std::vector<ScenarioResults>& reference,
                        const CheckOptions& options) {
  CheckReport report;
  const double fraction = options.success_fraction;
  for (Cell& cell : PairFrames(run, reference, &report)) {
    CellCheck& c = cell.check;
    c.paired = static_cast<int>(cell.pairs.size());
    c.vanished = cell.in_reference && c.paired == 0;
    c.added = !cell.in_reference;
    if (c.paired > 0) {
      c.metrics.push_back(SuccessCheck(cell.pairs, fraction));
      c.metrics.push_back(
          ErrorCheck(cell.pairs, fraction, "position error", "m", &PoseErrors::position_error_m));
      c.metrics.push_back(ErrorCheck(
          cell.pairs, fraction, "rotation error", "deg", &PoseErrors::rotation_error_deg));
    }
    report.cells.push_back(std::move(c));
  }
  Judge(&report.cells, options.alpha, [&](const MetricCheck& m, bool worse) {
    if (m.metric == "success") {
      const double drop = worse ? m.reference - m.now : m.now - m.reference;
      return drop >= options.min_success_change - 1e-12;
    }
    const double ratio = worse ? m.now / m.reference : m.reference / m.now;
    return ratio > 1.0 + options.min_error_change;
  });
  if (!options.speed_tracker.empty()) {
    report.speed = SpeedChecks(run, reference, options.speed_tracker);
    Judge(&report.speed, options.alpha, [&](const MetricCheck& m, bool worse) {
      const double ratio = worse ? m.now / m.reference : m.reference / m.now;
      return ratio > 1.0 + options.speed_tolerance;
    });
  }
  return report;
}

}  // namespace markerbench
