// Writes the seed corpus of capture_reader_fuzz (tests/fuzz/corpus/): small valid captures in the
// fuzz input layout (capture.json, NUL, frames/0000.exr), so mutations start from inputs that
// reach the EXR checks. Usage: capture_reader_make_seeds OUTPUT_DIR
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "capture/image_io.h"

namespace fs = std::filesystem;

namespace {

const char* kJsonHead = R"({"format": "aoreplay-capture", "version": 1, "width": 4, "height": 3, "scene": {"ao_radius": 1},
 "frames": [{"gbuffer": "frames/0000.exr",)";
const char* kMatrices = R"( "view": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,-2,1],
 "projection": [1.299038,0,0,0, 0,1.732051,0,0, 0,0,-1.001001,-1, 0,0,-0.1001001,0]}]})";

void writeSeed(const fs::path& out, const std::string& name, const std::string& json, const std::vector<aor::ExrChannel>& channels) {
  fs::path exr = out / "tmp.exr";
  std::string bytes = json;
  if (!channels.empty()) {
    aor::writeExr(exr, 4, 3, channels);
    std::ifstream in(exr, std::ios::binary);
    bytes.push_back('\0');
    bytes.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    fs::remove(exr);
  }
  std::ofstream(out / name, std::ios::binary) << bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  fs::path out = argv[1];
  fs::create_directories(out);
  std::vector<float> depth = {0.9f, 0.95f, 0.99f, 1.0f, 0.5f, 0.7f, 0.8f, 0.999f, 0.2f, 0.3f, 0.4f, 0.6f};
  std::vector<float> nx(12, 0.0f), ny(12, 1.0f), nz(12, 0.0f), vis(12, 0.5f);
  using aor::ExrPixelType;
  writeSeed(out, "depth-normals", std::string(kJsonHead) + kMatrices,
            {{"depth", ExrPixelType::Float, depth.data()},
             {"normal.X", ExrPixelType::Half, nx.data()},
             {"normal.Y", ExrPixelType::Half, ny.data()},
             {"normal.Z", ExrPixelType::Half, nz.data()}});
  writeSeed(out, "depth-only", std::string(kJsonHead) + kMatrices, {{"depth", ExrPixelType::Float, depth.data()}});
  writeSeed(out, "reference-cut", std::string(kJsonHead) + R"( "reference": "frames/0000.exr", "cut": true,)" + kMatrices,
            {{"depth", ExrPixelType::Float, depth.data()}, {"visibility", ExrPixelType::Float, vis.data()}});
  writeSeed(out, "json-only", std::string(kJsonHead) + kMatrices, {});
  return 0;
}
