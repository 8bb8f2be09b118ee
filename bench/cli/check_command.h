// markerbench check RUN_DIR --reference REF_DIR: the regression gate (regression_check.h)
// with its outputs, and --bless to accept the run as the new reference.
#pragma once

#include <ostream>
#include <string>

#include "bench/report/regression_check.h"

namespace markerbench {

struct CheckCommandOptions {
  std::string run_dir;
  std::string reference_dir;
  std::string markdown_path;  // empty: none
  std::string junit_path;     // empty: none
  // After printing the differences, copy the run's frames.csv, timing.csv and run.json (per
  // scenario) and manifest.json into the reference, which then holds exactly the run's
  // scenarios. A ground truth that differs from the reference's is then no error.
  bool bless = false;
  CheckOptions check;
};

// Prints the table to `out` and returns the exit status: 1 when a cell regressed (and the run
// was not blessed), else 0. Bad input throws ConfigError (exit 2).
int RunCheckCommand(const CheckCommandOptions& options, std::ostream& out);

}  // namespace markerbench
