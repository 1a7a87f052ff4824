#pragma once
// Riemann-based dissipation (Zhang, Hu, Adams 2017, "A weakly compressible SPH method based on
// a low-dissipation Riemann solver", JCP 335, 605): each pair of particles i, j is a
// one-dimensional Riemann problem along e_ij = (r_j - r_i) / |r_j - r_i| with the left state i
// and the right state j,
//   U_L = v_i . e_ij,  U_R = v_j . e_ij,  P_L = p_i,  P_R = p_j,
// whose linearised (acoustic) solution is
//   U* = (U_L + U_R)/2 + (P_L - P_R) / (2 rho_bar c),
//   P* = (P_L + P_R)/2 + rho_bar c (U_L - U_R)/2,
// with rho_bar = (rho_i + rho_j)/2 and c the material's sound speed (its reference value:
// the weakly compressible EOS keeps the local one within a few per cent of it).
//
// Continuity (Tang, Zhang, Haidn, Hu 2023, Acta Mech. Sin. 39, eq. 16, the thesis' TFSI
// solver; Zhang et al. 2017's Riemann-SPH continuity equation):
//   d rho_i/dt = 2 rho_i sum_j V_j (v_i - v*_ij) . grad_i W_ij,
//   v*_ij = (v_i + v_j)/2 + (U* - (U_L + U_R)/2) e_ij.
// Its first part is the continuity equation the solver integrates already (Adami 2012 eq. 6,
// rho_i sum_j V_j v_ij . grad_i W_ij); what the star velocity adds is, with
// grad_i W_ij = -(dW/dr)_ij e_ij,
//   D_i = rho_i / c sum_j V_j (p_i - p_j) / rho_bar (dW/dr)_ij,
// a diffusion of pressure (with p = c^2 (rho - rho0) near rho0 it is c sum_j V_j
// (rho_i - rho_j) dW/dr: the density diffusion of delta-SPH with delta h in place of |r_ij|/2,
// delta = |r_ij|/(2h), up to 1.5 at the quintic's support radius). This unit adds D_i; the
// built-in continuity stage adds the rest.
//
// Hydrostatic correction (on by default): like the Molteni-Colagrossi density diffusion, D_i
// diffuses the hydrostatic pressure gradient wherever the kernel support is cut, which at a
// free surface makes a fluid at rest under gravity creep. As Fourtakas, Dominguez, Vacondio,
// Rogers 2019 (Comput. Fluids 190, eqs. 12-13) do for density diffusion, the hydrostatic
// difference rho0 b . (r_i - r_j) (b the body force with its ramp, Adami 2012 eq. 13) is
// taken out of p_i - p_j, so the term is zero in hydrostatic rest whatever the support.
//
// Momentum (optional, Zhang et al. 2017's low-dissipation limiter): the dissipative part of
// P* with the velocity jump limited,
//   P* = P_bar + beta rho_bar (U_L - U_R)/2,  beta = min(eta max(U_L - U_R, 0), c),
// zero where the pair separates and at most the acoustic solver's rho_bar c (U_L - U_R)/2
// where it approaches fast (eta = 3 in the paper). The fluid forces (Adami 2012 eq. 8)
// already carry the average pressure p~_ij; this unit adds the rest of P* in the same form,
//   a_i += -1/m_i sum_j (V_i^2 + V_j^2) beta rho_bar (U_L - U_R)/2 grad_i W_ij,
// between fluid particles only (antisymmetric in i, j, so momentum is conserved pairwise),
// as the artificial viscosity it stands in for (Adami 2012 sec. 3.2): walls and bodies get
// no share, so rigid and elastic bodies need no reaction from it.
//
// Walls: the dummy particles of Adami's wall condition (walls, rigid and elastic bodies)
// enter the continuity term like fluid neighbours, with the pressure the wall condition
// extrapolated into them with its hydrostatic and acceleration terms (Adami 2012 eq. 27),
// the density of that pressure (eq. 28) and the volume dx^D, as they enter the continuity
// equation itself. Their pressure is the fluid's own continued into the wall, so the walls
// complete the kernel support and a fluid at rest against a wall sees no pressure jump there.
//
// The continuity term is evaluated in kAfterSearch with p^n, rho^n (the state before this
// step's continuity update; on wall particles the wall condition of the last step) at the
// positions r^{n+1} of the search, from the pair kernel, and added to rho as an explicit Euler
// step before the continuity equation (Adami 2012 eq. 16) adds its own increment; the ghosts'
// density is refreshed in between, so every rank sees the same values. The momentum term runs
// in kForces with rho^{n+1} and v^{n+1/2}, after the fluid forces.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "solver/core/pair_access.h"
#include "solver/physics/body_force.h"
#include "solver/physics/fluid_table.h"
#include "solver/seam/unit.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class RiemannDissipation final : public Unit<D> {
 public:
  static constexpr const char* kName = "riemann_dissipation";
  // `fluid`: the constants of the case's one fluid material (validation refuses more).
  // `body`: the body force on the fluid (zero without gravity).
  RiemannDissipation(const v1::RiemannDissipation& rd, const FluidConstants& fluid,
                     const BodyForce<D>& body, double wall_volume)
      : momentum_(rd.scope() == v1::RiemannDissipation::CONTINUITY_AND_MOMENTUM),
        hydrostatic_(!rd.has_hydrostatic_correction() || rd.hydrostatic_correction()),
        eta_(rd.has_limiter_eta() ? rd.limiter_eta() : 3.0),
        c_(fluid.c),
        inv_c_(1.0 / fluid.c),
        rho0_(fluid.rho0),
        body_(body),
        wall_volume_(wall_volume) {}

  const char* name() const override { return kName; }
  PhaseMask phases() const override {
    return phase_bit(StepPhase::kAfterSearch) |
           (momentum_ ? phase_bit(StepPhase::kForces) : PhaseMask{0});
  }
  std::size_t scratch_bytes() const override { return rate_.capacity() * sizeof(double); }

  void run(StepPhase phase, StepContext<D>& ctx) override {
    with_pair_form(ctx.pairs, [&](auto compact) {
      constexpr bool kCompact = decltype(compact)::value;
      if (phase == StepPhase::kAfterSearch)
        continuity<kCompact>(ctx);
      else
        momentum<kCompact>(ctx);
    });
  }

 private:
  // D_i = rho_i / c sum_j V_j (p_i - p_j - rho0 b . r_ij) / rho_bar (dW/dr)_ij, added as
  // dt D_i (without the hydrostatic correction b = 0 here).
  template <bool kCompact>
  void continuity(StepContext<D>& ctx) {
    if (ctx.dt <= 0) return;  // priming: the density is the initial one
    ParticleStore<D>& s = ctx.particles;
    const NeighborList<D>& nl = ctx.neighbors;
    const std::size_t n = s.owned();
    rate_.resize(n);
    const Vec<D> grad_p = hydrostatic_ ? Vec<D>(rho0_ * body_.at(ctx.t)) : Vec<D>::Zero();
    const bool hydro = !grad_p.isZero();
    for (std::size_t i = 0; i < n; ++i) {
      if (s.kind[i] != Kind::kFluid) continue;
      const double rhoi = s.rho[i], pi = s.p[i];
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
        const double rhoj = s.rho[j];
        const double vol = jp < fluid_end ? s.m[j] / rhoj : wall_volume_;
        double dp = pi - s.p[j];
        if (hydro) dp -= grad_p.dot(xij);
        sum += vol * dp / (0.5 * (rhoi + rhoj)) * g.dwdr_at(k, g.distance(k, xij));
      }
      rate_[i] = rhoi * inv_c_ * sum;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (s.kind[i] == Kind::kFluid) s.rho[i] += ctx.dt * rate_[i];
    // The continuity equation reads the neighbours' density next.
    ctx.halo.update(s, {&s.rho});
  }

  // a_i += 1/m_i sum_j (V_i^2 + V_j^2) beta rho_bar (U_L - U_R)/2 (dW/dr)_ij e_ij over fluid j.
  template <bool kCompact>
  void momentum(StepContext<D>& ctx) {
    ParticleStore<D>& s = ctx.particles;
    const NeighborList<D>& nl = ctx.neighbors;
    const std::size_t n = s.owned();
    for (std::size_t i = 0; i < n; ++i) {
      if (s.kind[i] != Kind::kFluid) continue;
      const double rhoi = s.rho[i], Vi = s.m[i] / rhoi;
      const Vec<D> xi = s.x[i], vi = s.v[i];
      const auto g = pairs_of<kCompact>(ctx.pairs, nl, i);
      const std::uint32_t* first = nl.begin(i);
      const std::uint32_t* fluid_end = nl.fluid_end(i);
      Vec<D> acc = Vec<D>::Zero();
      std::size_t k = 0;
      for (const std::uint32_t* jp = first; jp != fluid_end; ++jp, ++k) {
        const std::uint32_t j = *jp;
        const Vec<D> xji = s.x[j] - xi;
        if (g.coincident(k, xji)) continue;
        const double r = g.distance(k, xji);
        const Vec<D> e = xji / r;
        const double jump = (vi - s.v[j]).dot(e);  // U_L - U_R
        if (!(jump > 0.0)) continue;               // beta = 0: the pair separates
        const double beta = std::min(eta_ * jump, c_);
        const double rhoj = s.rho[j], Vj = s.m[j] / rhoj;
        const double dp = 0.25 * beta * (rhoi + rhoj) * jump;  // beta rho_bar (U_L - U_R)/2
        acc += ((Vi * Vi + Vj * Vj) * dp * g.dwdr_at(k, r)) * e;
      }
      s.a[i] += acc / s.m[i];
    }
  }

  bool momentum_, hydrostatic_;
  double eta_, c_, inv_c_, rho0_;
  BodyForce<D> body_;
  double wall_volume_;
  std::vector<double> rate_;
};

}  // namespace sph
