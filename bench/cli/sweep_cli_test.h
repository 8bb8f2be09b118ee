// Test fixture for markerbench sweep run as users run it (cli_test.h), with the small scenario
// the sweep, resume and external-tracker tests share.
#pragma once

#include <string>

#include "bench/cli/cli_test.h"
#include "core/test_files.h"

namespace markerbench {

class SweepCliTest : public CliTest {
 protected:
  // Two tag markers and their trackers under a three-value noise sweep.
  static std::string Scenario(const std::string& name, int trials) {
    return WriteTestFile(name + ".yaml",
                         "name: " + name + "\ncamera: " + kRoot +
                             "/scenarios/cameras/default.yaml\nmarkers:\n  - " + kRoot +
                             "/scenarios/markers/apriltag.yaml\n  - " + kRoot +
                             "/scenarios/markers/aruco.yaml\nequal_ink_area_m2: 0.01\ntrackers:\n"
                             "  - {name: apriltag}\n  - {name: apriltag-ippe}\n  - {name: aruco}\n"
                             "poses: {sampler: look_at, distance_m: 0.8, tilt_deg: [0, 40]}\n"
                             "render: {blur_sigma_px: 1.0}\n"
                             "sweep: {parameter: noise_var, values: [0.0, 0.05, 0.15]}\ntrials: " +
                             std::to_string(trials) + "\nseed: 9\n");
  }
};

}  // namespace markerbench
