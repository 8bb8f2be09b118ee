// markerbench sweep (and check) as users run them, as a subprocess: determinism across thread
// counts and runs, exit status 2 with a located message for bad input, and the regression gate
// on real sweeps. A run that is killed or shares its folder: sweep_resume_cli_test.cc; users'
// own trackers in a sweep: external_tracker_cli_test.cc.

#include "bench/cli/sweep_cli_test.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "bench/run/frames_csv.h"
#include "bench/run/manifest.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

TEST_F(SweepCliTest, FramesCsvIsByteIdenticalAcrossThreadCountsAndRuns) {
  const std::string scenario = Scenario("det", 4);
  const std::string one = (work_ / "one").string(), two = (work_ / "two").string(),
                    again = (work_ / "again").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", one, "--threads", "1"}).status, 0);
  ASSERT_EQ(Run({"sweep", scenario, "--out", two, "--threads", "2"}).status, 0);
  ASSERT_EQ(Run({"sweep", scenario, "--out", again, "--threads", "2"}).status, 0);
  const std::string frames = Read(one + "/det/frames.csv");
  // Header, then 3 values x 4 trials x (apriltag: 2 trackers, aruco: 1).
  EXPECT_EQ(Lines(one + "/det/frames.csv"), 1u + 3 * 4 * 3);
  EXPECT_EQ(Lines(one + "/det/timing.csv"), 1u + 3 * 4 * 3);
  EXPECT_EQ(Read(two + "/det/frames.csv"), frames);
  EXPECT_EQ(Read(again + "/det/frames.csv"), frames);
  EXPECT_EQ(Read(two + "/det/examples/aruco.png"), Read(one + "/det/examples/aruco.png"));
}

// The columns of frames.csv, by name, for every data row.
std::vector<std::map<std::string, std::string>> FramesTable(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream names(line);
  for (std::string name; std::getline(names, name, ',');) header.push_back(name);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size(); ++i) std::getline(fields, row[header[i]], ',');
    rows.push_back(row);
  }
  return rows;
}

