// image_io: EXR helpers and PNG previews, read back with OpenEXR and libpng directly.
#include <limits>

#include <Imath/ImathBox.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <png.h>

#include "test_support.h"

namespace aor::test {
namespace {

struct PngPixels {
  int width = 0, height = 0;
  png_uint_32 format = 0;
  std::vector<std::uint8_t> bytes;
};

PngPixels readPng(const fs::path& path, png_uint_32 format) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  PngPixels out;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    ADD_FAILURE() << "libpng cannot read " << path << ": " << image.message;
    return out;
  }
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.format = image.format;  // as stored
  image.format = format;
  out.bytes.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.bytes.data(), 0, nullptr))
    ADD_FAILURE() << "libpng cannot decode " << path << ": " << image.message;
  return out;
}

using ImageIo = TempDirTest;

TEST_F(ImageIo, PngGrayValuesClampedAndRounded) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // 4x2, row 0 at the top.
  const std::vector<float> v = {0.0f, 1.0f, 0.5f, 0.2f,  //
                                -0.3f, 7.0f, nan, inf};
  writePngGray(dir / "g.png", 4, 2, v.data());
  const PngPixels p = readPng(dir / "g.png", PNG_FORMAT_GRAY);
  EXPECT_EQ(p.width, 4);
  EXPECT_EQ(p.height, 2);
  EXPECT_EQ(p.format, static_cast<png_uint_32>(PNG_FORMAT_GRAY));  // stored as 8-bit gray
  const std::vector<std::uint8_t> expected = {0, 255, 128, 51, 0, 255, 0, 255};
  EXPECT_EQ(p.bytes, expected);
}

TEST_F(ImageIo, PngRgbValues) {
  // 2x2 RGB: distinct values per channel and pixel so a transposition or channel swap shows.
  const std::vector<float> v = {1.0f, 0.0f, 0.0f,  0.0f, 1.0f, 0.0f,  //
                                0.0f, 0.0f, 1.0f,  0.25f, 0.75f, 0.1f};
  writePngRgb(dir / "c.png", 2, 2, v.data());
  const PngPixels p = readPng(dir / "c.png", PNG_FORMAT_RGB);
  EXPECT_EQ(p.format, static_cast<png_uint_32>(PNG_FORMAT_RGB));
  const std::vector<std::uint8_t> expected = {255, 0, 0, 0, 255, 0, 0, 0, 255, 64, 191, 26};
  EXPECT_EQ(p.bytes, expected);
}

TEST_F(ImageIo, PngIsDeterministicAndHasNoTimeChunk) {
  std::vector<float> v(16 * 9);
  for (size_t i = 0; i < v.size(); ++i) v[i] = hash01(static_cast<std::uint32_t>(i));
  writePngGray(dir / "a.png", 16, 9, v.data());
  writePngGray(dir / "b.png", 16, 9, v.data());
  const std::string a = readBytes(dir / "a.png");
  EXPECT_EQ(a, readBytes(dir / "b.png"));
  EXPECT_EQ(a.find("tIME"), std::string::npos);
  EXPECT_EQ(a.substr(1, 3), "PNG");
}

TEST_F(ImageIo, PngToAMissingFolderIsAnInputError) {
  const float v = 0.5f;
  EXPECT_INPUT_ERROR(writePngGray(dir / "no/such/folder/x.png", 1, 1, &v), "x.png", "cannot create");
}

TEST_F(ImageIo, ExrRoundTripAndHeader) {
  const int w = 5, h = 3;
  std::vector<float> a(w * h), b(w * h);
  for (int i = 0; i < w * h; ++i) {
    a[i] = 0.1f * i;
    b[i] = -0.5f + 0.03125f * i;  // exactly representable in half
  }
  writeExr(dir / "t.exr", w, h, {{"a", ExrPixelType::Float, a.data()}, {"b", ExrPixelType::Half, b.data()}});
  const auto header = readExrHeader(dir / "t.exr");
  EXPECT_EQ(header.width, w);
  EXPECT_EQ(header.height, h);
  EXPECT_EQ(header.channels, (std::map<std::string, ExrPixelType>{{"a", ExrPixelType::Float}, {"b", ExrPixelType::Half}}));
  auto planes = readExrChannels(dir / "t.exr", {"a", "b"});
  EXPECT_EQ(planes["a"], a);
  EXPECT_EQ(planes["b"], b);
}

TEST_F(ImageIo, ExrMissingChannelNamesFileAndChannel) {
  const float v[4] = {1, 2, 3, 4};
  writeExr(dir / "t.exr", 2, 2, {{"depth", ExrPixelType::Float, v}});
  EXPECT_INPUT_ERROR(readExrChannels(dir / "t.exr", {"depth", "visibility"}), "t.exr", "channel \"visibility\"",
                     "missing", "depth");
}

TEST_F(ImageIo, ExrMissingOrGarbageFile) {
  EXPECT_INPUT_ERROR(readExrHeader(dir / "none.exr"), "none.exr", "does not exist");
  writeBytes(dir / "text.exr", "this is not an EXR file at all, just text");
  EXPECT_INPUT_ERROR(readExrHeader(dir / "text.exr"), "text.exr", "not a readable OpenEXR file");
  EXPECT_INPUT_ERROR(readExrChannels(dir / "text.exr", {"depth"}), "text.exr");
}

// Files from other tools: a data window that does not start at (0, 0), and tiles.
TEST_F(ImageIo, ExrWithOffsetDataWindowReadsRowZeroAtTheTop) {
  const int w = 3, h = 2;
  const Imath::Box2i dw(Imath::V2i(10, 20), Imath::V2i(10 + w - 1, 20 + h - 1));
  Imf::Header header(dw, dw);
  header.channels().insert("depth", Imf::Channel(Imf::FLOAT));
  const std::vector<float> v = {1, 2, 3, 4, 5, 6};
  {
    Imf::OutputFile file((dir / "o.exr").c_str(), header);
    Imf::FrameBuffer fb;
    fb.insert("depth", Imf::Slice::Make(Imf::FLOAT, v.data(), dw));
    file.setFrameBuffer(fb);
    file.writePixels(h);
  }
  EXPECT_EQ(readExrHeader(dir / "o.exr").width, w);
  EXPECT_EQ(readExrChannels(dir / "o.exr", {"depth"})["depth"], v);
}

TEST_F(ImageIo, TiledExrIsReadable) {
  const int w = 7, h = 5;
  Imf::Header header(w, h);
  header.setTileDescription(Imf::TileDescription(4, 4, Imf::ONE_LEVEL));
  header.channels().insert("visibility", Imf::Channel(Imf::FLOAT));
  std::vector<float> v(w * h);
  for (int i = 0; i < w * h; ++i) v[i] = 0.01f * i;
  {
    Imf::TiledOutputFile file((dir / "t.exr").c_str(), header);
    Imf::FrameBuffer fb;
    fb.insert("visibility", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(v.data()), 4, 4 * w));
    file.setFrameBuffer(fb);
    file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
  }
  EXPECT_EQ(readExrHeader(dir / "t.exr").height, h);
  EXPECT_EQ(readExrChannels(dir / "t.exr", {"visibility"})["visibility"], v);
}

}  // namespace
}  // namespace aor::test
