// sphctl health: the server's grpc.health.v1 status (for scripts and probes).
#include <cstdio>

#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "render/json.h"

namespace sph::ctl {

int cmd_health(const GlobalOptions& g, ArgScanner args) {
  std::vector<std::string> pos;
  if (!expect_positionals(args, 0, "usage: sphctl health", pos)) return kUsage;
  auto conn = Connection::open(g);
  if (!conn) return kUsage;
  grpc::health::v1::HealthCheckRequest req;
  grpc::health::v1::HealthCheckResponse resp;
  const auto status = conn->health().Check(conn->unary_context().get(), req, &resp);
  if (!status.ok()) return report_error(status, "health", conn->address());
  if (g.json)
    std::printf("%s\n", to_json(resp).c_str());
  else
    std::printf("%s: %s\n", conn->address().c_str(),
                grpc::health::v1::HealthCheckResponse::ServingStatus_Name(resp.status()).c_str());
  return resp.status() == grpc::health::v1::HealthCheckResponse::SERVING ? kOk : kUnavailable;
}

}  // namespace sph::ctl
