// Which .rdc files an import reads, and in what order.
#include <fstream>

#include <gtest/gtest.h>

#include "core/input_error.h"
#include "import/renderdoc_import.h"

namespace aor {
namespace {
namespace fs = std::filesystem;

TEST(RenderDocInputs, FramesFromDirAreInFileNameOrderWithNumbersCompared) {
  const fs::path dir = fs::path(AOR_BINARY_DIR) / "import-inputs-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {"app_frame10.rdc", "app_frame9.rdc", "app_frame100.rdc", "notes.txt"})
    std::ofstream(dir / name) << "x";
  RenderDocImportOptions o;
  o.framesFromDir = dir;
  const auto files = renderDocInputs(o);
  ASSERT_EQ(files.size(), 3u) << "only .rdc files";
  EXPECT_EQ(files[0].filename(), "app_frame9.rdc");
  EXPECT_EQ(files[1].filename(), "app_frame10.rdc");
  EXPECT_EQ(files[2].filename(), "app_frame100.rdc");
  fs::remove_all(dir);
}

TEST(RenderDocInputs, MissingFilesAndEmptyFoldersAreBadInput) {
  RenderDocImportOptions o;
  EXPECT_THROW(renderDocInputs(o), InputError);
  o.files = {"/nonexistent/x.rdc"};
  EXPECT_THROW(renderDocInputs(o), InputError);
}

}  // namespace
}  // namespace aor
