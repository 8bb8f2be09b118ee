// What markerbench check prints: a terminal table and a Markdown comment of every cell that
// changed, and JUnit XML with one test case per cell for CI systems to show natively.
#pragma once

#include <string>

#include "bench/report/regression_check.h"

namespace markerbench {

// One line: how many cells regressed, improved, changed within tolerance or stayed the same,
// and the rows found on one side only.
std::string CheckHeadline(const CheckReport& report);

// The headline, a fixed-width table of the changed metrics (scenario, tracker, marker, value,
// metric, reference, now, change, Holm-adjusted p, verdict), and the unpaired rows.
std::string CheckTable(const CheckReport& report);

// The same as a Markdown section for a pull-request comment.
std::string CheckMarkdown(const CheckReport& report, const CheckOptions& options);

// JUnit XML: a testsuite per scenario (and one for speed), a testcase per cell, a <failure>
// per regressed cell.
std::string CheckJunit(const CheckReport& report);

}  // namespace markerbench
