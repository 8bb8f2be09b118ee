// sweep --shard I/N and merge, as a cluster runs them: shards of every scenario shape merge to
// the bytes of a single-machine sweep, a killed shard resumes, merge refuses shards that do
// not make one plan or warns of shards built apart, and zstd-compressed runs read like plain
// ones.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "bench/cli/cli_test.h"
#include "bench/io/line_reader.h"
#include "bench/run/frames_csv.h"
#include "bench/run/manifest.h"
#include "core/test_files.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

std::string Marker(const std::string& name) {
  return kRoot + "/scenarios/markers/" + name + ".yaml";
}

// A scenario file of `name` with the given markers, trackers and sweep.
std::string ScenarioFile(const std::string& name,
                         const std::vector<std::string>& markers,
                         const std::string& trackers,
                         const std::string& sweep,
                         int trials,
                         int seed = 5) {
  std::string text = "name: " + name + "\ncamera: " + kRoot + "/scenarios/cameras/default.yaml\n";
  text += "markers:\n";
  for (const std::string& m : markers) text += "  - " + Marker(m) + "\n";
  text += "equal_ink_area_m2: 0.01\ntrackers:\n" + trackers +
          "poses: {sampler: look_at, distance_m: 0.7, tilt_deg: [0, 40]}\n"
          "render: {blur_sigma_px: 0.8}\nsweep: " +
          sweep + "\ntrials: " + std::to_string(trials) + "\nseed: " + std::to_string(seed) + "\n";
  return WriteTestFile(name + ".yaml", text);
}

// The three shapes: a sweep over distance, over noise, and several markers and trackers with
// a marker that no tracker reads (it is only rendered for the examples).
std::vector<std::string> ShapeScenarios() {
  return {
      ScenarioFile("distance",
                   {"apriltag"},
                   "  - {name: apriltag-ippe}\n",
                   "{parameter: distance_m, values: [0.5, 1.0, 2.0]}",
                   4),
      ScenarioFile("noise",
                   {"aruco"},
                   "  - {name: aruco}\n",
                   "{parameter: noise_var, values: [0.0, 0.1]}",
                   5),
      ScenarioFile("several",
                   {"apriltag", "aruco", "artkplus", "circles_a"},
                   "  - {name: apriltag}\n  - {name: aruco}\n  - {name: artkplus}\n",
                   "{parameter: blur_sigma_px, values: [0.5, 2.0]}",
                   3),
  };
}

class ShardMergeTest : public CliTest {
 protected:
  // Runs `args` and expects exit 0.
  void Ok(std::vector<std::string> args) {
    const Finished f = Run(args);
    ASSERT_EQ(f.status, 0) << f.error;
  }
  // Runs the sweep of `scenarios` as shards 0..n-1 into work_/<prefix>_<i>; returns the folders.
  std::vector<std::string> Shards(const std::vector<std::string>& scenarios,
                                  int n,
                                  const std::string& prefix) {
    std::vector<std::string> dirs;
    for (int i = 0; i < n; ++i) {
      dirs.push_back((work_ / (prefix + "_" + std::to_string(i))).string());
      std::vector<std::string> args = {"sweep"};
      args.insert(args.end(), scenarios.begin(), scenarios.end());
      args.insert(args.end(),
                  {"--out",
                   dirs.back(),
                   "--threads",
                   "2",
                   "--shard",
                   std::to_string(i) + "/" + std::to_string(n)});
      Ok(args);
    }
    return dirs;
  }
  Finished Merge(const std::vector<std::string>& dirs, const std::string& out) {
    std::vector<std::string> args = {"merge"};
    args.insert(args.end(), dirs.begin(), dirs.end());
    args.insert(args.end(), {"--out", out});
    return Run(args);
  }
};

