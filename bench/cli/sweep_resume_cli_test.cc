// Nothing of a sweep is lost: a run killed with kill -9, torn mid-row or out of disk resumes to
// the bytes of an uninterrupted one; a folder another run is writing or another scenario wrote
// is refused; a run resumed by another build says so; --overwrite leaves nothing of the run
// before.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "bench/cli/sweep_cli_test.h"
#include "bench/run/manifest.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

TEST_F(SweepCliTest, KilledRunResumesToTheSameFile) {
  const std::string scenario = Scenario("resume", 30);
  const std::string reference = (work_ / "reference").string(),
                    killed = (work_ / "killed").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", reference, "--threads", "2"}).status, 0);
  const size_t total = Lines(reference + "/resume/frames.csv");

  const pid_t pid = Start({"sweep", scenario, "--out", killed, "--threads", "2"});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (Lines(killed + "/resume/frames.csv") < total / 4 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  ASSERT_EQ(Wait(pid).status, 128 + SIGKILL);
  const size_t kept = Lines(killed + "/resume/frames.csv");
  ASSERT_GE(kept, total / 4);
  ASSERT_LT(kept, total) << "the run finished before it was killed";
  // What the killed run kept is a prefix of the uninterrupted file.
  const std::string prefix = Read(killed + "/resume/frames.csv");
  EXPECT_EQ(Read(reference + "/resume/frames.csv").compare(0, prefix.size(), prefix), 0);

  // Without --resume the folder is refused; with it the run completes to the same bytes.
  const Finished refused = Run({"sweep", scenario, "--out", killed});
  EXPECT_EQ(refused.status, 2);
  EXPECT_THAT(refused.error, HasSubstr("pass --resume"));
  EXPECT_EQ(Lines(killed + "/resume/frames.csv"), kept);
  ASSERT_EQ(Run({"sweep", scenario, "--out", killed, "--threads", "2", "--resume"}).status, 0);
  EXPECT_EQ(Read(killed + "/resume/frames.csv"), Read(reference + "/resume/frames.csv"));
  EXPECT_EQ(Lines(killed + "/resume/timing.csv"), total);
}

// A full disk, made by a file size limit (RLIMIT_FSIZE, SIGXFSZ ignored so that writes fail
// with EFBIG): exit 1 naming the file and the error, run.json intact, and once there is room
// again --resume completes to the bytes of an uninterrupted run.
TEST_F(SweepCliTest, AFullDiskIsExitOneAndTheRunStaysResumable) {
  const std::string scenario = Scenario("full", 10);
  const std::string reference = (work_ / "reference").string(), full = (work_ / "full").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", reference, "--threads", "2"}).status, 0);
  const uintmax_t size = fs::file_size(reference + "/full/frames.csv");
  // bash's ulimit -f counts 1024-byte blocks; the limit falls in the middle of frames.csv.
  const std::string limit = std::to_string(size / 2 / 1024);
  const std::string limited = "ulimit -f " + limit + "; trap '' XFSZ; exec \"$0\" \"$@\"";
  for (int attempt = 0; attempt < 2; ++attempt) {
    std::vector<std::string> args = {
        "-c", limited, MARKERBENCH_BINARY, "sweep", scenario, "--out", full, "--threads", "2"};
    if (attempt == 1) args.push_back("--resume");
    const Finished filled = RunProgram("/bin/bash", args);
    EXPECT_EQ(filled.status, 1) << filled.error;
    EXPECT_THAT(filled.error, HasSubstr("full/frames.csv: write failed: File too large"));
    EXPECT_THAT(Read(full + "/full/run.json"), HasSubstr("\"fingerprint\""));
    EXPECT_LT(fs::file_size(full + "/full/frames.csv"), size);
  }
  ASSERT_EQ(Run({"sweep", scenario, "--out", full, "--threads", "2", "--resume"}).status, 0);
  EXPECT_EQ(Read(full + "/full/frames.csv"), Read(reference + "/full/frames.csv"));
  EXPECT_EQ(Lines(full + "/full/timing.csv"), Lines(reference + "/full/timing.csv"));
}

TEST_F(SweepCliTest, TornTailIsCutOnResume) {
  const std::string scenario = Scenario("torn", 2);
  const std::string out = (work_ / "out").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", out}).status, 0);
  const std::string full = Read(out + "/torn/frames.csv");
  // Keep the header, three rows and half of the fourth, as a crash might.
  size_t cut = 0;
  for (int line = 0; line < 4; ++line) cut = full.find('\n', cut) + 1;
  cut += 20;
  fs::resize_file(out + "/torn/frames.csv", cut);
  ASSERT_EQ(Run({"sweep", scenario, "--out", out, "--resume"}).status, 0);
  EXPECT_EQ(Read(out + "/torn/frames.csv"), full);
}

// The rows of a run resumed by another build (here: run.json says commit 0123abc wrote them)
// keep both builds: a warning, run.json's and the manifest's `builds` (each with the frame it
// started at), and a line of the report. A resume that keeps no row names this build alone.
TEST_F(SweepCliTest, AResumeByAnotherBuildIsRecorded) {
  const std::string scenario = Scenario("rebuilt", 2);
  const std::string out = (work_ / "out").string(), run_json = out + "/rebuilt/run.json";
  ASSERT_EQ(Run({"sweep", scenario, "--out", out}).status, 0);
  const std::string full = Read(out + "/rebuilt/frames.csv");
  const auto from_frame = [](nlohmann::json build, int frame) {
    build["from_frame"] = frame;
    return build;
  };
  nlohmann::json run = ReadManifest(run_json);
  ASSERT_EQ(run["builds"], nlohmann::json::array({from_frame(BuildIdentity(), 0)}));
  const nlohmann::json earlier_from_0 =
      from_frame({{"git_commit", "0123abc"}, {"git_diff_sha256", ""}}, 0);
  run["builds"] = nlohmann::json::array({earlier_from_0});
  WriteManifest(run_json, run);
  // The header and nine rows: six frames, each of one marker (the tag's two trackers' rows, or
  // ArUco's one).
  size_t cut = 0;
  for (int line = 0; line < 10; ++line) cut = full.find('\n', cut) + 1;
  fs::resize_file(out + "/rebuilt/frames.csv", cut);

  const Finished resumed = Run({"sweep", scenario, "--out", out, "--resume"});
  ASSERT_EQ(resumed.status, 0) << resumed.error;
  EXPECT_EQ(Read(out + "/rebuilt/frames.csv"), full);
  EXPECT_THAT(resumed.error,
              HasSubstr("rebuilt: warning: resuming at frame 6 with " + BuildText(BuildIdentity()) +
                        "; the frames before were written by commit 0123abc"));
  const nlohmann::json both =
      nlohmann::json::array({earlier_from_0, from_frame(BuildIdentity(), 6)});
  EXPECT_EQ(ReadManifest(run_json)["builds"], both);
  const nlohmann::json entry = ReadManifest(out + "/manifest.json")["scenarios"]["rebuilt"];
  EXPECT_EQ(entry["builds"], both);
  EXPECT_EQ(entry["resumed_at_frame"], 6);
  ASSERT_EQ(Run({"report", out, "--no-plots"}).status, 0);
  EXPECT_THAT(Read(out + "/report.md"),
              HasSubstr("Rows of `rebuilt` were also written by another build:** commit 0123abc "));

  // Resumed again by this build from the torn header: no row of 0123abc's is kept.
  fs::resize_file(out + "/rebuilt/frames.csv", full.find('\n') + 5);
  const Finished again = Run({"sweep", scenario, "--out", out, "--resume"});
  ASSERT_EQ(again.status, 0) << again.error;
  EXPECT_THAT(again.error, Not(HasSubstr("warning")));
  EXPECT_EQ(ReadManifest(run_json)["builds"],
            nlohmann::json::array({from_frame(BuildIdentity(), 0)}));

  // A run.json written before builds were kept: its rows' build is unknown.
  run = ReadManifest(run_json);
  run.erase("builds");
  WriteManifest(run_json, run);
  fs::resize_file(out + "/rebuilt/frames.csv", cut);
  const Finished unknown = Run({"sweep", scenario, "--out", out, "--resume"});
  ASSERT_EQ(unknown.status, 0) << unknown.error;
  const nlohmann::json unknown_from_0 = from_frame({{"git_commit", "unknown"}}, 0);
  EXPECT_THAT(unknown.error,
              HasSubstr("the frames before were written by " + BuildText(unknown_from_0)));
  EXPECT_EQ(ReadManifest(run_json)["builds"],
            nlohmann::json::array({unknown_from_0, from_frame(BuildIdentity(), 6)}));

  // A complete run resumed by another build gains no row, so neither a warning nor a build.
  run = ReadManifest(run_json);
  run["builds"] = nlohmann::json::array({earlier_from_0});
  WriteManifest(run_json, run);
  const Finished complete = Run({"sweep", scenario, "--out", out, "--resume"});
  ASSERT_EQ(complete.status, 0) << complete.error;
  EXPECT_THAT(complete.error, Not(HasSubstr("warning")));
  EXPECT_EQ(ReadManifest(run_json)["builds"], nlohmann::json::array({earlier_from_0}));
  EXPECT_EQ(Read(out + "/rebuilt/frames.csv"), full);
}

// A run.json that is not an object of the keys it should have is bad input: exit 2 naming the file
// and the key, and the run's files are left alone.
TEST_F(SweepCliTest, ResumeRefusesARunJsonItCannotRead) {
  const std::string scenario = Scenario("damaged", 1);
  const std::string out = (work_ / "out").string(), run_json = out + "/damaged/run.json";
  ASSERT_EQ(Run({"sweep", scenario, "--out", out}).status, 0);
  const nlohmann::json written = ReadManifest(run_json);
  const std::string frames = Read(out + "/damaged/frames.csv");
  const auto with = [&](const std::string& key, const nlohmann::json& value) {
    nlohmann::json run = written;
    run[key] = value;
    return run;
  };
  const std::vector<std::pair<nlohmann::json, std::string>> cases = {
      {nlohmann::json::array(), ": expected a JSON object, got array"},
      {with("fingerprint", 5), ": key 'fingerprint': expected a string, got 5"},
      {with("shard", 3), ": key 'shard': expected {index, count}, got 3"},
      {with("shard", {{"index", "a"}, {"count", 1}}),
       ": key 'shard': key 'index': expected an integer, got \"a\""},
      {with("complete", "yes"), ": key 'complete': expected true or false, got \"yes\""}};
  for (const auto& [run, message] : cases) {
    SCOPED_TRACE(run.dump());
    WriteManifest(run_json, run);
    const Finished f = Run({"sweep", scenario, "--out", out, "--resume"});
    EXPECT_EQ(f.status, 2);
    EXPECT_THAT(f.error, HasSubstr(run_json + message));
    EXPECT_EQ(Read(out + "/damaged/frames.csv"), frames);
  }
}

// A complete run has nothing to resume: its files, run.json and manifest stay as they were (run
// again, its manifest entry took the cost of a run of nothing). One whose last row was written but
// not its completion (killed in between) is completed: run.json says so, and the manifest has it.
TEST_F(SweepCliTest, ACompleteRunIsLeftAsItWas) {
  const std::string scenario = Scenario("done", 1);
  const std::string out = (work_ / "out").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", out}).status, 0);
  const std::string frames = Read(out + "/done/frames.csv"), run = Read(out + "/done/run.json"),
                    manifest = Read(out + "/manifest.json");
  const Finished again = Run({"sweep", scenario, "--out", out, "--resume"});
  ASSERT_EQ(again.status, 0) << again.error;
  EXPECT_THAT(again.error, HasSubstr("done: complete (frames.csv); nothing to resume"));
  EXPECT_EQ(Read(out + "/done/frames.csv"), frames);
  EXPECT_EQ(Read(out + "/done/run.json"), run);
  EXPECT_EQ(Read(out + "/manifest.json"), manifest);

  nlohmann::json incomplete = ReadManifest(out + "/done/run.json");
  incomplete["complete"] = false;
  WriteManifest(out + "/done/run.json", incomplete);
  fs::remove(out + "/manifest.json");
  const Finished completed = Run({"sweep", scenario, "--out", out, "--resume"});
  ASSERT_EQ(completed.status, 0) << completed.error;
  EXPECT_THAT(completed.error, Not(HasSubstr("nothing to resume")));
  EXPECT_EQ(Read(out + "/done/frames.csv"), frames);
  EXPECT_TRUE(ReadManifest(out + "/done/run.json")["complete"].get<bool>());
  const nlohmann::json entry = ReadManifest(out + "/manifest.json")["scenarios"]["done"];
  EXPECT_EQ(entry["resumed_at_frame"], entry["frames"]);

  // With --zstd a complete run is compressed, and then it is complete as .zst.
  ASSERT_EQ(Run({"sweep", scenario, "--out", out, "--resume", "--zstd"}).status, 0);
  EXPECT_FALSE(fs::exists(out + "/done/frames.csv"));
  EXPECT_TRUE(fs::exists(out + "/done/frames.csv.zst"));
  EXPECT_TRUE(fs::exists(out + "/done/timing.csv.zst"));
  const Finished packed = Run({"sweep", scenario, "--out", out, "--resume"});
  ASSERT_EQ(packed.status, 0) << packed.error;
  EXPECT_THAT(packed.error, HasSubstr("done: complete (frames.csv.zst); nothing to resume"));
}

// A run.json whose builds are not a list of them is bad input: exit 2 naming the file and key.
TEST_F(SweepCliTest, ResumeRefusesBuildsItCannotRead) {
  const std::string scenario = Scenario("unread", 1);
  const std::string out = (work_ / "out").string(), run_json = out + "/unread/run.json";
  ASSERT_EQ(Run({"sweep", scenario, "--out", out}).status, 0);
  const nlohmann::json written = ReadManifest(run_json);
  const std::string full = Read(out + "/unread/frames.csv");
  // A count that is not one, a map, an empty list, a list not from frame 0, and not a list.
  for (const nlohmann::json& builds :
       {nlohmann::json::array({{{"git_commit", "0123abc"}, {"from_frame", "zero"}}}),
        nlohmann::json::object(),
        nlohmann::json::array(),
        nlohmann::json::array({{{"git_commit", "0123abc"}, {"from_frame", 1}}}),
        nlohmann::json("0123abc")}) {
    SCOPED_TRACE(builds.dump());
    nlohmann::json run = written;
    run["builds"] = builds;
    WriteManifest(run_json, run);
    fs::resize_file(out + "/unread/frames.csv", full.size() - 1);
    const Finished f = Run({"sweep", scenario, "--out", out, "--resume"});
    EXPECT_EQ(f.status, 2);
    EXPECT_THAT(f.error,
                HasSubstr(run_json + ": key 'builds': expected a list of the builds that wrote " +
                          "its rows, the first from frame 0, each with a 'from_frame' count, " +
                          "got " + builds.dump()));
  }
}

TEST_F(SweepCliTest, ResumeRefusesAnotherScenariosFolder) {
  const std::string out = (work_ / "out").string();
  ASSERT_EQ(Run({"sweep", Scenario("same", 1), "--out", out}).status, 0);
  const std::string before = Read(out + "/same/frames.csv");
  // Same name, different trials: a different scenario.
  const Finished f = Run({"sweep", Scenario("same", 2), "--out", out, "--resume"});
  EXPECT_EQ(f.status, 2);
  EXPECT_THAT(f.error, HasSubstr("was written by a different scenario"));
  EXPECT_EQ(Read(out + "/same/frames.csv"), before);
}

// A second sweep into a folder that one is writing gets exit 2 naming the lock file, and the
// first run's frames.csv is what it would have been alone.
TEST_F(SweepCliTest, ASecondWriterIsRefused) {
  const std::string scenario = Scenario("locked", 30);
  const std::string reference = (work_ / "reference").string(), out = (work_ / "out").string();
  ASSERT_EQ(Run({"sweep", scenario, "--out", reference, "--threads", "2"}).status, 0);
  const pid_t first = Start({"sweep", scenario, "--out", out, "--threads", "2"});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(out + "/locked/frames.csv") && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const Finished second = Run({"sweep", scenario, "--out", out, "--resume"});
  EXPECT_EQ(second.status, 2);
  EXPECT_THAT(second.error, HasSubstr(out + "/markerbench.lock: another markerbench sweep"));
  ASSERT_EQ(Wait(first).status, 0);
  EXPECT_EQ(Read(out + "/locked/frames.csv"), Read(reference + "/locked/frames.csv"));
}

// --overwrite starts from an empty folder: nothing of the earlier run stays.
TEST_F(SweepCliTest, OverwriteLeavesNothingOfTheEarlierRun) {
  const std::string out = (work_ / "out").string();
  ASSERT_EQ(Run({"sweep", Scenario("again", 1), "--out", out}).status, 0);
  std::ofstream(out + "/again/examples/stale.png") << "old";
  ASSERT_EQ(Run({"sweep", Scenario("again", 1), "--out", out, "--overwrite"}).status, 0);
  EXPECT_FALSE(fs::exists(out + "/again/examples/stale.png"));
  EXPECT_TRUE(fs::exists(out + "/again/examples/apriltag.png"));
}

}  // namespace
}  // namespace markerbench
