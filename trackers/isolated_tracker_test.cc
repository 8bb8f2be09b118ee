#include "trackers/isolated_tracker.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <stdexcept>
#include <thread>

#include "core/camera_yaml.h"
#include "core/marker_yaml.h"

namespace markerbench {
namespace {

// What the fake tracker does with a frame, chosen by the image's first pixel.
enum Behaviour : uint8_t { kAnswer = 0, kSegfault, kKillSelf, kHang, kThrow, kExit };

// Answers with the frames seen since its last Reset as the translation's x, and the image's
// width as y; misbehaves as the first pixel says.
class FakeTracker : public Tracker {
 public:
  TrackResult Track(const Observation& observation) override {
    switch (observation.image->pixels.front()) {
      case kSegfault: {
        volatile int* null = nullptr;
        *null = 1;
        break;
      }
      case kKillSelf:
        std::raise(SIGKILL);
        break;
      case kHang:
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
      case kThrow:
        throw std::runtime_error("bad frame");
      case kExit:
        ::_exit(7);
    }
    TrackResult result;
    result.status = TrackStatus::kOk;
    ++frames_;
    result.hypotheses.push_back(
        Rigid3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(frames_, observation.image->width, 0)));
    result.keypoints_px.push_back({1.5, 2.5});
    result.message = "fine";
    return result;
  }
  bool CanTrack(const MarkerSpec& marker) const override { return marker.name == "apriltag"; }
  void Reset() override { frames_ = 0; }
  std::vector<std::pair<std::string, std::string>> Parameters() const override {
    return {{"fake", "yes"}};
  }

 private:
  int frames_ = 0;
};

class IsolatedTrackerTest : public ::testing::Test {
 protected:
  IsolatedTrackerTest()
      : camera_(LoadCameraYaml("scenarios/cameras/default.yaml")),
        markers_({LoadMarkerYaml("scenarios/markers/apriltag.yaml"),
                  LoadMarkerYaml("scenarios/markers/circle_d.yaml")}) {}

  TrackResult TrackWith(IsolatedTracker* tracker, Behaviour behaviour, int width = 32) {
    Image8 image;
    image.width = width;
    image.height = 16;
    image.pixels.assign(static_cast<size_t>(width) * 16, 0);
    image.pixels.front() = behaviour;
    return tracker->Track({&image, &camera_, &markers_[0]});
  }

  std::unique_ptr<IsolatedTracker> Isolated(double timeout_s = 60.0) {
    return std::make_unique<IsolatedTracker>([] { return std::make_unique<FakeTracker>(); },
                                             &camera_,
                                             &markers_,
                                             IsolatedTrackerOptions{timeout_s});
  }

