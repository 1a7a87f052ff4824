#pragma once
// The oscillating cantilever plate of P-II (thesis digest sec. 8.4; cases/oscillating_plate_2d)
// resolved isotropically or with anisotropic kernels (ASPH, docs/asph.md): one run, its first
// period from the tip's zero crossings, its particle count and wall time. Shared by the ctest
// (tests/validation/asph_cantilever_test.cc) and the report (asph/cantilever_report.cc).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "case/estimate.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph::asph_test {

// Euler-Bernoulli, first clamped-free mode, plane strain: omega^2 = E' H^2 k^4 / (12 rho),
// E' = E / (1 - nu^2), k L = 1.875104 (digest sec. 8.4: T = 0.2541 s).
inline double euler_bernoulli_period() {
  const double E = 2e6, nu = 0.3975, rho = 1000, H = 0.02, L = 0.2;
  const double k = 1.875104 / L;
  return 2 * std::numbers::pi / std::sqrt(E / (1 - nu * nu) * H * H * std::pow(k, 4) / (12 * rho));
}

struct CantileverRun {
  double ratio = 1;          // anisotropic ratio r (1: isotropic, no anisotropy block)
  double particles = 0;      // elastic particles
  double iso_particles = 0;  // the same plate resolved isotropically
  double period = 0;         // first period [s] (second zero crossing of the tip's y)
  double amplitude = 0;      // largest |y| of the tip over the first period [m]
  double energy_drift = 0;   // largest |E/E0 - 1| of kinetic + strain energy
  double wall_seconds = 0;
  double search_seconds = 0;   // neighbour search and pair kernel (rank 0's timers)
  double elastic_seconds = 0;  // the elastic unit
  long long steps = 0;
  std::string status;
};

// The plate with dx through its thickness (H / dx particles across it), tip velocity v_tip,
// anisotropic ratio r (1: the isotropic case as shipped), to end_time.
inline v1::Case cantilever_case(double dx, double r, double v_tip, double end_time) {
  v1::Case c = test::load_case("oscillating_plate_2d");
  c.set_dx(dx);
  c.mutable_time()->set_end_time(end_time);
  c.mutable_output()->set_interval(end_time);  // snapshots at the ends only
  v1::ElasticBody& b = *c.mutable_elastic_bodies(0);
  b.mutable_initial_velocity_field()->mutable_beam_mode()->set_tip_velocity(v_tip);
  if (r > 1) {
    b.mutable_anisotropy()->set_ratio(r);
    b.mutable_anisotropy()->mutable_thickness_direction()->set_y(1);
  }
  return c;
}

inline CantileverRun run_cantilever(double dx, double r, double v_tip, double end_time,
                                    const std::string& name) {
  const v1::Case c = cantilever_case(dx, r, v_tip, end_time);
  CantileverRun out;
  out.ratio = r;
  const CaseEstimate e = estimate_case(c);
  out.particles = e.elastic_particles;
  out.iso_particles = e.elastic_isotropic_particles;
  const std::string dir = test::output_dir(name);
  const RunOutcome o = test::run(c, dir);
  out.status = to_string(o.status);
  out.wall_seconds = o.wall_seconds;
  out.steps = o.steps;
  for (const auto& [unit, seconds] : o.unit_seconds) {
    if (unit == "neighbor_search" || unit == "pair_kernel") out.search_seconds += seconds;
    if (unit == "elastic_solid") out.elastic_seconds += seconds;
  }
  if (o.status != RunStatus::kCompleted) return out;
  test::ResultReader rr(dir + "/result.h5");
  const std::vector<double> t = rr.series("diagnostics/time");
  const std::vector<double> d = rr.series("elastic/plate/displacement");
  const std::size_t row = d.size() / t.size();
  std::vector<double> y(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) y[k] = d[k * row + 1];
  // The tip starts at y = 0 moving up: it crosses zero at T/2 and T.
  std::vector<double> z;
  for (std::size_t k = 1; k < t.size(); ++k)
    if ((y[k - 1] > 0) != (y[k] > 0) && y[k - 1] != 0)
      z.push_back(t[k - 1] + (t[k] - t[k - 1]) * y[k - 1] / (y[k - 1] - y[k]));
  if (z.size() >= 2) out.period = z[1];
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] <= out.period) out.amplitude = std::max(out.amplitude, std::abs(y[k]));
  const std::vector<double> ek = rr.series("elastic/plate/kinetic_energy");
  const std::vector<double> es = rr.series("elastic/plate/strain_energy");
  const double e0 = ek[0] + es[0];
  for (std::size_t k = 0; k < ek.size(); ++k)
    out.energy_drift = std::max(out.energy_drift, std::abs((ek[k] + es[k]) / e0 - 1));
  return out;
}

}  // namespace sph::asph_test