// A sequence scenario (issue 22): one job per (trial, marker) video, its frames in order; the
// same bytes for any thread count and for shards merged; the marker's hidden frames are not
// found and have no bound; with exposure_s the frames are motion-blurred renders.
TEST_F(SweepCliTest, SequencesAreReproducibleAndTheirOcclusionsHideTheMarker) {
  const std::string scenario = WriteTestFile(
      "seq.yaml",
      "name: seq\ncamera: " + kRoot + "/scenarios/cameras/default.yaml\nmarkers:\n  - " + kRoot +
          "/scenarios/markers/circles_a.yaml\n  - " + kRoot +
          "/scenarios/markers/apriltag.yaml\nequal_ink_area_m2: 0.01\ntrackers:\n"
          "  - {name: circle}\n  - {name: apriltag}\n  - {name: counting, exec: [python3, " +
          kRoot +
          "/trackers/external/testdata/counting_tracker.py, counting], markers: [apriltag]}\n"
          "poses: {sampler: look_at, distance_m: 0.7, tilt_deg: [20, 30], max_offset_px: 30}\n"
          "trajectory: {kind: handheld, fps: 10, duration_s: 1.5, static_s: 0.3, exposure_s: 0.02,"
          " readout_s: 0.01, linear_speed_m_s: 0.1, angular_speed_deg_s: 10, occlusions: [[6, "
          "8]]}\n"
          "sweep: {parameter: noise_var, values: [0.01]}\ntrials: 3\nseed: 4\n");
  const std::string one = (work_ / "one").string(), two = (work_ / "two").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", one, "--threads", "1"}).status, 0);
  ASSERT_EQ(Run({"sweep", scenario, "--out", two, "--threads", "2"}).status, 0);
  const std::string frames = Read(one + "/seq/frames.csv");
  EXPECT_EQ(Read(two + "/seq/frames.csv"), frames);
  std::vector<std::string> shards;
  for (const std::string shard : {"0/2", "1/2"}) {
    shards.push_back((work_ / ("shard" + shard.substr(0, 1))).string());
    ASSERT_EQ(Run({"sweep", scenario, "--out", shards.back(), "--shard", shard}).status, 0);
  }
  const std::string merged = (work_ / "merged").string();
  ASSERT_EQ(Run({"merge", shards[0], shards[1], "--out", merged}).status, 0);
  EXPECT_EQ(Read(merged + "/seq/frames.csv"), frames);
  // 3 trials x 15 frames of circles_a (1 tracker) and of apriltag (2), in (trial, marker,
  // frame) order. The counting tracker is reset at each sequence's start only.
  const auto rows = FramesTable(frames);
  ASSERT_EQ(rows.size(), 3u * 15 * 3);
  int found = 0;
  for (const auto& row : rows) {
    const int frame = std::stoi(row.at("frame"));
    const int in_sequence = frame % 15;
    if (row.at("tracker") == "counting") {
      EXPECT_EQ(row.at("message"), "frames " + std::to_string(in_sequence + 1)) << frame;
    } else if (in_sequence >= 6 && in_sequence <= 8) {
      EXPECT_EQ(row.at("status"), "not_detected") << "frame " << frame;
      EXPECT_EQ(row.at("crlb_position_m"), "inf");
    } else {
      found += row.at("status") == "ok";
    }
  }
  EXPECT_GE(found, 3 * 2 * 12 - 2);
  // The report: per sequence and tracker a row, TUM files of the truth (every frame) and of
  // each tracker (its frames with a pose).
  ASSERT_EQ(Run({"report", one, "--no-plots"}).status, 0);
  EXPECT_EQ(Lines(one + "/seq/sequences.csv"), 1u + 3 * 3);
  // summary.csv's sample is the frames where the marker shows: 3 videos x (15 - 3 hidden).
  EXPECT_THAT(Read(one + "/summary.csv"), HasSubstr("seq,noise_var,0.01,,circle,circles_a,36,"));
  EXPECT_EQ(Lines(one + "/seq/tum/truth/apriltag_noise_var=0.01_t1.tum"), 15u);
  const auto posed = [&](const std::string& marker, const std::string& tracker, int trial) {
    size_t n = 0;
    for (const auto& row : rows) {
      const int frame = std::stoi(row.at("frame"));
      n += row.at("marker") == marker && row.at("tracker") == tracker && frame / 30 == trial &&
           row.at("status") == "ok";
    }
    return n;
  };
  EXPECT_EQ(Lines(one + "/seq/tum/circle/circles_a_noise_var=0.01_t2.tum"),
            posed("circles_a", "circle", 2));
  EXPECT_EQ(Lines(one + "/seq/tum/counting/apriltag_noise_var=0.01_t0.tum"), 0u);
  EXPECT_THAT(Read(one + "/report.md"), HasSubstr("### seq: tracking over time"));
  // Trial 0 of each marker is also a video with the trackers' poses drawn.
  cv::VideoCapture video(one + "/seq/examples/apriltag.mp4");
  ASSERT_TRUE(video.isOpened());
  int video_frames = 0;
  for (cv::Mat image; video.read(image); ++video_frames) {
    EXPECT_EQ(image.cols, 640);
    EXPECT_EQ(image.rows, 480);
  }
  EXPECT_EQ(video_frames, 15);
  EXPECT_FALSE(fs::exists(one + "/seq/examples/apriltag.mp4.part.mp4"));
  const nlohmann::json manifest = ReadManifest(one + "/manifest.json");
  EXPECT_EQ(manifest["scenarios"]["seq"]["trajectory"]["frames"], 15);
  // `render` writes each frame's place in its video: the frame, the truth's time (the middle
  // row at mid-exposure: k / 10 + (0.02 + 0.01) / 2), the occlusion, exposure and readout.
  const std::string rendered = (work_ / "rendered").string();
  ASSERT_EQ(Run({"render", scenario, "--out", rendered, "--limit", "30"}).status, 0);
  const auto truth = FramesTable(Read(rendered + "/groundtruth.csv"));
  ASSERT_EQ(truth.size(), 30u);  // trial 0's videos: circles_a, then apriltag
  for (const auto& row : truth) {
    const int k = std::stoi(row.at("frame")) % 15;
    EXPECT_EQ(row.at("sequence_frame"), std::to_string(k));
    EXPECT_NEAR(std::stod(row.at("time_s")), k / 10.0 + 0.015, 1e-12);
    EXPECT_EQ(row.at("occluded"), k >= 6 && k <= 8 ? "1" : "0");
    EXPECT_EQ(row.at("exposure_s"), "0.02");
    EXPECT_EQ(row.at("readout_s"), "0.01");
  }
}

