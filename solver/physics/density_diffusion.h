#pragma once
// Density diffusion in the continuity equation (the diffusive term of delta-SPH), which damps
// the high-frequency pressure noise of weakly compressible SPH:
//
//   d rho_i/dt += D_i,  D_i = delta h c0 sum_j psi_ij . grad_i W_ij V_j,
//
// with the form of psi_ij chosen per case:
//  - Molteni & Colagrossi 2009 (Comput. Phys. Commun. 180, 861):
//      psi_ij = 2 (rho_j - rho_i) r_ji / |r_ij|^2, r_ji = r_j - r_i;
//    a Laplacian of the density (Brookshaw's form), which in a fluid at rest diffuses the
//    hydrostatic gradient too where the kernel support is cut (free surface), so the column
//    creeps;
//  - Fourtakas, Dominguez, Vacondio, Rogers 2019 (Comput. Fluids 190, 346):
//      psi_ij = 2 (rho^T_ji - rho^H_ji) r_ji / |r_ij|^2, rho^T_ji = rho_j - rho_i,
//    with rho^H_ji the hydrostatic part of the density difference: the EOS density at the
//    hydrostatic pressure difference p_j - p_i = rho0 b . r_ji (b the body force, with its
//    ramp, Adami 2012 eq. 13), rho^H_ji = rho(rho0 b . r_ji) - rho0 (the Tait form
//    rho0 [(1 + rho0 g z_ij / B)^(1/gamma) - 1] of the paper for gravity b = -g e_z). Zero in
//    hydrostatic rest, whatever the support.
// With r_ji . grad_i W_ij = -|r_ij| dW/dr both read
//   D_i = 2 delta h c0 sum_j (rho_i - rho_j + rho^H_ji) (dW/dr)_ij / |r_ij| V_j.
//
// Walls: the dummy particles of Adami's wall condition enter like fluid neighbours, with the
// density the wall condition gives them (Adami 2012 eq. 28, from the pressure extrapolated
// with the local force balance, eq. 27) and their volume dx^D. Fourtakas et al. leave
// boundary particles out of the term because their dynamic boundary particles carry a
// density of their own from the continuity equation, unrelated to the fluid's; Adami's wall
// density is the fluid's own, extrapolated with its hydrostatic term, so the walls complete
// the kernel support, the Laplacian stays consistent at walls and rho^H cancels the
// hydrostatic difference across the wall as in the fluid. Leaving them out would cut the
// support at every wall, the source of the drift that Fourtakas' correction removes at the
// free surface.
//
// The term is evaluated with rho^n (before this step's continuity update) at the positions
// r^{n+1} of the search, from the pair kernel, and added to rho as an explicit Euler step,
// rho <- rho^n + dt D_i, before the continuity equation (Adami 2012 eq. 16) adds its own
// increment; the ghosts' density is refreshed in between, so every rank sees the same values.
// One fluid material (validation refuses more: between phases the term would diffuse the
// density jump of the interface).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/core/pair_access.h"
#include "solver/physics/body_force.h"
#include "solver/physics/fluid_table.h"
#include "solver/seam/unit.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class DensityDiffusion final : public Unit<D> {
 public:
  static constexpr const char* kName = "density_diffusion";
  // `fluid`: the constants of the case's one fluid material; `body`: the body force on the
  // fluid (nullopt-free: zero without gravity).
  DensityDiffusion(const v1::DensityDiffusion& dd, const FluidConstants& fluid,
                   const BodyForce<D>& body, double h, double wall_volume, double cfl_factor)
      : hydrostatic_(dd.form() != v1::DensityDiffusion::MOLTENI_COLAGROSSI),
        delta_(dd.has_delta() ? dd.delta() : 0.1),
        fluid_(fluid),
        body_(body),
        wall_volume_(wall_volume) {
    coef_ = 2.0 * delta_ * h * fluid.c;
    // As the viscous bound of Fuchs 2021 eq. 41, dt <= 0.125 h^2 / nu, with the term's
    // diffusivity delta h c0 in place of nu.
    max_dt_ = cfl_factor * 0.125 * h / (delta_ * fluid.c);
    // The binomial coefficients of (1 + x)^a, a = 1/gamma, from x^1 to x^4.
    const double a = fluid.inv_gamma;
    series_[0] = a;
    series_[1] = series_[0] * (a - 1) / 2;
    series_[2] = series_[1] * (a - 2) / 3;
    series_[3] = series_[2] * (a - 3) / 4;
  }

  const char* name() const override { return kName; }
  PhaseMask phases() const override { return phase_bit(StepPhase::kAfterSearch); }
  double max_time_step() const override { return max_dt_; }
  std::size_t scratch_bytes() const override { return rate_.capacity() * sizeof(double); }

  void run(StepPhase, StepContext<D>& ctx) override {
    if (ctx.dt <= 0) return;  // priming: the density is the initial one
    with_pair_form(ctx.pairs, [&](auto compact) { diffuse<decltype(compact)::value>(ctx); });
  }

 private:
  template <bool kCompact>
  void diffuse(StepContext<D>& ctx) {
    ParticleStore<D>& s = ctx.particles;
    const NeighborList<D>& nl = ctx.neighbors;
    const std::size_t n = s.owned();
    rate_.resize(n);
    const Vec<D> b = body_.at(ctx.t);
    // rho^H_ji = rho(rho0 b . r_ji) - rho0 = rho(-rho0 b . r_ij) - rho0.
    const Vec<D> grad_p = -fluid_.rho0 * b;
    const bool hydro = hydrostatic_ && !b.isZero();
    for (std::size_t i = 0; i < n; ++i) {
      if (s.kind[i] != Kind::kFluid) continue;
      const double rhoi = s.rho[i];
      const Vec<D> xi = s.x[i];
      const auto g = pairs_of<kCompact>(ctx.pairs, nl, i);
      const std::uint32_t* first = nl.begin(i);
      const std::uint32_t* fluid_end = nl.fluid_end(i);
      const std::uint32_t* end = nl.end(i);
      double sum = 0.0;
      std::size_t k = 0;
      for (const std::uint32_t* jp = first; jp != end; ++jp, ++k) {
        const std::uint32_t j = *jp;
        const Vec<D> xij = xi - s.x[j];
        if (g.coincident(k, xij)) continue;
        double drho = rhoi - s.rho[j];
        if (hydro) drho += hydrostatic_difference(grad_p.dot(xij));
        const double vol = jp < fluid_end ? s.m[j] / s.rho[j] : wall_volume_;
        sum += g.times_dwdr_over_r(drho, k) * vol;
      }
      rate_[i] = coef_ * sum;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (s.kind[i] == Kind::kFluid) s.rho[i] += ctx.dt * rate_[i];
    // The continuity equation reads the neighbours' density next.
    ctx.halo.update(s, {&s.rho});
  }

  // rho(dp) - rho0 = rho0 [(1 + x)^(1/gamma) - 1], x = dp / p0, for the hydrostatic pressure
  // difference dp by the material's EOS (Fourtakas et al. 2019: the Tait form; linear:
  // dp / c^2). Across a kernel support x is of the order of the Mach number squared of the
  // hydrostatic head, b r_c / c^2 (1e-3 in a dam break): there four terms of the binomial
  // series give the power to 1e-12, without the pow() that cost as much as the rest of the
  // pass; larger x takes the power.
  double hydrostatic_difference(double dp) const {
    const double x = dp * fluid_.inv_p0;
    if (fluid_.gamma == 1.0) return fluid_.rho0 * x;
    if (std::abs(x) < 1e-3)
      return fluid_.rho0 * x * (series_[0] + x * (series_[1] + x * (series_[2] + x * series_[3])));
    return fluid_.density(dp + fluid_.chi) - fluid_.rho0;
  }

  bool hydrostatic_;
  double delta_;
  FluidConstants fluid_;
  BodyForce<D> body_;
  double wall_volume_;
  double coef_ = 0, max_dt_ = 0;
  double series_[4] = {};
  std::vector<double> rate_;
};

}  // namespace sph
