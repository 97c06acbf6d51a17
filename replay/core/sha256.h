#pragma once
// SHA-256 digests (OpenSSL), as lower-case hex: the identity of captures, reports and cached
// shaders.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace aor {

// A digest fed piece by piece. Throws std::runtime_error when OpenSSL fails or a file cannot be read.
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void update(const void* data, size_t size);
  void update(std::string_view text) { update(text.data(), text.size()); }
  void updateWithFile(const std::filesystem::path& path);  // its bytes, read in 1 MiB pieces
  std::string hex();                                        // ends the digest

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

// Lower-case hex SHA-256 of a file's bytes.
std::string fileSha256(const std::filesystem::path& path);

// Lower-case hex SHA-256 of text.
std::string textSha256(std::string_view text);

}  // namespace aor
