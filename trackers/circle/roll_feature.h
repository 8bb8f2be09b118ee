// The rotation about the circle's axis for markers (e) and (f) of the paper's Fig. 3, whose
// circle (and centre) fix every other degree of freedom: without m1 the refinement's Jacobian
// has rank 5 (circle-method.md, erratum 7). The design painted inside the circle (the mouth,
// the wedge) gives it, and its centre m0 too, in two steps:
// - its first moment about the circle's centre, M = ∫ w(|q|) (I(q) - I_disk) q dq over a disk
//   window w of radius 0.8 R: blur preserves first moments (§11) and noise has zero mean, so
//   M measured from the pixels, mapped into the plane by the pose, points where the design's
//   M points once the pose's roll is right, whatever the start;
// - then Gauss-Newton fits the roll and centre (and a gain and offset) to the pixels near
//   the design's ink, each modelled as the design blurred as the image is (blurred_design.h):
//   the maximum-likelihood estimate under Gaussian noise.
// Both designs are symmetric about M, so a mirrored print is the same print turned: it is
// read as that.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "core/camera.h"
#include "core/image.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"
#include "trackers/circle/blurred_design.h"
#include "trackers/circle/circle_geometry.h"

namespace markerbench {

struct RollFeatureOptions {
  // The window: inside the circle, clear of its edge by 0.2 R; it holds the whole mouth of
  // (e) (out to 0.67 R) and most of the wedge of (f). Its weight falls linearly to 0 over
  // the outer taper, so that the pixels it cuts (on the wedge) count smoothly.
  double window_per_radius = 0.8;
  double taper_per_radius = 0.1;
  // The image's moment must reach this fraction of the design's (at the image's contrast):
  // else the design is not there to be read (too small, too blurred, not the marker).
  double min_moment_fraction = 0.5;
  int max_iterations = 10;  // Gauss-Newton on the roll, from the moment's
  // The design shows where it fits the pixels near its ink (RollAlignment): its misfit not
  // above max_misfit and its contrast ratio not off 1 by more than max_contrast_error, each
  // by more than min_significance standard errors of the noise; and the contrast ratio
  // measured to max_contrast_ratio_error at least (a design too small or too noisy to see
  // cannot be told from clutter). Measured over the paper sweeps (2450 frames of e and f,
  // 40 per value): misfits up to 0.11, contrast ratios 0.73-1.31, known to 0.04 or better;
  // the negative set's clutter that passes the other tests misfits by more (0.14 the least),
  // or shows other ratios, or has them only to 0.08 or worse.
  double max_misfit = 0.12;
  // Where the design's colour inside the circle is an intermediate one (f's grey wedge), the
  // print's or the camera's response places it anywhere between the disk's level and the
  // paper's (printed_appearance.h): there the contrast ratio measures its level, which must lie
  // in [kMinIntermediateLevel, kMaxIntermediateLevel] (RollAlignment::design_level), within
  // min_significance standard errors, in place of max_contrast_error.
  double max_contrast_error = 0.4;
  double max_contrast_ratio_error = 0.06;
  double min_significance = 1.0;
};

struct RollAlignment {
  Rigid3 cam_from_paper;      // turned about the paper frame's z axis
  double turn_rad = 0.0;      // how far it was turned
  double moment_ratio = 0.0;  // |image moment| / |design moment at the image's contrast|
  // Where the design's centre (m0) lies in that pose's paper frame: fitted with the roll,
  // from the design's edges (the nose of e, the wedge's sides for f). Ideally zero.
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  // RMS of the residuals that pixels two apart share, over the pixels near the design's ink,
  // as a fraction of the image's contrast.
  double misfit = 0.0;
  // The fitted gain of the printed design over the image's contrast (paper - disk): 1 where
  // the mouth or wedge shows at its printed level between the disk and the paper.
  double contrast_ratio = 0.0;
  // Where the design's colour shows, in PrintedLevel's measure (printed_appearance.h: the way
  // from the design's darkest luma to its lightest, the bounds' measure): the disk's level
  // moved by the colour's printed step from it times the contrast ratio (1 for e's mouth, 0.5
  // for f's wedge, upright or printed white on black).
  double design_level = 0.0;
  double contrast_ratio_error = 0.0;  // its standard error under the image's noise
  // The design is seen, and seen well enough to tell (RollFeatureOptions).
  bool shows_design = false;
};

class RollFeature {
 public:
  // `geometry` must have roll_from_design; `marker` is the file's (its layers are painted in
  // the marker frame, which geometry.marker_from_paper maps to the paper frame).
  RollFeature(const MarkerSpec& marker,
              const CircleGeometry& geometry,
              const RollFeatureOptions& options = {});

  // `cam_from_paper` right up to its roll (and, with `fit_center`, its centre); `paper_level`
  // the paper's grey level and `noise_sigma` the image's noise (0-255); `blur_sigma_px` the σ of
  // its edges (the blur with the pixel's area, as edge points measure it). nullopt when the
  // image's moment is too weak, or the window leaves the image.
  // `marker` must outlive this.
  std::optional<RollAlignment> Align(const Image8& image,
                                     const Camera& camera,
                                     const Rigid3& cam_from_paper,
                                     double paper_level,
                                     double blur_sigma_px,
                                     double noise_sigma,
                                     bool fit_center) const;

  const Eigen::Vector2d& design_moment() const { return design_moment_; }

 private:
  const MarkerSpec& marker_;
  BlurredDesign blurred_;
  Rigid3 marker_from_paper_;
  double window_m_ = 0.0;
  double taper_m_ = 0.0;
  double disk_luma_ = 0.0;
  double background_luma_ = 1.0;
  // Whether the design's colour inside the window is an intermediate one, and its and the
  // disk's printed levels (PrintedLevel, printed_appearance.h).
  bool intermediate_design_ = false;
  double design_level_ = 1.0;
  double disk_level_ = 0.0;
  Eigen::Vector2d design_moment_ = Eigen::Vector2d::Zero();  // paper frame, luma · m³
  RollFeatureOptions options_;
};

}  // namespace markerbench
