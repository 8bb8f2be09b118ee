// markerbench report DIR: summary.csv, report.md (summary tables, breakdown values, the
// reproduction table of experiments.md, plots), the same as a self-contained report.html, and
// the success criterion in manifest.json,
// from the frames.csv and timing.csv of every scenario folder in DIR.
#pragma once

#include <string>

#include "bench/report/summary.h"

namespace markerbench {

struct ReportOptions {
  SummaryOptions summary;
  // Runs scripts/plot_sweep.py (Debian python3-matplotlib) on DIR; off for tests.
  bool plots = true;
};

// Throws ConfigError when DIR holds no scenario results or a file is malformed.
void WriteReport(const std::string& dir, const ReportOptions& options);

}  // namespace markerbench
