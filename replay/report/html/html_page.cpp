#include "report/html/html_page.h"

#include "report/svg_plot.h"

#include <cctype>

#include <fmt/format.h>

namespace aor::html {
namespace {

constexpr const char* kStyle = R"css(
body { font-family: sans-serif; margin: 24px auto; max-width: 1280px; color: #222; background: #fff; }
h1 { font-size: 22px; margin-bottom: 4px; }
h2 { font-size: 17px; border-bottom: 1px solid #ccc; padding-bottom: 3px; margin-top: 28px; }
table { border-collapse: collapse; font-size: 13px; margin: 6px 0; }
th, td { border: 1px solid #ddd; padding: 3px 8px; text-align: right; }
td.text { text-align: left; }
th { background: #f2f2f2; }
td:first-child, th:first-child { text-align: left; }
table.sortable th { cursor: pointer; }
table.sortable th::after { content: " \2195"; color: #999; }
dl.facts { display: grid; grid-template-columns: max-content auto; gap: 2px 14px; font-size: 14px; }
dl.facts dt { font-weight: bold; }
dl.facts dd { margin: 0; font-family: monospace; word-break: break-all; }
figure { display: inline-block; margin: 4px 8px 4px 0; vertical-align: top; }
.graph svg { max-width: 100%; height: auto; }
.distribution { display: inline-block; vertical-align: top; margin-right: 16px; }
.distribution h3 { font-size: 14px; margin: 10px 0 2px; }
figure img { image-rendering: pixelated; border: 1px solid #ccc; }
figcaption { font-size: 12px; max-width: 300px; }
.note { font-size: 13px; color: #555; }
.fail { color: #b00; font-weight: bold; }
.pass { color: #070; }
svg text { font-family: sans-serif; }
)css";

// Sorts a table.sortable by the clicked column: numbers by value (a cell's data-value when it
// has one), other text alphabetically; a second click reverses.
constexpr const char* kScript = R"js(
document.querySelectorAll('table.sortable').forEach(function (table) {
  table.querySelectorAll('th').forEach(function (th, column) {
    th.addEventListener('click', function () {
      var body = table.tBodies[0];
      var rows = Array.prototype.slice.call(body.rows);
      var ascending = th.dataset.order !== 'asc';
      th.dataset.order = ascending ? 'asc' : 'desc';
      var key = function (row) {
        var cell = row.cells[column];
        var text = cell.dataset.value !== undefined ? cell.dataset.value : cell.textContent;
        var number = parseFloat(text);
        return isNaN(number) ? text : number;
      };
      rows.sort(function (a, b) {
        var x = key(a), y = key(b);
        var order = (typeof x === typeof y) ? (x < y ? -1 : x > y ? 1 : 0) : (typeof x === 'number' ? -1 : 1);
        return ascending ? order : -order;
      });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
)js";

// Numbers (and "x1.02" ratios) align right, text left.
bool looksNumeric(const std::string& cell) {
  size_t i = cell.starts_with("x") || cell.starts_with("-") ? 1 : 0;
  return i < cell.size() && std::isdigit(static_cast<unsigned char>(cell[i]));
}

}  // namespace

std::string escape(std::string_view text) { return escapeXml(text); }

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t chunk = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) chunk |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) chunk |= uint32_t(uint8_t(bytes[i + 2]));
    out += kDigits[(chunk >> 18) & 63];
    out += kDigits[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[chunk & 63] : '=';
  }
  return out;
}

std::string pngDataUri(const std::string& pngBytes) { return "data:image/png;base64," + base64(pngBytes); }

std::string Table::html() const {
  std::string out = fmt::format("<table id=\"{}\"{}>\n<thead><tr>", escape(id), sortable ? " class=\"sortable\"" : "");
  for (const auto& h : header) out += "<th>" + escape(h) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const auto& cell : row) out += cell.starts_with("<td") ? cell : looksNumeric(cell) ? "<td>" + cell + "</td>" : "<td class=\"text\">" + cell + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody></table>\n";
}

std::string factList(const std::vector<std::pair<std::string, std::string>>& facts) {
  std::string out = "<dl class=\"facts\">\n";
  for (const auto& [name, value] : facts) out += fmt::format("<dt>{}</dt><dd>{}</dd>\n", escape(name), escape(value));
  return out + "</dl>\n";
}

Page::Page(std::string title) : title_(std::move(title)) {}

void Page::section(const std::string& id, const std::string& heading, const std::string& body) {
  body_ += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n", escape(id), escape(heading), body);
}

std::string Page::html() const {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{0}</title>\n<style>{1}</style>\n"
      "</head>\n<body>\n<h1>{0}</h1>\n{2}<script>{3}</script>\n</body>\n</html>\n",
      escape(title_), kStyle, body_, kScript);
}

}  // namespace aor::html
