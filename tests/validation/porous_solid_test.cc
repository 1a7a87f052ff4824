// Porous elastic solids (Material.porous, ElasticBody.concentration_holds; docs/porous_media.md;
// thesis sec. 2.3, P-III eqs. 2.17 and 2.21) against analytic answers, relaxed by quasi-static
// loading (time.quasi_static):
//  - a block at uniform saturation c swells to the stretch s at which the solid's stress carries
//    the pore pressure p = C (c - c0), for both elastic laws;
//  - a beam whose upper half alone is saturated bends like Timoshenko's bimetal strip (1925);
//  - a strip wetted at one end takes the erfc profile of diffusion into a half-space.
// Particles on the lattice i dx (lattice_origin -dx/2), so a block's centre particle is at 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "case/load.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

constexpr double kDx = 1e-4;
// The Nafion of the thesis' porous beam (Table 5.4, digest sec. 8.13).
constexpr double kE = 8.242e6, kNu = 0.2631, kRho = 2000, kC = 3e6;
constexpr double kLambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), kMu = kE / (2 * (1 + kNu));

// An elastic body of the box [x0, x1] x [y0, y1] (on lattice cell faces), its one constrained
// particle at the origin, with hourglass control 0.1 (without it the checkerboard mode of total
// Lagrangian SPH grows at a few percent of strain, docs/elastic_solids.md: the Saint
// Venant-Kirchhoff block swollen by 8% never relaxed), relaxed by `load_steps` quasi-static steps
// over `end_time`. `body`: more of the body (concentration holds, initial concentration),
// `material`: more of its material, `diffusivity` the material's (rho D [kg/(m s)]).
std::string porous_case(double x0, double x1, double y0, double y1, const std::string& material,
                        double diffusivity, const std::string& body, double end_time,
                        int load_steps, double threshold) {
  // The thesis' damping eta = beta / 4 sqrt(rho E) L, beta the aspect ratio, L the length.
  const double L = x1 - x0, eta = 0.25 * (y1 - y0) / L * std::sqrt(kRho * kE) * L;
  char buf[3000];
  std::snprintf(buf, sizeof buf, R"(name: "porous"
dimension: 2
dx: %.17g
lattice_origin { x: %.17g y: %.17g }
kernel: WENDLAND_C2
smoothing_length_ratio: 1.3
domain { lo { x: %.17g y: %.17g } hi { x: %.17g y: %.17g } }
materials {
  name: "nafion" phase: SOLID density: %g youngs_modulus: %.17g poisson_ratio: %.17g
  hourglass_control: 0.1 diffusivity: %.17g %s
}
diffusion { }
elastic_bodies {
  name: "film" material: "nafion"
  shape { box { lo { x: %.17g y: %.17g } hi { x: %.17g y: %.17g } } }
  constraints { region { ball { center { x: 0 y: 0 } radius: %.17g } } }
  %s
}
time { end_time: %g quasi_static { load_step: %.17g damping: %.17g kinetic_energy_threshold: %g } }
output { interval: %g series_interval: %g }
)",
                kDx, -0.5 * kDx, -0.5 * kDx, 2 * x0, 2 * y0, 2 * x1, 2 * y1, kRho, kE, kNu,
                diffusivity, material.c_str(), x0, y0, x1, y1, 0.3 * kDx, body.c_str(), end_time,
                end_time / load_steps, eta, threshold, end_time / 4, end_time / load_steps);
  return buf;
}

std::string porous_law(double c0, const char* law) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "elastic_law: %s porous { swelling_modulus: %.17g reference_saturation: %.17g }",
                law, kC, c0);
  return buf;
}

// The last snapshot's particles: reference position X (x minus the displacement), displacement
// and concentration.
struct Particle {
  double X, Y, ux, uy, c;
};
std::vector<Particle> final_particles(const std::string& out) {
  test::ResultReader rr(out + "/result.h5");
  const int k = rr.snapshot_count() - 1;
  const test::Snapshot s = rr.snapshot(k);
  const auto ux = rr.snapshot_field(k, "elastic_displacement_x");
  const auto uy = rr.snapshot_field(k, "elastic_displacement_y");
  const auto c = rr.snapshot_field(k, "concentration");
  std::vector<Particle> p;
  for (std::size_t i = 0; i < s.size(); ++i)
    p.push_back({s.position[3 * i] - ux[i], s.position[3 * i + 1] - uy[i], ux[i], uy[i], c[i]});
  return p;
}

