// Steps 1-3 of the ARToolKitPlus pipeline (baselines.md): a global threshold, 8-connected
// labelling of the dark pixels at full resolution, and the area and image-border filters.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace markerbench {

struct DarkRegionOptions {
  int threshold = 100;   // a pixel is dark when its grey level is below this (0..255)
  int min_area_px = 70;  // the original's area limits
  int max_area_px = 100000;
};

struct DarkRegion {
  int label = 0;
  int area_px = 0;
  Eigen::Vector2i first_px;  // its first pixel in raster order: the top row's leftmost
};

struct DarkRegions {
  int width = 0;
  int height = 0;
  std::vector<int32_t> labels;      // row-major; 0 = not dark
  std::vector<DarkRegion> regions;  // those that pass the filters

  int LabelAt(int x, int y) const { return labels[static_cast<size_t>(y * width + x)]; }
};

// grey: row-major, stride = width. Regions touching the image border are dropped.
DarkRegions FindDarkRegions(const uint8_t* grey,
                            int width,
                            int height,
                            const DarkRegionOptions& options);

}  // namespace markerbench
