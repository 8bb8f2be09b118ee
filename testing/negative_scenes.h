// The negative set: frames that show no circle marker a-d (paper Fig. 3), for false-positive
// tests (issue 21). Each is a sheet of clutter drawn by the renderer at a random pose, with
// random noise and blur: blank paper, checkerboards, scattered squares, black dots, rings
// (disks with a concentric hole, no feature dot), coloured dots, and the other marker
// systems, e and f among them (negatives for every kind but their own; the label names the
// marker). Sheets that would be a circle marker by construction (a red and a blue disk of
// one size) are not drawn. Deterministic in the index: the same set on every machine.
#pragma once

#include <string>
#include <vector>

#include "renderer/render_frame.h"

namespace markerbench {

constexpr int kNegativeSetSize = 560;

struct NegativeFrame {
  std::string label;  // what it shows, e.g. "checkerboard 37"
  RenderedFrame frame;
  Degradations degradations;  // drawn for it
};

struct NegativeSceneOptions {
  // The optics' blur σ (px) of a frame: one of these (not none), each equally likely. The set's
  // own reach 4 px; the paper's blur sweep reaches 10 (kPaperBlurSigmasPx: its heavier half).
  std::vector<double> blur_sigmas_px = {0.0, 0.0, 1.0, 2.0, 4.0};
};
inline const std::vector<double> kPaperBlurSigmasPx = {5.0, 6.0, 7.0, 8.0, 9.0, 10.0};

// Frame `index` (0 <= index < kNegativeSetSize) of the set, RGB, from the default camera.
// Marker files of the other systems are read from scenarios/markers/ (the working directory
// is the source root, as in every test). Set 0 is the committed set the tests use; sets 1, 2,
// ... are fresh draws of the same kinds (other poses, sheets and noise), for the false-positive
// rate out of the sample the trackers were checked on. Other blurs leave every other draw of a
// frame as it is.
NegativeFrame RenderNegative(int index, int set = 0, const NegativeSceneOptions& options = {});

}  // namespace markerbench
