#include "trackers/tracker_factory.h"

#include "core/joined.h"
#include "core/yaml_reader.h"
#include "trackers/apriltag/apriltag_tracker.h"
#include "trackers/artkplus/artkplus_tracker.h"
#include "trackers/aruco/aruco_tracker.h"
#include "trackers/circle/circle_tracker.h"
#include "trackers/runetag/runetag_tracker.h"

namespace markerbench {
namespace {

// FromYaml validates; the defaults are valid.
template <typename Options>
Options ReadOptions(const YamlMap* map) {
  return map ? Options::FromYaml(*map) : Options{};
}

// An improved variant's options: its preset, with the map's keys over it.
template <typename Options>
Options ReadOptionsOver(const YamlMap* map, const Options& preset) {
  return map ? Options::FromYaml(*map, preset) : preset;
}

}  // namespace

std::vector<std::string> TrackerNames() {
  return {"apriltag",
          "apriltag-ippe",
          "artkplus",
          "artkplus-improved",
          "aruco",
          "circle",
          "runetag",
          "runetag-improved"};
}

bool RunsThirdPartyCCode(const std::string& name) {
  return name == "apriltag" || name == "apriltag-ippe";
}

std::unique_ptr<Tracker> MakeTracker(const std::string& name, const YamlMap* options) {
  if (name == "apriltag" || name == "apriltag-ippe") {
    return MakeAprilTagTracker(ReadOptions<AprilTagOptions>(options),
                               name == "apriltag" ? AprilTagPose::kNative : AprilTagPose::kIppe);
  }
  if (name == "artkplus") return MakeArtkPlusTracker(ReadOptions<ArtkPlusOptions>(options));
  if (name == "artkplus-improved") {
    return MakeArtkPlusTracker(ReadOptionsOver(options, ArtkPlusOptions::Improved()));
  }
  if (name == "aruco") return MakeArucoTracker(ReadOptions<ArucoOptions>(options));
  if (name == "runetag") return MakeRuneTagTracker(ReadOptions<RuneTagOptions>(options));
  if (name == "runetag-improved") {
    return MakeRuneTagTracker(ReadOptionsOver(options, RuneTagOptions::Improved()));
  }
  if (name == "circle") return MakeCircleTracker(ReadOptions<CircleTrackerOptions>(options));
  throw ConfigError("unknown tracker '" + name + "'; available: " + Joined(TrackerNames()));
}

}  // namespace markerbench