  Camera camera_;
  std::vector<MarkerSpec> markers_;
};

TEST_F(IsolatedTrackerTest, ReturnsTheWorkersResultAndTime) {
  const auto tracker = Isolated();
  EXPECT_TRUE(tracker->CanTrack(markers_[0]));
  EXPECT_FALSE(tracker->CanTrack(markers_[1]));
  EXPECT_EQ(tracker->Parameters().front().first, "fake");
  const TrackResult result = TrackWith(tracker.get(), kAnswer, 40);
  ASSERT_EQ(result.status, TrackStatus::kOk);
  ASSERT_EQ(result.hypotheses.size(), 1u);
  EXPECT_EQ(result.hypotheses[0].translation, Eigen::Vector3d(1, 40, 0));
  EXPECT_EQ(result.hypotheses[0].rotation, Eigen::Matrix3d::Identity());
  ASSERT_EQ(result.keypoints_px.size(), 1u);
  EXPECT_EQ(result.keypoints_px[0], Eigen::Vector2d(1.5, 2.5));
  EXPECT_EQ(result.message, "fine");
  ASSERT_TRUE(result.time_ms.has_value());
  EXPECT_GE(*result.time_ms, 0.0);
}

// The worker keeps its tracker's state between frames until Reset, like a tracker in-process.
TEST_F(IsolatedTrackerTest, StateLastsUntilReset) {
  const auto tracker = Isolated();
  EXPECT_EQ(TrackWith(tracker.get(), kAnswer).hypotheses[0].translation.x(), 1);
  EXPECT_EQ(TrackWith(tracker.get(), kAnswer).hypotheses[0].translation.x(), 2);
  tracker->Reset();
  EXPECT_EQ(TrackWith(tracker.get(), kAnswer).hypotheses[0].translation.x(), 1);
}

// A crash of any kind is an error row naming it, and the next frame gets a fresh worker.
TEST_F(IsolatedTrackerTest, ACrashIsAnErrorAndTheWorkerRestarts) {
  const auto tracker = Isolated();
  TrackWith(tracker.get(), kAnswer);
  const TrackResult killed = TrackWith(tracker.get(), kKillSelf);
  EXPECT_EQ(killed.status, TrackStatus::kError);
  EXPECT_EQ(killed.message,
            "tracker worker killed by signal 9 (Killed); restarted for the next frame");
  EXPECT_EQ(TrackWith(tracker.get(), kAnswer).hypotheses[0].translation.x(), 1);

  const TrackResult segfault = TrackWith(tracker.get(), kSegfault);
  EXPECT_EQ(segfault.status, TrackStatus::kError);
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_UNDEFINED__)
  // A sanitizer catches the null store first and ends the worker its own way.
  EXPECT_THAT(segfault.message, ::testing::StartsWith("tracker worker "));
#else
  EXPECT_EQ(segfault.message,
            "tracker worker killed by signal 11 (Segmentation fault); restarted for the next "
            "frame");
#endif
  EXPECT_EQ(TrackWith(tracker.get(), kAnswer).status, TrackStatus::kOk);

  const TrackResult exited = TrackWith(tracker.get(), kExit);
  EXPECT_EQ(exited.message, "tracker worker exited with status 7; restarted for the next frame");
  EXPECT_EQ(TrackWith(tracker.get(), kAnswer).status, TrackStatus::kOk);
}

TEST_F(IsolatedTrackerTest, AHangIsKilledAtTheTimeLimit) {
  const auto tracker = Isolated(0.3);
  const auto start = std::chrono::steady_clock::now();
  const TrackResult hung = TrackWith(tracker.get(), kHang);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  EXPECT_EQ(hung.status, TrackStatus::kError);
  EXPECT_EQ(hung.message,
            "tracker worker timed out after 0.3 s and was killed; restarted for the next frame");
  EXPECT_EQ(TrackWith(tracker.get(), kAnswer).status, TrackStatus::kOk);
}

TEST_F(IsolatedTrackerTest, AnExceptionIsAnErrorAndTheWorkerLives) {
  const auto tracker = Isolated();
  TrackWith(tracker.get(), kAnswer);
  const TrackResult thrown = TrackWith(tracker.get(), kThrow);
  EXPECT_EQ(thrown.status, TrackStatus::kError);
  EXPECT_EQ(thrown.message, "exception: bad frame");
  EXPECT_EQ(TrackWith(tracker.get(), kAnswer).hypotheses[0].translation.x(), 2);
}

TEST_F(IsolatedTrackerTest, RefusesAMarkerItWasNotGiven) {
  const auto tracker = Isolated();
  const MarkerSpec other = markers_[0];
  Image8 image;
  image.width = image.height = 16;
  image.pixels.assign(256, 0);
  EXPECT_EQ(tracker->Track({&image, &camera_, &other}).status, TrackStatus::kError);
}

// Workers of several threads run side by side; closing one tracker ends only its worker.
TEST_F(IsolatedTrackerTest, WorkersOfManyThreads) {
  std::vector<std::thread> threads;
  std::vector<int> answers(4, 0);
  for (size_t i = 0; i < answers.size(); ++i) {
    threads.emplace_back([&, i] {
      for (int round = 0; round < 3; ++round) {
        const auto tracker = Isolated();
        for (int frame = 0; frame < 5; ++frame) {
          answers[i] += TrackWith(tracker.get(), kAnswer).status == TrackStatus::kOk;
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (const int n : answers) EXPECT_EQ(n, 15);
}

}  // namespace
}  // namespace markerbench
