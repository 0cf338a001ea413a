#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <openssl/evp.h>

namespace thetad {

// SHA-256 (OpenSSL) fed piece by piece, for files written as a stream: hex() after the last update().
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void update(std::string_view bytes);
  // The lower-case hex digest of everything given; the object is spent afterwards.
  std::string hex();

 private:
  EVP_MD_CTX* context_;
};

std::string sha256_hex(std::string_view bytes);
// Throws thetad::Error naming the file when it cannot be read.
std::string sha256_of_file(const std::filesystem::path& file);

}  // namespace thetad
