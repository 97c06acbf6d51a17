#include "core/json_input.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <simdjson.h>

#include "core/input_error.h"

namespace aor {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

[[noreturn]] void fail(const std::string& display, const std::string& field, const std::string& problem) {
  throw InputError(display, std::nullopt, field, problem);
}

std::string tooDeep(int maxDepth) {
  return fmt::format("nested deeper than {} levels (objects and arrays inside each other)", maxDepth);
}
std::string tooLong(std::uint64_t maxElements) {
  return fmt::format("has more than {} elements, the limit for this file", maxElements);
}
constexpr const char* kDuplicate = "appears twice in the same object";

// Where a value is, as a chain of links from the value up to the top, spelt out only for a
// message: "frames[3].view".
struct PathLink {
  const PathLink* parent = nullptr;
  std::string_view key;  // member name; unused for an array element
  size_t index = 0;
  bool isIndex = false;
};

std::string pathText(const PathLink* link) {
  std::vector<const PathLink*> chain;
  for (; link; link = link->parent) chain.push_back(link);
  std::string text;
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    if ((*it)->isIndex) {
      text += fmt::format("[{}]", (*it)->index);
    } else {
      if (!text.empty()) text += '.';
      text += (*it)->key;
    }
  }
  return text;
}

// ---- fast path: simdjson's DOM, converted to nlohmann's -------------------------------------------

class SimdjsonConverter {
 public:
  SimdjsonConverter(const JsonLimits& limits, const std::string& display) : limits_(limits), display_(display) {}

  json convert(simdjson::dom::element e, const PathLink* where, int depth) const {
    using Type = simdjson::dom::element_type;
    switch (e.type()) {
      case Type::ARRAY: return convertArray(e.get_array().value_unsafe(), where, depth);
      case Type::OBJECT: return convertObject(e.get_object().value_unsafe(), where, depth);
      case Type::INT64: {
        // nlohmann keeps non-negative integers unsigned; so does this, for identical documents.
        const std::int64_t v = e.get_int64().value_unsafe();
        return v >= 0 ? json(static_cast<std::uint64_t>(v)) : json(v);
      }
      case Type::UINT64: return json(e.get_uint64().value_unsafe());
      case Type::DOUBLE: return json(e.get_double().value_unsafe());
      case Type::STRING: return json(std::string(e.get_string().value_unsafe()));
      case Type::BOOL: return json(e.get_bool().value_unsafe());
      case Type::NULL_VALUE: return json(nullptr);
    }
    return json(nullptr);
  }

 private:
  void checkDepth(const PathLink* where, int depth) const {
    if (depth > limits_.maxDepth) fail(display_, pathText(where), tooDeep(limits_.maxDepth));
  }

  json convertArray(simdjson::dom::array a, const PathLink* where, int depth) const {
    checkDepth(where, depth);
    const size_t size = a.size();
    if (size > limits_.maxArrayElements) fail(display_, pathText(where), tooLong(limits_.maxArrayElements));
    json out = json::array();
    auto& elements = out.get_ref<json::array_t&>();
    elements.reserve(size);
    PathLink link{where, {}, 0, true};
    for (simdjson::dom::element child : a) {
      elements.push_back(convert(child, &link, depth + 1));
      ++link.index;
    }
    return out;
  }

  json convertObject(simdjson::dom::object o, const PathLink* where, int depth) const {
    checkDepth(where, depth);
    json out = json::object();
    auto& members = out.get_ref<json::object_t&>();
    for (simdjson::dom::key_value_pair member : o) {
      PathLink link{where, member.key, 0, false};
      auto [it, inserted] = members.try_emplace(std::string(member.key));
      if (!inserted) fail(display_, pathText(&link), kDuplicate);
      it->second = convert(member.value, &link, depth + 1);
    }
    return out;
  }

  const JsonLimits& limits_;
  const std::string& display_;
};

std::optional<json> parseWithSimdjson(std::string_view text, const JsonLimits& limits, const std::string& display) {
  simdjson::dom::parser parser;
  // One level more than allowed, so a document just over the limit still parses and gets the
  // same message (with its path) as from the converter.
  if (parser.allocate(text.size(), size_t(limits.maxDepth) + 1) != simdjson::SUCCESS) return std::nullopt;
  simdjson::dom::element root;
  if (parser.parse(text.data(), text.size()).get(root) != simdjson::SUCCESS) return std::nullopt;
  return SimdjsonConverter(limits, display).convert(root, nullptr, 1);
}

// ---- slow path: nlohmann's SAX parser, for the line and column of an error ----------------------------

// Builds the document as nlohmann's own DOM parser does, with the limits checked at each event.
class BoundedSaxBuilder : public nlohmann::json_sax<json> {
 public:
  BoundedSaxBuilder(std::string_view text, const JsonLimits& limits, const std::string& display)
      : text_(text), limits_(limits), display_(display) {}

  json take() { return std::move(root_); }

  bool null() override { return place(json(nullptr)); }
  bool boolean(bool v) override { return place(json(v)); }
  bool number_integer(number_integer_t v) override { return place(json(v)); }
  bool number_unsigned(number_unsigned_t v) override { return place(json(v)); }
  bool number_float(number_float_t v, const string_t&) override { return place(json(v)); }
  bool string(string_t& v) override { return place(json(std::move(v))); }
  bool binary(binary_t& v) override { return place(json::binary(std::move(v))); }
  bool start_object(std::size_t) override { return open(json::object()); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& name) override {
    Open& top = stack_.back();
    auto [it, inserted] = top.node->get_ref<json::object_t&>().try_emplace(name);
    top.segment = name;
    if (!inserted) fail(display_, currentPath(), kDuplicate);
    top.slot = &it->second;
    return true;
  }

