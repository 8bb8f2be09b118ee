// A tracker in a worker process: the same results as in-process, and a crash, a hang, an
// exception or an exit on one frame is that frame's `error` row, with the next frame tracked
// by a fresh worker. The worker is this test program, started with --serve-test-tracker.
#include "trackers/isolated/isolated_tracker.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>

#include "trackers/isolated/tracker_worker.h"
#include "trackers/isolated/worker_protocol.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// What the test tracker does is the image's first pixel.
enum Behaviour : uint8_t { kPose = 0, kSegfault = 1, kHang = 2, kThrow = 3, kExit = 4, kCount = 5 };

// Returns a pose made of the image's bytes, so that every frame's result differs.
class ScriptedTracker : public Tracker {
 public:
  TrackResult Track(const Observation& observation) override {
    const Image8& image = *observation.image;
    TrackResult result;
    switch (image.pixels[0]) {
      case kSegfault:
        std::raise(SIGSEGV);
        break;
      case kHang:
        for (;;) pause();
      case kThrow:
        throw std::runtime_error("scripted failure");
      case kExit:
        std::_Exit(7);
      case kCount:
        result.message = "frames since reset: " + std::to_string(frames_since_reset_);
        break;
      default:
        break;
    }
    ++frames_since_reset_;
    result.status = TrackStatus::kOk;
    for (int h = 0; h < 2; ++h) {
      Rigid3 pose;
      pose.rotation(0, 1) = image.pixels[1] / 7.0 + h;
      pose.translation = Eigen::Vector3d(0.1 * image.pixels[2], 1.0 / 3.0, observation.camera->fx);
      result.hypotheses.push_back(pose);
    }
    result.keypoints_px = {{0.5, 1.0 / 9.0}, {image.width, image.height}};
    result.message += " on " + observation.marker->name;
    return result;
  }
  bool CanTrack(const MarkerSpec& marker) const override { return marker.name != "untrackable"; }
  void Reset() override { frames_since_reset_ = 0; }
  std::vector<std::pair<std::string, std::string>> Parameters() const override {
    return {{"scripted", "yes"}};
  }

 private:
  int frames_since_reset_ = 0;
};

MarkerSpec TestMarker() {
  MarkerSpec marker;
  marker.name = "scripted_marker";
  return marker;
}

std::string g_program;  // this test program's file, which serves as its own worker

IsolationOptions WorkerOptions(double timeout_s = 20.0) {
  IsolationOptions options;
  options.worker_argv = {kThisProgram, "--serve-test-tracker"};
  options.timeout_s = timeout_s;
  return options;
}

struct Frame {
  Image8 image;
  Camera camera;
  MarkerSpec marker = TestMarker();

  explicit Frame(uint8_t behaviour, uint8_t a = 0, uint8_t b = 0) {
    image.width = 32;
    image.height = 24;
    image.pixels.assign(32 * 24, 200);
    image.pixels[0] = behaviour;
    image.pixels[1] = a;
    image.pixels[2] = b;
    camera.fx = 612.25;
  }
  Observation observation() const { return {&image, &camera, &marker}; }
};

void ExpectSameResult(const TrackResult& a, const TrackResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  ASSERT_EQ(a.hypotheses.size(), b.hypotheses.size());
  for (size_t i = 0; i < a.hypotheses.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a.hypotheses[i], &b.hypotheses[i], sizeof(Rigid3)), 0) << i;
  }
  ASSERT_EQ(a.keypoints_px.size(), b.keypoints_px.size());
  for (size_t i = 0; i < a.keypoints_px.size(); ++i) {
    EXPECT_EQ(a.keypoints_px[i], b.keypoints_px[i]) << i;
  }
}

TEST(IsolatedTracker, GivesTheResultsOfTheTrackerInProcess) {
  IsolatedTracker isolated(std::make_unique<ScriptedTracker>(), WorkerOptions());
  ScriptedTracker local;
  for (uint8_t a = 0; a < 5; ++a) {
    const Frame frame(kPose, a, static_cast<uint8_t>(3 * a + 1));
    const TrackResult result = isolated.Track(frame.observation());
    ExpectSameResult(result, local.Track(frame.observation()));
    ASSERT_TRUE(result.time_ms.has_value());
    EXPECT_GE(*result.time_ms, 0.0);
  }
  EXPECT_TRUE(isolated.CanTrack(TestMarker()));
  MarkerSpec untrackable;
  untrackable.name = "untrackable";
  EXPECT_FALSE(isolated.CanTrack(untrackable));
  EXPECT_THAT(isolated.Parameters(),
              testing::ElementsAre(testing::Pair("scripted", "yes"),
                                   testing::Pair("isolated", "true"),
                                   testing::Pair("timeout_s", "20")));
}

