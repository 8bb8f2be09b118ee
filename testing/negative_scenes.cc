#include "testing/negative_scenes.h"

#include <array>
#include <cmath>

#include "core/marker_yaml.h"
#include "core/random.h"
#include "renderer/test_scenes.h"

namespace markerbench {
namespace {

constexpr double kSheetHalfM = 0.2;  // clutter lies within ±this of the sheet's origin

// Counts per kind, in index order; they sum to kNegativeSetSize.
enum class Clutter { kPaper, kCheckerboard, kSquares, kDots, kRings, kColourDots, kOtherMarker };
constexpr std::array<std::pair<Clutter, int>, 7> kCounts = {{{Clutter::kPaper, 40},
                                                             {Clutter::kCheckerboard, 80},
                                                             {Clutter::kSquares, 80},
                                                             {Clutter::kDots, 100},
                                                             {Clutter::kRings, 60},
                                                             {Clutter::kColourDots, 100},
                                                             {Clutter::kOtherMarker, 100}}};
constexpr const char* kOtherMarkers[] = {
    "apriltag", "aruco", "artkplus", "runetag", "dot_rings", "bit_grid", "circle_e", "circle_f"};

const char* Name(Clutter clutter) {
  switch (clutter) {
    case Clutter::kPaper:
      return "paper";
    case Clutter::kCheckerboard:
      return "checkerboard";
    case Clutter::kSquares:
      return "squares";
    case Clutter::kDots:
      return "dots";
    case Clutter::kRings:
      return "rings";
    case Clutter::kColourDots:
      return "colour dots";
    case Clutter::kOtherMarker:
      return "other marker";
  }
  return "";
}

Eigen::Vector2d OnSheet(Rng* rng) {
  return {rng->Uniform(-kSheetHalfM, kSheetHalfM), rng->Uniform(-kSheetHalfM, kSheetHalfM)};
}

GridShape Square(const Eigen::Vector2d& top_left, double size_m) {
  GridShape grid;
  grid.rows = grid.cols = 1;
  grid.cell_m = size_m;
  grid.top_left = top_left;
  grid.ink = {1};
  return grid;
}

void AddCheckerboard(Rng* rng, MarkerSpec* sheet) {
  GridShape board;
  board.rows = 3 + static_cast<int>(rng->Uniform(0.0, 7.0));
  board.cols = 3 + static_cast<int>(rng->Uniform(0.0, 7.0));
  board.cell_m = rng->Uniform(0.015, 0.05);
  board.top_left = {-0.5 * board.cols * board.cell_m, 0.5 * board.rows * board.cell_m};
  for (int r = 0; r < board.rows; ++r) {
    for (int c = 0; c < board.cols; ++c) board.ink.push_back((r + c) % 2);
  }
  sheet->layers.push_back({board, Rgb::Zero()});
}

void AddSquares(Rng* rng, MarkerSpec* sheet) {
  const int count = 3 + static_cast<int>(rng->Uniform(0.0, 10.0));
  for (int i = 0; i < count; ++i) {
    const double grey = rng->Uniform(0.0, 0.6);
    const double size_m = rng->Uniform(0.01, 0.08);  // before the corner: g++'s order
    sheet->layers.push_back({Square(OnSheet(rng), size_m), Rgb::Constant(grey)});
  }
}

void AddDots(Rng* rng, MarkerSpec* sheet) {
  const int count = 5 + static_cast<int>(rng->Uniform(0.0, 26.0));
  for (int i = 0; i < count; ++i) {
    const double grey = rng->Uniform(0.0, 0.3);
    sheet->layers.push_back(
        {DiskShape{OnSheet(rng), rng->Uniform(0.003, 0.04)}, Rgb::Constant(grey)});
  }
}

// Black disks with a concentric white disk: a ring, like marker c without its feature dot.
void AddRings(Rng* rng, MarkerSpec* sheet) {
  const int count = 1 + static_cast<int>(rng->Uniform(0.0, 5.0));
  for (int i = 0; i < count; ++i) {
    const DiskShape outer{OnSheet(rng), rng->Uniform(0.01, 0.06)};
    sheet->layers.push_back({outer, Rgb::Zero()});
    sheet->layers.push_back(
        {DiskShape{outer.center, rng->Uniform(0.3, 0.8) * outer.radius}, Rgb::Ones()});
  }
}

// Disks of saturated colours. A red and a blue disk of about one size (within 1.5x) at about
// circles_a's spacing (2 to 3.4 radii) would be that marker, so such a pair is not drawn.
void AddColourDots(Rng* rng, MarkerSpec* sheet) {
  const std::array<Rgb, 8> palette = {Rgb(1, 0, 0),
                                      Rgb(0, 1, 0),
                                      Rgb(0, 0, 1),
                                      Rgb(1, 1, 0),
                                      Rgb(0, 1, 1),
                                      Rgb(1, 0, 1),
                                      Rgb(1, 0.5, 0),
                                      Rgb(0, 0, 0)};
  const Rgb red = palette[0], blue = palette[2];
  const int count = 4 + static_cast<int>(rng->Uniform(0.0, 20.0));
  while (static_cast<int>(sheet->layers.size()) < count) {
    const Rgb color = palette[static_cast<size_t>(rng->Uniform(0.0, palette.size()))];
    const DiskShape disk{OnSheet(rng), rng->Uniform(0.004, 0.04)};
    bool marker_like = false;
    for (const PaintedShape& layer : sheet->layers) {
      const DiskShape& other = std::get<DiskShape>(layer.shape);
      const bool red_blue =
          (color == red && layer.color == blue) || (color == blue && layer.color == red);
      const double size_ratio = disk.radius / other.radius;
      const double spacing = (disk.center - other.center).norm() / disk.radius;
      marker_like |=
          red_blue && size_ratio > 1 / 1.5 && size_ratio < 1.5 && spacing > 2.0 && spacing < 3.4;
    }
    if (!marker_like) sheet->layers.push_back({disk, color});
  }
}

}  // namespace

NegativeFrame RenderNegative(int index, int set, const NegativeSceneOptions& options) {
  Clutter clutter = Clutter::kPaper;
  int within = index;
  for (const auto& [kind, count] : kCounts) {
    clutter = kind;
    if (within < count) break;
    within -= count;
  }
  const uint64_t seed = 21 + static_cast<uint64_t>(set);
  Rng rng(SeedFor(seed, static_cast<uint64_t>(index), 0, SeedPurpose::kPose));
  MarkerSpec sheet;
  sheet.kind = MarkerKind::kBitGrid;
  std::string label = std::string(Name(clutter)) + " " + std::to_string(index);
  switch (clutter) {
    case Clutter::kPaper:
      break;
    case Clutter::kCheckerboard:
      AddCheckerboard(&rng, &sheet);
      break;
    case Clutter::kSquares:
      AddSquares(&rng, &sheet);
      break;
    case Clutter::kDots:
      AddDots(&rng, &sheet);
      break;
    case Clutter::kRings:
      AddRings(&rng, &sheet);
      break;
    case Clutter::kColourDots:
      AddColourDots(&rng, &sheet);
      break;
    case Clutter::kOtherMarker: {
      const char* name = kOtherMarkers[within % std::size(kOtherMarkers)];
      sheet = LoadMarkerYaml(std::string("scenarios/markers/") + name + ".yaml");
      label += std::string(" (") + name + ")";
      break;
    }
  }
  FrameRequest request;
  request.scene.marker = &sheet;
  const double distance = rng.Uniform(0.3, 2.5);
  request.scene.cam_from_marker = RandomTiltedView(distance, 0.0, 60.0, &rng);
  request.scene.cam_from_marker.translation.x() += rng.Uniform(-0.15, 0.15) * distance;
  request.scene.cam_from_marker.translation.y() += rng.Uniform(-0.15, 0.15) * distance;
  const double noise_vars[] = {0.0, 0.01, 0.02, 0.05, 0.1, 0.3};
  const std::vector<double>& blur_sigmas = options.blur_sigmas_px;
  request.degradations.noise_var = noise_vars[static_cast<size_t>(rng.Uniform(0.0, 6.0))];
  const double blur = rng.Uniform(0.0, static_cast<double>(blur_sigmas.size()));
  request.degradations.blur_sigma_px = blur_sigmas.at(static_cast<size_t>(blur));
  request.channels = 3;
  request.noise_seed = SeedFor(seed, static_cast<uint64_t>(index), 0, SeedPurpose::kNoise);
  return {label, RenderFrame(request), request.degradations};
}

}  // namespace markerbench
