#include "bench/report/report.h"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/io/atomic_file.h"
#include "bench/io/data_dir.h"
#include "bench/io/progress.h"
#include "bench/report/report_html.h"
#include "bench/report/reproduction_table.h"
#include "bench/report/sequence_report.h"
#include "bench/run/manifest.h"
#include "bench/run/run_results.h"
#include "core/number_text.h"
#include "core/yaml_reader.h"

namespace fs = std::filesystem;

extern char** environ;

namespace markerbench {
namespace {

std::string Percent(double rate) { return FormattedOrDash(100.0 * rate, "%.0f%%"); }

// "31–83%": a rate's interval.
std::string PercentRange(const Interval& ci) {
  return FormattedOrDash(100.0 * ci.lo, "%.0f") + "–" + FormattedOrDash(100.0 * ci.hi, "%.0f%%");
}

// Three significant digits for tables (1.42, 0.0812, 108), whole numbers from 1000 on.
std::string Significant(double value) {
  return FormattedOrDash(value, std::fabs(value) >= 1000.0 ? "%.0f" : "%.3g");
}

// " (1.2–3.4)": a median error's interval in mm; nothing when the sample is too small.
// " (lo–hi)" of an interval times `scale` (1e3: metres to millimetres), or nothing.
std::string ScaledRange(const Interval& ci, double scale) {
  if (std::isnan(ci.lo)) return "";
  return " (" + Significant(scale * ci.lo) + "–" + Significant(scale * ci.hi) + ")";
}

std::string ScenarioSection(const std::string& scenario,
                            const std::vector<SummaryRow>& summary,
                            const nlohmann::json& entry,
                            const SummaryOptions& options,
                            const std::string& dir) {
  std::string parameter;
  bool grid = false;
  for (const SummaryRow& r : summary) {
    if (r.scenario != scenario) continue;
    parameter = r.sweep_parameter;
    grid = grid || !r.grid.empty();
  }
  std::string md = "## " + scenario + " (" + (grid ? "grid" : "sweep") + " of `" + parameter + "`" +
                   (grid ? " and the grid's other axes" : "") + ")\n\n";
  if (entry.contains("file")) {
    md += "Scenario `" + entry["file"].get<std::string>() + "`, " +
          std::to_string(entry.value("trials", 0)) + " trials per value, seed " +
          std::to_string(entry.value("seed", 0)) + ".";
    if (entry.contains("wall_s")) {
      md += " Ran " + std::to_string(entry.value("frames", 0)) + " frames in " +
            DurationText(entry["wall_s"].get<double>()) + " (" +
            FormattedOrDash(entry["frames_per_s"].get<double>(), "%.1f") + " frames/s, " +
            std::to_string(entry.value("threads", 0)) + " threads).";
    }
    md += "\n\n";
  }
  if (fs::exists(dir + "/" + scenario + ".png")) {
    md += "![" + scenario + ": error and success rate](" + scenario + ".png)\n\n";
  }
  if (fs::exists(dir + "/" + scenario + "_rotation_time.png")) {
    md += "![" + scenario + ": rotation error and time per frame](" + scenario +
          "_rotation_time.png)\n\n";
  }
  if (fs::exists(dir + "/" + scenario + "_heatmap.png")) {
    md += "![" + scenario + ": success rate and median error over the grid](" + scenario +
          "_heatmap.png)\n\n";
  }
  if (fs::exists(dir + "/" + scenario + "_examples.png")) {
    md += "![" + scenario + ": example images](" + scenario + "_examples.png)\n\n";
  }
  md += "Breakdown (first value with success rate below " + Percent(options.breakdown_rate) +
        "):\n\n| tracker | marker | " + (grid ? "grid | " : "") + "breakdown " + parameter +
        " |\n|---|---|" + (grid ? "---|" : "") + "---|\n";
  for (const SeriesName& series : SeriesNames(summary, scenario)) {
    const std::optional<double> b = BreakdownValue(
        SeriesOf(summary, scenario, series.tracker, series.marker, series.grid), options);
    md += "| " + series.tracker + " | " + series.marker + " | " +
          (grid ? series.grid + " | " : "") + (b ? FormattedOrDash(*b, "%g") : "none") + " |\n";
  }
  md += "\nSuccess and median error with their 95 % intervals (Wilson; order statistics).\n";
  md += "\n| " + parameter + (grid ? " | grid" : "") +
        " | tracker | marker | n | size (px) | detected | success" +
        " | median pos. err (mm) | mean (mm) | p90 (mm) | median rot. err (°)" +
        " | oracle median (mm) | oracle success | flips | median ms | bound (mm) | × bound" +
        " | rot. × bound | success at bound |\n" + (grid ? "|---" : "") +
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SummaryRow& r : summary) {
    if (r.scenario != scenario) continue;
    md += "| " + FormattedOrDash(r.sweep_value, "%g") + (grid ? " | " + r.grid : "") + " | " +
          r.tracker + " | " + r.marker + " | " + std::to_string(r.n) + " | " +
          Significant(r.apparent_size_median_px) + " | " + Percent(r.detection_rate) + " | " +
          Percent(r.success_rate) + " (" + PercentRange(r.success_rate_ci) + ") | " +
          Significant(1e3 * r.position_error_median_m) +
          ScaledRange(r.position_error_median_ci_m, 1e3) + " | " +
          Significant(1e3 * r.position_error_mean_m) + " | " +
          Significant(1e3 * r.position_error_p90_m) + " | " +
          Significant(r.rotation_error_median_deg) + " | " +
          Significant(1e3 * r.best_position_error_median_m) + " | " + Percent(r.best_success_rate) +
          " (" + PercentRange(r.best_success_rate_ci) + ") | " + Percent(r.flip_rate) + " | " +
          Significant(r.time_median_ms) + " | " + Significant(1e3 * r.crlb_position_median_m) +
          " | " + Significant(r.efficiency) + " | " + Significant(r.rotation_efficiency) + " | " +
          Percent(r.success_at_bound) + " |\n";
  }
  return md + "\n";
}

// The builds of a scenario's manifest entry other than `built` (BuildIdentity()'s keys): a run
// resumed by another build, a shard built apart, or a scenario run into the folder by another.
std::vector<std::string> OtherBuilds(const nlohmann::json& entry, const nlohmann::json& built) {
  std::vector<nlohmann::json> builds;
  const auto add = [&](const nlohmann::json& list) {
    if (list.is_array()) builds.insert(builds.end(), list.begin(), list.end());
  };
  add(entry.value("builds", nlohmann::json()));
  for (const nlohmann::json& shard : entry.value("shards", nlohmann::json::array())) {
    if (shard.is_object()) add(shard.value("builds", nlohmann::json()));
  }
  std::vector<std::string> others;
  for (const nlohmann::json& build : builds) {
    if (!build.is_object()) continue;
    const std::string text = BuildText(build);
    if (!SameBuild(build, built) && std::find(others.begin(), others.end(), text) == others.end()) {
      others.push_back(text);
    }
  }
  return others;
}

std::string EnvironmentSection(const nlohmann::json& manifest) {
  if (!manifest.contains("environment")) return "";
  const nlohmann::json& env = manifest["environment"];
  std::string md = "Built from " + BuildText(env) + ", " + env.value("compiler", std::string("?")) +
                   ", " + env.value("build_type", std::string("?")) + "; run on " +
                   env.value("cpu_model", std::string("?")) + " with " +
                   std::to_string(env.value("threads", 0)) + " threads";
  double wall_s = 0.0, frames = 0.0;
  std::string mixed;
  const nlohmann::json scenarios = manifest.value("scenarios", nlohmann::json::object());
  for (const auto& [name, entry] : scenarios.items()) {
    wall_s += entry.value("wall_s", 0.0);
    frames += entry.value("frames", 0.0);
    const std::vector<std::string> others = OtherBuilds(entry, env);
    if (others.empty()) continue;
    mixed += "**Rows of `" + name + "` were also written by another build:** ";
    for (size_t i = 0; i < others.size(); ++i) mixed += (i ? "; " : "") + others[i];
    mixed += " (its manifest entry's `builds` says which frames).\n\n";
  }
  if (wall_s > 0.0) {
    md += ": " + FormattedOrDash(frames, "%.0f") + " frames in " + DurationText(wall_s) + " (" +
          FormattedOrDash(frames / wall_s, "%.1f") + " frames/s)";
  }
  return md + ". Details: `manifest.json`.\n\n" + mixed;
}

// A sequence scenario's figures over its videos (bench/report/sequence_report.h).
std::string SequencesSection(const std::vector<SequenceSummaryRow>& rows, const std::string& dir) {
  if (rows.empty()) return "";
  const std::string& scenario = rows.front().scenario;
  std::string md =
      "### " + scenario +
      ": tracking over time\n\n"
      "Per marker and tracker over the sequences (the trials), each run with the tracker's state "
      "kept from frame to frame. `lost`: visible frames without a pose (95 % Wilson interval "
      "with the videos as the sample size: a video's frames are lost in runs, not "
      "independently); "
      "`hidden found`: poses returned while the marker was hidden; ATE: RMS camera-position "
      "error over a sequence (median over the sequences, 95 % interval); RPE: RMS error of the "
      "camera's motion over 1 s; jitter: RMS spread of the position over the still start; "
      "re-acquire: seconds from the marker's reappearance to the next pose (median over the "
      "occlusions; `never` counts those not followed by any pose); ms: median time per frame "
      "over the visible frames, right after a frame with a pose (tracking) and otherwise (full "
      "detection: the first frame, after a loss or an occlusion), the median over the videos "
      "with its 95 % interval. TUM files for evo: "
      "`" +
      scenario + "/tum/`; per sequence: `" + scenario + "/sequences.csv`.\n\n";
  if (fs::exists(dir + "/" + scenario + "_error_time.png")) {
    md += "![" + scenario + ": error against time](" + scenario + "_error_time.png)\n\n";
  }
  md +=
      "| value | marker | tracker | sequences | lost | hidden found | ATE (mm) | RPE (mm) | "
      "RPE (°) | jitter (mm) | re-acquire (s) | never | ms tracking | ms detection |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SequenceSummaryRow& r : rows) {
    const double lost = r.visible > 0 ? static_cast<double>(r.lost) / r.visible : NAN;
    md += "| " + FormattedOrDash(r.sweep_value, "%g") + (r.grid.empty() ? "" : " " + r.grid) +
          " | " + r.marker + " | " + r.tracker + " | " + std::to_string(r.sequences) + " | " +
          Percent(lost) + " (" + PercentRange(r.lost_rate_ci) + ") | " +
          std::to_string(r.found_hidden) + " | " + Significant(1e3 * r.ate_m) +
          ScaledRange(r.ate_ci_m, 1e3) + " | " + Significant(1e3 * r.rpe_m) + " | " +
          Significant(r.rpe_deg) + " | " + Significant(1e3 * r.jitter_m) + " | " +
          Significant(r.reacquire_median_s) + " | " +
          (r.occlusions > 0 ? std::to_string(r.never_reacquired) : "-") + " | " +
          Significant(r.tracking_ms) + ScaledRange(r.tracking_ci_ms, 1.0) + " | " +
          Significant(r.detection_ms) + ScaledRange(r.detection_ci_ms, 1.0) + " |\n";
  }
  return md + "\n";
}

