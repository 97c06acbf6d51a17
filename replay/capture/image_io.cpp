#include "capture/image_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <type_traits>

#include <Imath/ImathBox.h>
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfVersion.h>
#include <OpenEXR/Iex.h>
#include <fmt/format.h>
#include <png.h>

#include "capture/exr_detail.h"
#include "core/input_error.h"

namespace fs = std::filesystem;

namespace aor {
namespace detail {

const char* kindName(ExrChannelKind kind) {
  switch (kind) {
    case ExrChannelKind::Half: return "HALF";
    case ExrChannelKind::Float: return "FLOAT";
    case ExrChannelKind::Uint: return "UINT";
  }
  return "?";
}

std::string channelList(const ExrHeaderDetail& h) {
  std::string s;
  for (const auto& [name, kind] : h.channels) {
    if (!s.empty()) s += ", ";
    s += name;
  }
  return s.empty() ? std::string("none") : s;
}

std::string displayPath(const fs::path& path) {
  std::error_code ec;
  fs::path abs = fs::absolute(path, ec);
  if (ec) return path.string();
  abs = abs.lexically_normal();
  fs::path cwd = fs::current_path(ec);
  if (ec) return abs.string();
  fs::path rel = abs.lexically_relative(cwd);
  if (rel.empty() || *rel.begin() == "..") return abs.string();
  return rel.string();
}

}  // namespace detail

namespace {

using detail::ExrChannelKind;
using detail::ExrHeaderDetail;

// OpenEXR allocates tables from header fields before anything else is checked; these limits make
// a damaged header fail with an exception instead of a huge allocation. Process-wide, set once.
void configureOpenExr() {
  static std::once_flag once;
  std::call_once(once, [] {
    Imf::Header::setMaxImageSize(4 * detail::kMaxImageSide, 4 * detail::kMaxImageSide);
    Imf::Header::setMaxTileSize(4096, 4096);
    // Line blocks are (de)compressed on OpenEXR's own pool: the first frame's decode is on the
    // replay's critical path. The pixels do not depend on the thread count.
    Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency())));
  });
}

std::string errnoText() { return std::strerror(errno); }

// Existence / type of the file before OpenEXR sees it, for clearer messages.
void checkIsFile(const fs::path& path, const std::string& display, std::optional<int> frame) {
  std::error_code ec;
  auto st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputError(display, frame, "", "file does not exist");
  if (fs::is_directory(st)) throw InputError(display, frame, "", "is a folder, not an EXR file");
  if (!fs::is_regular_file(st)) throw InputError(display, frame, "", "is not a regular file");
}

int linesPerChunk(int compression) {
  switch (compression) {
    case Imf::NO_COMPRESSION:
    case Imf::RLE_COMPRESSION:
    case Imf::ZIPS_COMPRESSION: return 1;
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION: return 16;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION: return 32;
    case Imf::DWAB_COMPRESSION: return 256;
    default: return 0;
  }
}