TEST(IsolatedTracker, ResetReachesTheWorker) {
  IsolatedTracker isolated(std::make_unique<ScriptedTracker>(), WorkerOptions());
  const Frame count(kCount);
  EXPECT_THAT(isolated.Track(count.observation()).message, StartsWith("frames since reset: 0"));
  EXPECT_THAT(isolated.Track(count.observation()).message, StartsWith("frames since reset: 1"));
  isolated.Reset();
  EXPECT_THAT(isolated.Track(count.observation()).message, StartsWith("frames since reset: 0"));
}

// Under AddressSanitizer the worker reports the SEGV and exits with status 1 instead.
#if defined(MARKERBENCH_ASAN)
constexpr const char* kSegfaultEnd = "the worker exited with status 1 on this frame";
#else
constexpr const char* kSegfaultEnd = "the worker was killed by signal SIGSEGV on this frame";
#endif

TEST(IsolatedTracker, EachFailureIsAnErrorRowAndTheNextFrameIsTracked) {
  // Only the hang waits for the short timeout: under AddressSanitizer a crashing worker can take
  // longer than that to write its report and exit.
  IsolatedTracker patient(std::make_unique<ScriptedTracker>(), WorkerOptions());
  IsolatedTracker impatient(std::make_unique<ScriptedTracker>(), WorkerOptions(0.5));
  struct Failure {
    IsolatedTracker* tracker;
    uint8_t behaviour;
    std::string message;
  };
  const std::vector<Failure> failures = {
      {&patient, kSegfault, kSegfaultEnd},
      {&impatient, kHang, "no result within timeout_s 0.5 s; the worker was stopped"},
      {&patient, kThrow, "exception: scripted failure"},
      {&patient, kExit, "the worker exited with status 7 on this frame"}};
  for (const Failure& failure : failures) {
    const TrackResult failed = failure.tracker->Track(Frame(failure.behaviour).observation());
    EXPECT_EQ(failed.status, TrackStatus::kError);
    EXPECT_EQ(failed.message, failure.message);
    EXPECT_EQ(failure.tracker->Track(Frame(kPose, 1, 2).observation()).status, TrackStatus::kOk)
        << "after " << failure.message;
  }
  // A restarted worker's tracker starts from Reset.
  patient.Track(Frame(kSegfault).observation());
  EXPECT_THAT(patient.Track(Frame(kCount).observation()).message,
              StartsWith("frames since reset: 0"));
}

TEST(IsolatedTracker, UnusableImagesNeverReachTheWorker) {
  IsolatedTracker isolated(std::make_unique<ScriptedTracker>(), WorkerOptions());
  Frame tiny(kSegfault);
  tiny.image.width = tiny.image.height = 4;
  tiny.image.pixels.resize(16);
  EXPECT_EQ(isolated.Track(tiny.observation()).status, TrackStatus::kNotDetected);
}

TEST(IsolatedTracker, AWorkerThatCannotStartIsAnError) {
  IsolationOptions missing = WorkerOptions();
  missing.worker_argv = {"/nonexistent/worker"};
  EXPECT_THROW(IsolatedTracker(std::make_unique<ScriptedTracker>(), missing), std::runtime_error);
  IsolationOptions silent = WorkerOptions();
  silent.worker_argv = {"/bin/true"};
  try {
    IsolatedTracker tracker(std::make_unique<ScriptedTracker>(), silent);
    ADD_FAILURE() << "/bin/true sent no ready message";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("(tried twice): no ready message"));
    EXPECT_THAT(e.what(), HasSubstr("the worker exited with status 0"));
  }
}

