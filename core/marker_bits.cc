#include "core/marker_bits.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h10.h>
#include <apriltag/tag36h11.h>
#include <apriltag/tagCircle21h7.h>
#include <apriltag/tagCircle49h12.h>
#include <apriltag/tagCustom48h12.h>
#include <apriltag/tagStandard41h12.h>
#include <apriltag/tagStandard52h13.h>

#include <memory>
#include <opencv2/aruco.hpp>
#include <stdexcept>
#include <utility>

#include "core/codes/artkplus_id_code.h"

namespace markerbench {
namespace {

struct AprilTagFamilyEntry {
  const char* name;
  apriltag_family_t* (*create)();
  void (*destroy)(apriltag_family_t*);
};

constexpr AprilTagFamilyEntry kAprilTagFamilies[] = {
    {"tag36h11", tag36h11_create, tag36h11_destroy},
    {"tag36h10", tag36h10_create, tag36h10_destroy},
    {"tag25h9", tag25h9_create, tag25h9_destroy},
    {"tag16h5", tag16h5_create, tag16h5_destroy},
    {"tagCircle21h7", tagCircle21h7_create, tagCircle21h7_destroy},
    {"tagCircle49h12", tagCircle49h12_create, tagCircle49h12_destroy},
    {"tagCustom48h12", tagCustom48h12_create, tagCustom48h12_destroy},
    {"tagStandard41h12", tagStandard41h12_create, tagStandard41h12_destroy},
    {"tagStandard52h13", tagStandard52h13_create, tagStandard52h13_destroy},
};

const std::pair<const char*, cv::aruco::PREDEFINED_DICTIONARY_NAME> kArucoDictionaries[] = {
    {"DICT_4X4_50", cv::aruco::DICT_4X4_50},
    {"DICT_4X4_100", cv::aruco::DICT_4X4_100},
    {"DICT_4X4_250", cv::aruco::DICT_4X4_250},
    {"DICT_4X4_1000", cv::aruco::DICT_4X4_1000},
    {"DICT_5X5_50", cv::aruco::DICT_5X5_50},
    {"DICT_5X5_100", cv::aruco::DICT_5X5_100},
    {"DICT_5X5_250", cv::aruco::DICT_5X5_250},
    {"DICT_5X5_1000", cv::aruco::DICT_5X5_1000},
    {"DICT_6X6_50", cv::aruco::DICT_6X6_50},
    {"DICT_6X6_100", cv::aruco::DICT_6X6_100},
    {"DICT_6X6_250", cv::aruco::DICT_6X6_250},
    {"DICT_6X6_1000", cv::aruco::DICT_6X6_1000},
    {"DICT_7X7_50", cv::aruco::DICT_7X7_50},
    {"DICT_7X7_100", cv::aruco::DICT_7X7_100},
    {"DICT_7X7_250", cv::aruco::DICT_7X7_250},
    {"DICT_7X7_1000", cv::aruco::DICT_7X7_1000},
    {"DICT_ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL},
    {"DICT_APRILTAG_16h5", cv::aruco::DICT_APRILTAG_16h5},
    {"DICT_APRILTAG_25h9", cv::aruco::DICT_APRILTAG_25h9},
    {"DICT_APRILTAG_36h10", cv::aruco::DICT_APRILTAG_36h10},
    {"DICT_APRILTAG_36h11", cv::aruco::DICT_APRILTAG_36h11},
};

// A centred grid of n x n cells from an 8-bit bitmap where 0 is ink.
template <typename IsInk>
GridShape GridFromBitmap(int n, double cell_m, const IsInk& is_ink) {
  GridShape grid;
  grid.rows = grid.cols = n;
  grid.cell_m = cell_m;
  grid.top_left = Eigen::Vector2d(-0.5 * n * cell_m, 0.5 * n * cell_m);
  grid.ink.resize(static_cast<size_t>(n * n));
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) grid.ink[static_cast<size_t>(r * n + c)] = is_ink(r, c) ? 1 : 0;
  }
  return grid;
}

}  // namespace

std::vector<std::string> AprilTagFamilies() {
  std::vector<std::string> names;
  for (const auto& f : kAprilTagFamilies) names.emplace_back(f.name);
  return names;
}

