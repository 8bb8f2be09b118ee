// libFuzzer target: every tracker's Track() on arbitrary image bytes and sizes. Input: a
// tracker byte, width - 1, height - 1, a channels byte (1 or 3; other values give a
// malformed buffer), then pixels, repeated to fill the image. Each tracker sees the first of
// scenarios/markers/*.yaml it can track, through a camera of the image's size. Track() must
// return a status: an exception, a crash, a leak or a slow input is a finding.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/marker_yaml.h"
#include "trackers/tracker_factory.h"

namespace {

struct TrackerUnderTest {
  std::unique_ptr<markerbench::Tracker> tracker;
  markerbench::MarkerSpec marker;
};

std::vector<TrackerUnderTest>& Trackers() {
  static std::vector<TrackerUnderTest> trackers = [] {
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(
             std::string(MARKERBENCH_SOURCE_DIR) + "/scenarios/markers")) {
      files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    std::vector<TrackerUnderTest> made;
    for (const std::string& name : markerbench::TrackerNames()) {
      TrackerUnderTest t;
      t.tracker = markerbench::MakeTracker(name, nullptr);
      for (const std::string& file : files) {
        t.marker = markerbench::LoadMarkerYaml(file);
        if (t.tracker->CanTrack(t.marker)) break;
      }
      made.push_back(std::move(t));
    }
    return made;
  }();
  return trackers;
}

}  // namespace

// Builds the trackers (dictionaries, marker files) before the first input, whose time the
// per-input timeout would otherwise charge with them.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  Trackers();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace markerbench;
  if (size < 4) return 0;
  std::vector<TrackerUnderTest>& trackers = Trackers();
  TrackerUnderTest& t = trackers[data[0] % trackers.size()];
  Image8 image;
  image.width = data[1] + 1;
  image.height = data[2] + 1;
  image.channels = data[3] == 3 ? 3 : data[3] == 1 ? 1 : data[3] % 5;
  const size_t pixels =
      static_cast<size_t>(image.width) * image.height * std::max(image.channels, 1);
  const size_t payload = size - 4;
  // A zero channels byte stands for a buffer one byte short.
  image.pixels.resize(data[3] == 0 ? pixels - 1 : pixels);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = payload ? data[4 + i % payload] : 0;
  }
  Camera camera;
  camera.width = image.width;
  camera.height = image.height;
  camera.fx = camera.fy = 1.2 * image.width;
  camera.cx = 0.5 * (image.width - 1);
  camera.cy = 0.5 * (image.height - 1);
  t.tracker->Reset();
  t.tracker->Track({&image, &camera, &t.marker});
  return 0;
}