// The particle whose reference position is (X, Y) (a lattice point).
const Particle& at(const std::vector<Particle>& p, double X, double Y) {
  return *std::min_element(p.begin(), p.end(), [&](const Particle& a, const Particle& b) {
    return std::hypot(a.X - X, a.Y - Y) < std::hypot(b.X - X, b.Y - Y);
  });
}

// A free block (21 x 11 particles, held at its centre particle) at saturation 0.5 with c0 = 0.1:
// p = 0.4 C = 1.2 MPa. In plane strain with F = s I the Cauchy stress of the solid is s^-2 F S F^T
// = S (J = s^2), and it carries p where
//   Saint Venant-Kirchhoff: (lambda + mu)(s^2 - 1) = p,
//   neo-Hookean:            mu (1 - s^-2) + 2 lambda ln(s) s^-2 = p.
// An affine field is exact in corrected total Lagrangian SPH, so what is left is the relaxation's.
TEST(PorousSolid, UniformSaturationSwellsABlockToTheAnalyticStretch) {
  const double p = kC * (0.5 - 0.1);
  for (const char* law : {"SAINT_VENANT_KIRCHHOFF", "NEO_HOOKEAN"}) {
    const bool svk = std::string(law) == "SAINT_VENANT_KIRCHHOFF";
    double s = std::sqrt(1 + p / (kLambda + kMu));
    if (!svk)
      for (int it = 0; it < 50; ++it) {  // Newton on the neo-Hookean balance
        const double f = kMu * (1 - 1 / (s * s)) + 2 * kLambda * std::log(s) / (s * s) - p;
        const double df = 2 * kMu / (s * s * s) + 2 * kLambda * (1 - 2 * std::log(s)) / (s * s * s);
        s -= f / df;
      }
    const v1::Case c = parse_case_text(porous_case(-10.5 * kDx, 10.5 * kDx, -5.5 * kDx, 5.5 * kDx,
                                                   porous_law(0.1, law), 0.0,
                                                   "initial_concentration: 0.5", 1.0, 4, 1e-9));
    const std::string out = test::output_dir(std::string("porous_block_") + law);
    const RunOutcome r = test::run(c, out);
    ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
    const auto parts = final_particles(out);
    // The stretch of every particle from the held centre, along each axis.
    double worst = 0;
    for (const Particle& q : parts) {
      if (std::abs(q.X) > 0.5 * kDx)
        worst = std::max(worst, std::abs(q.ux / q.X + 1 - s) / (s - 1));
      if (std::abs(q.Y) > 0.5 * kDx)
        worst = std::max(worst, std::abs(q.uy / q.Y + 1 - s) / (s - 1));
    }
    test::ResultReader rr(out + "/result.h5");
    std::printf(
        "porous block, %s: analytic stretch %.6f; the particles' stretches within %.3f %% of "
        "s - 1 = %.5f; %.0f inner steps over %.0f load steps\n",
        law, s, 100 * worst, s - 1, rr.series("elastic/relaxation_steps").back(),
        rr.series("diagnostics/step").back());
    // Measured: see docs/porous_media.md.
    EXPECT_LT(worst, 0.005) << law;
    EXPECT_EQ(rr.series("elastic/unrelaxed_load_steps").back(), 0);
  }
}

