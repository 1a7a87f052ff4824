#pragma once
// The figures the stability suite records over a run, read back from its result file:
// density deviation, speed, fluid mass, momentum, mechanical energy (fluid kinetic, potential
// and elastic, bodies' kinetic and potential, elastic bodies' kinetic and strain), how far
// fluid entered a solid, the closest contact, and the phase-change counters. Printed as a table so
// a CI log shows how each hard case evolved, not only that it passed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "case/load.h"
#include "tests/support/result_reader.h"

namespace sph::test {

struct StabilityFigures {
  std::vector<double> t, density_deviation, max_speed, fluid_mass, momentum, fluid_energy;
  std::vector<double> solid_fraction, contact_distance;  // empty without walls / contact
  std::vector<double> body_energy, body_mass;            // empty without bodies
  // Kinetic + strain energy of all elastic bodies (elastic/<body>/*); empty without them.
  std::vector<double> elastic_energy;
  std::vector<double> melted, solidified, bodies;  // empty without phase change
  // Interface and stray particles (solver/diagnostics/phase_mixing.h); empty with one phase.
  std::vector<double> interface, stray;
  bool all_finite = true;  // every diagnostic sample finite

  // Fluid + bodies mechanical energy at sample k.
  double energy(std::size_t k) const {
    return fluid_energy[k] + (body_energy.empty() ? 0.0 : body_energy[k]) +
           (elastic_energy.empty() ? 0.0 : elastic_energy[k]);
  }
  double total_mass(std::size_t k) const {
    return fluid_mass[k] + (body_mass.empty() ? 0.0 : body_mass[k]);
  }
  static double max_of(const std::vector<double>& v, std::size_t from = 0) {
    double m = -std::numeric_limits<double>::infinity();
    for (std::size_t k = from; k < v.size(); ++k) m = std::max(m, v[k]);
    return m;
  }
  static double min_of(const std::vector<double>& v, std::size_t from = 0) {
    double m = std::numeric_limits<double>::infinity();
    for (std::size_t k = from; k < v.size(); ++k) m = std::min(m, v[k]);
    return m;
  }
  // First sample at or after time t0.
  std::size_t index_at(double t0) const {
    std::size_t k = 0;
    while (k + 1 < t.size() && t[k] < t0) ++k;
    return k;
  }
  // Largest relative deviation of the total mass from its first sample (elastic particles keep
  // their mass by construction and are not counted; 0 without fluid or bodies).
  double mass_drift() const {
    double worst = 0;
    if (t.empty() || total_mass(0) == 0) return 0;
    for (std::size_t k = 0; k < t.size(); ++k)
      worst = std::max(worst, std::abs(total_mass(k) / total_mass(0) - 1));
    return worst;
  }
};

// `body_gravity`: the acceleration bodies feel (with a buoyancy factor if the case reduces it);
// the body potential energy is -m g.x of the centres.
inline StabilityFigures read_stability_figures(const std::string& result_path,
                                               const std::vector<double>& body_gravity = {}) {
  ResultReader rr(result_path);
  StabilityFigures f;
  f.t = rr.series("diagnostics/time");
  f.density_deviation = rr.series("diagnostics/max_density_deviation");
  f.max_speed = rr.series("diagnostics/max_speed");
  f.fluid_mass = rr.series("diagnostics/mass");
  const auto ke = rr.series("diagnostics/kinetic_energy");
  const auto pe = rr.series("diagnostics/potential_energy");
  // The elastic energy completes the fluid's mechanical energy (results of older code lack it).
  const auto el = rr.has_series("diagnostics/elastic_energy")
                      ? rr.series("diagnostics/elastic_energy")
                      : std::vector<double>(ke.size(), 0.0);
  const auto mom = rr.series("diagnostics/momentum");
  const std::size_t n = f.t.size(), d = mom.size() / std::max<std::size_t>(n, 1);
  for (std::size_t k = 0; k < n; ++k) {
    f.fluid_energy.push_back(ke[k] + pe[k] + el[k]);
    double m2 = 0;
    for (std::size_t a = 0; a < d; ++a) m2 += mom[k * d + a] * mom[k * d + a];
    f.momentum.push_back(std::sqrt(m2));
    for (double v : {f.density_deviation[k], f.max_speed[k], f.fluid_mass[k], ke[k], pe[k], el[k]})
      f.all_finite = f.all_finite && std::isfinite(v);
  }
  if (rr.has_series("diagnostics/max_solid_fraction"))
    f.solid_fraction = rr.series("diagnostics/max_solid_fraction");
  if (rr.has_series("diagnostics/stray_phase_particles")) {
    f.interface = rr.series("diagnostics/interface_particles");
    f.stray = rr.series("diagnostics/stray_phase_particles");
  }
  if (rr.has_series("diagnostics/min_contact_distance"))
    f.contact_distance = rr.series("diagnostics/min_contact_distance");
  if (rr.has_series("bodies/mass")) {
    // Body series have one column per body slot; slots of bodies not born yet or gone are NaN.
    const auto mass = rr.series("bodies/mass");
    const auto bke = rr.series("bodies/kinetic_energy");
    const auto pos = rr.series("bodies/position");
    const auto shape = rr.series_shape("bodies/position");
    const std::size_t samples = shape[0], slots = shape[1], dim = shape[2];
    // Bodies are sampled on the same schedule as the diagnostics.
    for (std::size_t k = 0; k < std::min(samples, n); ++k) {
      double m = 0, e = 0;
      for (std::size_t b = 0; b < slots; ++b) {
        const double mb = mass[k * slots + b];
        if (std::isnan(mb)) continue;
        m += mb;
        e += bke[k * slots + b];
        for (std::size_t a = 0; a < dim && a < body_gravity.size(); ++a)
          e -= mb * body_gravity[a] * pos[(k * slots + b) * dim + a];
      }
      f.body_mass.push_back(m);
      f.body_energy.push_back(e);
    }
  }
  // Elastic bodies, named in the case the result file records.
  const v1::Case c = parse_case_text(rr.meta("case_text"));
  for (int j = 0; j < c.elastic_bodies_size(); ++j) {
    // An unnamed body's series go by "body<index>" (solver/elastic/elastic_solid.h).
    const std::string& name = c.elastic_bodies(j).name();
    const std::string base = "elastic/" + (name.empty() ? "body" + std::to_string(j) : name) + "/";
    const auto ek = rr.series(base + "kinetic_energy");
    const auto es = rr.series(base + "strain_energy");
    f.elastic_energy.resize(n, 0.0);
    for (std::size_t k = 0; k < std::min(n, ek.size()); ++k) {
      f.elastic_energy[k] += ek[k] + es[k];
      f.all_finite = f.all_finite && std::isfinite(ek[k]) && std::isfinite(es[k]);
    }
  }
  if (rr.has_series("phase/melted")) {
    f.melted = rr.series("phase/melted");
    f.solidified = rr.series("phase/solidified");
    f.bodies = rr.series("phase/active_bodies");
  }
  return f;
}

// About `rows` rows of the figures over time, for the log.
inline void print_stability_table(const std::string& name, const StabilityFigures& f,
                                  int rows = 10) {
  std::printf("%s over time:\n  %9s %9s %9s %12s %13s %9s %9s%s%s\n", name.c_str(), "t",
              "max|drho|", "max|u|", "mass drift", "energy", "|momentum|",
              f.solid_fraction.empty() ? "" : "solid", f.stray.empty() ? "" : " interface  stray",
              f.melted.empty() ? "" : "   melted  frozen  bodies");
  const std::size_t n = f.t.size(),
                    step = std::max<std::size_t>(1, n / static_cast<std::size_t>(rows));
  for (std::size_t k = 0; k < n; k += step) {
    std::printf("  %9.4g %9.3g %9.3g %12.2e %13.6g %9.3g %9.3g", f.t[k], f.density_deviation[k],
                f.max_speed[k], f.total_mass(0) == 0 ? 0.0 : f.total_mass(k) / f.total_mass(0) - 1,
                f.energy(k), f.momentum[k], f.solid_fraction.empty() ? 0.0 : f.solid_fraction[k]);
    if (!f.stray.empty()) std::printf(" %10.0f %6.0f", f.interface[k], f.stray[k]);
    if (!f.melted.empty())
      std::printf(" %8.0f %7.0f %7.0f", f.melted[k], f.solidified[k], f.bodies[k]);
    std::printf("\n");
  }
}

}  // namespace sph::test
