#pragma once
// The HTTP endpoint Prometheus scrapes: GET /metrics on --metrics-address HOST:PORT, served
// by cpp-httplib on its own threads, separate from the gRPC port (no token: bind it to an
// address only the scraper reaches).
#include <functional>
#include <memory>
#include <string>
#include <thread>

namespace httplib {
class Server;
}

namespace sph::server::metrics {

class MetricsEndpoint {
 public:
  // Listens on `address` (HOST:PORT, port 0 picks one) and answers GET /metrics with
  // render(); throws std::runtime_error when it cannot listen.
  MetricsEndpoint(const std::string& address, std::function<std::string()> render);
  ~MetricsEndpoint();
  MetricsEndpoint(const MetricsEndpoint&) = delete;
  MetricsEndpoint& operator=(const MetricsEndpoint&) = delete;

  const std::string& bound_address() const { return bound_; }
  void stop();

 private:
  std::unique_ptr<httplib::Server> http_;
  std::thread thread_;
  std::string bound_;
};

}  // namespace sph::server::metrics