TEST_F(SweepCliTest, EveryFrameCarriesItsBoundUnlessTurnedOff) {
  const std::string with = Scenario("bound", 2);
  ASSERT_EQ(Run({"sweep", with, "--out", (work_ / "on").string()}).status, 0);
  const auto rows = FramesTable(Read(work_ / "on/bound/frames.csv"));
  ASSERT_EQ(rows.size(), 3u * 2 * 3);
  std::map<std::string, std::string> bound_of_frame;
  for (const auto& row : rows) {
    const double rms = std::stod(row.at("crlb_position_m"));
    const double median = std::stod(row.at("crlb_position_med_m"));
    // A 0.1 m tag at 0.8 m: a fraction of a millimetre to a few centimetres, depending on noise.
    EXPECT_GT(median, 1e-6);
    EXPECT_LT(median, 0.1);
    EXPECT_LT(median, rms);  // for a 3-D Gaussian, 0.67-0.89 of the RMS
    EXPECT_GT(median, 0.6 * rms);
    EXPECT_GT(std::stod(row.at("crlb_rotation_med_deg")), 0.0);
    // One frame, one bound, whichever tracker the row belongs to.
    auto [it, inserted] = bound_of_frame.try_emplace(row.at("frame"), row.at("crlb_position_m"));
    if (!inserted) {
      EXPECT_EQ(it->second, row.at("crlb_position_m"));
    }
  }
  const std::string without = WriteTestFile("nobound.yaml", Read(with) + "crlb: false\n");
  ASSERT_EQ(Run({"sweep", without, "--out", (work_ / "off").string()}).status, 0);
  for (const auto& row : FramesTable(Read(work_ / "off/bound/frames.csv"))) {
    EXPECT_EQ(row.at("crlb_position_m"), "");
    EXPECT_EQ(row.at("crlb_rotation_med_deg"), "");
  }
}

TEST_F(SweepCliTest, CrlbCommandPrintsTheBoundOfEachPose) {
  const std::string poses = WriteTestFile("poses.csv",
                                          "r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz\n"
                                          "1,0,0,0,-1,0,0,0,-1,0,0,0.6\n"
                                          "1,0,0,0,-1,0,0,0,-1,0,0,1.2\n");
  const std::string marker = kRoot + "/scenarios/markers/apriltag.yaml";
  const std::string camera = kRoot + "/scenarios/cameras/default.yaml";
  const Finished f = Run(
      {"crlb", "--marker", marker, "--camera", camera, "--poses", poses, "--noise-var", "0.02"});
  ASSERT_EQ(f.status, 0) << f.error;
  EXPECT_THAT(f.error, HasSubstr("median over 2 poses"));
  const auto rows = FramesTable(Read(work_ / "stdout.txt"));
  ASSERT_EQ(rows.size(), 2u);
  // Twice as far, the bound is several times larger (about D^2.5, crlb.md).
  EXPECT_GT(std::stod(rows[1].at("crlb_position_m")),
            4.0 * std::stod(rows[0].at("crlb_position_m")));
  EXPECT_EQ(rows[0].at("noise_var"), "0.02");
  EXPECT_EQ(Run({"crlb", "--marker", marker, "--camera", camera, "--poses", marker}).status, 2);
}

// render's and crlb's explicit forms take the camera's response: render writes it in
// groundtruth.csv with the bound it gives, crlb prints it, and a noise-free frame's bound
// changes with it (its rounding is of the written values); out of range it is bad input.
TEST_F(SweepCliTest, TheExplicitFormsTakeTheCamerasResponse) {
  const std::string poses = WriteTestFile("poses.csv",
                                          "r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz\n"
                                          "1,0,0,0,-1,0,0,0,-1,0,0,0.6\n");
  const std::vector<std::string> inputs = {"--marker",
                                           kRoot + "/scenarios/markers/circle_d.yaml",
                                           "--camera",
                                           kRoot + "/scenarios/cameras/default.yaml",
                                           "--poses",
                                           poses};
  const auto bound_at = [&](const std::string& gamma) {
    std::vector<std::string> args = {"crlb"};
    args.insert(args.end(), inputs.begin(), inputs.end());
    args.insert(args.end(), {"--gamma", gamma});
    const Finished f = Run(args);
    EXPECT_EQ(f.status, 0) << f.error;
    const auto rows = FramesTable(Read(work_ / "stdout.txt"));
    EXPECT_EQ(rows.at(0).at("gamma"), gamma);
    return rows.at(0).at("crlb_position_m");
  };
  const std::string encoded_bound = bound_at("2.2");
  EXPECT_NE(encoded_bound, bound_at("1"));
  std::vector<std::string> render = {"render"};
  render.insert(render.end(), inputs.begin(), inputs.end());
  render.insert(render.end(), {"--gamma", "2.2", "--out", (work_ / "dataset").string()});
  ASSERT_EQ(Run(render).status, 0) << Read(work_ / "stderr.txt");
  const auto truth = FramesTable(Read(work_ / "dataset" / "groundtruth.csv"));
  EXPECT_EQ(truth.at(0).at("gamma"), "2.2");
  EXPECT_EQ(truth.at(0).at("crlb_position_m"), encoded_bound);
  render.back() = (work_ / "zero").string();
  render.at(render.size() - 3) = "0";
  EXPECT_EQ(Run(render).status, 2);
  EXPECT_EQ(
      Run({"render", Scenario("quick", 1), "--out", (work_ / "s").string(), "--gamma", "2"}).status,
      2);
}