// Reads a file at given offsets with pread: the first kHeadBytes (header and, usually, the line offset
// table) once, the rest a few bytes at a time. Seeking an ifstream re-reads its whole buffer at
// every seek, which made checking a capture of 10^5 frames take half a minute.
class OffsetReader {
 public:
  static constexpr size_t kHeadBytes = size_t(1) << 13;
  // O_NONBLOCK: opening a FIFO does not wait for a writer (it is then refused).
  explicit OffsetReader(const fs::path& path) : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)) {
    if (fd_ < 0) return;
    struct stat st {};
    if (::fstat(fd_, &st) != 0) return;
    size_ = std::uintmax_t(st.st_size);
    regular_ = S_ISREG(st.st_mode);
    if (!regular_) return;  // a FIFO or device is not read
    head_.resize(kHeadBytes);
    const ssize_t n = ::pread(fd_, head_.data(), head_.size(), 0);
    head_.resize(n > 0 ? size_t(n) : 0);
  }
  ~OffsetReader() {
    if (fd_ >= 0) ::close(fd_);
  }
  OffsetReader(const OffsetReader&) = delete;
  OffsetReader& operator=(const OffsetReader&) = delete;
  bool ok() const { return fd_ >= 0; }
  const std::vector<char>& head() const { return head_; }
  std::uintmax_t size() const { return size_; }
  bool isRegularFile() const { return regular_; }

  bool read(std::uint64_t offset, void* out, size_t n) const {
    if (offset + n <= head_.size()) {
      std::memcpy(out, head_.data() + offset, n);
      return true;
    }
    return ::pread(fd_, out, n, off_t(offset)) == ssize_t(n);
  }
  template <typename T>
  bool readLE(std::uint64_t& offset, T& value) const {
    unsigned char bytes[sizeof(T)];
    if (!read(offset, bytes, sizeof(T))) return false;
    offset += sizeof(T);
    std::make_unsigned_t<T> v = 0;
    for (size_t i = 0; i < sizeof(T); ++i) v |= static_cast<std::make_unsigned_t<T>>(bytes[i]) << (8 * i);
    value = static_cast<T>(v);
    return true;
  }

 private:
  int fd_;
  std::uintmax_t size_ = 0;
  bool regular_ = false;
  std::vector<char> head_;
};

// An Imf::IStream over the first bytes of a file (OffsetReader::head): the header is parsed from
// memory. Reading past them throws, as reading past the end of a file does.
class HeadStream : public Imf::IStream {
 public:
  HeadStream(const std::vector<char>& bytes, const char* name) : Imf::IStream(name), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || pos_ + std::uint64_t(n) > bytes_.size()) throw Iex::InputExc("Early end of file.");
    std::memcpy(c, bytes_.data() + pos_, size_t(n));
    pos_ += std::uint64_t(n);
    return pos_ < bytes_.size();
  }
  std::uint64_t tellg() override { return pos_; }
  void seekg(std::uint64_t pos) override { pos_ = pos; }
  void clear() override {}

 private:
  const std::vector<char>& bytes_;
  std::uint64_t pos_ = 0;
};

// Whether the header's attribute list ends inside `head` (names, types and sizes walked, values
// skipped): only then is it parsed from memory, with no attribute size larger than those bytes.
bool headerEndsWithin(const std::vector<char>& head, int version) {
  const size_t maxName = (version & Imf::LONG_NAMES_FLAG) ? 256 : 32;
  size_t at = 8;
  const auto skipName = [&](bool& empty) {
    const size_t start = at;
    while (at < head.size() && head[at] != '\0' && at - start <= maxName) ++at;
    if (at >= head.size() || head[at] != '\0') return false;
    empty = at == start;
    ++at;
    return true;
  };
  for (;;) {
    bool empty = false, emptyType = false;
    if (!skipName(empty)) return false;
    if (empty) return true;
    if (!skipName(emptyType) || at + 4 > head.size()) return false;
    std::int32_t size = 0;
    std::memcpy(&size, head.data() + at, 4);
    at += 4;
    if (size < 0 || std::uint64_t(size) > head.size() - at) return false;
    at += size_t(size);
  }
}

