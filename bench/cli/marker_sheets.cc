#include "bench/cli/marker_sheets.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <variant>

#include "bench/io/atomic_file.h"
#include "bench/io/output_folder.h"
#include "core/config_error.h"
#include "core/marker_yaml.h"
#include "renderer/image_io.h"

namespace markerbench {
namespace {

// Layout in millimetres (the drawing's user unit).
constexpr double kMarginMm = 12.0;
constexpr double kFooterMm = 36.0;  // four lines of text and the check bar
constexpr double kCheckBarMm = 50.0;
constexpr double kPngDpi = 300.0;
constexpr double kMmPerInch = 25.4;
constexpr double kPointsPerInch = 72.0;  // PDF and SVG units

struct Paper {
  double width_mm;
  double height_mm;
};

const std::map<std::string, Paper>& Papers() {
  static const std::map<std::string, Paper> papers = {
      {"a4", {210.0, 297.0}}, {"letter", {215.9, 279.4}}, {"a3", {297.0, 420.0}}};
  return papers;
}

// Where a marker goes on its pages: the ink box in metres, the drawing area in mm, and the
// number of tiles.
struct SheetLayout {
  Paper paper;
  Eigen::AlignedBox2d ink;  // metres, marker frame
  double area_width_mm = 0.0;
  double area_height_mm = 0.0;
  int rows = 1;
  int cols = 1;
  double InkWidthMm() const { return 1e3 * ink.sizes().x(); }
  double InkHeightMm() const { return 1e3 * ink.sizes().y(); }
};

std::string Millimetres(double mm) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f mm", mm);
  return text;
}

// The sizes a user checks with a ruler.
std::string SizeText(const MarkerSpec& marker) {
  if (IsSquareKind(marker.kind)) return "black square edge " + Millimetres(1e3 * marker.size_m);
  if (IsCircleKind(marker.kind)) {
    std::string text = "circle radius " + Millimetres(1e3 * marker.circles[0].radius_m);
    if (marker.keypoints.size() > 1) {
      text += ", m0 to m1 " + Millimetres(1e3 * (marker.keypoints[1] - marker.keypoints[0]).norm());
    }
    return text;
  }
  if (marker.kind == MarkerKind::kRuneTag) {
    return "outer ring diameter " + Millimetres(1e3 * marker.size_m);
  }
  return "ink width " + Millimetres(1e3 * marker.InkBounds().sizes().x());
}

std::string TitleText(const MarkerSpec& marker) {
  std::string text = "markerbench: " + marker.name + " (" + ToString(marker.kind);
  if (!marker.family.empty()) text += " " + marker.family;
  if (marker.id >= 0) text += " id " + std::to_string(marker.id);
  return text + ")";
}

SheetLayout Layout(const MarkerSpec& marker, const std::string& file, const SheetOptions& options) {
  SheetLayout layout;
  layout.paper = Papers().at(options.paper);
  layout.ink = marker.InkBounds();
  layout.area_width_mm = layout.paper.width_mm - 2.0 * kMarginMm;
  layout.area_height_mm = layout.paper.height_mm - 2.0 * kMarginMm - kFooterMm;
  // A micrometre of slack: a marker exactly as wide as the area fits.
  layout.cols =
      std::max(1, static_cast<int>(std::ceil(layout.InkWidthMm() / layout.area_width_mm - 1e-6)));
  layout.rows =
      std::max(1, static_cast<int>(std::ceil(layout.InkHeightMm() / layout.area_height_mm - 1e-6)));
  if (!options.tile && layout.rows * layout.cols > 1) {
    throw ConfigError(file + ": the marker's ink is " + Millimetres(layout.InkWidthMm()) + " x " +
                      Millimetres(layout.InkHeightMm()) + "; " + options.paper +
                      " paper has room for " + Millimetres(layout.area_width_mm) + " x " +
                      Millimetres(layout.area_height_mm) +
                      ": choose a larger --paper or --tile it over pages");
  }
  return layout;
}

void SetColor(cairo_t* cr, const Rgb& color) {
  cairo_set_source_rgb(cr, color.x(), color.y(), color.z());
}

void DiskPath(cairo_t* cr, const DiskShape& disk) {
  cairo_new_sub_path(cr);
  cairo_arc(cr, disk.center.x(), disk.center.y(), disk.radius, 0.0, 2.0 * M_PI);
  cairo_close_path(cr);
}

// One painted layer, in marker coordinates (metres, y up).
void DrawShape(cairo_t* cr, const PaintedShape& painted) {
  if (const auto* disk = std::get_if<DiskShape>(&painted.shape)) {
    DiskPath(cr, *disk);
    SetColor(cr, painted.color);
    cairo_fill(cr);
  } else if (const auto* crescent = std::get_if<CrescentShape>(&painted.shape)) {
    // Inside the outer disk and outside the inner one.
    cairo_save(cr);
    DiskPath(cr, crescent->outer);
    cairo_clip(cr);
    DiskPath(cr, crescent->outer);
    DiskPath(cr, crescent->inner);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
    SetColor(cr, painted.color);
    cairo_fill(cr);
    cairo_restore(cr);
  } else if (const auto* sector = std::get_if<SectorShape>(&painted.shape)) {
    cairo_move_to(cr, sector->center().x(), sector->center().y());
    cairo_arc(cr,
              sector->center().x(),
              sector->center().y(),
              sector->radius(),
              sector->start_rad(),
              sector->end_rad());
    cairo_close_path(cr);
    SetColor(cr, painted.color);
    cairo_fill(cr);
  } else if (const auto* grid = std::get_if<GridShape>(&painted.shape)) {
    // Paper first, then the ink cells as one path: no seams between neighbouring cells.
    const double s = grid->cell_m;
    cairo_rectangle(cr,
                    grid->top_left.x(),
                    grid->top_left.y() - grid->rows * s,
                    grid->cols * s,
                    grid->rows * s);
    SetColor(cr, grid->paper_color);
    cairo_fill(cr);
    for (int row = 0; row < grid->rows; ++row) {
      for (int col = 0; col < grid->cols; ++col) {
        if (grid->Ink(row, col)) {
          cairo_rectangle(
              cr, grid->top_left.x() + col * s, grid->top_left.y() - (row + 1) * s, s, s);
        }
      }
    }
    SetColor(cr, painted.color);
    cairo_fill(cr);
  }
}

void Text(cairo_t* cr, double x, double y, double size_mm, const std::string& text) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size_mm);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, text.c_str());
}

