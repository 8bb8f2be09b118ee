// Marker sheets are to be printed and measured: the drawing must be the marker the renderer
// draws, at its printed size, on the page asked for, and never clipped.
#include "bench/cli/marker_sheets.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "bench/cli/list_command.h"
#include "core/config_error.h"
#include "core/file_bytes.h"
#include "core/marker_yaml.h"
#include "core/test_files.h"
#include "renderer/image_io.h"
#include "renderer/render_frame.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

constexpr double kPxPerMm = 300.0 / 25.4;
constexpr double kMarginMm = 12.0, kFooterMm = 36.0;  // the sheet's layout

std::string OutDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("markerbench_sheets_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  return dir.string();
}

// The marker as the renderer draws it, fronto-parallel at 300 dpi, its ink centre at pixel
// (cx, cy) of a width x height image (pixel centres at integer coordinates).
Image8 Rendered(const MarkerSpec& marker, int width, int height, double cx, double cy) {
  FrameRequest request;
  request.scene.marker = &marker;
  request.channels = 3;
  Camera& page = request.scene.camera;
  page.width = width;
  page.height = height;
  page.fx = page.fy = 1e3 * kPxPerMm;
  page.cx = cx;
  page.cy = cy;
  const Eigen::Vector2d c = marker.InkBounds().center();
  request.scene.cam_from_marker =
      Rigid3(Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal().toDenseMatrix(),
             Eigen::Vector3d(-c.x(), c.y(), 1.0));
  return RenderFrame(request).image;
}

bool Dark(const Image8& image, int x, int y) {
  return image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2) < 3 * 128;
}

// Every marker's sheet draws what the renderer draws, in the same place and orientation:
// inside the ink box (2 mm around it included), pixels differ only along edges.
TEST(MarkerSheets, PngSheetsShowTheRenderersMarkerAtScale) {
  const std::string out = OutDir("png");
  SheetOptions options;
  options.format = SheetFormat::kPng;
  const std::vector<std::string> files = MarkerFilesIn("scenarios/markers");
  const std::vector<std::string> written = WriteMarkerSheets(files, out, options);
  ASSERT_EQ(written.size(), files.size());
  for (size_t i = 0; i < files.size(); ++i) {
    const MarkerSpec marker = LoadMarkerYaml(files[i]);
    const Image8 sheet = ReadImage(written[i]);
    ASSERT_EQ(sheet.width, 2480);  // A4 at 300 dpi
    ASSERT_EQ(sheet.height, 3508);
    // The ink centre sits at the centre of the drawing area.
    const double cx = 0.5 * 210.0 * kPxPerMm - 0.5;
    const double cy = (kMarginMm + 0.5 * (297.0 - 2 * kMarginMm - kFooterMm)) * kPxPerMm - 0.5;
    const Image8 expected = Rendered(marker, sheet.width, sheet.height, cx, cy);
    const Eigen::Vector2d half = 0.5e3 * kPxPerMm * marker.InkBounds().sizes();
    const int pad = static_cast<int>(2.0 * kPxPerMm);
    int differing = 0, pixels = 0, ink = 0;
    for (int y = static_cast<int>(cy - half.y()) - pad; y <= cy + half.y() + pad; ++y) {
      for (int x = static_cast<int>(cx - half.x()) - pad; x <= cx + half.x() + pad; ++x) {
        ++pixels;
        ink += Dark(expected, x, y);
        for (int c = 0; c < 3; ++c) {
          if (std::abs(sheet.at(x, y, c) - expected.at(x, y, c)) > 100) {
            ++differing;
            break;
          }
        }
      }
    }
    EXPECT_GT(ink, pixels / 20) << files[i];
    EXPECT_LT(differing, pixels / 500) << files[i] << ": " << differing << " of " << pixels;
  }
  fs::remove_all(out);
}

