#include "bench/report/check_output.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "core/number_text.h"

namespace markerbench {
namespace {

constexpr size_t kListedRows = 10;  // unpaired rows shown before "and N more"

std::string Printf(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string ValueText(const CellCheck& c) {
  if (c.sweep_parameter.empty()) return "all";
  return c.sweep_parameter + "=" + NumberText(c.sweep_value) + (c.grid.empty() ? "" : ";" + c.grid);
}

std::string Amount(const MetricCheck& m, double value) {
  if (std::isnan(value)) return "-";
  if (m.metric == "success") return Printf("%.1f%%", 100.0 * value);
  if (m.unit == "m") return Printf("%.3g mm", 1e3 * value);
  if (m.unit == "deg") return Printf("%.3g°", value);
  return Printf("%.3g", value);
}

// Whether the change goes towards worse: fewer successes, larger errors or time ratios.
bool Worse(const MetricCheck& m) {
  return m.metric == "success" ? m.now < m.reference : m.now > m.reference;
}

std::string Change(const MetricCheck& m) {
  if (std::isnan(m.reference) || std::isnan(m.now)) return "-";
  if (m.metric == "success") return Printf("%+.1f pts", 100.0 * (m.now - m.reference));
  return m.reference > 0.0 ? Printf("×%.2f", m.now / m.reference) : "-";
}

std::string PText(double p) { return p < 1e-4 ? Printf("%.1e", p) : Printf("%.4f", p); }

using Row = std::vector<std::string>;

const Row kHeader = {"scenario",
                     "tracker",
                     "marker",
                     "value",
                     "metric",
                     "reference",
                     "now",
                     "change",
                     "p (Holm)",
                     "verdict"};

// The rows of every changed metric, regressions first.
std::vector<Row> ChangedRows(const CheckReport& report) {
  std::vector<std::pair<int, Row>> rows;
  const auto add = [&](const std::vector<CellCheck>& cells) {
    for (const CellCheck& c : cells) {
      const Row head = {c.scenario, c.tracker, c.marker, ValueText(c)};
      if (c.vanished || c.added) {
        Row row = head;
        row.insert(row.end(),
                   {"cell",
                    c.vanished ? "present" : "-",
                    c.vanished ? "-" : "present",
                    "-",
                    "-",
                    c.vanished ? "REGRESSED (vanished)" : "new"});
        rows.push_back({c.vanished ? 0 : 2, row});
        continue;
      }
      for (const MetricCheck& m : c.metrics) {
        if (m.verdict == Verdict::kSame) continue;
        Row row = head;
        const std::string metric = m.metric + (m.metric == "time ratio" ? " " + m.unit : "");
        row.insert(row.end(),
                   {metric,
                    Amount(m, m.reference),
                    Amount(m, m.now),
                    Change(m),
                    PText(Worse(m) ? m.p_worse : m.p_better),
                    ToString(m.verdict)});
        rows.push_back({m.verdict == Verdict::kRegressed ? 0 : 1, row});
      }
    }
  };
  add(report.cells);
  add(report.speed);
  std::stable_sort(
      rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Row> sorted;
  for (auto& [rank, row] : rows) sorted.push_back(std::move(row));
  return sorted;
}

std::string UnpairedText(const std::vector<std::string>& rows, const std::string& side) {
  if (rows.empty()) return "";
  std::string text = std::to_string(rows.size()) + " rows only in the " + side + ":\n";
  for (size_t i = 0; i < rows.size() && i < kListedRows; ++i) text += "  " + rows[i] + "\n";
  if (rows.size() > kListedRows) {
    text += "  and " + std::to_string(rows.size() - kListedRows) + " more\n";
  }
  return text;
}

// Display width of UTF-8 text (° and × are one column each).
size_t Width(const std::string& text) {
  return static_cast<size_t>(std::count_if(text.begin(), text.end(), [](char ch) {
    return (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
  }));
}

std::string XmlEscaped(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

// What a regressed cell's failure says: each regressed metric, or the vanished cell.
std::string FailureText(const CellCheck& c) {
  if (c.vanished) return "the cell vanished: the reference has it, the run has no frame of it";
  std::string text;
  for (const MetricCheck& m : c.metrics) {
    if (m.verdict != Verdict::kRegressed) continue;
    if (!text.empty()) text += "; ";
    text += m.metric + " " + Amount(m, m.reference) + " -> " + Amount(m, m.now) + " (" + Change(m) +
            ", p = " + PText(m.p_worse) + ", n = " + std::to_string(m.n) + ")";
  }
  return text;
}

}  // namespace

std::string CheckHeadline(const CheckReport& report) {
  std::map<Verdict, int> count;
  for (const CellCheck& c : report.cells) ++count[c.Overall()];
  for (const CellCheck& c : report.speed) ++count[c.Overall()];
  int added = 0;
  for (const CellCheck& c : report.cells) added += c.added;
  return std::string(report.Regressed() ? "REGRESSION" : "no regression") + ": " +
         std::to_string(report.cells.size() + report.speed.size()) + " cells, " +
         std::to_string(count[Verdict::kRegressed]) + " regressed, " +
         std::to_string(count[Verdict::kImproved]) + " improved, " +
         std::to_string(count[Verdict::kWithinTolerance]) + " changed within tolerance, " +
         std::to_string(count[Verdict::kSame] - added) + " the same, " + std::to_string(added) +
         " new; " + std::to_string(report.reference_only.size()) + " rows only in the reference, " +
         std::to_string(report.run_only.size()) + " only in the run\n";
}

std::string CheckTable(const CheckReport& report) {
  std::string text = CheckHeadline(report);
  const std::vector<Row> rows = ChangedRows(report);
  if (!rows.empty()) {
    std::vector<size_t> widths(kHeader.size());
    for (size_t i = 0; i < kHeader.size(); ++i) widths[i] = Width(kHeader[i]);
    for (const Row& row : rows) {
      for (size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], Width(row[i]));
    }
    const auto line = [&](const Row& row) {
      std::string out;
      for (size_t i = 0; i < row.size(); ++i) {
        out += row[i] + std::string(widths[i] - Width(row[i]) + (i + 1 < row.size() ? 2 : 0), ' ');
      }
      while (!out.empty() && out.back() == ' ') out.pop_back();
      return out + "\n";
    };
    text += "\n" + line(kHeader);
    for (const Row& row : rows) text += line(row);
  }
  return text + UnpairedText(report.reference_only, "reference") +
         UnpairedText(report.run_only, "run");
}

std::string CheckMarkdown(const CheckReport& report, const CheckOptions& options) {
  std::string md = std::string("### markerbench check: ") + (report.Regressed() ? "❌ " : "✅ ") +
                   CheckHeadline(report) + "\n";
  md +=
      "One-sided paired tests per cell (exact McNemar on success, Wilcoxon signed-rank on "
      "the log error ratios of frames that succeed in both), Holm-corrected at α = " +
      NumberText(options.alpha) + "; a regression also needs a median error ratio above " +
      NumberText(1.0 + options.min_error_change) + " or a success drop of at least " +
      NumberText(100.0 * options.min_success_change) + " points.\n\n";
  if (!report.run_build.empty()) {
    md += "The run was built from " + report.run_build + "; the reference, from " +
          report.reference_build + ".\n\n";
  }
  const std::vector<Row> rows = ChangedRows(report);
  if (!rows.empty()) {
    const auto line = [](const Row& row) {
      std::string out = "|";
      for (const std::string& cell : row) out += " " + cell + " |";
      return out + "\n";
    };
    md += line(kHeader) + "|";
    for (size_t i = 0; i < kHeader.size(); ++i) md += "---|";
    md += "\n";
    for (const Row& row : rows) md += line(row);
    md += "\n";
  }
  const std::string unpaired =
      UnpairedText(report.reference_only, "reference") + UnpairedText(report.run_only, "run");
  if (!unpaired.empty()) md += "```\n" + unpaired + "```\n";
  return md;
}

std::string CheckJunit(const CheckReport& report) {
  std::map<std::string, std::vector<const CellCheck*>> suites;
  std::vector<std::string> order;
  const auto add = [&](const std::string& suite, const CellCheck& c) {
    if (!suites.count(suite)) order.push_back(suite);
    suites[suite].push_back(&c);
  };
  for (const CellCheck& c : report.cells) add(c.scenario, c);
  for (const CellCheck& c : report.speed) add("speed", c);
  int total = 0, failures = 0;
  std::string body;
  for (const std::string& name : order) {
    int suite_failures = 0, skipped = 0;
    std::string cases;
    for (const CellCheck* c : suites[name]) {
      const std::string case_name = c->metrics.size() == 1 && c->sweep_parameter.empty()
                                        ? c->metrics.front().metric
                                        : ValueText(*c);
      cases += "    <testcase classname=\"" +
               XmlEscaped(c->scenario + "." + c->tracker + "." + c->marker) + "\" name=\"" +
               XmlEscaped(case_name) + "\" time=\"0\"";
      if (c->Overall() == Verdict::kRegressed) {
        const std::string failure = FailureText(*c);
        cases += ">\n      <failure message=\"" + XmlEscaped(failure) + "\" type=\"regression\">" +
                 XmlEscaped(failure) + "</failure>\n    </testcase>\n";
        ++suite_failures;
      } else if (c->added) {
        cases +=
            ">\n      <skipped message=\"new cell: not in the reference\"/>\n    </testcase>\n";
        ++skipped;
      } else {
        cases += "/>\n";
      }
    }
    const int tests = static_cast<int>(suites[name].size());
    body += "  <testsuite name=\"" + XmlEscaped(name) + "\" tests=\"" + std::to_string(tests) +
            "\" failures=\"" + std::to_string(suite_failures) + "\" errors=\"0\" skipped=\"" +
            std::to_string(skipped) + "\" time=\"0\">\n" + cases + "  </testsuite>\n";
    total += tests;
    failures += suite_failures;
  }
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"markerbench check\" "
         "tests=\"" +
         std::to_string(total) + "\" failures=\"" + std::to_string(failures) +
         "\" errors=\"0\" time=\"0\">\n" + body + "</testsuites>\n";
}

}  // namespace markerbench