// Short lines in the margin at the drawing area's corners: where to cut and join tiles.
void CropMarks(cairo_t* cr, const SheetLayout& layout) {
  const double x0 = kMarginMm, x1 = kMarginMm + layout.area_width_mm;
  const double y0 = kMarginMm, y1 = kMarginMm + layout.area_height_mm;
  constexpr double kLength = 6.0;
  for (const double x : {x0, x1}) {
    for (const double y : {y0, y1}) {
      const double out_x = x == x0 ? -1.0 : 1.0, out_y = y == y0 ? -1.0 : 1.0;
      cairo_move_to(cr, x + out_x * 1.0, y);
      cairo_line_to(cr, x + out_x * kLength, y);
      cairo_move_to(cr, x, y + out_y * 1.0);
      cairo_line_to(cr, x, y + out_y * kLength);
    }
  }
  cairo_set_line_width(cr, 0.15);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_stroke(cr);
}

// One page in mm: the marker's tile (row, col), then the footer.
void DrawPage(cairo_t* cr, const MarkerSpec& marker, const SheetLayout& layout, int row, int col) {
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);
  const bool tiled = layout.rows * layout.cols > 1;
  // The part of the ink box this page shows, in metres: columns from the left, rows from the
  // top; a single page centres the whole box in the area.
  const double window_left = tiled ? layout.ink.min().x() + 1e-3 * col * layout.area_width_mm
                                   : layout.ink.center().x() - 0.5e-3 * layout.area_width_mm;
  const double window_top = tiled ? layout.ink.max().y() - 1e-3 * row * layout.area_height_mm
                                  : layout.ink.center().y() + 0.5e-3 * layout.area_height_mm;
  cairo_save(cr);
  cairo_rectangle(cr, kMarginMm, kMarginMm, layout.area_width_mm, layout.area_height_mm);
  cairo_clip(cr);
  cairo_translate(cr, kMarginMm, kMarginMm);
  cairo_scale(cr, 1e3, -1e3);  // metres, y up
  cairo_translate(cr, -window_left, -window_top);
  if (marker.background != Rgb::Ones()) {
    const double pad = 0.1 * layout.ink.sizes().maxCoeff();
    cairo_rectangle(cr,
                    layout.ink.min().x() - pad,
                    layout.ink.min().y() - pad,
                    layout.ink.sizes().x() + 2 * pad,
                    layout.ink.sizes().y() + 2 * pad);
    SetColor(cr, marker.background);
    cairo_fill(cr);
  }
  for (const PaintedShape& layer : marker.layers) DrawShape(cr, layer);
  cairo_restore(cr);
  if (tiled) CropMarks(cr, layout);

  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  double y = layout.paper.height_mm - kMarginMm - kFooterMm + 7.0;
  Text(cr, kMarginMm, y, 4.2, TitleText(marker));
  y += 6.0;
  std::string size = SizeText(marker) + "; ink " + Millimetres(layout.InkWidthMm()) + " x " +
                     Millimetres(layout.InkHeightMm());
  if (tiled) {
    size += "; tile row " + std::to_string(row + 1) + " of " + std::to_string(layout.rows) +
            ", column " + std::to_string(col + 1) + " of " + std::to_string(layout.cols) +
            " (cut at the corner marks)";
  }
  Text(cr, kMarginMm, y, 3.0, size);
  y += 5.5;
  Text(
      cr, kMarginMm, y, 3.0, "Print at 100% (no fit-to-page). The bar below must measure 50.0 mm:");
  y += 2.5;
  cairo_rectangle(cr, kMarginMm, y, kCheckBarMm, 2.5);
  for (int mm = 0; mm <= 50; mm += 10)
    cairo_rectangle(cr, kMarginMm + mm - 0.15, y - 1.5, 0.3, 1.5);
  cairo_fill(cr);
  y += 8.5;
  Text(cr,
       kMarginMm,
       y,
       3.0,
       "Marker frame: origin at m0 / the centre, x right, y up, z out of the page.");
}

