// Direct ("photometric") refinement of a circle marker's pose on the pixels around its edges
// (issue 21). Each pixel u near a printed disk's edge is modelled as the printed design blurred
// by a Gaussian of σ: I_c(u) = offset_c + gain_c (base_c + jump_c G(R/σ, -d(u)/σ)), with G the
// exact blurred-disk profile (blurred_disk_profile.h), R the disk's radius in pixels, d the
// pixel's signed distance to the projected edge (along the edge's normal at the start pose,
// from the edge point at the pixel's angle about the disk), jump the colour step across the
// edge and base the colour of the other layers there. Pose, σ and each channel's gain and
// offset are fitted by Levenberg-Marquardt on every channel of every pixel within 3σ + 1 px of
// an edge. Under Gaussian pixel noise this is the maximum-likelihood pose; the edge points
// (one position per ray, kept from a whole profile) lose part of that information.
#pragma once

#include <optional>

#include "core/camera.h"
#include "core/image.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"

namespace markerbench {

struct PhotometricOptions {
  double band_sigmas = 3.0;  // pixels within this many σ (+ 1 px) of an edge take part
  int max_iterations = 15;   // per solve
  // Solves, each on the pixels chosen at the last result, until the translation moves by less
  // than 1e-4 of its length.
  int max_rounds = 3;
  // Each pixel is modelled from its nearest edge only, which holds while the blur is small
  // beside every printed disk (and so beside the gaps between them): the refinement is not
  // run where σ exceeds this fraction of a disk's radius in pixels. On the paper's blur
  // sweep (circles_a at 1 m, 18 px radius) it helps up to σ = 4 and hurts from 6.
  double max_blur_per_radius = 0.25;
};

struct PhotometricResult {
  Rigid3 cam_from_marker;
  double sigma_px = 0.0;
  int pixels = 0;
  int iterations = 0;  // over all rounds
  double initial_cost = 0.0;
  double final_cost = 0.0;
};

// nullopt for designs with layers other than disks, blur beyond max_blur_per_radius, or too
// few pixels.
std::optional<PhotometricResult> RefinePhotometric(const Image8& image,
                                                   const Camera& camera,
                                                   const MarkerSpec& marker,
                                                   const Rigid3& cam_from_marker,
                                                   double sigma_px,
                                                   const PhotometricOptions& options = {});

}  // namespace markerbench