TEST_F(ShardMergeTest, ShardsOfEveryShapeMergeToTheSingleRunBytes) {
  const std::vector<std::string> scenarios = ShapeScenarios();
  const std::string single = (work_ / "single").string();
  std::vector<std::string> args = {"sweep"};
  args.insert(args.end(), scenarios.begin(), scenarios.end());
  args.insert(args.end(), {"--out", single, "--threads", "2"});
  Ok(args);
  for (const int n : {1, 2, 3, 7}) {
    SCOPED_TRACE("N = " + std::to_string(n));
    const std::vector<std::string> dirs = Shards(scenarios, n, "n" + std::to_string(n));
    if (n == 7) {
      // A shard may hold rows of some cells only; 7 shards of 3 x 4 pose groups leave none
      // empty here, and each has fewer rows than the whole.
      EXPECT_LT(Lines(dirs[0] + "/distance/frames.csv"), Lines(single + "/distance/frames.csv"));
    }
    const std::string merged = (work_ / ("merged" + std::to_string(n))).string();
    const Finished f = Merge(dirs, merged);
    ASSERT_EQ(f.status, 0) << f.error;
    for (const std::string name : {"distance", "noise", "several"}) {
      EXPECT_EQ(Read(merged + "/" + name + "/frames.csv"),
                Read(single + "/" + name + "/frames.csv"))
          << name;
      EXPECT_EQ(Lines(merged + "/" + name + "/timing.csv"),
                Lines(single + "/" + name + "/timing.csv"));
      // Every marker's example image, circles_a's too (no tracker reads it).
      for (const std::string marker : {"apriltag", "aruco", "artkplus", "circles_a"}) {
        EXPECT_EQ(fs::exists(merged + "/" + name + "/examples/" + marker + ".png"),
                  fs::exists(single + "/" + name + "/examples/" + marker + ".png"));
      }
    }
  }
  // report and check read a merged run as any run.
  Ok({"report", (work_ / "merged3").string(), "--no-plots"});
  const Finished check = Run({"check", (work_ / "merged3").string(), "--reference", single});
  EXPECT_EQ(check.status, 0) << check.error;
  EXPECT_THAT(Read(work_ / "stdout.txt"), HasSubstr("no regression"));
  EXPECT_THAT(Read(work_ / "merged3/manifest.json"), HasSubstr("\"frames_per_core_s\""));
}