// Collects what cairo writes, so that the file is written atomically.
cairo_status_t AppendBytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

void Check(cairo_surface_t* surface, const std::string& path) {
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error(path +
                             ": cairo: " + cairo_status_to_string(cairo_surface_status(surface)));
  }
}

// A vector page (or a PDF of pages) of tiles; written to `path` atomically.
void WriteVector(const MarkerSpec& marker,
                 const SheetLayout& layout,
                 SheetFormat format,
                 const std::vector<std::pair<int, int>>& tiles,
                 const std::string& path) {
  std::string bytes;
  const double width_pt = layout.paper.width_mm / kMmPerInch * kPointsPerInch;
  const double height_pt = layout.paper.height_mm / kMmPerInch * kPointsPerInch;
  Surface surface(
      format == SheetFormat::kPdf
          ? cairo_pdf_surface_create_for_stream(AppendBytes, &bytes, width_pt, height_pt)
          : cairo_svg_surface_create_for_stream(AppendBytes, &bytes, width_pt, height_pt),
      cairo_surface_destroy);
  if (format == SheetFormat::kSvg)
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PT);
  // No creation date (cairo writes the clock's where it is not set): the same marker and paper
  // give the same file.
  if (format == SheetFormat::kPdf)
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "");
  {
    Context cr(cairo_create(surface.get()), cairo_destroy);
    cairo_scale(cr.get(), kPointsPerInch / kMmPerInch, kPointsPerInch / kMmPerInch);
    for (const auto& [row, col] : tiles) {
      DrawPage(cr.get(), marker, layout, row, col);
      cairo_show_page(cr.get());
    }
  }
  cairo_surface_finish(surface.get());
  Check(surface.get(), path);
  WriteFileAtomically(path, bytes);
}

