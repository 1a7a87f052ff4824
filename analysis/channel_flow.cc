#include "analysis/channel_flow.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace sph::analysis {
namespace {
constexpr double kPi = std::numbers::pi;
// Terms of the series; the slowest (Couette, 1/n) is below 1e-6 of the wall velocity for
// t > 1e-4 height^2/nu with 400 terms.
constexpr int kPoiseuilleTerms = 200;
constexpr int kCouetteTerms = 400;
}  // namespace

double poiseuille_startup(double y, double t, double body_force, double nu, double height) {
  const double L = height, F = body_force;
  double u = F / (2 * nu) * y * (L - y);
  for (int n = 0; n < kPoiseuilleTerms; ++n) {
    const double k = 2 * n + 1;
    u -= 4 * F * L * L / (nu * kPi * kPi * kPi * k * k * k) * std::sin(kPi * y * k / L) *
         std::exp(-k * k * kPi * kPi * nu * t / (L * L));
  }
  return u;
}

double couette_startup(double y, double t, double wall_velocity, double nu, double height) {
  const double L = height, V = wall_velocity;
  double u = V * y / L;
  for (int n = 1; n < kCouetteTerms; ++n)
    u += 2 * V / (n * kPi) * (n % 2 ? -1.0 : 1.0) * std::sin(n * kPi * y / L) *
         std::exp(-n * n * kPi * kPi * nu * t / (L * L));
  return u;
}

double channel_flow_velocity(const v1::ChannelFlowReference& r, double y, double t) {
  const double yl = y - r.lower_wall();
  double u = 0;
  if (r.body_force() != 0)
    u += poiseuille_startup(yl, t, r.body_force(), r.kinematic_viscosity(), r.height());
  if (r.wall_velocity() != 0)
    u += couette_startup(yl, t, r.wall_velocity(), r.kinematic_viscosity(), r.height());
  return u;
}

double channel_flow_velocity_scale(const v1::ChannelFlowReference& r) {
  if (r.has_velocity_scale()) return r.velocity_scale();
  return std::abs(r.body_force()) * r.height() * r.height() / (8 * r.kinematic_viscosity()) +
         std::abs(r.wall_velocity());
}

Measurement channel_flow_error(const Snapshot& s, const v1::ChannelFlowReference& r) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != 0) continue;
    sum += std::abs(s.velocity[3 * i] - channel_flow_velocity(r, s.position[3 * i + 1], s.time));
    ++n;
  }
  if (n == 0) throw std::runtime_error("channel flow: the snapshot has no fluid particles");
  Measurement m;
  const double scale = channel_flow_velocity_scale(r);
  m.error = sum / n / scale;
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "mean |u - u_exact| = %.3e (%.3f%% of %.4g) over %d fluid particles at t = %g",
                sum / n, 100 * m.error, scale, n, s.time);
  m.detail = buf;
  return m;
}

}  // namespace sph::analysis
