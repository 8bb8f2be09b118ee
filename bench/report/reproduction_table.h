// The reproduction table of experiments.md: each claim of the paper beside our measurement.
#pragma once

#include <string>
#include <vector>

#include "bench/report/summary.h"

namespace markerbench {

struct ClaimResult {
  std::string claim;
  std::string paper;
  std::string original;  // the original system measured on these renders, or "-"
  std::string measured;  // "not run: ..." when the scenario or tracker is missing
  std::string verdict;   // agrees, earlier, later, differs, faster, slower or "-"
  std::string improved;  // the tracker's `-improved` variant, or "-"
};

// Checks every claim against `summary` (scenarios fig6_noise, fig7_blur, fig8_distance, as
// shipped in scenarios/paper/; times over those scenarios only). Empty when the summary holds
// none of them: a user's own scenarios make no claims of the paper.
std::vector<ClaimResult> ReproduceClaims(const std::vector<SummaryRow>& summary,
                                         const SummaryOptions& options);

// The table as Markdown.
std::string ReproductionTableMarkdown(const std::vector<ClaimResult>& results);

}  // namespace markerbench