// A free beam of n rows (H = n dx) and 8 n + 1 columns (L = 8 H), held at its centre particle,
// whose upper half alone is held at a saturation that would swell it freely by eps = 1e-3 along
// the beam: in plane strain with sigma_yy = 0 that free strain is p / (2 (lambda + mu)).
// Timoshenko's bimetal strip with equal layers and moduli bends to the curvature
// kappa = 3 eps / (2 H), whatever the modulus (E' = E / (1 - nu^2) in both layers). Measured a
// quarter length either side of the centre (2 H from the free ends): each row's deflection
// there against its centre is kappa a^2 / 2. The bending stiffness of total Lagrangian SPH with
// few particles across is low (docs/elastic_solids.md: the cantilever plate's period is 6.1%
// long at H/dx = 10), so the curvature is high and falls towards kappa with dx.
TEST(PorousSolid, SwollenUpperHalfBendsABeamAsTimoshenkosBimetalStrip) {
  const double eps = 1e-3;
  std::vector<double> errors;
  for (int n : {6, 12}) {
    const double H = n * kDx, a = 2 * H;
    const double value = 2 * (kLambda + kMu) * eps / kC;  // c0 = 0
    char hold[300];
    std::snprintf(hold, sizeof hold,
                  "concentration_holds { region { box { lo { x: -1 y: %.17g } hi { x: 1 y: 1 } } } "
                  "value: %.17g }",
                  0.5 * kDx, value);
    // Rows -(n/2 - 1) .. n/2 (the centre particle in the lower half), columns -4n .. 4n.
    const v1::Case c = parse_case_text(porous_case(
        -(4 * n + 0.5) * kDx, (4 * n + 0.5) * kDx, -(n / 2 - 0.5) * kDx, (n / 2 + 0.5) * kDx,
        porous_law(0, "SAINT_VENANT_KIRCHHOFF"), 0.0, hold, 1.0, 4, 1e-16));
    const std::string out = test::output_dir("porous_bimetal_beam_" + std::to_string(n));
    const RunOutcome r = test::run(c, out);
    ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
    const auto parts = final_particles(out);
    const double kappa = 1.5 * eps / H;
    double sum = 0, lo = 1e300, hi = -1e300;
    for (int row = -(n / 2 - 1); row <= n / 2; ++row) {
      const double Y = row * kDx;
      const double centre = at(parts, 0, Y).uy;
      const double deflection =
          0.5 * (at(parts, -a, Y).uy + at(parts, a, Y).uy) - centre;  // -kappa a^2 / 2
      const double k = -2 * deflection / (a * a);
      sum += k;
      lo = std::min(lo, k);
      hi = std::max(hi, k);
    }
    const double mean = sum / n;
    errors.push_back(mean / kappa - 1);
    test::ResultReader rr(out + "/result.h5");
    std::printf(
        "porous bimetal beam, H = %d dx: curvature %.5f 1/m (rows %.5f to %.5f) against "
        "Timoshenko's %.5f: %+.2f %%; %.0f inner steps\n",
        n, mean, lo, hi, kappa, 100 * errors.back(), rr.series("elastic/relaxation_steps").back());
    EXPECT_EQ(rr.series("elastic/unrelaxed_load_steps").back(), 0);
    EXPECT_LT(hi - lo, 0.01 * kappa);  // one curvature through the thickness
  }
  std::printf("bimetal curvature error %+.2f %% at H = 6 dx, %+.2f %% at 12 dx: order %.2f\n",
              100 * errors[0], 100 * errors[1], std::log2(errors[0] / errors[1]));
  // Measured: see docs/porous_media.md.
  EXPECT_LT(std::abs(errors[0]), 0.2);
  EXPECT_LT(std::abs(errors[1]), 0.1);
  EXPECT_LT(std::abs(errors[1]), 0.6 * std::abs(errors[0]));
}

