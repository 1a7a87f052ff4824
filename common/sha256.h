#pragma once
// SHA-256 of result files (OpenSSL EVP), shared by the worker (manifest) and sphctl (fetch).
#include <memory>
#include <string>
#include <string_view>

namespace sph::service {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void update(std::string_view bytes);
  // Lowercase hex of the digest; the object is finished afterwards.
  std::string hex_digest();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Throws std::runtime_error when the file cannot be read.
std::string sha256_file(const std::string& path);

}  // namespace sph::service
