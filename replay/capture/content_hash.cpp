#include "capture/content_hash.h"

#include <fstream>
#include <memory>
#include <set>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <openssl/evp.h>

#ifndef AOREPLAY_VERSION
#define AOREPLAY_VERSION "unknown"
#endif

namespace aor {
namespace fs = std::filesystem;

namespace {

using DigestContext = std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)>;

DigestContext newSha256() {
  DigestContext context(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("cannot start a SHA-256 digest (OpenSSL)");
  return context;
}

void update(EVP_MD_CTX* context, const void* data, size_t size) {
  if (EVP_DigestUpdate(context, data, size) != 1) throw std::runtime_error("SHA-256 digest failed (OpenSSL)");
}

void updateWithFile(EVP_MD_CTX* context, const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {} to hash it", path.string()));
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    update(context, buffer.data(), size_t(in.gcount()));
  }
  if (in.bad()) throw std::runtime_error(fmt::format("cannot read {} to hash it", path.string()));
}

std::string hexDigest(EVP_MD_CTX* context) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_DigestFinal_ex(context, digest, &size) != 1) throw std::runtime_error("SHA-256 digest failed (OpenSSL)");
  std::string hex;
  for (unsigned int i = 0; i < size; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

}  // namespace

std::string captureContentSha256(const Capture& capture) {
  std::set<std::string> files{"capture.json"};  // relative, generic form: the same on every machine
  for (const auto& frame : capture.frames) {
    files.insert(fs::relative(frame.gbuffer, capture.folder).generic_string());
    if (frame.reference) files.insert(fs::relative(*frame.reference, capture.folder).generic_string());
  }
  if (capture.geometry) files.insert(fs::relative(*capture.geometry, capture.folder).generic_string());
  auto context = newSha256();
  for (const auto& name : files) {
    fs::path path = capture.folder / name;
    std::string header = fmt::format("{}\n{}\n", name, fs::file_size(path));
    update(context.get(), header.data(), header.size());
    updateWithFile(context.get(), path);
  }
  return hexDigest(context.get());
}

std::string fileSha256(const fs::path& path) {
  auto context = newSha256();
  updateWithFile(context.get(), path);
  return hexDigest(context.get());
}

std::string textSha256(std::string_view text) {
  auto context = newSha256();
  update(context.get(), text.data(), text.size());
  return hexDigest(context.get());
}

const char* aoreplayVersion() { return AOREPLAY_VERSION; }

}  // namespace aor