// For single-part scan-line files (what writeCapture and most exporters produce): walks the header
// to find the line offset table and checks that every chunk it lists lies inside the file. Returns
// a problem description, or an empty string when the file is fine or of another kind (tiled,
// multi-part, deep files are checked when their pixels are read).
std::string checkScanlineChunks(const OffsetReader& in, std::uintmax_t fileSize, int version, int compression,
                                int dataHeight) {
  if (Imf::isTiled(version) || Imf::isMultiPart(version) || Imf::isNonImage(version)) return {};
  const int lines = linesPerChunk(compression);
  if (lines == 0 || dataHeight <= 0) return {};
  std::uint64_t at = 0;
  std::int32_t magic = 0, ver = 0;
  if (!in.readLE(at, magic) || !in.readLE(at, ver)) return "file is truncated inside the header";
  const size_t maxName = (ver & Imf::LONG_NAMES_FLAG) ? 256 : 32;
  auto readName = [&](std::string& out) {
    out.clear();
    char c;
    while (in.read(at, &c, 1)) {
      ++at;
      if (c == '\0') return true;
      out.push_back(c);
      if (out.size() > maxName) return false;
    }
    return false;
  };
  std::string name, type;
  for (int attr = 0;; ++attr) {
    if (attr > 100000) return "header has too many attributes";
    if (!readName(name)) return "file is truncated or corrupt inside the header";
    if (name.empty()) break;
    std::int32_t size = 0;
    if (!readName(type) || !in.readLE(at, size) || size < 0) return "file is truncated or corrupt inside the header";
    if (at + static_cast<std::uintmax_t>(size) > fileSize) return "file is truncated inside the header";
    at += std::uint64_t(size);
  }
  const std::uint64_t chunks = (static_cast<std::uint64_t>(dataHeight) + lines - 1) / lines;
  const std::uintmax_t tableStart = at;
  const std::uintmax_t tableEnd = tableStart + chunks * 8;
  if (tableEnd > fileSize)
    return fmt::format("file is truncated: it ends ({} bytes) inside the table of {} pixel data chunks", fileSize,
                       chunks);
  std::vector<std::uint64_t> offsets(chunks);
  for (auto& o : offsets) {
    if (!in.readLE(at, o)) return "file is truncated inside the line offset table";
  }
  for (std::uint64_t i = 0; i < chunks; ++i) {
    std::uint64_t o = offsets[i];
    if (o < tableEnd || o > fileSize || fileSize - o < 8)
      return fmt::format("file is truncated or incomplete: pixel data chunk {} of {} is missing (file has {} bytes)",
                         i, chunks, fileSize);
    const std::uint64_t chunkStart = o;
    std::int32_t y = 0, packed = 0;
    if (!in.readLE(o, y) || !in.readLE(o, packed) || packed < 0)
      return fmt::format("pixel data chunk {} of {} is corrupt", i, chunks);
    if (static_cast<std::uintmax_t>(packed) > fileSize - chunkStart - 8)
      return fmt::format("file is truncated: pixel data chunk {} of {} ends past the end of the file ({} bytes)", i,
                         chunks, fileSize);
  }
  return {};
}

ExrChannelKind kindOf(Imf::PixelType t) {
  switch (t) {
    case Imf::HALF: return ExrChannelKind::Half;
    case Imf::FLOAT: return ExrChannelKind::Float;
    default: return ExrChannelKind::Uint;
  }
}

// Fills `out` from an open file's header; shared by header-only and pixel reading.
ExrHeaderDetail describeHeader(const Imf::Header& header, const std::string& display, std::optional<int> frame) {
  const Imath::Box2i dw = header.dataWindow();
  const std::int64_t w = std::int64_t(dw.max.x) - dw.min.x + 1;
  const std::int64_t h = std::int64_t(dw.max.y) - dw.min.y + 1;
  if (w <= 0 || h <= 0 || w > std::numeric_limits<int>::max() || h > std::numeric_limits<int>::max())
    throw InputError(display, frame, "", fmt::format("invalid data window ({}x{} pixels)", w, h));
  ExrHeaderDetail info;
  info.width = static_cast<int>(w);
  info.height = static_cast<int>(h);
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    const Imf::Channel& ch = it.channel();
    if (ch.xSampling != 1 || ch.ySampling != 1)
      throw InputError(display, frame, it.name(),
                       fmt::format("is subsampled ({}x{}); only full-resolution channels are supported",
                                   ch.xSampling, ch.ySampling));
    info.channels[it.name()] = kindOf(ch.type);
  }
  return info;
}