// A marker file named with a comma and quotes: every CSV keeps one field per column.
TEST_F(SweepCliTest, NamesWithCommasAndQuotesAreQuotedInEveryCsv) {
  const std::string name = "tag, \"quoted\"";
  fs::copy_file(kRoot + "/scenarios/markers/apriltag.yaml", work_ / (name + ".yaml"));
  const std::string scenario = WriteTestFile(
      "quoting.yaml",
      "name: quoting\ncamera: " + kRoot + "/scenarios/cameras/default.yaml\nmarkers:\n  - '" +
          (work_ / (name + ".yaml")).string() +
          "'\ntrackers:\n  - {name: apriltag}\n"
          "poses: {sampler: look_at, distance_m: 0.6, tilt_deg: [0, 30]}\n"
          "sweep: {parameter: noise_var, values: [0.01]}\ntrials: 2\nseed: 1\n");
  const std::string out = (work_ / "out").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", out}).status, 0) << Read(work_ / "stderr.txt");
  ASSERT_EQ(Run({"report", out, "--no-plots"}).status, 0) << Read(work_ / "stderr.txt");
  ASSERT_EQ(Run({"render", scenario, "--out", out + "/rendered"}).status, 0);
  for (const std::string file :
       {"/quoting/frames.csv", "/summary.csv", "/rendered/groundtruth.csv"}) {
    std::istringstream lines(Read(out + file));
    std::string line;
    ASSERT_TRUE(std::getline(lines, line)) << file;
    const std::vector<std::string> header = SplitCsvLine(line);
    const size_t marker = std::find(header.begin(), header.end(), "marker") - header.begin();
    ASSERT_LT(marker, header.size()) << file;
    int rows = 0;
    for (; std::getline(lines, line); ++rows) {
      const std::vector<std::string> fields = SplitCsvLine(line);
      ASSERT_EQ(fields.size(), header.size()) << file << ": " << line;
      EXPECT_EQ(fields[marker], name) << file;
    }
    EXPECT_GT(rows, 0) << file;
  }
}

