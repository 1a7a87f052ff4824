#pragma once
// The result manifest a pool sends with Finish: each file's name relative to the attempt's
// output directory, its size and its sha256.
#include <string>
#include <vector>

#include "sph/v1/service.pb.h"

namespace sph::worker::pool {

// Throws std::runtime_error when a file cannot be read or lies outside output_dir.
std::vector<v1::ResultFile> build_manifest(const std::vector<std::string>& files,
                                           const std::string& output_dir);

}  // namespace sph::worker::pool
