// `markerbench markers`: print-ready sheets of marker files, drawn as vectors with Debian's
// cairo: PDF (default), SVG, or PNG at 300 dpi. Each sheet carries the marker's name, kind,
// family, id and printed size, and a 50 mm check bar to measure after printing. A marker that
// does not fit the page is an error unless it is tiled over several pages; it is never clipped.
#pragma once

#include <string>
#include <vector>

namespace markerbench {

enum class SheetFormat { kPdf, kSvg, kPng };

struct SheetOptions {
  SheetFormat format = SheetFormat::kPdf;
  std::string paper = "a4";  // a4, letter or a3 (portrait)
  // Split a marker larger than the page over pages, each with its tile's row and column;
  // PDF: one file of pages; SVG and PNG: one file per tile (<name>_tile_<row>_<col>).
  bool tile = false;
};

// The paper sizes `--paper` accepts.
const std::vector<std::string>& PaperNames();

// Reads and checks every marker file, and that each fits the page (unless tiling), before it
// writes anything (ConfigError naming the file); then writes <out_dir>/<marker name>.<format>
// per marker. Returns the written paths.
std::vector<std::string> WriteMarkerSheets(const std::vector<std::string>& marker_files,
                                           const std::string& out_dir,
                                           const SheetOptions& options = {});

}  // namespace markerbench
