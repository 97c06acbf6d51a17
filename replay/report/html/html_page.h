#pragma once
// The parts every HTML report shares (report.html, sweep.html, compare.html): one self-contained
// file with its style and a small script inline and images as PNG data URIs, so it opens from
// disk, mailed or archived as CI output, with no network access.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace aor::html {

std::string escape(std::string_view text);  // & < > " '
std::string base64(std::string_view bytes);
std::string pngDataUri(const std::string& pngBytes);

// A table; with `sortable` a click on a column heading sorts by it (numbers by value).
struct Table {
  std::string id;
  std::vector<std::string> header;            // text
  std::vector<std::vector<std::string>> rows;  // cells as HTML (escape text yourself)
  bool sortable = false;
  std::string html() const;
};

// "name: value" rows for the page's facts (device, capture, settings).
std::string factList(const std::vector<std::pair<std::string, std::string>>& facts);

class Page {
 public:
  explicit Page(std::string title);
  // A section with an id the browser test looks for; `body` is HTML.
  void section(const std::string& id, const std::string& heading, const std::string& body);
  std::string html() const;

 private:
  std::string title_;
  std::string body_;
};

}  // namespace aor::html
