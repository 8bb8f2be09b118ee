// Direct refinement of a circle marker's whole pose on the pixels around every edge of its
// printed design, for the designs photometric_refinement.h does not model: (e)'s nose and
// mouth and (f)'s wedge inside the circle (paper Fig. 3). Each pixel u is modelled as
//   I(u) = offset + gain · D_σ(p(u)),
// with p(u) the marker-plane point u sees at the pose and D_σ the printed design blurred as
// the image is, through the local map from pixels to the plane (blurred_design.h). Pose, σ,
// gain and offset are fitted by Levenberg-Marquardt (pixel_fit.h) on every pixel within
// 3σ + 1.5 px of an edge: the maximum-likelihood pose under Gaussian noise, whose clipping
// at black and white (a sensor's saturation) is part of the model. For (f) the tilt
// then rests on the circle, the wedge's two sides and its apex at once; the edge points of
// the circle and one centre point (circle_tracker.cc) leave most of that out.
#pragma once

#include <optional>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"
#include "trackers/circle/pixel_fit.h"

namespace markerbench {

struct DesignRefinementOptions {
  // Pixels within this many σ, plus band_px, of an edge take part (the circle tracker's
  // `design_band_sigmas` and `design_band_px`).
  double band_sigmas = 3.0;
  double band_px = 1.5;
  int max_iterations = 20;  // per solve
  // Solves, each on the pixels chosen at the last result, until the translation moves by less
  // than 1e-4 of its length.
  int max_rounds = 3;
};

struct DesignRefinement {
  PixelFit fit;  // on a grey image: levels = (offset, gain) of the design's luma, 0-1
  int pixels = 0;
  double noise_sigma = 0.0;  // the image's, 0-1, as its residuals show (the model's clipping)
};

// `noise_sigma`: a first estimate of the image's, 0-1 units. nullopt when too few pixels near the
// design's edges are in front of the camera and in the image.
std::optional<DesignRefinement> RefineDesign(const Image8& image,
                                             const Camera& camera,
                                             const MarkerSpec& marker,
                                             const Rigid3& cam_from_marker,
                                             double sigma_px,
                                             double noise_sigma,
                                             const DesignRefinementOptions& options = {});

// Which of several refinements explains the image best: the least cost (the clipped pixels'
// likelihood) over the pixels near the design's edges at any of them (each fit judged on the
// same pixels). `fits` not empty.
size_t BestDesignRefinement(const Image8& image,
                            const Camera& camera,
                            const MarkerSpec& marker,
                            const std::vector<DesignRefinement>& fits,
                            const DesignRefinementOptions& options = {});

}  // namespace markerbench
