#include "server/metrics/metrics_endpoint.h"

#include <httplib.h>

#include <chrono>
#include <stdexcept>

namespace sph::server::metrics {

MetricsEndpoint::MetricsEndpoint(const std::string& address, std::function<std::string()> render)
    : http_(std::make_unique<httplib::Server>()) {
  const auto colon = address.rfind(':');
  if (colon == std::string::npos)
    throw std::runtime_error("--metrics-address: expected HOST:PORT, not '" + address + "'");
  std::string host = address.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']')
    host = host.substr(1, host.size() - 2);
  int port = 0;
  try {
    port = std::stoi(address.substr(colon + 1));
  } catch (const std::exception&) {
    port = -1;
  }
  if (port < 0 || port > 65535)
    throw std::runtime_error("--metrics-address: the port must be 0..65535, not '" +
                             address.substr(colon + 1) + "'");
  http_->Get("/metrics", [render](const httplib::Request&, httplib::Response& res) {
    // Prometheus text exposition format 0.0.4.
    res.set_content(render(), "text/plain; version=0.0.4; charset=utf-8");
  });
  const int bound =
      port == 0 ? http_->bind_to_any_port(host) : (http_->bind_to_port(host, port) ? port : -1);
  if (bound <= 0) throw std::runtime_error("--metrics-address: cannot listen on " + address);
  bound_ = address.substr(0, colon + 1) + std::to_string(bound);
  thread_ = std::thread([this] { http_->listen_after_bind(); });
}

MetricsEndpoint::~MetricsEndpoint() {
  stop();
}

void MetricsEndpoint::stop() {
  if (thread_.joinable()) {
    // stop() does nothing to a server that has not started listening yet.
    for (int i = 0; i < 2000 && !http_->is_running(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    http_->stop();
    thread_.join();
  }
}

}  // namespace sph::server::metrics
