// report.html: report.md as one self-contained page. GitHub-flavoured Markdown (Debian's
// cmark-gfm, with its table extension), every image embedded as a data URI, and tables that
// sort by a click on a column header.
#pragma once

#include <string>

namespace markerbench {

// `markdown`'s images are read from `image_dir` (relative paths); an image that is not there
// stays a link. Throws std::runtime_error when cmark-gfm fails.
std::string ReportHtml(const std::string& markdown, const std::string& image_dir);

}  // namespace markerbench