// A strip 80 x 4 particles whose first 10 columns are held at saturation 0.4 from t = 0, its pores
// pressing on nothing (swelling_modulus 0: the strip stays at rest and each relaxation ends at
// once): the rest takes the profile of diffusion into a half-space with its boundary at the held
// column of held particles x_b, c = 0.4 erfc((x - x_b) / (2 sqrt(D t))), here at 2 sqrt(D t) =
// 12 dx: held particles are Dirichlet nodes, so the boundary is where they are, half a spacing
// inside the hold's region (measured: against the region's face the profile lies 0.55 dx
// behind). Every row of the strip is within the kernel's reach of a free surface. The diffusion
// is explicit, one step of its bound 0.1 h^2 / D per load step.
TEST(PorousSolid, StripWettedAtOneEndTakesTheErfcProfile) {
  const double D = 1e-10;  // [m^2/s]; the material's diffusivity is rho D
  const double h = 1.3 * kDx, load_step = 0.1 * h * h / D;
  const double spread = 12 * kDx, end_time = spread * spread / (4 * D);
  const int load_steps = static_cast<int>(std::ceil(end_time / load_step));
  const double x_h = -30.5 * kDx;  // the hold's face: the held columns are X <= -31 dx
  const double x_b = x_h - 0.5 * kDx;
  char hold[300];
  std::snprintf(hold, sizeof hold,
                "concentration_holds { region { box { lo { x: -1 y: -1 } hi { x: %.17g y: 1 } } } "
                "value: 0.4 }",
                x_h);
  const v1::Case c = parse_case_text(porous_case(-40.5 * kDx, 39.5 * kDx, -1.5 * kDx, 2.5 * kDx,
                                                 "porous { swelling_modulus: 0 }", kRho * D, hold,
                                                 end_time, load_steps, 1e-16));
  const std::string out = test::output_dir("porous_wetted_strip");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const auto parts = final_particles(out);
  double worst = 0;
  std::map<int, double> column_mean;
  for (const Particle& q : parts) {
    if (q.X <= x_h) {
      EXPECT_EQ(q.c, 0.4);
      continue;
    }
    const double exact = 0.4 * std::erfc((q.X - x_b) / spread);
    worst = std::max(worst, std::abs(q.c - exact));
    column_mean[static_cast<int>(std::lround(q.X / kDx))] += q.c / 4;
  }
  for (int col : {-30, -27, -24, -18, -12})
    std::printf("x - x_b = %4.1f dx: c = %.4f, erfc profile %.4f\n", col - x_b / kDx,
                column_mean[col], 0.4 * std::erfc((col * kDx - x_b) / spread));
  test::ResultReader rr(out + "/result.h5");
  std::printf(
      "wetted strip: c within %.4f of the erfc profile (%.2f %% of the held 0.4) after %.0f load "
      "steps, %.0f inner steps\n",
      worst, 100 * worst / 0.4, rr.series("diagnostics/step").back(),
      rr.series("elastic/relaxation_steps").back());
  // Measured: see docs/porous_media.md.
  EXPECT_LT(worst, 0.02 * 0.4);
}

// The same strip in plain steps (no quasi_static: the diffusion and the holds run in the
// solver's own phases, solver/elastic/porous_diffusion.h), its diffusivity raised to 1e-3 m^2/s
// so that the diffusion's bound 0.1 h^2 / D (1.7e-6 s) is near the solid's acoustic step (thesis
// eq. 33, 1.4e-6 s) and 2 sqrt(D t) = 12 dx takes a few hundred steps. Same profile, same
// tolerance.
TEST(PorousSolid, StripWettedAtOneEndTakesTheErfcProfileInPlainSteps) {
  const double D = 1e-3;
  const double spread = 12 * kDx, end_time = spread * spread / (4 * D);
  const double x_h = -30.5 * kDx, x_b = x_h - 0.5 * kDx;
  char hold[300];
  std::snprintf(hold, sizeof hold,
                "concentration_holds { region { box { lo { x: -1 y: -1 } hi { x: %.17g y: 1 } } } "
                "value: 0.4 }",
                x_h);
  v1::Case c = parse_case_text(porous_case(-40.5 * kDx, 39.5 * kDx, -1.5 * kDx, 2.5 * kDx,
                                           "porous { swelling_modulus: 0 }", kRho * D, hold,
                                           end_time, 100, 1e-16));
  c.mutable_time()->clear_quasi_static();
  const std::string out = test::output_dir("porous_wetted_strip_plain_steps");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  double worst = 0;
  for (const Particle& q : final_particles(out)) {
    if (q.X <= x_h) {
      EXPECT_EQ(q.c, 0.4);
      continue;
    }
    worst = std::max(worst, std::abs(q.c - 0.4 * std::erfc((q.X - x_b) / spread)));
    EXPECT_LT(std::hypot(q.ux, q.uy), 1e-12);  // no swelling: the strip stays where it was
  }
  std::printf(
      "wetted strip, plain steps: c within %.4f of the erfc profile (%.2f %% of the held "
      "0.4) after %lld steps\n",
      worst, 100 * worst / 0.4, static_cast<long long>(r.steps));
  EXPECT_LT(worst, 0.02 * 0.4);
}

}  // namespace
}  // namespace sph
