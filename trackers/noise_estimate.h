// Robust estimate of an image's white-noise σ, shared by the trackers that adapt their
// smoothing to it.
#pragma once

#include <opencv2/core.hpp>

namespace markerbench {

// σ in 0-1 intensity units from the median absolute horizontal difference of neighbours,
// every other row (MAD · 1.4826 / √2): edges are too rare to move the median.
double EstimateNoiseSigma(const cv::Mat& channel);

}  // namespace markerbench
