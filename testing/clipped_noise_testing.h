// The photometric fits on clipped noise (photometric_refinement_test, design_refinement_test):
// frames whose white paper and black ink clip about half their noisy pixels, fitted from the
// true pose and a noise estimate as far too low as the detector's on such images.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "core/random.h"
#include "renderer/test_scenes.h"
#include "testing/square_tracker_testing.h"

namespace markerbench {

// 8 frames of `marker` from the default camera at 1 m, tilted 10-40° at any roll, blurred by
// `blur` px with noise of variance 0.02 (the paper's blur sweep). refine(image, truth, σ,
// noise σ) gives an optional fit with `noise_sigma` and `fit.sigma_px`; each is expected to
// find the noise within 10 %. Returns the mean of its σ over the blur (both fits take the
// pixel's area apart from the optics' σ).
template <class Refine>
double MeanBlurRatioUnderClippedNoise(const MarkerSpec& marker, double blur, const Refine& refine) {
  constexpr double kNoiseVar = 0.02;
  constexpr double kDetectorNoiseSigma = 0.06;  // the detector's estimate for these 0.14
  constexpr int kFrames = 8;
  Rng rng(5);
  double ratio = 0.0;
  for (int i = 0; i < kFrames; ++i) {
    const Rigid3 truth = RandomTiltedView(1.0, 10.0, 40.0, &rng);
    const RenderedFrame frame = RenderMarker(marker, truth, kNoiseVar, blur, 20 + i);
    const auto refined = refine(frame.image, truth, blur, kDetectorNoiseSigma);
    EXPECT_TRUE(refined) << "frame " << i;
    if (!refined) return NAN;
    EXPECT_NEAR(refined->noise_sigma, std::sqrt(kNoiseVar), 0.1 * std::sqrt(kNoiseVar));
    ratio += refined->fit.sigma_px / blur / kFrames;
  }
  return ratio;
}

}  // namespace markerbench