// --set, --trials and --trackers give the run of the scenario file edited that way; they are
// in the manifest and the fingerprint, and an isolated tracker's worker gets them: apriltag-ippe
// (third-party C code, so isolated) is the first tracker only after --trackers.
TEST_F(SweepCliTest, OverridesRunTheEditedScenarioAndAreRecorded) {
  const std::string out = (work_ / "out").string(), edited = (work_ / "edited").string();
  ASSERT_EQ(Run({"sweep",
                 Scenario("quick", 2),
                 "--out",
                 out,
                 "--set",
                 "render.blur_sigma_px=2",
                 "--set",
                 "sweep.values=[0.0, 0.1]",
                 "--trials",
                 "3",
                 "--trackers",
                 "aruco,apriltag-ippe"})
                .status,
            0);
  std::string text = Read(Scenario("quick", 3));
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"  - {name: apriltag}\n", ""},
           {"blur_sigma_px: 1.0", "blur_sigma_px: 2"},
           {"values: [0.0, 0.05, 0.15]", "values: [0.0, 0.1]"}}) {
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
  }
  ASSERT_EQ(Run({"sweep", WriteTestFile("quick.yaml", text), "--out", edited}).status, 0);
  const std::string frames = Read(out + "/quick/frames.csv");
  EXPECT_EQ(frames, Read(edited + "/quick/frames.csv"));
  // 2 values x 3 trials x (apriltag-ippe on the AprilTag, aruco on the ArUco marker).
  EXPECT_EQ(Lines(out + "/quick/frames.csv"), 1u + 2 * 3 * 2);
  for (const auto& row : FramesTable(frames)) {
    EXPECT_NE(row.at("tracker"), "apriltag");
    EXPECT_NE(row.at("status"), "error") << row.at("message");
  }
  const nlohmann::json entry = ReadManifest(out + "/manifest.json")["scenarios"]["quick"];
  EXPECT_EQ(entry["overrides"]["set"],
            nlohmann::json({"render.blur_sigma_px=2", "sweep.values=[0.0, 0.1]", "trials=3"}));
  EXPECT_EQ(entry["overrides"]["trackers"], nlohmann::json({"aruco", "apriltag-ippe"}));
  EXPECT_EQ(entry["trials"], 3);
  // Resuming without the overrides is resuming another scenario.
  const Finished resumed = Run({"sweep", Scenario("quick", 2), "--out", out, "--resume"});
  EXPECT_EQ(resumed.status, 2);
  EXPECT_THAT(resumed.error, HasSubstr("a different scenario or other overrides"));
  // A bad override is bad input, named.
  const Finished bad = Run({"sweep",
                            Scenario("quick", 2),
                            "--out",
                            (work_ / "bad").string(),
                            "--set",
                            "render.blur_sigma_px=wide"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_THAT(bad.error,
              HasSubstr("quick.yaml (--set render.blur_sigma_px=wide): key "
                        "'render.blur_sigma_px': expected"));
  EXPECT_FALSE(fs::exists(work_ / "bad"));
}

// A tracker entry with `linear_input: true` is told the camera's response: it gets each frame
// written with a gamma taken back to linear values. The circle tracker models linear light, so on
// frames written with gamma 2.2 its median error falls (measured on these 16 frames: 9.0 mm
// untold, 1.0 told; 0.78 on the linear frames, where both runs are the same).
TEST_F(SweepCliTest, ATrackerToldTheCamerasResponseSeesLinearFrames) {
  const auto run = [&](const std::string& linear_input) {
    const std::string scenario = WriteTestFile(
        "gamma_" + linear_input + ".yaml",
        "name: gamma\ncamera: " + kRoot + "/scenarios/cameras/default.yaml\nmarkers:\n  - " +
            kRoot + "/scenarios/markers/circles_a.yaml\nequal_ink_area_m2: 0.01\ntrackers:\n" +
            "  - {name: circle, linear_input: " + linear_input + "}\n" +
            "poses: {sampler: look_at, distance_m: 0.6, tilt_deg: [0, 40]}\n" +
            "render: {noise_var: 0.02}\nsweep: {parameter: gamma, values: [1, 2.2]}\n" +
            "trials: 16\nseed: 4\n");
    const std::string out = (work_ / linear_input).string();
    EXPECT_EQ(Run({"sweep", scenario, "--out", out}).status, 0) << Read(work_ / "stderr.txt");
    return FramesTable(Read(out + "/gamma/frames.csv"));
  };
  const auto untold = run("false"), told = run("true");
  ASSERT_EQ(untold.size(), 32u);
  ASSERT_EQ(told.size(), untold.size());
  std::map<std::string, std::vector<double>> untold_errors, told_errors;
  for (size_t i = 0; i < told.size(); ++i) {
    const std::string& gamma = told[i].at("sweep_value");
    EXPECT_EQ(told[i].at("crlb_position_m"), untold[i].at("crlb_position_m"));
    if (gamma == "1") {
      EXPECT_EQ(told[i].at("position_error_m"), untold[i].at("position_error_m"));
    }
    for (const auto* rows : {&untold, &told}) EXPECT_EQ((*rows)[i].at("status"), "ok") << gamma;
    untold_errors[gamma].push_back(std::stod(untold[i].at("position_error_m")));
    told_errors[gamma].push_back(std::stod(told[i].at("position_error_m")));
  }
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  EXPECT_LT(median(told_errors["2.2"]), 0.5 * median(untold_errors["2.2"]));
  EXPECT_LT(median(told_errors["2.2"]), 2.0 * median(told_errors["1"]));
}

// A grid sweep: every combination in frames.csv's grid column, a summary row per cell, a heat
// map in the report, and the regression gate pairs its cells (a run passes against itself).
TEST_F(SweepCliTest, AGridSweepIsSummarisedPlottedAndGated) {
  const std::string scenario = WriteTestFile(
      "grid.yaml",
      "name: grid\ncamera: " + kRoot + "/scenarios/cameras/default.yaml\nmarkers:\n  - " + kRoot +
          "/scenarios/markers/circles_a.yaml\ntrackers:\n  - {name: circle}\n"
          "poses: {sampler: look_at, distance_m: 0.8, tilt_deg: [0, 40]}\n"
          "render: {noise_var: 0.01}\n"
          "sweep:\n  grid: {distance_m: [0.5, 1.0], tilt_deg: [10, 50]}\n"
          "trials: 4\nseed: 3\n");
  const std::string out = (work_ / "out").string(), reference = (work_ / "ref").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", out}).status, 0) << Read(work_ / "stderr.txt");
  const auto rows = FramesTable(Read(out + "/grid/frames.csv"));
  ASSERT_EQ(rows.size(), 2u * 2 * 4);
  std::map<std::pair<std::string, std::string>, int> cells;
  for (const auto& row : rows) ++cells[{row.at("sweep_value"), row.at("grid")}];
  EXPECT_EQ(cells,
            (std::map<std::pair<std::string, std::string>, int>{{{"0.5", "tilt_deg=10"}, 4},
                                                                {{"1", "tilt_deg=10"}, 4},
                                                                {{"0.5", "tilt_deg=50"}, 4},
                                                                {{"1", "tilt_deg=50"}, 4}}));
  ASSERT_EQ(Run({"report", out}).status, 0) << Read(work_ / "stderr.txt");
  EXPECT_EQ(Lines(out + "/summary.csv"), 1u + 4);
  EXPECT_THAT(Read(out + "/summary.csv"), HasSubstr("grid,distance_m,1,tilt_deg=50,circle,"));
  EXPECT_TRUE(fs::exists(out + "/grid_heatmap.png"));
  const std::string report = Read(out + "/report.md");
  EXPECT_THAT(report, HasSubstr("grid_heatmap.png"));
  EXPECT_THAT(report, HasSubstr("| circle | circles_a | tilt_deg=50 |"));
  ASSERT_EQ(Run({"check", out, "--reference", reference, "--bless"}).status, 0);
  EXPECT_EQ(Run({"check", out, "--reference", reference}).status, 0);
  EXPECT_THAT(Read(work_ / "stdout.txt"), HasSubstr("no regression: 4 cells"));
}

// Each case: exit status 2, a message naming the file, line and key, and no output folder.
TEST_F(SweepCliTest, BadInputIsRejectedBeforeAnythingIsWritten) {
  const std::string good = Read(Scenario("bad", 1));
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const struct {
    std::string text;
    std::string message;
  } cases[] = {
      {"name: bad\nmarkers: [unclosed\n", "bad.yaml:3: not valid YAML"},
      {good + "threads: 4\n", "bad.yaml:16: key 'threads': unknown key"},
      {replaced("trials: 1\n", ""), "key 'trials': missing"},
      {replaced("trials: 1", "trials: one"), "bad.yaml:14: key 'trials': expected an integer"},
      {replaced("blur_sigma_px: 1.0", "blur_sigma_px: -1.0"),
       "bad.yaml:12: key 'render.blur_sigma_px': expected a number in [0, 100]"},
      {replaced("values: [0.0, 0.05, 0.15]", "values: [0.0, -0.05]"),
       "bad.yaml:13: key 'sweep.values'"},
      {replaced("values: [0.0, 0.05, 0.15]", "values: []"),
       "bad.yaml:13: key 'sweep.values': expected a non-empty list"},
      {replaced("{name: aruco}", "{name: aruko}"),
       "bad.yaml:10: key 'trackers[2].name': expected one of the available trackers: apriltag, "
       "apriltag-ippe, artkplus, artkplus-improved, aruco"},
      {replaced("/scenarios/markers/aruco.yaml", "/scenarios/markers/nosuch.yaml"),
       "nosuch.yaml: cannot open the file"},
      {replaced("/scenarios/cameras/default.yaml", "/scenarios/cameras/nosuch.yaml"),
       "nosuch.yaml: cannot open the file"},
      {replaced("distance_m: 0.8", "distance_m: 0.05"),
       "bad.yaml:11: key 'poses.distance_m': expected markers in view"},
      {replaced("{name: aruco}", "{name: truth, exec: [python3, tracker.py]}"),
       "bad.yaml:10: key 'trackers[2].name': expected a name other than 'truth'"},
      {good + "trajectory: {kind: spiral, fps: 30, duration_s: 2}\n",
       "bad.yaml:16: key 'trajectory.kind': expected orbit, approach or handheld"},
      {good + "trajectory: {kind: orbit, fps: 30, duration_s: 2, to_m: 3}\n",
       "bad.yaml:16: key 'trajectory.to_m': expected no such key for kind orbit"},
      {good + "trajectory: {kind: orbit, fps: 30, duration_s: 2, occlusions: [[5, 60]]}\n",
       "bad.yaml:16: key 'trajectory.occlusions': expected a list of [first, last] frame ranges "
       "with 0 <= first <= last < 60"},
      {good + "trajectory: {kind: approach, fps: 30, duration_s: 2, from_m: 3}\n",
       "bad.yaml:16: key 'trajectory.from_m': expected no such key: a trajectory starts at "
       "poses.distance_m"},
      {good + "trajectory: {kind: handheld, fps: 30, duration_s: 2, linear_speed_m_s: 9}\n",
       "bad.yaml:16: key 'trajectory': expected markers in view: no start in 1000 draws"},
  };
  for (const auto& c : cases) {
    const std::string path = WriteTestFile("bad.yaml", c.text);
    const std::string out = (work_ / "never").string();
    const Finished f = Run({"sweep", path, "--out", out});
    EXPECT_EQ(f.status, 2) << c.text;
    EXPECT_THAT(f.error, HasSubstr(c.message)) << c.text;
    EXPECT_FALSE(fs::exists(out)) << c.text;
  }
}

// Usage errors are bad input (exit 2 with CLI11's message), not CLI11's own codes 105-108.
TEST_F(SweepCliTest, UsageErrorsAreExitTwo) {
  const std::string scenario = Scenario("usage", 1);
  const std::string out = (work_ / "out").string();
  const struct {
    std::vector<std::string> args;
    std::string message;
  } cases[] = {
      {{"sweep", scenario, "--out", out, "--bogus"}, "--bogus"},
      {{"sweep", scenario}, "--out is required"},
      {{"sweep", scenario, "--out", out, "--threads", "many"}, "--threads"},
      {{"sweep", scenario, "--out", out, "--threads", "100000"},
       "--threads: expected a number in [1, 1024], got '100000'"},
      {{"render", scenario, "--out", out, "--seed", "-1"},
       "--seed: expected a number in [0, 2147483647], got '-1'"},
      {{"report", out, "--success-fraction", "nan"},
       "--success-fraction: expected a number in [0, 10], got 'nan'"},
  };
  for (const auto& c : cases) {
    const Finished f = Run(c.args);
    EXPECT_EQ(f.status, 2) << c.message;
    EXPECT_THAT(f.error, HasSubstr(c.message));
    EXPECT_FALSE(fs::exists(out)) << c.message;
  }
}

// The plotting script gets the folder as an argument, never through a shell.
TEST_F(SweepCliTest, ReportRunsNoShell) {
  const std::string out = (work_ / "x';touch PWNED;'").string();
  ASSERT_EQ(Run({"sweep", Scenario("plots", 1), "--out", out}).status, 0);
  EXPECT_EQ(Run({"report", out}).status, 0) << Read(work_ / "stderr.txt");
  EXPECT_FALSE(fs::exists("PWNED"));
  fs::remove("PWNED");
  EXPECT_TRUE(fs::exists(out + "/report.md"));
}

// The apriltag tracker at 0.8 m, with tracker options `options`.
std::string TagScenario(const std::string& file, const std::string& options, int seed) {
  return WriteTestFile(file,
                       "name: gate\ncamera: " + kRoot +
                           "/scenarios/cameras/default.yaml\nmarkers:\n  - " + kRoot +
                           "/scenarios/markers/apriltag.yaml\n"
                           "trackers:\n  - {name: apriltag, options: {" +
                           options +
                           "}}\n"
                           "poses: {sampler: look_at, distance_m: 0.8, tilt_deg: [0, 40]}\n"
                           "crlb: false\n"
                           "sweep: {parameter: noise_var, values: [0.02]}\ntrials: 40\nseed: " +
                           std::to_string(seed) + "\n");
}

// AprilTag without its edge refinement: errors about 1.8 times larger. (The circle tracker
// without its LM refinement moves the median by 1 % at 0.8 m: not a regression to inject.)
TEST_F(SweepCliTest, CheckCatchesAprilTagWithoutEdgeRefinement) {
  const std::string reference = (work_ / "reference").string(), run = (work_ / "run").string();
  ASSERT_EQ(Run({"sweep", TagScenario("refined.yaml", "refine_edges: true", 4), "--out", reference})
                .status,
            0);
  ASSERT_EQ(
      Run({"sweep", TagScenario("unrefined.yaml", "refine_edges: false", 4), "--out", run}).status,
      0);
  const std::string junit = (work_ / "check.xml").string();
  const std::string markdown = (work_ / "check.md").string();
  EXPECT_EQ(Run({"check", run, "--reference", reference, "--junit", junit, "--markdown", markdown})
                .status,
            1);
  const std::string table = Read(work_ / "stdout.txt");
  EXPECT_THAT(table, HasSubstr("REGRESSION: 1 cells, 1 regressed"));
  EXPECT_THAT(table,
              ::testing::ContainsRegex("gate +apriltag +apriltag +noise_var=0.02 +"
                                       "position error .* REGRESSED"));
  EXPECT_THAT(Read(markdown), HasSubstr("❌"));
  // The JUnit file validates against the common schema and fails the one cell.
  const std::string schema = kRoot + "/bench/testdata/junit.xsd";
  const std::string validate = "xmllint --noout --schema '" + schema + "' '" + junit + "'";
  EXPECT_EQ(std::system(validate.c_str()), 0) << Read(junit);
  EXPECT_THAT(Read(junit), HasSubstr("<failure message=\"position error"));
  // An identical run passes; blessing the worse run makes it the reference.
  EXPECT_EQ(Run({"check", reference, "--reference", reference}).status, 0);
  EXPECT_EQ(Run({"check", run, "--reference", reference, "--bless"}).status, 0);
  EXPECT_EQ(Read(run + "/gate/frames.csv"), Read(reference + "/gate/frames.csv"));
  EXPECT_EQ(Run({"check", run, "--reference", reference}).status, 0);
}

// Offline: a sweep's own poses, exported as ESTIMATES.csv for the rendered frames of the same
// scenario and scored, pass check against that sweep (same frames, same ground truth).
TEST_F(SweepCliTest, ScoredEstimatesPassCheckAgainstTheSweepTheyCameFrom) {
  const std::string scenario = TagScenario("offline.yaml", "", 6);
  const std::string swept = (work_ / "swept").string(), dataset = (work_ / "dataset").string(),
                    scored = (work_ / "scored").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", swept}).status, 0);
  ASSERT_EQ(Run({"render", scenario, "--out", dataset}).status, 0);
  std::istringstream rows(Read(swept + "/gate/frames.csv"));
  std::string line;
  std::getline(rows, line);
  const std::vector<std::string> header = SplitCsvLine(line);
  const size_t r11 = std::find(header.begin(), header.end(), "r11") - header.begin();
  std::string estimates = "frame,status,r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz\n";
  while (std::getline(rows, line)) {
    const std::vector<std::string> f = SplitCsvLine(line);
    estimates += f[4] + "," + f[10];
    for (size_t k = 0; k < 12; ++k) estimates += "," + f[r11 + k];
    estimates += "\n";
  }
  const std::string estimates_path = WriteTestFile("offline_estimates.csv", estimates);
  ASSERT_EQ(
      Run({"score", dataset, "--poses", estimates_path, "--tracker", "apriltag", "--out", scored})
          .status,
      0)
      << Read(work_ / "stderr.txt");
  const Finished checked = Run({"check", scored, "--reference", swept});
  EXPECT_EQ(checked.status, 0) << Read(work_ / "stdout.txt") << checked.error;
  EXPECT_THAT(Read(work_ / "stdout.txt"),
              HasSubstr("1 the same, 0 new; 0 rows only in the reference, 0 only in the run"));
}

TEST_F(SweepCliTest, CheckAgainstAnotherSeedIsBadInputNamingTheScenario) {
  const std::string reference = (work_ / "reference").string(), run = (work_ / "run").string();
  ASSERT_EQ(Run({"sweep", TagScenario("a.yaml", "", 4), "--out", reference}).status, 0);
  ASSERT_EQ(Run({"sweep", TagScenario("b.yaml", "", 5), "--out", run}).status, 0);
  const Finished f = Run({"check", run, "--reference", reference});
  EXPECT_EQ(f.status, 2);
  EXPECT_THAT(f.error, HasSubstr("gate: the ground truth of gate noise_var=0.02 trial 0 apriltag"));
  EXPECT_EQ(Run({"check", run, "--reference", (work_ / "nowhere").string()}).status, 2);
  // A reference in another format is bad input to check, and --bless replaces it.
  std::ofstream(reference + "/gate/timing.csv") << "frame,tracker,time_ms\n0,apriltag,1.0\n";
  const Finished old_format = Run({"check", run, "--reference", reference});
  EXPECT_EQ(old_format.status, 2);
  EXPECT_THAT(old_format.error, HasSubstr("gate/timing.csv:1: expected the header"));
  EXPECT_EQ(Run({"check", run, "--reference", reference, "--bless"}).status, 0);
  EXPECT_EQ(Run({"check", run, "--reference", reference}).status, 0);
}

}  // namespace
}  // namespace markerbench
