#include "bench/report/report_html.h"

#include <cmark-gfm-core-extensions.h>
#include <cmark-gfm.h>
#include <openssl/evp.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace markerbench {
namespace {

constexpr const char* kStyle = R"(
body { font-family: system-ui, sans-serif; max-width: 1200px; margin: 2em auto; padding: 0 1em;
       color: #222; line-height: 1.45; }
img { max-width: 100%; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: right; }
td:nth-child(-n+3), th:nth-child(-n+3) { text-align: left; }
th { background: #f2f2f2; cursor: pointer; user-select: none; position: sticky; top: 0; }
th[data-order="asc"]::after { content: " \25B2"; }
th[data-order="desc"]::after { content: " \25BC"; }
tr:nth-child(even) td { background: #fafafa; }
code { background: #f4f4f4; padding: 0 0.2em; }
)";

// Click a header to sort its table by that column: numbers by value (the leading number of
// "83% (64–93%)" or "1.42 (1.1–1.8)"), text alphabetically; "–" and empty cells sort last.
constexpr const char* kSortScript = R"(
document.querySelectorAll("table").forEach(function (table) {
  var headers = table.querySelectorAll("thead th");
  headers.forEach(function (th, column) {
    th.addEventListener("click", function () {
      var descending = th.dataset.order === "asc";
      headers.forEach(function (h) { delete h.dataset.order; });
      th.dataset.order = descending ? "desc" : "asc";
      var body = table.tBodies[0];
      var rows = Array.from(body.rows);
      var key = function (row) {
        var text = row.cells[column] ? row.cells[column].textContent.trim() : "";
        var number = parseFloat(text);
        return { missing: text === "" || text === "–", number: number, text: text };
      };
      rows.sort(function (a, b) {
        var x = key(a), y = key(b);
        if (x.missing || y.missing) return x.missing - y.missing;
        var order = !isNaN(x.number) && !isNaN(y.number)
            ? x.number - y.number : x.text.localeCompare(y.text);
        return descending ? -order : order;
      });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
)";

std::string Base64(const std::string& bytes) {
  std::string out(4 * ((bytes.size() + 2) / 3) + 1, '\0');
  const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                reinterpret_cast<const unsigned char*>(bytes.data()),
                                static_cast<int>(bytes.size()));
  out.resize(static_cast<size_t>(n));
  return out;
}

std::string MediaType(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".png") return "image/png";
  if (extension == ".jpg" || extension == ".jpeg") return "image/jpeg";
  return "";
}

// Replaces each image's relative URL by a data URI of the file it names.
void EmbedImages(cmark_node* document, const std::filesystem::path& image_dir) {
  cmark_iter* iter = cmark_iter_new(document);
  for (cmark_event_type e = cmark_iter_next(iter); e != CMARK_EVENT_DONE;
       e = cmark_iter_next(iter)) {
    cmark_node* node = cmark_iter_get_node(iter);
    if (e != CMARK_EVENT_ENTER || cmark_node_get_type(node) != CMARK_NODE_IMAGE) continue;
    const char* url = cmark_node_get_url(node);
    if (url == nullptr || std::string(url).find(':') != std::string::npos) continue;
    const std::filesystem::path file = image_dir / url;
    const std::string type = MediaType(file);
    std::ifstream in(file, std::ios::binary);
    if (type.empty() || !in) continue;
    std::ostringstream bytes;
    bytes << in.rdbuf();
    cmark_node_set_url(node, ("data:" + type + ";base64," + Base64(bytes.str())).c_str());
  }
  cmark_iter_free(iter);
}

// Escapes the characters that would end an HTML text node.
std::string HtmlText(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '&') {
      out += "&amp;";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string ReportHtml(const std::string& markdown, const std::string& image_dir) {
  cmark_gfm_core_extensions_ensure_registered();
  const std::unique_ptr<cmark_parser, decltype(&cmark_parser_free)> parser(
      cmark_parser_new(CMARK_OPT_DEFAULT), cmark_parser_free);
  cmark_syntax_extension* table = cmark_find_syntax_extension("table");
  if (!parser || table == nullptr || !cmark_parser_attach_syntax_extension(parser.get(), table)) {
    throw std::runtime_error("report.html: cmark-gfm's table extension is missing");
  }
  cmark_parser_feed(parser.get(), markdown.data(), markdown.size());
  const std::unique_ptr<cmark_node, decltype(&cmark_node_free)> document(
      cmark_parser_finish(parser.get()), cmark_node_free);
  EmbedImages(document.get(), image_dir);
  const std::unique_ptr<char, decltype(&std::free)> body(
      cmark_render_html(
          document.get(), CMARK_OPT_DEFAULT, cmark_parser_get_syntax_extensions(parser.get())),
      std::free);
  const size_t title_end = markdown.find('\n');
  const std::string title = markdown.rfind("# ", 0) == 0 ? markdown.substr(2, title_end - 2) : "";
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
         HtmlText(title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n" +
         body.get() + "<script>" + kSortScript + "</script>\n</body>\n</html>\n";
}

}  // namespace markerbench