AprilTagFamilyPtr CreateAprilTagFamily(const std::string& family) {
  for (const auto& entry : kAprilTagFamilies) {
    if (family != entry.name) continue;
    auto destroy = entry.destroy;
    return AprilTagFamilyPtr(entry.create(),
                             [destroy](void* p) { destroy(static_cast<apriltag_family_t*>(p)); });
  }
  std::string names;
  for (const auto& f : kAprilTagFamilies) names += std::string(names.empty() ? "" : ", ") + f.name;
  throw std::invalid_argument("one of the libapriltag families: " + names);
}

GridShape AprilTagGrid(const std::string& family, int id, double size_m) {
  const AprilTagFamilyPtr handle = CreateAprilTagFamily(family);
  auto* fam = static_cast<apriltag_family_t*>(handle.get());
  if (id < 0 || static_cast<uint32_t>(id) >= fam->ncodes) {
    throw std::invalid_argument("an id in [0, " + std::to_string(fam->ncodes - 1) + "] for " +
                                family);
  }
  const std::unique_ptr<image_u8_t, void (*)(image_u8_t*)> image(apriltag_to_image(fam, id),
                                                                 image_u8_destroy);
  return GridFromBitmap(fam->total_width, size_m / fam->width_at_border, [&](int r, int c) {
    return image->buf[r * image->stride + c] == 0;
  });
}

GridShape ArtkPlusGrid(const std::string& mode, int id, double border_fraction, double size_m) {
  const std::optional<ArtkPlusIdMode> id_mode = ArtkPlusIdModeFromString(mode);
  if (!id_mode) throw std::invalid_argument("an id mode: bch or simple");
  const int ids = ArtkPlusIdCount(*id_mode);
  if (id < 0 || id >= ids) {
    throw std::invalid_argument("an id in [0, " + std::to_string(ids - 1) + "] for mode " + mode);
  }
  int border = 0;
  if (border_fraction == 0.25) {
    border = 3;
  } else if (border_fraction == 0.125) {
    border = 1;
  } else {
    throw std::invalid_argument("a border fraction of 0.25 or 0.125");
  }
  const int inked = 6 + 2 * border;
  const uint64_t word = ArtkPlusEncode(*id_mode, id);
  return GridFromBitmap(inked + 2, size_m / inked, [&](int r, int c) {
    const int ri = r - 1 - border, ci = c - 1 - border;  // data cell, past quiet zone and border
    if (r == 0 || c == 0 || r == inked + 1 || c == inked + 1) return false;
    if (ri < 0 || ci < 0 || ri >= 6 || ci >= 6) return true;
    return (word >> (35 - (6 * ri + ci)) & 1) == 0;  // a set bit is white
  });
}

std::vector<std::string> ArucoDictionaries() {
  std::vector<std::string> names;
  for (const auto& [name, value] : kArucoDictionaries) names.emplace_back(name);
  return names;
}

int ArucoDictionaryId(const std::string& dictionary) {
  for (const auto& [name, value] : kArucoDictionaries) {
    if (dictionary == name) return value;
  }
  std::string names;
  for (const auto& [n, v] : kArucoDictionaries) names += std::string(names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("one of the OpenCV 4.6 aruco dictionaries: " + names);
}

GridShape ArucoGrid(const std::string& dictionary, int id, double size_m) {
  const cv::Ptr<cv::aruco::Dictionary> dict = cv::aruco::getPredefinedDictionary(
      static_cast<cv::aruco::PREDEFINED_DICTIONARY_NAME>(ArucoDictionaryId(dictionary)));
  if (id < 0 || id >= dict->bytesList.rows) {
    throw std::invalid_argument("an id in [0, " + std::to_string(dict->bytesList.rows - 1) +
                                "] for " + dictionary);
  }
  const int n = dict->markerSize + 2;
  cv::Mat bitmap;
  cv::aruco::drawMarker(dict, id, n, bitmap, 1);
  return GridFromBitmap(
      n, size_m / n, [&](int r, int c) { return bitmap.at<uint8_t>(r, c) < 128; });
}

}  // namespace markerbench