// A 300 dpi page with its resolution in the file.
void WritePng(const MarkerSpec& marker,
              const SheetLayout& layout,
              int row,
              int col,
              const std::string& path) {
  const double px_per_mm = kPngDpi / kMmPerInch;
  Image8 image;
  image.width = static_cast<int>(std::lround(layout.paper.width_mm * px_per_mm));
  image.height = static_cast<int>(std::lround(layout.paper.height_mm * px_per_mm));
  image.channels = 3;
  Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height),
                  cairo_surface_destroy);
  Check(surface.get(), path);
  {
    Context cr(cairo_create(surface.get()), cairo_destroy);
    cairo_scale(cr.get(), px_per_mm, px_per_mm);
    DrawPage(cr.get(), marker, layout, row, col);
  }
  cairo_surface_flush(surface.get());
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  image.pixels.resize(static_cast<size_t>(image.width) * image.height * 3);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      uint32_t pixel;
      std::memcpy(&pixel, data + static_cast<size_t>(y) * stride + 4 * x, 4);
      uint8_t* out = &image.pixels[(static_cast<size_t>(y) * image.width + x) * 3];
      out[0] = static_cast<uint8_t>(pixel >> 16);
      out[1] = static_cast<uint8_t>(pixel >> 8);
      out[2] = static_cast<uint8_t>(pixel);
    }
  }
  WriteImage(path, image, kPngDpi);
}

const char* Extension(SheetFormat format) {
  switch (format) {
    case SheetFormat::kSvg:
      return ".svg";
    case SheetFormat::kPng:
      return ".png";
    default:
      return ".pdf";
  }
}

}  // namespace

const std::vector<std::string>& PaperNames() {
  static const std::vector<std::string> names = {"a4", "letter", "a3"};
  return names;
}

std::vector<std::string> WriteMarkerSheets(const std::vector<std::string>& marker_files,
                                           const std::string& out_dir,
                                           const SheetOptions& options) {
  if (Papers().count(options.paper) == 0) {
    throw ConfigError("--paper: expected a4, letter or a3, got '" + options.paper + "'");
  }
  // Every file is read, and every marker laid out, before the first sheet is written.
  std::vector<MarkerSpec> markers;
  std::vector<SheetLayout> layouts;
  std::map<std::string, std::string> file_of_name;
  for (const std::string& file : marker_files) {
    markers.push_back(LoadMarkerYaml(file));
    const auto [earlier, inserted] = file_of_name.emplace(markers.back().name, file);
    if (!inserted) {
      throw ConfigError(file + " and " + earlier->second + " both name their marker '" +
                        earlier->first + "': their sheets would overwrite each other");
    }
    layouts.push_back(Layout(markers.back(), file, options));
  }
  CreateOutputFolder(out_dir);
  std::vector<std::string> written;
  for (size_t m = 0; m < markers.size(); ++m) {
    const SheetLayout& layout = layouts[m];
    std::vector<std::pair<int, int>> tiles;
    for (int row = 0; row < layout.rows; ++row) {
      for (int col = 0; col < layout.cols; ++col) tiles.emplace_back(row, col);
    }
    const std::string stem = out_dir + "/" + markers[m].name;
    if (options.format == SheetFormat::kPdf) {
      written.push_back(stem + ".pdf");
      WriteVector(markers[m], layout, options.format, tiles, written.back());
      continue;
    }
    for (const auto& [row, col] : tiles) {
      const std::string suffix =
          tiles.size() == 1 ? ""
                            : "_tile_" + std::to_string(row + 1) + "_" + std::to_string(col + 1);
      written.push_back(stem + suffix + Extension(options.format));
      if (options.format == SheetFormat::kSvg) {
        WriteVector(markers[m], layout, options.format, {{row, col}}, written.back());
      } else {
        WritePng(markers[m], layout, row, col, written.back());
      }
    }
  }
  return written;
}

}  // namespace markerbench