void RunPlots(const std::string& dir) {
  const std::string script = DataFile("scripts/plot_sweep.py");
  // Debian's interpreter has python3-matplotlib; another python3 on PATH may not.
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  // An argument vector, never a shell: a folder name is data, whatever its characters.
  std::vector<std::string> args = {python, script, dir};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  if (const int error = ::posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ)) {
    throw std::runtime_error("plotting failed: cannot start " + python + ": " +
                             std::strerror(error));
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("plotting failed: " + python + " " + script + " " + dir);
  }
}

}  // namespace

void WriteReport(const std::string& dir, const ReportOptions& options) {
  // Streamed: memory grows with a sweep cell, not with frames.csv (results/speed.md).
  const std::vector<std::string> folders = ScenarioFolders(dir);
  nlohmann::json manifest = ReadManifest(dir + "/manifest.json");
  const auto entry_of = [&](const std::string& folder) {
    const std::string name = fs::path(folder).filename().string();
    return manifest.contains("scenarios") && manifest["scenarios"].contains(name)
               ? manifest["scenarios"][name]
               : nlohmann::json::object();
  };
  SummaryBuilder builder(options.summary);
  std::map<std::string, std::vector<SequenceSummaryRow>> sequences;  // per scenario folder
  std::vector<SequenceSummaryRow> all_sequences;
  for (const std::string& folder : folders) {
    const nlohmann::json entry = entry_of(folder);
    std::optional<SequenceResults> sequence_results;
    if (entry.contains("trajectory")) sequence_results.emplace(folder, entry);
    ScenarioRowReader reader(folder);
    FrameRow row;
    double time_ms = NAN;
    while (reader.Next(&row, &time_ms)) {
      try {
        const bool visible = !sequence_results || sequence_results->Add(row, time_ms);
        if (visible) builder.Add(row, time_ms);
      } catch (const ConfigError& e) {
        throw ConfigError(reader.location() + ": " + e.what());
      }
    }
    if (!sequence_results) continue;
    sequences[folder] = sequence_results->Finish();
    all_sequences.insert(all_sequences.end(), sequences[folder].begin(), sequences[folder].end());
  }
  const std::vector<SummaryRow> summary = builder.Finish();
  WriteFileAtomically(dir + "/summary.csv", SummaryCsv(summary));
  WriteFileAtomically(dir + "/breakdowns.csv", BreakdownsCsv(summary, options.summary));
  if (!all_sequences.empty()) {
    WriteFileAtomically(dir + "/sequence_summary.csv", SequenceSummaryCsv(all_sequences));
  }
  manifest["report"] = {{"success_position_fraction_of_distance", options.summary.success_fraction},
                        {"breakdown_success_rate", options.summary.breakdown_rate}};
  WriteManifest(dir + "/manifest.json", manifest);
  if (options.plots) RunPlots(dir);

  std::string md = "# markerbench report\n\n";
  md += EnvironmentSection(manifest);
  md += "Success: a pose whose camera-centre error is at most " +
        Percent(options.summary.success_fraction) +
        " of the true distance. Breakdown: the first sweep value whose success rate is below " +
        Percent(options.summary.breakdown_rate) +
        ". Errors are over the frames with a pose; `oracle` takes the hypothesis nearest the "
        "truth in rotation; `flips` counts first hypotheses more than 30° off while another "
        "is within 5°. `bound` is the physical limit: the median over the cell's frames of the "
        "camera-centre error that an efficient estimator would have, from each frame's "
        "Cramér-Rao bound (noise, blur, pixel size, marker and pose); `× bound` is the median "
        "error divided by the median bound over the same frames (1 is the limit; a better "
        "algorithm cannot go below it, only a bigger marker, a closer camera or less noise "
        "can); `success at bound` is the success rate such an estimator would have on the "
        "same frames (its error Gaussian with the bound's covariance; a ceiling for unbiased "
        "trackers, reached only by efficient ones). Both are local: they take the estimate to "
        "be in the true pose's basin. Far away or near face-on a planar marker looks nearly "
        "the same from its tilt mirrored about the line of sight (the planar two-fold "
        "ambiguity); frames whose likelier fit is that mirror fail where the bound foresees "
        "success, so there the limit is below `success at bound`.\n\n";
  const std::vector<ClaimResult> claims = ReproduceClaims(summary, options.summary);
  if (!claims.empty()) {
    md += "## The paper's claims beside ours\n\n" + ReproductionTableMarkdown(claims) + "\n";
  }
  for (const std::string& folder : folders) {
    const std::string name = fs::path(folder).filename().string();
    md += ScenarioSection(name, summary, entry_of(folder), options.summary, dir);
    md += SequencesSection(sequences[folder], dir);
  }
  WriteFileAtomically(dir + "/report.md", md);
  WriteFileAtomically(dir + "/report.html", ReportHtml(md, dir));
}

}  // namespace markerbench