std::string exceptionText(const std::exception& e) {
  std::string s = e.what();
  return s.empty() ? std::string("unknown error") : s;
}

}  // namespace

namespace detail {

ExrHeaderDetail readExrHeaderDetail(const fs::path& path, const std::string& display, std::optional<int> frame) {
  configureOpenExr();
  const OffsetReader reader(path);
  if (!reader.ok() || !reader.isRegularFile()) {
    const std::string why = reader.ok() ? std::string("not a regular file") : errnoText();
    checkIsFile(path, display, frame);  // the message for what it is instead
    throw InputError(display, frame, "", "cannot open: " + why);
  }
  const std::uintmax_t fileSize = reader.size();
  ExrHeaderDetail info;
  int version = 0, compression = 0;
  try {
    // The header alone, parsed from the file's first bytes: opening an Imf::InputFile would also
    // set up its decoding, for every one of up to 2*10^5 files of a capture. Multi-part and deep
    // files, and headers that do not end within those bytes, still go through Imf::InputFile.
    const auto& head = reader.head();
    std::int32_t magic = 0;
    if (head.size() >= 8) {
      std::memcpy(&magic, head.data(), 4);
      std::memcpy(&version, head.data() + 4, 4);
    }
    const bool simple = head.size() >= 8 && magic == Imf::MAGIC && Imf::getVersion(version) == Imf::EXR_VERSION &&
                        Imf::supportsFlags(Imf::getFlags(version)) && !Imf::isMultiPart(version) &&
                        !Imf::isNonImage(version) && headerEndsWithin(head, version);
    std::optional<Imf::Header> header;
    if (simple) {
      HeadStream stream(head, display.c_str());
      stream.seekg(8);
      header.emplace();
      header->readFrom(stream, version);
      header->sanityCheck(Imf::isTiled(version));
    }
    if (header) {
      info = describeHeader(*header, display, frame);
      compression = static_cast<int>(header->compression());
    } else {
      Imf::InputFile file(path.c_str());
      info = describeHeader(file.header(), display, frame);
      version = file.version();
      compression = static_cast<int>(file.header().compression());
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(display, frame, "", "not a readable OpenEXR file: " + exceptionText(e));
  }
  const std::string problem = checkScanlineChunks(reader, fileSize, version, compression, info.height);
  if (!problem.empty()) throw InputError(display, frame, "", problem);
  return info;
}

std::map<std::string, std::vector<float>> readExrChannelsDetail(const fs::path& path, const std::string& display,
                                                                std::optional<int> frame,
                                                                const std::vector<std::string>& names,
                                                                std::optional<int> expectWidth,
                                                                std::optional<int> expectHeight) {
  configureOpenExr();
  checkIsFile(path, display, frame);
  std::map<std::string, std::vector<float>> planes;
  std::unique_ptr<Imf::InputFile> opened;
  try {
    opened = std::make_unique<Imf::InputFile>(path.c_str());
  } catch (const std::exception& e) {
    throw InputError(display, frame, "", "not a readable OpenEXR file: " + exceptionText(e));
  }
  try {
    Imf::InputFile& file = *opened;
    const Imf::Header& header = file.header();
    const ExrHeaderDetail info = describeHeader(header, display, frame);
    if ((expectWidth && info.width != *expectWidth) || (expectHeight && info.height != *expectHeight))
      throw InputError(display, frame, "",
                       fmt::format("image is {}x{} but {}x{} was expected", info.width, info.height,
                                   expectWidth.value_or(info.width), expectHeight.value_or(info.height)));
    const std::int64_t pixels = std::int64_t(info.width) * info.height;
    if (pixels > kMaxImagePixels)
      throw InputError(display, frame, "",
                       fmt::format("image is {}x{} = {} pixels, more than the limit of {} pixels", info.width,
                                   info.height, pixels, kMaxImagePixels));
    const Imath::Box2i dw = header.dataWindow();
    Imf::FrameBuffer fb;
    for (const std::string& name : names) {
      if (planes.count(name)) continue;
      if (!info.channels.count(name))
        throw InputError(display, frame, name, "missing (channels present: " + channelList(info) + ")");
      auto& plane = planes[name];
      plane.assign(static_cast<size_t>(pixels), 0.0f);
      // Slice::Make handles data windows that do not start at (0, 0); row dw.min.y is row 0.
      fb.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data(), dw));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(display, frame, "", "cannot read pixel data (truncated or corrupt file?): " + exceptionText(e));
  }
  return planes;
}

}  // namespace detail

