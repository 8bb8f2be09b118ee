// markerbench command line (architecture.md, "CLI"). Bad input: message naming the file and
// key, exit status 2.
#include <CLI/CLI.hpp>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "bench/cli/check_command.h"
#include "bench/cli/crlb_command.h"
#include "bench/cli/list_command.h"
#include "bench/cli/marker_sheets.h"
#include "bench/cli/merge_command.h"
#include "bench/cli/render_command.h"
#include "bench/cli/score_command.h"
#include "bench/cli/track_command.h"
#include "bench/cli/tracker_worker_command.h"
#include "bench/io/data_dir.h"
#include "bench/report/report.h"
#include "bench/run/manifest.h"
#include "bench/run/sweep_runner.h"
#include "core/joined.h"
#include "core/marker_spec.h"
#include "core/number_text.h"
#include "core/yaml_reader.h"
#include "trackers/tracker_factory.h"

namespace {

constexpr int kBadInput = 2;

// A number in [lo, hi]; NaN is outside every range (CLI::Range lets it through).
CLI::Validator FiniteRange(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        const std::optional<double> value = markerbench::ParseFiniteNumber(text);
        if (value && *value >= lo && *value <= hi) return "";
        std::ostringstream expected;
        expected << std::setprecision(12) << "expected a number in [" << lo << ", " << hi
                 << "], got '" << text << "'";
        return expected.str();
      },
      "");
}

