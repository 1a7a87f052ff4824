#include "worker/pool/result_manifest.h"

#include <filesystem>
#include <stdexcept>

#include "common/sha256.h"

namespace sph::worker::pool {

std::vector<v1::ResultFile> build_manifest(const std::vector<std::string>& files,
                                           const std::string& output_dir) {
  namespace fs = std::filesystem;
  std::vector<v1::ResultFile> out;
  const fs::path base = fs::absolute(output_dir).lexically_normal();
  for (const auto& f : files) {
    const fs::path p = fs::absolute(f).lexically_normal();
    const fs::path rel = p.lexically_relative(base);
    if (rel.empty() || *rel.begin() == "..")
      throw std::runtime_error("result file " + p.string() + " is outside " + base.string());
    v1::ResultFile r;
    r.set_name(rel.string());
    r.set_size(static_cast<std::int64_t>(fs::file_size(p)));
    r.set_sha256(service::sha256_file(p.string()));
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace sph::worker::pool