// ---- public EXR API ---------------------------------------------------------------------------

void writeExr(const fs::path& path, int width, int height, const std::vector<ExrChannel>& channels) {
  if (width <= 0 || height <= 0) throw std::invalid_argument(fmt::format("writeExr: invalid size {}x{}", width, height));
  if (channels.empty()) throw std::invalid_argument("writeExr: no channels");
  std::set<std::string> seen;
  for (const auto& ch : channels) {
    if (ch.name.empty()) throw std::invalid_argument("writeExr: empty channel name");
    if (!seen.insert(ch.name).second) throw std::invalid_argument("writeExr: duplicate channel " + ch.name);
    if (!ch.data) throw std::invalid_argument("writeExr: channel " + ch.name + " has no data");
  }
  configureOpenExr();
  const std::string display = path.string();
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);

  // Only the attributes every EXR must have (channels, compression, dataWindow, displayWindow,
  // lineOrder, pixelAspectRatio, screenWindowCenter, screenWindowWidth): no time stamps, no
  // host names, so the same pixels always give the same bytes.
  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  header.lineOrder() = Imf::INCREASING_Y;
  Imf::FrameBuffer fb;
  std::vector<std::vector<Imath::half>> halves;
  halves.reserve(channels.size());
  for (const auto& ch : channels) {
    if (ch.type == ExrPixelType::Half) {
      auto& buf = halves.emplace_back(pixels);
      for (size_t i = 0; i < pixels; ++i) buf[i] = Imath::half(ch.data[i]);
      header.channels().insert(ch.name, Imf::Channel(Imf::HALF));
      fb.insert(ch.name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(buf.data()), sizeof(Imath::half),
                                    sizeof(Imath::half) * static_cast<size_t>(width)));
    } else {
      header.channels().insert(ch.name, Imf::Channel(Imf::FLOAT));
      fb.insert(ch.name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(ch.data)), sizeof(float),
                                    sizeof(float) * static_cast<size_t>(width)));
    }
  }

  std::ofstream os(path, std::ios::binary | std::ios::trunc);
  if (!os) throw InputError(display, std::nullopt, "", "cannot create file: " + errnoText());
  try {
    Imf::StdOFStream stream(os, display.c_str());
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(fb);
    file.writePixels(height);
  } catch (const std::exception& e) {
    throw InputError(display, std::nullopt, "", "cannot write EXR: " + exceptionText(e));
  }
  os.close();
  if (!os) throw InputError(display, std::nullopt, "", "cannot write EXR: " + errnoText());
}

ExrHeaderInfo readExrHeader(const fs::path& path) {
  const std::string display = path.string();
  const ExrHeaderDetail detail = detail::readExrHeaderDetail(path, display, std::nullopt);
  ExrHeaderInfo info;
  info.width = detail.width;
  info.height = detail.height;
  for (const auto& [name, kind] : detail.channels) {
    if (kind == ExrChannelKind::Uint)
      throw InputError(display, std::nullopt, name, "has type UINT; only HALF and FLOAT channels are supported");
    info.channels[name] = kind == ExrChannelKind::Half ? ExrPixelType::Half : ExrPixelType::Float;
  }
  return info;
}

std::map<std::string, std::vector<float>> readExrChannels(const fs::path& path, const std::vector<std::string>& names) {
  return detail::readExrChannelsDetail(path, path.string(), std::nullopt, names);
}