  bool parse_error(std::size_t position, const std::string& lastToken, const nlohmann::detail::exception& e) override {
    std::string what = e.what();
    if (!what.empty() && what.front() == '[') {  // drop nlohmann's "[json.exception.parse_error.101] " tag
      const auto close = what.find("] ");
      if (close != std::string::npos) what = what.substr(close + 2);
    }
    if (lastToken.size() > 100) {  // a 200 MB string is not echoed back
      const std::string quoted = "'" + lastToken + "'";
      if (const auto at = what.find(quoted); at != std::string::npos)
        what.replace(at, quoted.size(), quoteForMessage(lastToken));
    }
    if (e.id == 406) {  // a number too large for a double: nlohmann gives no position
      const size_t start = std::min(text_.size(), position >= lastToken.size() ? position - lastToken.size() : 0);
      const size_t lineStart = text_.rfind('\n', start == 0 ? 0 : start - 1);
      const size_t line = 1 + size_t(std::count(text_.begin(), text_.begin() + std::ptrdiff_t(start), '\n'));
      const size_t column = start - (lineStart == std::string_view::npos || lineStart >= start ? 0 : lineStart + 1) + 1;
      what = fmt::format("at line {}, column {}: {} (numbers must be finite)", line, column, what);
    }
    fail(display_, "", "malformed JSON: " + what);
  }

 private:
  struct Open {
    json* node;
    json* slot = nullptr;  // the member a key was read for (objects)
    std::string segment;   // this container's current member name (objects)
  };

  // The path to the value being read now (a member of, or the next element of, the innermost container).
  std::string currentPath() const {
    std::string text;
    for (const Open& open : stack_) {
      if (open.node->is_array()) {
        text += fmt::format("[{}]", open.node->size() - (&open == &stack_.back() ? 0 : 1));
      } else {
        if (!text.empty()) text += '.';
        text += open.segment;
      }
    }
    return text;
  }

  json* place(json&& value) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Open& top = stack_.back();
    if (!top.node->is_array()) {
      *top.slot = std::move(value);
      return top.slot;
    }
    auto& elements = top.node->get_ref<json::array_t&>();
    if (elements.size() >= limits_.maxArrayElements) {
      // The path of the array itself, not of the element past the limit.
      std::string path = currentPath();
      path.erase(path.rfind('['));
      fail(display_, path, tooLong(limits_.maxArrayElements));
    }
    elements.push_back(std::move(value));
    return &elements.back();
  }

  bool open(json&& container) {
    if (int(stack_.size()) >= limits_.maxDepth) fail(display_, currentPath(), tooDeep(limits_.maxDepth));
    json* node = place(std::move(container));
    stack_.push_back({node});
    return true;
  }

  bool close() {
    stack_.pop_back();
    return true;
  }

  std::string_view text_;
  const JsonLimits& limits_;
  const std::string& display_;
  json root_;
  std::vector<Open> stack_;
};

json parseWithNlohmann(std::string_view text, const JsonLimits& limits, const std::string& display) {
  BoundedSaxBuilder builder(text, limits, display);
  json::sax_parse(text.begin(), text.end(), &builder);
  return builder.take();
}

// ---- reading ---------------------------------------------------------------------------------------

struct FileDescriptor {
  int fd;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

json parseBoundedJson(std::string_view text, const JsonLimits& limits, const std::string& display) {
  if (auto parsed = parseWithSimdjson(text, limits, display)) return std::move(*parsed);
  return parseWithNlohmann(text, limits, display);
}

namespace detail {
json parseBoundedJsonSlowly(std::string_view text, const JsonLimits& limits, const std::string& display) {
  return parseWithNlohmann(text, limits, display);
}
}  // namespace detail

std::string readBoundedText(const fs::path& path, std::uint64_t maxBytes, const std::string& display) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer (it is refused right after).
  FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC)};
  if (file.fd < 0) fail(display, "", fmt::format("cannot open: {}", std::strerror(errno)));
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) fail(display, "", fmt::format("cannot read: {}", std::strerror(errno)));
  if (S_ISDIR(st.st_mode)) fail(display, "", "is a folder, not a file");
  if (!S_ISREG(st.st_mode))
    fail(display, "", "is not a regular file (a FIFO, socket or device); only regular files are read");
  const auto tooLarge = [&](std::uint64_t size) {
    fail(display, "", fmt::format("is {} bytes, over the limit of {} bytes for this file", size, maxBytes));
  };
  if (std::uint64_t(st.st_size) > maxBytes) tooLarge(std::uint64_t(st.st_size));
  std::string text;
  text.reserve(size_t(st.st_size));
  std::vector<char> chunk(size_t(1) << 16);
  for (;;) {
    const ssize_t n = ::read(file.fd, chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(display, "", fmt::format("cannot read: {}", std::strerror(errno)));
    if (n == 0) break;
    text.append(chunk.data(), size_t(n));
    if (text.size() > maxBytes) tooLarge(text.size());  // it grew while being read
  }
  return text;
}

json readBoundedJson(const fs::path& path, const JsonLimits& limits, const std::string& display) {
  const std::string name = display.empty() ? path.string() : display;
  return parseBoundedJson(readBoundedText(path, limits.maxBytes, name), limits, name);
}

std::string quoteForMessage(std::string_view text, size_t maxChars) {
  size_t cut = text.size();
  if (cut > maxChars) {
    cut = maxChars;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 sequence
  }
  std::string quoted = json(std::string(text.substr(0, cut))).dump(-1, ' ', false, json::error_handler_t::replace);
  if (cut < text.size()) quoted += fmt::format("... ({} bytes)", text.size());
  return quoted;
}

}  // namespace aor