TEST_F(ShardMergeTest, AKilledShardResumesAndMergesToTheSameBytes) {
  const std::string scenario = ScenarioFile("long",
                                            {"apriltag", "aruco"},
                                            "  - {name: apriltag-ippe}\n  - {name: aruco}\n",
                                            "{parameter: noise_var, values: [0.0, 0.05]}",
                                            40);
  const std::string single = (work_ / "single").string();
  Ok({"sweep", scenario, "--out", single, "--threads", "2"});
  const std::string shard0 = (work_ / "s0").string(), shard1 = (work_ / "s1").string();
  Ok({"sweep", scenario, "--out", shard0, "--shard", "0/2"});
  const pid_t pid = Start({"sweep", scenario, "--out", shard1, "--shard", "1/2"});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (Lines(shard1 + "/long/frames.csv") < 20 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  ASSERT_EQ(Wait(pid).status, 128 + SIGKILL);
  ASSERT_LT(Lines(shard1 + "/long/frames.csv"), Lines(single + "/long/frames.csv") / 2)
      << "the shard finished before it was killed";

  // An incomplete shard is refused, by name, and nothing is written.
  const std::string merged = (work_ / "merged").string();
  const Finished incomplete = Merge({shard0, shard1}, merged);
  EXPECT_EQ(incomplete.status, 2);
  EXPECT_THAT(incomplete.error, HasSubstr(shard1 + "/long/run.json: shard 1/2 is incomplete"));
  EXPECT_FALSE(fs::exists(merged + "/long"));

  // Resuming with another shard is refused; with its own it completes.
  const Finished other = Run({"sweep", scenario, "--out", shard1, "--shard", "0/2", "--resume"});
  EXPECT_EQ(other.status, 2);
  EXPECT_THAT(other.error, HasSubstr("holds shard 1/2"));
  Ok({"sweep", scenario, "--out", shard1, "--shard", "1/2", "--resume"});
  const Finished f = Merge({shard1, shard0}, merged);  // in any order
  ASSERT_EQ(f.status, 0) << f.error;
  EXPECT_EQ(Read(merged + "/long/frames.csv"), Read(single + "/long/frames.csv"));
}

TEST_F(ShardMergeTest, MergeRefusesShardsThatAreNotOnePlan) {
  const std::string scenario = ScenarioFile(
      "plan", {"aruco"}, "  - {name: aruco}\n", "{parameter: noise_var, values: [0.0, 0.05]}", 3);
  const std::vector<std::string> dirs = Shards({scenario}, 3, "s");
  const std::string out = (work_ / "out").string();

  const Finished missing = Merge({dirs[0], dirs[2]}, out);
  EXPECT_EQ(missing.status, 2);
  EXPECT_THAT(missing.error, HasSubstr("plan: shards 1 of 3 are missing"));

  const Finished twice = Merge({dirs[0], dirs[1], dirs[2], dirs[1]}, out);
  EXPECT_EQ(twice.status, 2);
  EXPECT_THAT(twice.error,
              HasSubstr("shard 1/3 given twice: " + dirs[1] + "/plan and " + dirs[1] + "/plan"));

  // The same name, another seed: another plan.
  const std::string reseeded = ScenarioFile("plan",
                                            {"aruco"},
                                            "  - {name: aruco}\n",
                                            "{parameter: noise_var, values: [0.0, 0.05]}",
                                            3,
                                            6);
  const std::string other = (work_ / "other").string();
  Ok({"sweep", reseeded, "--out", other, "--shard", "1/3"});
  const Finished mixed = Merge({dirs[0], other, dirs[2]}, out);
  EXPECT_EQ(mixed.status, 2);
  EXPECT_THAT(mixed.error, HasSubstr("the shards come from different scenarios"));

  // Shards of another N.
  const std::vector<std::string> halves = Shards({scenario}, 2, "h");
  const Finished counts = Merge({dirs[0], halves[1]}, out);
  EXPECT_EQ(counts.status, 2);
  EXPECT_THAT(counts.error, HasSubstr("shard 1/2"));

  // A shard whose frames.csv lost rows after it completed.
  const std::string frames = dirs[1] + "/plan/frames.csv";
  const std::string text = Read(frames);
  std::ofstream(frames, std::ios::binary) << text.substr(0, text.rfind('\n', text.size() - 2) + 1);
  const Finished damaged = Merge(dirs, out);
  EXPECT_EQ(damaged.status, 2);
  EXPECT_THAT(damaged.error, HasSubstr("the shard is damaged"));
  EXPECT_FALSE(fs::exists(out + "/plan/frames.csv"));

  EXPECT_EQ(Run({"sweep", scenario, "--out", out, "--shard", "3/3"}).status, 2);
  EXPECT_THAT(Read(work_ / "stderr.txt"), HasSubstr("--shard: expected I/N with 0 <= I < N"));
  EXPECT_EQ(Merge({dirs[0]}, dirs[0]).status, 2);
}

// Shards built from the same commit with other local changes merge, with a warning naming both
// builds by their changes' hashes; the merged manifest keeps each shard's builds, the report
// says that another build wrote rows, and `check` names the builds it compares.
TEST_F(ShardMergeTest, MergeWarnsOfShardsBuiltApart) {
  const std::string scenario = ScenarioFile(
      "apart", {"aruco"}, "  - {name: aruco}\n", "{parameter: noise_var, values: [0.0, 0.05]}", 2);
  const std::vector<std::string> dirs = Shards({scenario}, 2, "s");
  const std::string out = (work_ / "out").string();
  const Finished alike = Merge(dirs, out);
  ASSERT_EQ(alike.status, 0) << alike.error;
  EXPECT_THAT(alike.error, Not(HasSubstr("warning")));
  nlohmann::json this_build = BuildIdentity();
  this_build["from_frame"] = 0;
  EXPECT_EQ(ReadManifest(out + "/apart/run.json")["builds"], nlohmann::json::array({this_build}));

  nlohmann::json other = BuildIdentity();
  other["git_diff_sha256"] = std::string(64, 'f');
  const std::string manifest_path = dirs[1] + "/manifest.json";
  nlohmann::json manifest = ReadManifest(manifest_path);
  manifest["environment"].update(other);
  other["from_frame"] = 0;
  manifest["scenarios"]["apart"]["builds"] = nlohmann::json::array({other});
  WriteManifest(manifest_path, manifest);
  const std::string run_path = dirs[1] + "/apart/run.json";
  nlohmann::json run = ReadManifest(run_path);
  run["builds"] = nlohmann::json::array({other});
  WriteManifest(run_path, run);
  const Finished apart = Merge(dirs, (work_ / "merged").string());
  ASSERT_EQ(apart.status, 0) << apart.error;
  // The merged rows' builds differ by shard: the manifest lists them, run.json names none.
  EXPECT_FALSE(ReadManifest((work_ / "merged/apart/run.json").string()).contains("builds"));
  EXPECT_THAT(apart.error,
              HasSubstr("merge: warning: apart shard 1/2 was built from " + BuildText(other) +
                        ", shard 0 from " + BuildText(BuildIdentity())));
  EXPECT_THAT(BuildText(other), HasSubstr("with local changes (SHA-256 ffffffffffff"));
  const nlohmann::json merged = ReadManifest((work_ / "merged/manifest.json").string());
  EXPECT_EQ(merged["scenarios"]["apart"]["shards"][1]["builds"], nlohmann::json::array({other}));
  Ok({"report", (work_ / "merged").string(), "--no-plots"});
  EXPECT_THAT(
      Read(work_ / "merged/report.md"),
      HasSubstr("Rows of `apart` were also written by another build:** " + BuildText(other)));

  // The gate's markdown names the builds it compared: here the merged run against a single
  // run whose manifest says the other build made it.
  const std::string single = (work_ / "single").string();
  Ok({"sweep", scenario, "--out", single});
  nlohmann::json single_manifest = ReadManifest(single + "/manifest.json");
  single_manifest["environment"].update(other);
  WriteManifest(single + "/manifest.json", single_manifest);
  const std::string markdown = (work_ / "check.md").string();
  Ok({"check", (work_ / "merged").string(), "--reference", single, "--markdown", markdown});
  EXPECT_THAT(Read(markdown),
              HasSubstr("The run was built from " + BuildText(BuildIdentity()) +
                        "; the reference, from " + BuildText(other) + ".\n"));
}

// A shard's run.json with a key of another type is bad input: exit 2 naming the file and the key.
TEST_F(ShardMergeTest, MergeRefusesARunJsonItCannotRead) {
  const std::string scenario = ScenarioFile(
      "damaged", {"aruco"}, "  - {name: aruco}\n", "{parameter: noise_var, values: [0.0]}", 2);
  const std::vector<std::string> dirs = Shards({scenario}, 2, "s");
  const std::string run_json = dirs[1] + "/damaged/run.json";
  const nlohmann::json written = ReadManifest(run_json);
  for (const char* key : {"fingerprint", "complete", "rows"}) {
    SCOPED_TRACE(key);
    nlohmann::json run = written;
    run[key] = nlohmann::json::array();
    WriteManifest(run_json, run);
    const Finished f = Merge(dirs, (work_ / "out").string());
    EXPECT_EQ(f.status, 2);
    EXPECT_THAT(f.error, HasSubstr(run_json + ": key '" + key + "': expected "));
  }
  // The shard, read as --resume reads it, but required.
  const std::vector<std::pair<nlohmann::json, std::string>> shards = {
      {nlohmann::json(), "key 'shard': missing; written by a markerbench older than shards"},
      {"1/2", "key 'shard': expected {index, count}, got \"1/2\""},
      {{{"index", 1.5}, {"count", 2}}, "key 'shard': key 'index': expected an integer, got 1.5"},
      {{{"index", 2}, {"count", 2}}, "key 'shard'"}};
  for (const auto& [shard, message] : shards) {
    SCOPED_TRACE(shard.dump());
    nlohmann::json run = written;
    if (shard.is_null()) {
      run.erase("shard");
    } else {
      run["shard"] = shard;
    }
    WriteManifest(run_json, run);
    const Finished f = Merge(dirs, (work_ / "out").string());
    EXPECT_EQ(f.status, 2);
    EXPECT_THAT(f.error, HasSubstr(run_json + ": " + message));
  }
}

// A shard's manifest read only once its rows are merged (its wall time, here of another type):
// the merge is exit 2 naming the file and the key, and leaves no folder behind, or the one it
// was to replace as it was.
TEST_F(ShardMergeTest, AMergeThatFailsLeavesNoFolder) {
  const std::string scenario = ScenarioFile(
      "halted", {"aruco"}, "  - {name: aruco}\n", "{parameter: noise_var, values: [0.0]}", 2);
  const std::vector<std::string> dirs = Shards({scenario}, 2, "s");
  const std::string out = (work_ / "out").string();
  const std::string manifest_path = dirs[1] + "/manifest.json";
  const nlohmann::json written = ReadManifest(manifest_path);
  nlohmann::json damaged = written;
  damaged["scenarios"]["halted"]["wall_s"] = "slow";
  WriteManifest(manifest_path, damaged);
  Finished f = Merge(dirs, out);
  EXPECT_EQ(f.status, 2);
  EXPECT_THAT(f.error, HasSubstr(manifest_path + ": key 'scenarios/halted/wall_s': expected"));
  EXPECT_FALSE(fs::exists(out + "/halted"));
  EXPECT_FALSE(fs::exists(out + "/halted.merging"));
  // Merged whole, then again over it with the damage: the first merge stays.
  WriteManifest(manifest_path, written);
  ASSERT_EQ(Merge(dirs, out).status, 0);
  const std::string merged = Read(fs::path(out) / "halted/frames.csv");
  WriteManifest(manifest_path, damaged);
  std::vector<std::string> again = dirs;
  again.push_back("--overwrite");
  f = Merge(again, out);
  EXPECT_EQ(f.status, 2);
  EXPECT_EQ(Read(fs::path(out) / "halted/frames.csv"), merged);
  EXPECT_FALSE(fs::exists(out + "/halted.merging"));
}

TEST_F(ShardMergeTest, CompressedRunsReadLikePlainOnes) {
  const std::string scenario = ScenarioFile(
      "packed", {"aruco"}, "  - {name: aruco}\n", "{parameter: noise_var, values: [0.0, 0.05]}", 6);
  const std::string plain = (work_ / "plain").string(), packed = (work_ / "packed").string();
  Ok({"sweep", scenario, "--out", plain});
  Ok({"sweep", scenario, "--out", packed, "--zstd"});
  EXPECT_FALSE(fs::exists(packed + "/packed/frames.csv"));
  ASSERT_TRUE(fs::exists(packed + "/packed/frames.csv.zst"));
  ASSERT_EQ(
      RunProgram(
          "zstd",
          {"-q", "-d", packed + "/packed/frames.csv.zst", "-o", (work_ / "unpacked.csv").string()})
          .status,
      0);
  EXPECT_EQ(Read(work_ / "unpacked.csv"), Read(plain + "/packed/frames.csv"));
  // A complete compressed run has nothing to resume; without --resume it is refused.
  Ok({"sweep", scenario, "--out", packed, "--resume"});
  EXPECT_EQ(Run({"sweep", scenario, "--out", packed}).status, 2);
  Ok({"report", packed, "--no-plots"});
  Ok({"report", plain, "--no-plots"});
  const auto without_times = [](const std::string& summary) {
    std::string kept;
    std::istringstream lines(summary);
    size_t time_column = 0;
    for (std::string line; std::getline(lines, line);) {
      const std::vector<std::string> f = SplitCsvLine(line);
      if (kept.empty()) {
        time_column = std::find(f.begin(), f.end(), "time_median_ms") - f.begin();
      }
      for (size_t i = 0; i < f.size(); ++i) {
        if (i != time_column) kept += f[i] + ",";
      }
      kept += "\n";
    }
    return kept;
  };
  EXPECT_EQ(without_times(Read(packed + "/summary.csv")),
            without_times(Read(plain + "/summary.csv")));
  EXPECT_EQ(Run({"check", packed, "--reference", plain}).status, 0);
  // A compressed run blessed as the reference stays compressed there and gates plain runs.
  const std::string reference = (work_ / "reference").string();
  Ok({"check", packed, "--reference", reference, "--bless"});
  EXPECT_TRUE(fs::exists(reference + "/packed/frames.csv.zst"));
  EXPECT_TRUE(fs::exists(reference + "/packed/timing.csv.zst"));
  EXPECT_EQ(Run({"check", plain, "--reference", reference}).status, 0);
  // Shards compressed, merged compressed: the same rows.
  const std::vector<std::string> dirs = {(work_ / "z0").string(), (work_ / "z1").string()};
  Ok({"sweep", scenario, "--out", dirs[0], "--shard", "0/2", "--zstd"});
  Ok({"sweep", scenario, "--out", dirs[1], "--shard", "1/2"});
  const std::string merged = (work_ / "merged").string();
  ASSERT_EQ(Run({"merge", dirs[0], dirs[1], "--out", merged, "--zstd"}).status, 0);
  LineReader reader(merged + "/packed/frames.csv.zst");
  std::string text, line;
  while (reader.Next(&line)) text += line + "\n";
  EXPECT_EQ(text, Read(plain + "/packed/frames.csv"));
}

}  // namespace
}  // namespace markerbench
