#pragma once
// The plane-strain steel bar of the plasticity tests (tests/validation/plasticity_test.cc,
// tests/mpi/rank_consistency_test.cc): the material of the thesis' necking bar (Table 5.1,
// digest sec. 8.11) in a 46 x 10 mm bar at dx = 1 mm (460 particles), whose 3 mm grips at the two
// ends are pulled apart at -v and +v, ramped up linearly over t_ramp.
#include <cmath>
#include <cstdio>
#include <string>

namespace sph::test {

// Table 5.1: mu = 80.1938 GPa, K = 164.21 GPa (E and nu from them).
constexpr double kPlasticBarShear = 80.1938e9, kPlasticBarBulk = 164.21e9;

// time_extra: more of the time block (e.g. plastic_bar_quasi_static()).
inline std::string plastic_bar_case(double v, double t_ramp, double end_time,
                                    const std::string& time_extra = "") {
  constexpr double K = kPlasticBarBulk, mu = kPlasticBarShear;
  const double E = 9 * K * mu / (3 * K + mu);
  const double nu = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  char buf[3000];
  std::snprintf(buf, sizeof buf, R"(name: "plastic_bar_2d"
dimension: 2
dx: 0.001
kernel: WENDLAND_C2
smoothing_length_ratio: 1.3
domain { lo { x: -0.03 y: -0.01 } hi { x: 0.03 y: 0.01 } }
materials {
  name: "steel" phase: SOLID density: 7850 youngs_modulus: %.17g poisson_ratio: %.17g
  elastic_law: NEO_HOOKEAN elastic_damping: 2000
  plasticity { yield_stress: 4.5e8 saturation_stress: 7.15e8 saturation_exponent: 16.93
               linear_hardening: 1.2924e8 }
}
elastic_bodies {
  name: "bar" material: "steel"
  shape { box { lo { x: -0.023 y: -0.005 } hi { x: 0.023 y: 0.005 } } }
  constraints { region { box { lo { x: -0.024 y: -0.006 } hi { x: -0.020 y: 0.006 } } }
                motion { velocity_x { piecewise_linear { times: [0, %g, 1] values: [0, %g, %g] } } } }
  constraints { region { box { lo { x: 0.020 y: -0.006 } hi { x: 0.024 y: 0.006 } } }
                motion { velocity_x { piecewise_linear { times: [0, %g, 1] values: [0, %g, %g] } } } }
  observation_points { x: -0.0105 y: -0.0005 }
  observation_points { x: 0.0105 y: -0.0005 }
}
time { end_time: %g %s }
output { interval: %g series_interval: %g }
)",
                E, nu, t_ramp, -v, -v, t_ramp, v, v, end_time, time_extra.c_str(), end_time / 4,
                end_time / 100);
  return buf;
}

// Quasi-static loading of the bar (time.quasi_static, docs/quasi_static.md) in load steps of
// load_step, the inner loops ending below `threshold` [J/m]: the thesis' damping eta = beta / 4
// sqrt(rho E) L (beta = width / length, L the length).
inline std::string plastic_bar_quasi_static(double load_step, double threshold) {
  constexpr double K = kPlasticBarBulk, mu = kPlasticBarShear;
  const double E = 9 * K * mu / (3 * K + mu);
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "quasi_static { load_step: %.17g damping: %.17g kinetic_energy_threshold: %.17g }",
                load_step, 0.25 * (0.010 / 0.046) * std::sqrt(7850 * E) * 0.046, threshold);
  return buf;
}

}  // namespace sph::test