// --set KEY=VALUE (repeatable) and --trackers a,b: a scenario's overrides (bench/plan/scenario.h).
void AddOverrideOptions(CLI::App* command, markerbench::ScenarioOverrides* overrides) {
  command
      ->add_option("--set",
                   overrides->set,
                   "Change a scenario key for this run: KEY=VALUE, VALUE in YAML "
                   "(render.noise_var=0.05, sweep.values=[1,2], trackers[0].options.x=1); "
                   "repeatable")
      ->allow_extra_args(false);
  command
      ->add_option("--trackers", overrides->trackers, "Run only these of the scenario's trackers")
      ->delimiter(',')
      ->allow_extra_args(false);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace markerbench;
  CLI::App app{"markerbench: synthetic benchmark of fiducial-marker pose tracking"};
  app.require_subcommand(1);
  app.set_version_flag("--version", [] { return VersionText(); });

  CLI::App* list =
      app.add_subcommand("list", "The trackers (options, defaults, markers they read) or markers");
  std::string list_what;
  std::string list_markers_dir = DataDir() + "/scenarios/markers";
  list->add_option("what", list_what, "trackers or markers")
      ->required()
      ->check(CLI::IsMember({"trackers", "markers"}));
  list->add_option("--markers-dir", list_markers_dir, "Folder of marker YAML files");

  CLI::App* render = app.add_subcommand(
      "render", "Render frames with ground truth: from a SCENARIO, or --marker/--camera/--poses");
  std::string scenario;
  int limit = 0;
  ExplicitRenderOptions explicit_options;
  render->add_option("scenario", scenario, "Scenario YAML");
  render->add_option("--out", explicit_options.out_dir, "Output folder")->required();
  render->add_option("--limit", limit, "Render at most N frames of the scenario")
      ->check(CLI::NonNegativeNumber);
  render->add_option("--marker", explicit_options.marker_path, "Marker YAML");
  render->add_option("--camera", explicit_options.camera_path, "Camera YAML (ROS camera_info)");
  render->add_option("--poses", explicit_options.poses_path, "POSES.csv (r11..r33, tx, ty, tz)");
  render
      ->add_option(
          "--noise-var", explicit_options.degradations.noise_var, "imnoise variance on [0, 1]")
      ->check(FiniteRange(0.0, 10.0));
  render
      ->add_option(
          "--blur-sigma", explicit_options.degradations.blur_sigma_px, "Gaussian blur sigma (px)")
      ->check(FiniteRange(0.0, 100.0));
  render
      ->add_option(
          "--gamma", explicit_options.degradations.gamma, "Camera response: v -> v^(1/gamma)")
      ->check(FiniteRange(0.1, 10.0));
  render->add_option("--seed", explicit_options.seed, "Noise seed")
      ->check(FiniteRange(0.0, 2147483647.0));
  render->add_flag("--overwrite",
                   explicit_options.overwrite,
                   "Replace the dataset an earlier render wrote into --out");
  render->add_flag("--float",
                   explicit_options.write_float,
                   "Also write frame_NNNNNN.exr (linear float, after noise and clipping)");
  render->add_flag_callback(
      "--no-crlb",
      [&explicit_options] { explicit_options.crlb = false; },
      "With --poses: leave groundtruth.csv's Cramer-Rao bound empty (it takes about as long "
      "as the render)");

  CLI::App* markers = app.add_subcommand(
      "markers", "Print-ready sheets of markers (PDF, SVG or 300 dpi PNG) with a check bar");
  std::string markers_out;
  std::string markers_dir = DataDir() + "/scenarios/markers";
  std::vector<std::string> marker_files;
  markers->add_option("--out", markers_out, "Output folder")->required();
  markers->add_option("--markers-dir", markers_dir, "Folder of marker YAML files");
  markers->add_option("--marker", marker_files, "Marker YAML files (instead of the folder)");
  SheetOptions sheet_options;
  markers->add_option("--format", sheet_options.format, "pdf (default), svg or png (300 dpi)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, SheetFormat>{
          {"pdf", SheetFormat::kPdf}, {"svg", SheetFormat::kSvg}, {"png", SheetFormat::kPng}}));
  markers->add_option("--paper", sheet_options.paper, "a4 (default), letter or a3")
      ->check(CLI::IsMember(PaperNames()));
  markers->add_flag("--tile",
                    sheet_options.tile,
                    "Split a marker larger than the page over pages (else it is an error)");

  CLI::App* track = app.add_subcommand("track", "Run a tracker on images or video files");
  TrackCommandOptions track_options;
  track
      ->add_option("--tracker",
                   track_options.tracker,
                   "One of " + Joined(TrackerNames()) + " (markerbench list trackers)")
      ->required();
  track
      ->add_option(
          "--marker", track_options.marker_path, "Marker YAML of kind " + Joined(MarkerKindNames()))
      ->required();
  track->add_option("--camera", track_options.camera_path, "Camera YAML")->required();
  track->add_option("--out", track_options.out_csv, "Output CSV (default: standard output)");
  track
      ->add_option("--option",
                   track_options.tracker_options,
                   "A tracker option KEY=VALUE, as in a scenario's options: (repeatable)")
      ->allow_extra_args(false);
  track->add_flag("--sequence",
                  track_options.sequence,
                  "The images are one sequence (tracking mode); else each is independent");
  track->add_option("--tum", track_options.tum_path, "Also write a TUM trajectory to this file");
  track->add_option("--overlay",
                    track_options.overlay_path,
                    "Also write a video (MP4) of the frames with the pose's axes and a cube drawn");
  track->add_option("--gamma",
                    track_options.gamma,
                    "The frames' encoding gamma (sRGB cameras: about 2.2): each value v is taken "
                    "as 255 (v/255)^gamma before tracking; 1 (default): frames are linear");
  track->add_option("inputs", track_options.inputs, "Images or videos")->required();

  CLI::App* sweep = app.add_subcommand(
      "sweep", "Run scenarios' sweeps into DIR/<scenario name>/ (frames.csv, timing.csv)");
  std::vector<std::string> sweep_scenarios;
  SweepOptions sweep_options;
  sweep->add_option("scenarios", sweep_scenarios, "Scenario YAML files")->required();
  sweep->add_option("--out", sweep_options.out_dir, "Output folder")->required();
  sweep->add_option("--threads", sweep_options.threads, "Worker threads (default: all cores)")
      ->check(FiniteRange(1.0, kMaxThreads));
  sweep->add_flag("--resume", sweep_options.resume, "Continue a killed run of the same scenarios");
  sweep->add_flag("--overwrite", sweep_options.overwrite, "Start again over an earlier run");
  sweep->get_option("--resume")->excludes("--overwrite");
  std::string sweep_shard;
  sweep->add_option("--shard", sweep_shard, "Run only shard I of N (I/N, 0 <= I < N); see merge");
  sweep->add_flag("--zstd",
                  sweep_options.compress,
                  "Once complete, write frames.csv.zst and timing.csv.zst instead of plain CSV");
  AddOverrideOptions(sweep, &sweep_options.overrides);
  std::string sweep_trials;
  sweep->add_option("--trials", sweep_trials, "Trials per sweep value (--set trials=N)")
      ->check(FiniteRange(1.0, 1e6));

  CLI::App* merge = app.add_subcommand(
      "merge", "Merge the N shards of sweeps (sweep --shard I/N) into one run folder");
  MergeOptions merge_options;
  merge->add_option("shards", merge_options.shard_dirs, "The shards' --out folders")->required();
  merge->add_option("--out", merge_options.out_dir, "Output folder")->required();
  merge->add_flag("--zstd", merge_options.compress, "Write frames.csv.zst and timing.csv.zst");
  merge->add_flag("--overwrite", merge_options.overwrite, "Replace an earlier merge in --out");

  CLI::App* score = app.add_subcommand(
      "score", "Score a tracker's estimates for a rendered dataset into a run folder");
  ScoreOptions score_options;
  score->add_option("dataset", score_options.dataset_dir, "The folder markerbench render wrote")
      ->required();
  score->add_option("--poses", score_options.estimates_path, "ESTIMATES.csv")->required();
  score->add_option("--tracker", score_options.tracker, "The tracker's name in the run")
      ->required();
  score->add_option("--out", score_options.out_dir, "Run folder (report and check read it)")
      ->required();

  // Started by sweep for each isolated tracker; hidden from --help (an empty group).
  CLI::App* worker = app.add_subcommand("tracker-worker", "")->group("");
  std::string worker_scenario;
  size_t worker_tracker_index = 0;
  worker->add_option("scenario", worker_scenario)->required();
  worker->add_option("--tracker-index", worker_tracker_index)->required();
  std::string worker_fingerprint;
  worker->add_option("--fingerprint", worker_fingerprint)->required();
  ScenarioOverrides worker_overrides;
  AddOverrideOptions(worker, &worker_overrides);

  CLI::App* report =
      app.add_subcommand("report", "summary.csv, report.md and plots from a sweep's DIR");
  std::string report_dir;
  ReportOptions report_options;
  report->add_option("dir", report_dir, "The sweep's output folder")->required();
  report
      ->add_option("--success-fraction",
                   report_options.summary.success_fraction,
                   "Success: position error <= this fraction of the true distance")
      ->check(FiniteRange(0.0, 10.0));
  report->add_flag("!--no-plots", report_options.plots, "Skip scripts/plot_sweep.py");

  CLI::App* crlb = app.add_subcommand(
      "crlb", "The Cramér-Rao bound on the camera pose for a marker, camera and poses");
  CrlbCommandOptions crlb_options;
  std::string crlb_channels = "auto";
  crlb->add_option("--marker", crlb_options.marker_path, "Marker YAML")->required();
  crlb->add_option("--camera", crlb_options.camera_path, "Camera YAML (ROS camera_info)")
      ->required();
  crlb->add_option("--poses", crlb_options.poses_path, "POSES.csv (r11..r33, tx, ty, tz)")
      ->required();
  crlb->add_option("--noise-var", crlb_options.degradations.noise_var, "imnoise variance on [0, 1]")
      ->check(FiniteRange(0.0, 10.0));
  crlb->add_option(
          "--blur-sigma", crlb_options.degradations.blur_sigma_px, "Gaussian blur sigma (px)")
      ->check(FiniteRange(0.0, 100.0));
  crlb->add_option("--gamma", crlb_options.degradations.gamma, "Camera response: v -> v^(1/gamma)")
      ->check(FiniteRange(0.1, 10.0));
  crlb->add_option("--channels", crlb_channels, "auto (RGB for coloured markers), grey or rgb")
      ->check(CLI::IsMember({"auto", "grey", "rgb"}));
  crlb->add_option("--out", crlb_options.out_csv, "Output CSV (default: standard output)");

  CLI::App* check = app.add_subcommand(
      "check", "Regression gate: compare a sweep's RUN_DIR with an accepted --reference");
  CheckCommandOptions check_options;
  CheckOptions& gate = check_options.check;
  check->add_option("run", check_options.run_dir, "The sweep's output folder")->required();
  check->add_option("--reference", check_options.reference_dir, "The reference sweep's folder")
      ->required();
  check->add_option("--alpha", gate.alpha, "Family-wise error rate (Holm)")
      ->check(FiniteRange(1e-12, 0.5));
  check
      ->add_option("--min-effect-error",
                   gate.min_error_change,
                   "A regression's median error ratio must exceed 1 + this")
      ->check(FiniteRange(0.0, 100.0));
  check
      ->add_option("--min-effect-success",
                   gate.min_success_change,
                   "A regression's success rate must drop by at least this (fraction)")
      ->check(FiniteRange(0.0, 1.0));
  check
      ->add_option("--success-fraction",
                   gate.success_fraction,
                   "Success: position error <= this fraction of the true distance")
      ->check(FiniteRange(0.0, 10.0));
  check->add_option(
      "--speed", gate.speed_tracker, "Also compare times as ratios to this tracker's");
  check
      ->add_option("--speed-tolerance",
                   gate.speed_tolerance,
                   "A speed regression's median time ratio must grow by more than this")
      ->check(FiniteRange(0.0, 100.0));
  check->add_option("--markdown", check_options.markdown_path, "Write a Markdown summary");
  check->add_option("--junit", check_options.junit_path, "Write JUnit XML");
  check->add_flag("--bless", check_options.bless, "Accept the run as the new reference");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help is exit 0; every usage error (unknown flag, missing argument, a bad number) is
    // bad input.
    return app.exit(e) == 0 ? 0 : kBadInput;
  }
  try {
    if (list->parsed()) {
      ListCommand(list_what, list_markers_dir, std::cout);
    } else if (render->parsed()) {
      const bool explicit_form = !explicit_options.marker_path.empty() ||
                                 !explicit_options.camera_path.empty() ||
                                 !explicit_options.poses_path.empty();
      if (explicit_form == !scenario.empty()) {
        std::cerr << "render: give either SCENARIO or all of --marker, --camera and --poses\n";
        return kBadInput;
      }
      if (explicit_form) {
        if (explicit_options.marker_path.empty() || explicit_options.camera_path.empty() ||
            explicit_options.poses_path.empty()) {
          std::cerr << "render: the explicit form needs --marker, --camera and --poses\n";
          return kBadInput;
        }
        if (render->count("--limit") > 0) {
          std::cerr << "render: --limit applies to a scenario's frames; with --poses, render "
                       "fewer poses\n";
          return kBadInput;
        }
        RenderPoses(explicit_options);
      } else {
        for (const char* option :
             {"--noise-var", "--blur-sigma", "--gamma", "--seed", "--no-crlb"}) {
          if (render->count(option) > 0) {
            std::cerr << "render: " << option
                      << " is for the explicit form; a scenario sets its noise, blur, response, "
                         "seed and bound in its render:, seed: and crlb: keys\n";
            return kBadInput;
          }
        }
        RenderScenario(scenario,
                       explicit_options.out_dir,
                       limit,
                       explicit_options.write_float,
                       explicit_options.overwrite);
      }
    } else if (track->parsed()) {
      RunTrackCommand(track_options);
    } else if (sweep->parsed()) {
      if (!sweep_shard.empty()) sweep_options.shard = ParseShard(sweep_shard);
      if (!sweep_trials.empty()) sweep_options.overrides.set.push_back("trials=" + sweep_trials);
      RunSweeps(sweep_scenarios, sweep_options);
    } else if (merge->parsed()) {
      MergeShards(merge_options, std::cerr);
    } else if (score->parsed()) {
      RunScoreCommand(score_options, std::cerr);
    } else if (worker->parsed()) {
      return RunTrackerWorker(
          worker_scenario, worker_overrides, worker_tracker_index, worker_fingerprint);
    } else if (report->parsed()) {
      WriteReport(report_dir, report_options);
    } else if (check->parsed()) {
      return RunCheckCommand(check_options, std::cout);
    } else if (crlb->parsed()) {
      crlb_options.channels = crlb_channels == "grey"  ? Channels::kGrey
                              : crlb_channels == "rgb" ? Channels::kRgb
                                                       : Channels::kAuto;
      std::cerr << RunCrlbCommand(crlb_options) << '\n';
    } else if (markers->parsed()) {
      if (marker_files.empty()) marker_files = MarkerFilesIn(markers_dir);
      for (const std::string& path : WriteMarkerSheets(marker_files, markers_out, sheet_options)) {
        std::cout << path << '\n';
      }
    }
  } catch (const ConfigError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
