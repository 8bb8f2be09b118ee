#include "bench/report/sequence_report.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <tuple>

#include "bench/io/atomic_file.h"
#include "bench/io/tum_trajectory.h"
#include "bench/metrics/metrics.h"
#include "bench/report/sequence_metrics.h"
#include "bench/run/run_results.h"
#include "core/number_text.h"
#include "core/yaml_reader.h"

namespace fs = std::filesystem;

namespace markerbench {
namespace {

TrajectoryOptions TrajectoryOf(const nlohmann::json& entry) {
  const nlohmann::json& t = entry.at("trajectory");
  TrajectoryOptions o;
  o.fps = t.at("fps").get<double>();
  o.duration_s = t.at("frames").get<int>() / o.fps;
  o.static_s = t.at("static_s").get<double>();
  o.exposure_s = t.at("exposure_s").get<double>();
  o.readout_s = t.at("readout_s").get<double>();
  for (const nlohmann::json& r : t.at("occlusions")) {
    o.occlusions.push_back({r.at(0).get<int>(), r.at(1).get<int>()});
  }
  return o;
}

bool SameSequence(const FrameRow& a, const FrameRow& b) {
  return a.sweep_value == b.sweep_value && a.grid == b.grid && a.trial == b.trial &&
         a.marker == b.marker;
}

// "circles_a_noise_var=0.01_t3": the sequence's file name (a grid's ';' become '_').
std::string SequenceName(const FrameRow& r) {
  std::string grid = r.grid;
  std::replace(grid.begin(), grid.end(), ';', '_');
  return r.marker + "_" + r.sweep_parameter + "=" + NumberText(r.sweep_value) +
         (grid.empty() ? "" : "_" + grid) + "_t" + std::to_string(r.trial);
}

std::string SequencesCsvHeader() {
  return "scenario,sweep_parameter,sweep_value,grid,trial,marker,tracker,frames,visible,lost,"
         "found_hidden,ate_m,rpe_m,rpe_deg,jitter_m,reacquire_s,tracking_ms,detection_ms\n";
}

}  // namespace

SequenceSummaryRow SummaryOfSequences(const SequenceSummaryRow& cell,
                                      const std::vector<SequenceMetrics>& sequences) {
  SequenceSummaryRow s = cell;
  std::vector<double> ate, rpe, rpe_deg, jitter, reacquire, tracking, detection;
  for (const SequenceMetrics& m : sequences) {
    ++s.sequences;
    s.visible += m.visible;
    s.lost += m.lost;
    s.found_hidden += m.found_hidden;
    ate.push_back(m.ate_m);
    rpe.push_back(m.rpe_m);
    rpe_deg.push_back(m.rpe_deg);
    jitter.push_back(m.jitter_m);
    tracking.push_back(m.tracking_ms);
    detection.push_back(m.detection_ms);
    for (const double seconds : m.reacquire_s) {
      if (std::isnan(seconds)) continue;
      ++s.occlusions;
      s.never_reacquired += std::isinf(seconds);
      reacquire.push_back(seconds);
    }
  }
  // Frames of a video are not independent samples (a tracker loses runs of them): the
  // videos are.
  if (s.visible > 0) {
    s.lost_rate_ci = WilsonIntervalOfRate(static_cast<double>(s.lost) / s.visible, s.sequences);
  }
  s.ate_m = Median(ate);
  s.ate_ci_m = MedianInterval(ate);
  s.rpe_m = Median(rpe);
  s.rpe_deg = Median(rpe_deg);
  s.jitter_m = Median(jitter);
  s.reacquire_median_s = Median(reacquire);
  s.tracking_ms = Median(tracking);
  s.tracking_ci_ms = MedianInterval(tracking);
  s.detection_ms = Median(detection);
  s.detection_ci_ms = MedianInterval(detection);
  return s;
}

SequenceResults::SequenceResults(const std::string& folder, const nlohmann::json& entry)
    : folder_(folder), trajectory_(TrajectoryOf(entry)), csv_(SequencesCsvHeader()) {}

bool SequenceResults::Add(const FrameRow& row, double time_ms) {
  if (!open_ || !SameSequence(open_->first, row)) {
    Close();
    open_.emplace();
    open_->first = row;
  }
  SequenceRows& s = *open_;
  if (row.frame != s.last_frame) {
    if (s.frames >= trajectory_.Frames()) {
      throw ConfigError("a sequence longer than its trajectory's " +
                        std::to_string(trajectory_.Frames()) + " frames");
    }
    s.last_frame = row.frame;
    s.truth.push_back(row.truth);
    ++s.frames;
  }
  auto [it, added] = s.of_tracker.try_emplace(row.tracker);
  if (added) s.trackers.push_back(row.tracker);
  SequenceFrame frame;
  frame.occluded = trajectory_.Occluded(s.frames - 1);
  frame.truth = row.truth;
  if (row.status == TrackStatus::kOk) frame.estimate = row.estimate;
  frame.time_ms = time_ms;
  it->second.push_back(frame);
  return !frame.occluded;
}

void SequenceResults::Close() {
  if (!open_) return;
  const SequenceRows& s = *open_;
  const std::string name = SequenceName(s.first);
  std::string truth;
  for (int k = 0; k < s.frames; ++k) truth += TumLine(trajectory_.TruthTime(k), s.truth[k]);
  WriteTum("truth", name, truth);
  for (const std::string& tracker : s.trackers) {
    const std::vector<SequenceFrame>& frames = s.of_tracker.at(tracker);
    std::string tum;
    for (size_t k = 0; k < frames.size(); ++k) {
      if (frames[k].estimate)
        tum += TumLine(trajectory_.TruthTime(static_cast<int>(k)), *frames[k].estimate);
    }
    WriteTum(tracker, name, tum);
    const SequenceMetrics m = MeasureSequence(frames, trajectory_);
    std::string reacquire;
    for (const double seconds : m.reacquire_s) {
      reacquire += (reacquire.empty() ? "" : ";") + NumberTextOrEmpty(seconds);
    }
    const FrameRow& r = s.first;
    csv_ += CsvField(r.scenario) + ',' + r.sweep_parameter + ',' + NumberText(r.sweep_value) + ',' +
            CsvField(r.grid) + ',' + std::to_string(r.trial) + ',' + CsvField(r.marker) + ',' +
            CsvField(tracker) + ',' + std::to_string(m.frames) + ',' + std::to_string(m.visible) +
            ',' + std::to_string(m.lost) + ',' + std::to_string(m.found_hidden) + ',' +
            NumberTextOrEmpty(m.ate_m) + ',' + NumberTextOrEmpty(m.rpe_m) + ',' +
            NumberTextOrEmpty(m.rpe_deg) + ',' + NumberTextOrEmpty(m.jitter_m) + ',' + reacquire +
            ',' + NumberTextOrEmpty(m.tracking_ms) + ',' + NumberTextOrEmpty(m.detection_ms) + '\n';
    measured_.push_back({r, tracker, m});
  }
  open_.reset();
}

void SequenceResults::WriteTum(const std::string& who,
                               const std::string& name,
                               const std::string& text) const {
  fs::create_directories(folder_ + "/tum/" + who);
  WriteFileAtomically(folder_ + "/tum/" + who + "/" + name + ".tum", text);
}

std::vector<SequenceSummaryRow> SequenceResults::Finish() {
  Close();
  WriteFileAtomically(folder_ + "/sequences.csv", csv_);
  // Per (cell, marker, tracker), over the trials, in order of first appearance.
  std::vector<std::pair<SequenceSummaryRow, std::vector<SequenceMetrics>>> cells;
  std::map<std::tuple<double, std::string, std::string, std::string>, size_t> index;
  for (const MeasuredSequence& m : measured_) {
    const FrameRow& r = m.sequence;
    const auto [it, added] =
        index.try_emplace({r.sweep_value, r.grid, r.marker, m.tracker}, cells.size());
    if (added) {
      SequenceSummaryRow cell;
      cell.scenario = r.scenario;
      cell.sweep_parameter = r.sweep_parameter;
      cell.sweep_value = r.sweep_value;
      cell.grid = r.grid;
      cell.marker = r.marker;
      cell.tracker = m.tracker;
      cells.emplace_back(cell, std::vector<SequenceMetrics>{});
    }
    cells[it->second].second.push_back(m.metrics);
  }
  std::vector<SequenceSummaryRow> rows;
  for (const auto& [cell, sequences] : cells) rows.push_back(SummaryOfSequences(cell, sequences));
  return rows;
}

std::string SequenceSummaryCsv(const std::vector<SequenceSummaryRow>& rows) {
  std::string csv =
      "scenario,sweep_parameter,sweep_value,grid,marker,tracker,sequences,visible,lost,"
      "lost_rate_lo,lost_rate_hi,found_hidden,ate_median_m,ate_median_lo_m,ate_median_hi_m,"
      "rpe_median_m,rpe_median_deg,jitter_median_m,occlusions,never_reacquired,"
      "reacquire_median_s,tracking_median_ms,tracking_median_lo_ms,tracking_median_hi_ms,"
      "detection_median_ms,detection_median_lo_ms,detection_median_hi_ms\n";
  for (const SequenceSummaryRow& s : rows) {
    csv += CsvField(s.scenario) + ',' + s.sweep_parameter + ',' + NumberText(s.sweep_value) + ',' +
           CsvField(s.grid) + ',' + CsvField(s.marker) + ',' + CsvField(s.tracker) + ',' +
           std::to_string(s.sequences) + ',' + std::to_string(s.visible) + ',' +
           std::to_string(s.lost) + ',' + NumberTextOrEmpty(s.lost_rate_ci.lo) + ',' +
           NumberTextOrEmpty(s.lost_rate_ci.hi) + ',' + std::to_string(s.found_hidden) + ',' +
           NumberTextOrEmpty(s.ate_m) + ',' + NumberTextOrEmpty(s.ate_ci_m.lo) + ',' +
           NumberTextOrEmpty(s.ate_ci_m.hi) + ',' + NumberTextOrEmpty(s.rpe_m) + ',' +
           NumberTextOrEmpty(s.rpe_deg) + ',' + NumberTextOrEmpty(s.jitter_m) + ',' +
           std::to_string(s.occlusions) + ',' + std::to_string(s.never_reacquired) + ',' +
           NumberTextOrEmpty(s.reacquire_median_s) + ',' + NumberTextOrEmpty(s.tracking_ms) + ',' +
           NumberTextOrEmpty(s.tracking_ci_ms.lo) + ',' + NumberTextOrEmpty(s.tracking_ci_ms.hi) +
           ',' + NumberTextOrEmpty(s.detection_ms) + ',' + NumberTextOrEmpty(s.detection_ci_ms.lo) +
           ',' + NumberTextOrEmpty(s.detection_ci_ms.hi) + '\n';
  }
  return csv;
}

}  // namespace markerbench
