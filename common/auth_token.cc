#include "common/auth_token.h"

#include <grpcpp/client_context.h>

#include <fstream>
#include <stdexcept>

namespace sph::service {

std::string read_token_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read token file '" + path + "'");
  std::string line;
  std::getline(in, line);
  const auto first = line.find_first_not_of(" \t\r\n");
  const auto last = line.find_last_not_of(" \t\r\n");
  if (first == std::string::npos) throw std::runtime_error("token file '" + path + "' is empty");
  return line.substr(first, last - first + 1);
}

void add_token(grpc::ClientContext& context, const std::string& token) {
  if (!token.empty()) context.AddMetadata(kAuthorizationKey, "Bearer " + token);
}

}  // namespace sph::service
