// Bitmaps of library-defined square markers, as bit grids centred on the marker origin.
// Third-party headers stay in the .cc (style.md rule 5).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/shapes.h"

namespace markerbench {

// libapriltag's apriltag_to_image(family, id): total_width² cells, with the black square
// (width_at_border cells) spanning size_m. Throws std::invalid_argument naming the valid
// families or the id range.
GridShape AprilTagGrid(const std::string& family, int id, double size_m);
std::vector<std::string> AprilTagFamilies();

// An opaque libapriltag family (apriltag_family_t*) that destroys itself with its family's
// destroy function. Throws std::invalid_argument naming the valid families.
using AprilTagFamilyPtr = std::unique_ptr<void, std::function<void(void*)>>;
AprilTagFamilyPtr CreateAprilTagFamily(const std::string& family);

// An ARToolKitPlus-style marker (baselines.md): the 6x6 word of `id` in `mode` ("bch" or
// "simple"; a set bit is white) inside a black border of border_fraction * size_m (0.25:
// 3 cells, 0.125: 1 cell) and a 1-cell white quiet zone. Throws std::invalid_argument starting
// "an id" for an id out of range, else naming the valid modes or border fractions.
GridShape ArtkPlusGrid(const std::string& mode, int id, double border_fraction, double size_m);

// OpenCV 4.6 cv::aruco::drawMarker with a 1-cell border: (bits + 2)² cells spanning size_m.
GridShape ArucoGrid(const std::string& dictionary, int id, double size_m);
std::vector<std::string> ArucoDictionaries();
// The cv::aruco::PREDEFINED_DICTIONARY_NAME value of a dictionary name, as an int. Throws
// std::invalid_argument naming the valid dictionaries.
int ArucoDictionaryId(const std::string& dictionary);

}  // namespace markerbench
