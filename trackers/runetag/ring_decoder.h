// Steps 3-5 of the RUNETag pipeline (baselines.md): find the image of one of the marker's
// rings, rectify the plane with K in both orientations the ring allows (circle-method.md
// §4.7), fit the three rings, sweep the 43 sectors and decode.
//
// Deliberate differences: the original rectifies with the conic of each dot of each pair of
// dots; we rectify with the conic of a whole ring, found by RANSAC over the dot centres (a
// 5-point conic through dots of similar size, scored by the PND distance of all centres).
// A ring 20-60 dots long fixes the plane orientation far better than one 2-6 px dot. With
// read_slot_levels (runetag-improved), besides the dots found, we read every slot's grey
// level through the rectified plane, which reads dots that the threshold merged or lost; the
// better of the two readings is decoded.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "trackers/runetag/dot_detector.h"

namespace markerbench {

struct RingDecoderOptions {
  // Ours (runetag-improved): also decode the slots' grey levels, and the dots read as
  // dots lost (RuneDecodeMissingDots). The original decodes the dots found, a missing dot
  // being a wrong symbol.
  bool read_slot_levels = false;
  bool decode_missing_dots = false;
  int max_ransac_iterations = 1000;
  int ring_candidates = 3;  // distinct RANSAC conics tried, most inliers first
  // PND distance of a dot centre to the ring conic: at most ring_tolerance_px, and at most
  // ring_tolerance_radii dot radii, since rings are only 3 outer-dot radii apart (R / 6).
  double ring_tolerance_px = 1.0;
  double ring_tolerance_radii = 0.7;
  int min_ring_dots = 8;
  double neighbour_reach = 5.0;  // RANSAC samples dots with a neighbour within this many radii
  // A dot is on ring j when |radius / R - ring fraction j| < radius_tolerance, and in the
  // sector whose angle is within angle_tolerance sector widths. The original's slot fitter
  // takes the nearest slot (half the ring spacing, half a sector); ours (runetag-improved)
  // leaves dots between slots unread: 0.04 and 0.3.
  double radius_tolerance = 1.0 / 12.0;
  double angle_tolerance = 0.5;
  // Sweeping the slots: the paper level is sampled at these radii (units of R, clear of the
  // dots); a ring is read when its dark level is below the paper by max(min_slot_contrast,
  // slot_contrast_per_noise × the noise); a slot within slot_margin (fraction of that
  // contrast) of the midway level is erased.
  std::array<double, 2> paper_radii = {0.5, 1.15};
  double min_slot_contrast = 20.0;
  double slot_contrast_per_noise = 4.0;
  double slot_margin = 0.1;
  // A dot whose semi-major axis exceeds its slot's imaged dot's by this factor is merged
  // with a neighbour (the threshold bridged their gap) and is not matched for the pose.
  double max_dot_growth = 0.0;  // 0: off (the original); runetag-improved: 1.5
  // The original's findPose drops a dot whose neighbour on its ring, one sector either side,
  // was read otherwise than the codeword (a merged blob there is likely off-centre).
  bool exclude_next_to_errors = true;
  // Ours (runetag-improved) reads the dots through the lens: each dot's ray undistorted, and
  // each ring's ellipse fitted where the pinhole would image its dots. The original's detector
  // knows the intrinsics alone and takes the image's pixels as a pinhole's (only its findPose
  // knows the lens), so under distortion its rings are no conics of the plane it assumes.
  bool undistort_dots = false;
};

struct RingMatch {
  int id = -1;
  int mismatches = 0;  // sectors read with another symbol
  int erasures = 0;    // sectors with no dot seen
  int ring_dots = 0;   // RANSAC inliers of the ring conic
  // (index into the dots, marker slot 3 * sector + ring) for every dot that agrees with the
  // decoded codeword.
  std::vector<std::pair<int, int>> dot_slots;
};

// The best-decoding ring hypothesis, or nullopt. seed makes RANSAC deterministic;
// expected_id is the marker that decode_missing_dots may confirm.
std::optional<RingMatch> MatchRings(const std::vector<ImagedDot>& dots,
                                    const DotImage& image,
                                    const Camera& camera,
                                    uint64_t seed,
                                    int expected_id,
                                    const RingDecoderOptions& options);

}  // namespace markerbench
