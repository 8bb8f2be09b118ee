#include "bench/marker_sheets.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <opencv2/imgproc.hpp>

#include "bench/output_folder.h"
#include "core/config_error.h"
#include "core/marker_yaml.h"
#include "renderer/image_io.h"
#include "renderer/render_frame.h"

namespace markerbench {
namespace {

constexpr double kDpi = 300.0;
constexpr double kMetresPerInch = 0.0254;
constexpr int kPageWidthPx = 2480;  // A4 portrait at 300 dpi
constexpr int kPageHeightPx = 3508;
constexpr double kCheckBarM = 0.05;

double PxPerMetre() { return kDpi / kMetresPerInch; }

std::string Millimetres(double metres) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f mm", metres * 1000.0);
  return text;
}

// The sizes a user checks with a ruler.
std::string SizeText(const MarkerSpec& marker) {
  if (IsSquareKind(marker.kind)) return "black square edge " + Millimetres(marker.size_m);
  if (IsCircleKind(marker.kind)) {
    std::string text = "circle radius " + Millimetres(marker.circles[0].radius_m);
    if (marker.keypoints.size() > 1) text += ", Lx " + Millimetres(marker.keypoints[1].norm());
    return text;
  }
  return "ink width " + Millimetres(marker.InkBounds().sizes().x());
}

}  // namespace

std::vector<std::string> WriteMarkerSheets(const std::vector<std::string>& marker_files,
                                           const std::string& out_dir) {
  // Every file is read and checked before the first sheet is written.
  std::vector<MarkerSpec> markers;
  std::map<std::string, std::string> file_of_name;
  for (const std::string& file : marker_files) {
    markers.push_back(LoadMarkerYaml(file));
    const auto [earlier, inserted] = file_of_name.emplace(markers.back().name, file);
    if (!inserted) {
      throw ConfigError(file + " and " + earlier->second + " both name their marker '" +
                        earlier->first + "': their sheets would overwrite each other");
    }
  }
  CreateOutputFolder(out_dir);
  std::vector<std::string> written;
  for (const MarkerSpec& marker : markers) {
    // Fronto-parallel at 1 m with f = px/m: an exact orthographic scale of 300 dpi.
    FrameRequest request;
    request.scene.marker = &marker;
    request.channels = 3;
    Camera& page = request.scene.camera;
    page.width = kPageWidthPx;
    page.height = kPageHeightPx;
    page.fx = page.fy = PxPerMetre();
    page.cx = 0.5 * (kPageWidthPx - 1);
    page.cy = 0.42 * kPageHeightPx;
    const Eigen::Vector2d c = marker.InkBounds().center();
    request.scene.cam_from_marker =
        Rigid3(Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal().toDenseMatrix(),
               Eigen::Vector3d(-c.x(), c.y(), 1.0));
    RenderedFrame frame = RenderFrame(request);
    cv::Mat sheet(page.height, page.width, CV_8UC3, frame.image.pixels.data());

    const cv::Scalar black(0, 0, 0);
    const int left = 150;
    int y = static_cast<int>(0.42 * kPageHeightPx +
                             0.5 * marker.InkBounds().sizes().y() * PxPerMetre()) +
            200;
    auto line = [&](const std::string& text, double scale) {
      cv::putText(sheet, text, {left, y}, cv::FONT_HERSHEY_SIMPLEX, scale, black, 3, cv::LINE_AA);
      y += static_cast<int>(60 * scale);
    };
    line("markerbench: " + marker.name + " (" + ToString(marker.kind) + ")", 2.0);
    line(SizeText(marker), 1.6);
    line("Print at 100% (no fit-to-page), 300 dpi. The bar below must measure 50.0 mm.", 1.2);
    const int bar_px = static_cast<int>(std::lround(kCheckBarM * PxPerMetre()));
    cv::rectangle(sheet, {left, y}, {left + bar_px, y + 30}, black, cv::FILLED);
    y += 110;
    line("Marker frame: origin at m0 / centre, x right, y up, z out of the page.", 1.2);

    const std::string path = out_dir + "/" + marker.name + ".png";
    WriteImage(path, frame.image, kDpi);
    written.push_back(path);
  }
  return written;
}

}  // namespace markerbench
