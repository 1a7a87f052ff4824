#pragma once
// Stability guards: checks that stop a run with a diagnosis instead of letting it write
// garbage. Per particle: non-finite state, density deviation |rho/rho0 - 1| past a bound,
// speed past a multiple of the sound speed (weak compressibility assumes |u| << c), position
// outside the domain. Per step: dt collapse (checked by the caller on the reduced dt), fluid
// inside a wall or body (solid_fraction.h), contact too stiff for the step (the caller).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "case/materials.h"
#include "solver/core/particle_store.h"
#include "solver/physics/fluid_table.h"

namespace sph {

struct GuardSettings {
  double max_density_deviation = 0.5;
  double min_dt_fraction = 1e-3;
  double max_mach = 1.0;
  double max_solid_fraction = 0.9;
  std::int64_t max_contact_substeps = 10000;
};

template <int D>
struct GuardScan {
  std::string violation;        // empty when all checks pass on this rank
  double max_speed = 0;         // over owned fluid particles (for the time step)
  double max_acceleration = 0;  // over owned fluid particles (for the time step)
  double max_density_dev = 0;   // over owned fluid particles
};

inline std::string format_vec(const double* x, int d) {
  char buf[128];
  if (d == 2)
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g)", x[0], x[1]);
  else
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", x[0], x[1], x[2]);
  return buf;
}

// " at particle id N (kind, material M) at (x, y), step S, t = T": where a guard tripped.
template <int D>
std::string describe_particle(const ParticleStore<D>& s, const std::vector<MaterialParams>& mats,
                              std::size_t i, std::int64_t step, double t) {
  const char* kind = s.kind[i] == Kind::kFluid     ? "fluid"
                     : s.kind[i] == Kind::kWall    ? "wall"
                     : s.kind[i] == Kind::kElastic ? "elastic"
                                                   : "rigid";
  std::string mat = s.material[i] < mats.size() ? mats[s.material[i]].name : "-";
  char buf[160];
  std::snprintf(buf, sizeof buf, " at particle id %lld (%s, material %s) at ",
                static_cast<long long>(s.id[i]), kind, mat.c_str());
  char tail[96];
  std::snprintf(tail, sizeof tail, ", step %lld, t = %.9g", static_cast<long long>(step), t);
  return buf + format_vec(s.x[i].data(), D) + tail;
}

template <int D>
GuardScan<D> scan_particles(const ParticleStore<D>& s, const std::vector<FluidConstants>& fluids,
                            const std::vector<MaterialParams>& mats, const GuardSettings& g,
                            const Vec<D>& lo, const Vec<D>& hi, const std::array<bool, D>& periodic,
                            std::int64_t step, double t) {
  GuardScan<D> out;
  auto fail = [&](std::size_t i, const std::string& what) {
    if (out.violation.empty()) out.violation = what + describe_particle(s, mats, i, step, t);
  };
  for (std::size_t i = 0; i < s.owned(); ++i) {
    const Vec<D>& x = s.x[i];
    if (!x.allFinite()) {
      fail(i, "non-finite position");
      continue;
    }
    for (int a = 0; a < D; ++a)
      if (!periodic[a] &&
          (x[a] < lo[a] - 1e-9 * (hi[a] - lo[a]) || x[a] > hi[a] + 1e-9 * (hi[a] - lo[a]))) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "particle left the domain along %c (domain [%g, %g])",
                      "xyz"[a], lo[a], hi[a]);
        fail(i, buf);
      }
    if (s.kind[i] != Kind::kFluid) continue;
    const FluidConstants& f = fluids[s.material[i]];
    const double speed = s.v[i].norm();
    if (!std::isfinite(speed) || !std::isfinite(s.rho[i]) || !std::isfinite(s.p[i])) {
      fail(i, "non-finite velocity, density or pressure");
      continue;
    }
    out.max_speed = std::max(out.max_speed, speed);
    out.max_acceleration = std::max(out.max_acceleration, s.a[i].norm());
    const double dev = std::abs(s.rho[i] * f.inv_rho0 - 1.0);
    out.max_density_dev = std::max(out.max_density_dev, dev);
    if (dev > g.max_density_deviation) {
      char buf[128];
      std::snprintf(
          buf, sizeof buf,
          "density deviation |rho/rho0 - 1| = %.4g exceeds %.4g (guards.max_density_deviation)",
          dev, g.max_density_deviation);
      fail(i, buf);
    }
    if (speed > g.max_mach * f.c) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "speed %.4g exceeds %.3g x sound speed %.4g (guards.max_mach)",
                    speed, g.max_mach, f.c);
      fail(i, buf);
    }
  }
  return out;
}

}  // namespace sph