// The check bar is 50 mm long: 590.6 px at 300 dpi.
TEST(MarkerSheets, CheckBarMeasuresFiftyMillimetres) {
  const std::string out = OutDir("bar");
  SheetOptions options;
  options.format = SheetFormat::kPng;
  const Image8 sheet =
      ReadImage(WriteMarkerSheets({"scenarios/markers/circles_a.yaml"}, out, options).at(0));
  int longest = 0;
  const int footer_top = static_cast<int>((297.0 - kMarginMm - kFooterMm) * kPxPerMm);
  for (int y = footer_top; y < sheet.height; ++y) {
    int run = 0;
    for (int x = 0; x < sheet.width; ++x) {
      run = Dark(sheet, x, y) ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  EXPECT_NEAR(longest, 50.0 * kPxPerMm, 1.5);
  fs::remove_all(out);
}

// "/MediaBox [ 0 0 w h ]" of each page of a cairo PDF, in points.
std::vector<std::pair<double, double>> PdfPages(const std::string& pdf) {
  std::vector<std::pair<double, double>> pages;
  const std::string key = "/MediaBox [";
  for (size_t at = pdf.find(key); at != std::string::npos; at = pdf.find(key, at + 1)) {
    double x0 = 0, y0 = 0, width = 0, height = 0;
    if (std::sscanf(pdf.c_str() + at + key.size(), "%lf %lf %lf %lf", &x0, &y0, &width, &height) ==
            4 &&
        x0 == 0.0 && y0 == 0.0) {
      pages.emplace_back(width, height);
    }
  }
  return pages;
}

TEST(MarkerSheets, PdfPagesHaveThePapersSizeAndNoCreationDate) {
  for (const auto& [paper, width_pt, height_pt] :
       std::vector<std::tuple<std::string, double, double>>{
           {"a4", 595.276, 841.89}, {"letter", 612.0, 792.0}, {"a3", 841.89, 1190.551}}) {
    const std::string out = OutDir(paper);
    SheetOptions options;
    options.paper = paper;
    const std::string pdf =
        ReadFileBytes(WriteMarkerSheets({"scenarios/markers/runetag.yaml"}, out, options).at(0));
    EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
    EXPECT_EQ(pdf.find("CreationDate"), std::string::npos) << paper;  // the same bytes each time
    const auto pages = PdfPages(pdf);
    ASSERT_EQ(pages.size(), 1u) << paper;
    EXPECT_NEAR(pages[0].first, width_pt, 0.01) << paper;
    EXPECT_NEAR(pages[0].second, height_pt, 0.01) << paper;
    fs::remove_all(out);
  }
}

// A 250 mm tag does not fit A4: an error naming the file and the room, with nothing written,
// unless --paper a3 or --tile (2 x 2 pages that hold all of its ink).
TEST(MarkerSheets, AMarkerLargerThanThePageIsRefusedOrTiledNeverClipped) {
  const std::string big = WriteTestFile("big_tag.yaml",
                                        "kind: apriltag\nfamily: tag36h11\nid: 3\nsize_m: 0.1\n"
                                        "scale: 2.5\n");
  const std::string out = OutDir("big");
  try {
    WriteMarkerSheets({"scenarios/markers/circles_a.yaml", big}, out);
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(),
                HasSubstr(big + ": the marker's ink is 250.0 mm x 250.0 mm; a4 paper "
                                "has room for 186.0 mm x 237.0 mm"));
  }
  EXPECT_FALSE(fs::exists(out));

  SheetOptions a3;
  a3.paper = "a3";
  EXPECT_EQ(PdfPages(ReadFileBytes(WriteMarkerSheets({big}, out, a3).at(0))).size(), 1u);
  fs::remove_all(out);

  SheetOptions tiled;
  tiled.tile = true;
  EXPECT_EQ(PdfPages(ReadFileBytes(WriteMarkerSheets({big}, out, tiled).at(0))).size(), 4u);
  fs::remove_all(out);
  tiled.format = SheetFormat::kSvg;
  EXPECT_EQ(WriteMarkerSheets({big}, out, tiled),
            (std::vector<std::string>{out + "/big_tag_tile_1_1.svg",
                                      out + "/big_tag_tile_1_2.svg",
                                      out + "/big_tag_tile_2_1.svg",
                                      out + "/big_tag_tile_2_2.svg"}));
  fs::remove_all(out);

  // The tiles' drawing areas together hold exactly the marker's ink.
  tiled.format = SheetFormat::kPng;
  const std::vector<std::string> tiles = WriteMarkerSheets({big}, out, tiled);
  ASSERT_EQ(tiles.size(), 4u);
  long tiled_ink = 0;
  for (const std::string& tile : tiles) {
    const Image8 page = ReadImage(tile);
    for (int y = static_cast<int>(kMarginMm * kPxPerMm);
         y < static_cast<int>((297.0 - kMarginMm - kFooterMm) * kPxPerMm);
         ++y) {
      for (int x = static_cast<int>(kMarginMm * kPxPerMm);
           x < static_cast<int>((210.0 - kMarginMm) * kPxPerMm);
           ++x) {
        tiled_ink += Dark(page, x, y);
      }
    }
  }
  const int side = static_cast<int>(270.0 * kPxPerMm);
  const Image8 whole = Rendered(LoadMarkerYaml(big), side, side, 0.5 * side, 0.5 * side);
  long ink = 0;
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) ink += Dark(whole, x, y);
  }
  EXPECT_NEAR(static_cast<double>(tiled_ink) / ink, 1.0, 0.002);
  fs::remove_all(out);
}

}  // namespace
}  // namespace markerbench
