// Tracking mode's coarse step (issue 21): a predicted pose moved onto the frame by how far its
// circles' edges have shifted. The fit on the pixels (photometric_refinement.h) converges in a
// few steps only from within about a pixel of its result; a hand-held camera's prediction is
// often several pixels off, and a degree of unpredicted turn is 10-15 px at 0.6 m. Along rays
// normal to each circle's predicted image (through the lens), each edge is found on the raw
// image as the best step between two levels (its polarity and contrast those the last frame's
// fit measured), to a fraction of a pixel by the area under the profile about it. The pose is
// then fitted to those edge points by Gauss-Newton on their PND distances to the circles' images
// (conic.h; a linear fit of each ray's shift along its fixed normal misses the edge's curvature,
// (t·Δ)²/2R, up to 1.4 px for a 12 px move, and tilted the pose by up to 0.27 rad), the points
// farthest off left out; then all of it again from there. The move's own size counts too, so
// that directions the edges do not fix (the roll of a single circle or of two concentric ones)
// stay the prediction's.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"
#include "trackers/circle/circle_detector.h"
#include "trackers/circle/circle_geometry.h"

namespace markerbench {

// One round of the alignment's search for the edges.
struct EdgeShiftRound {
  int rays_per_circle;
  // The farthest an edge is looked for from its predicted place, in px (within the margins
  // that keep a ray clear of other ink).
  double max_shift_px;
  int samples_across;  // each sample the mean of this many, a pixel apart, across the ray
  // Of each circle's rays, the fraction that must find their edge. A ray's reach inward stops
  // short of other ink (b's feature dot, c's inner circle, d's centre dot), and an edge moved
  // beyond it is missed in the first round.
  double min_found_fraction;
};

// Its YAML keys (CircleTrackerOptions::FromYaml): edge_shift_alignment; the first round's
// edge_shift_first_rays, edge_shift_max_px, edge_shift_first_samples_across and
// edge_shift_first_min_found_fraction; the second's edge_shift_rays, edge_shift_second_max_px,
// edge_shift_samples_across and edge_shift_min_found_fraction; edge_shift_step_px,
// edge_shift_min_step_per_contrast and edge_shift_max_rms_px.
struct EdgeShiftOptions {
  // Off, a prediction more than half a pixel off takes the detector's edge pass from the
  // predicted ellipses instead.
  bool enabled = true;
  // The first round only brings the edges within the second's reach, which places them. In it,
  // 24 rays per circle instead of 32 took 12 % off the alignment's instructions, and no sequence
  // frame's success changed (16 fail edge_shift_alignment_test); 3 samples across instead of 5
  // took 15 % fewer, and on 128 rendered frames of the four disk markers its result moved by at
  // most 0.04 px at σ² 0.02 and 0.4 px at σ² 0.3, where 7 more frames declined and 3 fewer (1
  // across: 0.06 and 0.5 px, 10 more and 1 fewer; results/speed.md).
  EdgeShiftRound first{24, 16.0, 3, 0.4};
  EdgeShiftRound second{32, 4.0, 5, 0.6};
  double sample_step_px = 1.0;  // along a ray
  // A ray's edge counts where its step between the two levels is at least this fraction of
  // the contrast expected there, and of the expected polarity.
  double min_step_per_contrast = 0.5;
  // The alignment stands where the edge points' distances to its circles have an RMS of at
  // most this (a single profile's edge under σ² 0.3 and blur 2 px: about 1 px).
  double max_rms_px = 1.5;

  // false with `error` naming the key, by its YAML name, where a value is out of its range.
  bool IsValid(std::string* error) const;
};

struct EdgeShiftAlignment {
  Rigid3 cam_from_paper;
  double rms_px = 0.0;  // of the edge points kept: their distances to the circles' images
  int points_kept = 0;
  // The same points fitted from the circle's other tilt (OtherTilt, §4.7), and their RMS there:
  // how far the edges rule that tilt out.
  Rigid3 other_tilt;
  double other_tilt_rms_px = 0.0;
};

// `levels`: offset and gain per channel of the image (PixelFit::levels: a channel reads
// offset + gain · printed, 0-1); `clearances` per circle (CircleDetector::ClearanceOf);
// `blur_sigma_px` the edges' blur. nullopt, with `why` set, where too few rays find their edge
// or the edges do not agree on a pose.
std::optional<EdgeShiftAlignment> AlignByEdgeShifts(
    const Image8& image,
    const Camera& camera,
    const MarkerSpec& marker,
    const CircleGeometry& geometry,
    const std::vector<CircleDetector::EdgeClearance>& clearances,
    const Rigid3& predicted_cam_from_paper,
    const Eigen::VectorXd& levels,
    double blur_sigma_px,
    const EdgeShiftOptions& options,
    std::string* why);

}  // namespace markerbench