// A worker killed before its ready message (here: one that kills itself on its first start) is
// started once more, and the tracker works as one whose worker started the first time.
TEST(IsolatedTracker, AWorkerThatDiesWhileItStartsIsStartedOnceMore) {
  const std::filesystem::path started_once =
      std::filesystem::temp_directory_path() /
      ("isolated_tracker_test_started_" + std::to_string(getpid()));
  std::filesystem::remove(started_once);
  IsolationOptions flaky = WorkerOptions();
  flaky.worker_argv = {"/bin/sh",
                       "-c",
                       "if [ -e \"$1\" ]; then exec \"$0\" --serve-test-tracker; fi; "
                       "touch \"$1\"; kill -KILL $$",
                       g_program,
                       started_once.string()};
  IsolatedTracker isolated(std::make_unique<ScriptedTracker>(), flaky);
  EXPECT_TRUE(std::filesystem::exists(started_once)) << "the first start did not run";
  std::filesystem::remove(started_once);
  ScriptedTracker local;
  const Frame frame(kPose, 3, 4);
  ExpectSameResult(isolated.Track(frame.observation()), local.Track(frame.observation()));
}

// A worker started as kThisProgram is the running program, even after its file is removed (as a
// build does when it replaces it during a sweep): a copy of this test program removes itself,
// then tracks a frame in a worker (in main, --track-without-my-file) and exits 0 on its result.
TEST(IsolatedTracker, StartsItsWorkerFromTheRunningProgramWhoseFileIsGone) {
  const std::filesystem::path copy = std::filesystem::temp_directory_path() /
                                     ("isolated_tracker_test_copy_" + std::to_string(getpid()));
  std::filesystem::copy_file(g_program, copy, std::filesystem::copy_options::overwrite_existing);
  const std::string command = copy.string() + " --track-without-my-file";
  const int status = std::system(command.c_str());
  std::error_code ignored;
  const bool removed = !std::filesystem::exists(copy, ignored);
  std::filesystem::remove(copy, ignored);
  EXPECT_TRUE(removed) << "the copy did not remove its file";
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

// Workers started from several threads at once, each tracker failing on some frames: every
// thread sees exactly its own results (the race a fork of a multithreaded process had).
TEST(IsolatedTracker, WorkersOfManyThreads) {
  constexpr int kThreads = 4;
  constexpr int kFrames = 40;
  std::vector<std::vector<TrackResult>> results(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      IsolatedTracker isolated(std::make_unique<ScriptedTracker>(), WorkerOptions());
      for (int f = 0; f < kFrames; ++f) {
        const uint8_t behaviour = f % 7 == 3 ? kSegfault : f % 11 == 5 ? kThrow : kPose;
        isolated.Reset();
        results[t].push_back(isolated.Track(
            Frame(behaviour, static_cast<uint8_t>(t), static_cast<uint8_t>(f)).observation()));
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  ScriptedTracker local;
  for (int t = 0; t < kThreads; ++t) {
    for (int f = 0; f < kFrames; ++f) {
      const TrackResult& result = results[t][static_cast<size_t>(f)];
      if (f % 7 == 3) {
        EXPECT_EQ(result.message, kSegfaultEnd);
      } else if (f % 11 == 5) {
        EXPECT_EQ(result.message, "exception: scripted failure");
      } else {
        local.Reset();
        const Frame frame(kPose, static_cast<uint8_t>(t), static_cast<uint8_t>(f));
        ExpectSameResult(result, local.Track(frame.observation()));
      }
    }
  }
}

}  // namespace
}  // namespace markerbench

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--serve-test-tracker") == 0) {
    markerbench::ScriptedTracker tracker;
    return markerbench::ServeTrackerWorker(
        &tracker, {markerbench::TestMarker()}, markerbench::kWorkerFd);
  }
  if (argc == 2 && std::strcmp(argv[1], "--track-without-my-file") == 0) {
    std::filesystem::remove(std::filesystem::read_symlink(markerbench::kThisProgram));
    try {
      markerbench::IsolatedTracker isolated(std::make_unique<markerbench::ScriptedTracker>(),
                                            markerbench::WorkerOptions());
      const markerbench::Frame frame(markerbench::kPose, 3, 4);
      const markerbench::TrackResult result = isolated.Track(frame.observation());
      std::fprintf(stderr, "%s\n", result.message.c_str());
      return result.status == markerbench::TrackStatus::kOk ? 0 : 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 2;
    }
  }
  markerbench::g_program = std::filesystem::read_symlink(markerbench::kThisProgram).string();
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