// ---- PNG ------------------------------------------------------------------------------------------

namespace {

std::uint8_t toByte(float v) {
  if (!(v > 0.0f)) return 0;  // NaN, negative, zero
  if (v >= 1.0f) return 255;
  return static_cast<std::uint8_t>(std::lround(static_cast<double>(v) * 255.0));
}

struct PngErrorState {
  std::jmp_buf jump;
  char message[256] = {};
};

void pngError(png_structp png, png_const_charp msg) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof(state->message), "%s", msg ? msg : "libpng error");
  std::longjmp(state->jump, 1);
}

void pngWarning(png_structp, png_const_charp) {}

// libpng reports errors by longjmp; everything with a destructor lives outside this function
// (the caller owns bytes and rows), so the jump skips no C++ cleanup. Returns an error message or
// an empty string.
std::string writePngRaw(FILE* fp, int width, int height, int colorType, png_bytep* rows) {
  PngErrorState state;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, pngError, pngWarning);
  if (!png) return "cannot initialise libpng";
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return "cannot initialise libpng";
  }
  if (setjmp(state.jump)) {
    png_destroy_write_struct(&png, &info);
    return state.message;
  }
  png_init_io(png, fp);
  // Fixed settings and no tIME/text chunks: identical pixels give identical files.
  png_set_compression_level(png, 6);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, colorType,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return {};
}

// 8-bit samples of `values` and the row pointers libpng takes.
struct PngRows {
  std::vector<std::uint8_t> bytes;
  std::vector<png_bytep> rows;
  PngRows(int width, int height, int channels, const float* values) {
    if (width <= 0 || height <= 0) throw std::invalid_argument(fmt::format("writePng: invalid size {}x{}", width, height));
    if (!values) throw std::invalid_argument("writePng: no data");
    const size_t rowBytes = static_cast<size_t>(width) * channels;
    bytes.resize(rowBytes * static_cast<size_t>(height));
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = toByte(values[i]);
    rows.resize(static_cast<size_t>(height));
    for (int y = 0; y < height; ++y) rows[y] = bytes.data() + rowBytes * static_cast<size_t>(y);
  }
};

int pngColorType(int channels) { return channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB; }

void writePng(const fs::path& path, int width, int height, int channels, const float* values) {
  PngRows png(width, height, channels, values);
  const std::string display = path.string();
  FILE* fp = std::fopen(path.c_str(), "wb");
  if (!fp) throw InputError(display, std::nullopt, "", "cannot create file: " + errnoText());
  const std::string error =
      writePngRaw(fp, width, height, pngColorType(channels), png.rows.data());
  const bool closeFailed = std::fclose(fp) != 0;
  if (!error.empty()) throw InputError(display, std::nullopt, "", "cannot write PNG: " + error);
  if (closeFailed) throw InputError(display, std::nullopt, "", "cannot write PNG: " + errnoText());
}

}  // namespace

void writePngGray(const fs::path& path, int width, int height, const float* values) {
  writePng(path, width, height, 1, values);
}

void writePngRgb(const fs::path& path, int width, int height, const float* values) {
  writePng(path, width, height, 3, values);
}

std::string encodePng(int width, int height, int channels, const float* values) {
  if (channels != 1 && channels != 3) throw std::invalid_argument("encodePng: 1 or 3 channels");
  PngRows png(width, height, channels, values);
  char* buffer = nullptr;
  size_t size = 0;
  FILE* memory = open_memstream(&buffer, &size);
  if (!memory) throw std::runtime_error("encodePng: " + errnoText());
  const std::string error = writePngRaw(memory, width, height, pngColorType(channels), png.rows.data());
  std::fclose(memory);  // sets buffer and size
  std::string bytes(buffer ? buffer : "", buffer ? size : 0);
  std::free(buffer);
  if (!error.empty()) throw std::runtime_error("encodePng: " + error);
  return bytes;
}

}  // namespace aor
