// The report of a sequence scenario (a run whose manifest entry has a `trajectory`, issue 22):
// - DIR/<scenario>/sequences.csv: one row per sequence (cell, trial, marker) and tracker,
//   with bench/report/sequence_metrics.h's figures;
// - DIR/<scenario>/tum/<tracker>/<sequence>.tum and tum/truth/<sequence>.tum: each tracker's
//   camera trajectory and the ground truth, for `evo_ape tum truth.tum tracker.tum`;
// - rows of DIR/sequence_summary.csv and a report.md section: per cell, marker and tracker,
//   over the trials, with 95 % intervals (report.md's section is written by report.cc).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/metrics/intervals.h"

namespace markerbench {

struct SequenceSummaryRow {
  std::string scenario;
  std::string sweep_parameter;
  double sweep_value = 0.0;
  std::string grid;
  std::string marker;
  std::string tracker;
  int sequences = 0;
  int visible = 0;  // frames where the marker shows, over the sequences
  int lost = 0;     // of those, frames without a pose
  int found_hidden = 0;
  Interval lost_rate_ci;  // Wilson, with the videos as the sample size (frames are clustered)
  // Medians over the sequences (metres, degrees, seconds, milliseconds); NaN when none.
  double ate_m = NAN;
  Interval ate_ci_m;
  double rpe_m = NAN;
  double rpe_deg = NAN;
  double jitter_m = NAN;
  // Over every occlusion of every sequence: the median re-acquisition time (+inf counts as
  // the longest), and how many were never followed by a pose.
  double reacquire_median_s = NAN;
  int occlusions = 0;
  int never_reacquired = 0;
  double tracking_ms = NAN;
  double detection_ms = NAN;
};

// Writes the scenario folder's sequences.csv and TUM files from its frames.csv and
// timing.csv; `entry` is the scenario's manifest entry (its `trajectory`). Returns the
// summary rows, in order of first appearance. Throws ConfigError naming the file and line of a
// row out of plan order.
std::vector<SequenceSummaryRow> WriteSequenceResults(const std::string& folder,
                                                     const nlohmann::json& entry);

std::string SequenceSummaryCsv(const std::vector<SequenceSummaryRow>& rows);

}  // namespace markerbench
