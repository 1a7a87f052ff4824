#pragma once
// Fickian particle shifting (Lind, Xu, Stansby, Rogers 2012, J. Comput. Phys. 231, 1499):
// after each step every fluid particle moves down the gradient of the particle concentration,
//
//   dr_i = -D_i grad C_i,  C_i = sum_j V_j W_ij,  grad C_i = sum_j V_j grad_i W_ij
//
// (Lind eqs. 6-8), which spreads clusters and fills voids, with the diffusivity of Skillen,
// Lind, Stansby, Rogers 2013 (Comput. Methods Appl. Mech. Eng. 265, 163, eq. 25)
//
//   D_i = A h |u| dt,  A = `coefficient` (default 2),
//
// |u| the particle's own speed (LOCAL) or the largest fluid speed of the step (MAXIMUM, as
// the CFL Ma (2h)^2 = 4 h U_max dt of Sun et al. 2017's delta+-SPH). Lind's D = 0.5 h^2 is a
// shift of half the disorder every step, made for incompressible SPH's steps of ~0.1 h / U;
// a weakly compressible step is ten times shorter (0.25 h / c, c = 10 U), so the same D would
// relax the lattice ten times faster relative to the flow and, in a tank at rest, keep moving
// particles that the flow does not move. D proportional to |u| dt shifts a fixed fraction of
// each step's motion, whatever the step, and nothing at rest.
//
// Free surface (Lind 2012 sec. 3.2): a particle whose kernel support is incomplete,
// C_i < `surface_threshold` (default 0.99: the outermost row of a flat surface has 0.78 with
// the quintic spline at h = dx, the next 0.993; at h = 2 dx the rows have 0.64, 0.86, 0.97), is
// shifted only tangentially to the surface,
//   dr_i <- (I - n_i n_i) dr_i,
// else grad C, which points into the fluid there, would push it out through the surface. The
// normal cannot be grad C_i itself (its tangential part would vanish with the normal part): it
// is the kernel average of the neighbours' gradients, n_i ~ sum_j V_j grad C_j W_ij over the
// fluid, in which the tangential disorder of single particles averages out while the missing
// support of the surface adds up. A particle whose neighbours fill less than kIsolated of its
// support (a spray droplet) is not shifted: there is no surface to be tangential to.
//
// Walls and bodies: dummy wall particles and rigid particles enter C and grad C like fluid
// neighbours with the volume dx^D (as in the wall condition, Adami 2012). A wall lattice
// continues the fluid's, so a fluid particle at its lattice distance sees no gradient, one
// that comes closer sees C rise towards the wall and is shifted away from it: the walls' share
// of the shift always points away from them, so they keep particles off them.
//
// The velocity is moved to the shifted position by a first-order Taylor step (Lind 2012
// eq. 10),
//   u_i <- u_i + dr_i . grad u_i,  grad u_i = sum_j V_j (u_j - u_i) grad_i W_ij
// over fluid neighbours; leaving it out would diffuse the velocity by the shift every step.
// The continuity density is not Taylor-corrected but changed as the particle's volume changes
// when the shift moves it and its neighbours apart or together (the continuity equation of
// the displacement, as the transport-velocity scheme integrates it with the velocity the
// particles move with, Adami, Hu, Adams 2013):
//   rho_i <- rho_i (1 - div dr_i),  div dr_i = sum_j V_j (dr_j - dr_i) . grad_i W_ij
// over fluid, wall and rigid neighbours (dr = 0 for the last two). A particle of fixed mass
// keeps m_i / rho_i equal to the room it has: with the Taylor step instead (the density as a
// field sampled at the new position), shifting spread the particles near the free surface
// without a pressure response, and the Colagrossi dam break's water rose (plateau +17%,
// docs/particle_shifting.md). Summation density needs neither (it is recomputed from the
// positions). Neither correction is conservative (nor is shifting).
//
// It runs in kEndOfStep, on u^{n+1}, rho^{n+1} at r^{n+1} with this step's neighbour lists
// and pair kernel: the shifts of all owned particles are computed from unshifted positions
// first and then applied, so the result does not depend on the order of the particles or on
// which rank owns a neighbour. The neighbour lists stay valid: the shift is part of the
// displacement that the Verlet skin's half-skin test measures.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "solver/core/pair_access.h"
#include "solver/physics/fluid_table.h"
#include "solver/seam/unit.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class ParticleShifting final : public Unit<D> {
 public:
  static constexpr const char* kName = "particle_shifting";
  // A particle whose neighbours fill less than this of its kernel support, C_i - V_i W(0), is
  // isolated and not shifted. On a flat free surface of a square lattice the outermost row has
  // 0.47 (quintic spline, h = dx; 0.56 at h = 2 dx; Wendland C2 at h = dx 0.35), one neighbour
  // at dx gives 0.12 (quintic, h = dx); the particle's own share W(0) V_i (0.31, 0.08, 0.56)
  // says nothing about its neighbours.
  static constexpr double kIsolated = 0.2;

  // `self_kernel`: W(0); `correct_density`: the density is integrated (continuity), so it is
  // moved with the particle.
  ParticleShifting(const v1::ParticleShifting& ps, const std::vector<FluidConstants>& fluids,
                   ParticleStore<D>& particles, double h, double wall_volume, double self_kernel,
                   bool correct_density)
      : coefficient_(ps.has_coefficient() ? ps.coefficient() : 2.0),
        threshold_(ps.has_surface_threshold() ? ps.surface_threshold() : 0.99),
        maximum_speed_(ps.speed() == v1::ParticleShifting::MAXIMUM),
        correct_density_(correct_density),
        fluids_(fluids),
        h_(h),
        wall_volume_(wall_volume),
        w0_(self_kernel),
        gradient_(particles.template add<Vec<D>>("shifting_gradient", kName, false)),
        shift_(particles.template add<Vec<D>>("shifting_displacement", kName, false)) {}

  const char* name() const override { return kName; }
  PhaseMask phases() const override { return phase_bit(StepPhase::kEndOfStep); }
  std::size_t scratch_bytes() const override {
    return completeness_.capacity() * sizeof(double) + dv_.capacity() * sizeof(Vec<D>) +
           drho_.capacity() * sizeof(double);
  }

  void run(StepPhase, StepContext<D>& ctx) override {
    if (ctx.dt <= 0) return;  // priming
    ParticleStore<D>& s = ctx.particles;
    const std::size_t n = s.owned();
    completeness_.resize(n);
    dv_.resize(n);
    drho_.resize(n);
    // The ghosts carry the velocity of the drift (u^{n+1/2}); the Taylor step reads u^{n+1}.
    ctx.halo.update(s, {&s.v});
    with_pair_form(ctx.pairs, [&](auto compact) { concentration<decltype(compact)::value>(ctx); });
    ctx.halo.update(s, {&gradient_});  // the surface normal averages the neighbours' gradients
    double speed = 0;
    if (maximum_speed_) {
      for (std::size_t i = 0; i < n; ++i)
        if (s.kind[i] == Kind::kFluid) speed = std::max(speed, s.v[i].norm());
      speed = ctx.comm.max(speed);  // an exact maximum: the same on every rank count
    }
    with_pair_form(ctx.pairs, [&](auto compact) {
      constexpr bool kCompact = decltype(compact)::value;
      shifts<kCompact>(ctx, speed);
      if (correct_density_) {
        ctx.halo.update(s, {&shift_});  // the divergence reads the neighbours' shifts
        volume_change<kCompact>(ctx);
      }
    });
    surface_ = 0;
    largest_ = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (s.kind[i] != Kind::kFluid) continue;
      s.x[i] += shift_[i];
      s.v[i] += dv_[i];
      if (correct_density_) {
        s.rho[i] *= 1.0 - drho_[i];
        s.p[i] = fluids_[s.material[i]].pressure(s.rho[i]);
      }
      if (completeness_[i] < threshold_) ++surface_;
      largest_ = std::max(largest_, shift_[i].norm());
    }
  }

  // The free-surface particles and the largest shift (in h) of the last step.
  void sample(ResultFile& result, const StepContext<D>& ctx) override {
    result.put("particle_shifting/surface_particles", static_cast<double>(ctx.comm.sum(surface_)));
    result.put("particle_shifting/max_shift", ctx.comm.max(largest_) / h_);
  }

 private:
  // C_i and grad C_i (Lind 2012 eqs. 6-7) of the owned fluid particles.
  template <bool kCompact>
  void concentration(StepContext<D>& ctx) {
    ParticleStore<D>& s = ctx.particles;
    const NeighborList<D>& nl = ctx.neighbors;
    for (std::size_t i = 0; i < s.owned(); ++i) {
      gradient_[i] = Vec<D>::Zero();
      if (s.kind[i] != Kind::kFluid) continue;
      const Vec<D> xi = s.x[i];
      const auto pairs = pairs_of<kCompact>(ctx.pairs, nl, i);
      const std::uint32_t* first = nl.begin(i);
      const std::uint32_t* fluid_end = nl.fluid_end(i);
      const std::uint32_t* end = nl.end(i);
      double c = w0_ * s.m[i] / s.rho[i];
      Vec<D> g = Vec<D>::Zero();
      std::size_t k = 0;
      for (const std::uint32_t* jp = first; jp != end; ++jp, ++k) {
        const std::uint32_t j = *jp;
        const Vec<D> xij = xi - s.x[j];
        if (pairs.coincident(k, xij)) continue;
        const double vol = jp < fluid_end ? s.m[j] / s.rho[j] : wall_volume_;
        c += vol * pairs.W(k);
        g += pairs.times_dwdr_over_r(vol, k) * xij;
      }
      completeness_[i] = c;
      gradient_[i] = g;
    }
  }

  // dr_i with the free-surface treatment, and the Taylor correction of u.
  template <bool kCompact>
  void shifts(StepContext<D>& ctx, double max_speed) {
    ParticleStore<D>& s = ctx.particles;
    const NeighborList<D>& nl = ctx.neighbors;
    for (std::size_t i = 0; i < s.owned(); ++i) {
      shift_[i] = Vec<D>::Zero();
      dv_[i] = Vec<D>::Zero();
      if (s.kind[i] != Kind::kFluid) continue;
      if (completeness_[i] - w0_ * s.m[i] / s.rho[i] < kIsolated) continue;
      const double speed = maximum_speed_ ? max_speed : s.v[i].norm();
      // Skillen et al. 2013 eq. 25: D = A h |u| dt.
      Vec<D> d = (-coefficient_ * h_ * speed * ctx.dt) * gradient_[i];
      const Vec<D> xi = s.x[i];
      const auto pairs = pairs_of<kCompact>(ctx.pairs, nl, i);
      const std::uint32_t* first = nl.begin(i);
      const std::uint32_t* fluid_end = nl.fluid_end(i);
      if (completeness_[i] < threshold_) {
        // Lind 2012 sec. 3.2: only the part tangential to the surface.
        Vec<D> normal = (w0_ * s.m[i] / s.rho[i]) * gradient_[i];
        std::size_t k = 0;
        for (const std::uint32_t* jp = first; jp != fluid_end; ++jp, ++k) {
          const std::uint32_t j = *jp;
          normal += (s.m[j] / s.rho[j] * pairs.W(k)) * gradient_[j];
        }
        const double n2 = normal.squaredNorm();
        if (!(n2 > 0)) continue;
        d -= (d.dot(normal) / n2) * normal;
      }
      // Lind 2012 eq. 10: u_i + dr_i . grad u_i.
      const Vec<D> vi = s.v[i];
      Vec<D> dv = Vec<D>::Zero();
      std::size_t k = 0;
      for (const std::uint32_t* jp = first; jp != fluid_end; ++jp, ++k) {
        const std::uint32_t j = *jp;
        const Vec<D> xij = xi - s.x[j];
        if (pairs.coincident(k, xij)) continue;
        // V_j grad_i W_ij . dr_i
        const double g = pairs.times_dwdr_over_r(s.m[j] / s.rho[j], k) * xij.dot(d);
        dv += g * (s.v[j] - vi);
      }
      shift_[i] = d;
      dv_[i] = dv;
    }
  }

  // div dr_i (into drho_) over fluid, wall and rigid neighbours; walls and bodies do not shift.
  template <bool kCompact>
  void volume_change(StepContext<D>& ctx) {
    ParticleStore<D>& s = ctx.particles;
    const NeighborList<D>& nl = ctx.neighbors;
    for (std::size_t i = 0; i < s.owned(); ++i) {
      drho_[i] = 0;
      if (s.kind[i] != Kind::kFluid) continue;
      const Vec<D> xi = s.x[i], di = shift_[i];
      const auto pairs = pairs_of<kCompact>(ctx.pairs, nl, i);
      const std::uint32_t* first = nl.begin(i);
      const std::uint32_t* fluid_end = nl.fluid_end(i);
      const std::uint32_t* end = nl.end(i);
      double div = 0;
      std::size_t k = 0;
      for (const std::uint32_t* jp = first; jp != end; ++jp, ++k) {
        const std::uint32_t j = *jp;
        const Vec<D> xij = xi - s.x[j];
        if (pairs.coincident(k, xij)) continue;
        const bool fluid = jp < fluid_end;
        const double vol = fluid ? s.m[j] / s.rho[j] : wall_volume_;
        const Vec<D> dj = fluid ? shift_[j] : Vec<D>::Zero();
        div += pairs.times_dwdr_over_r(vol, k) * xij.dot(dj - di);
      }
      drho_[i] = div;
    }
  }

  double coefficient_, threshold_;
  bool maximum_speed_, correct_density_;
  std::vector<FluidConstants> fluids_;
  double h_, wall_volume_, w0_;
  Column<Vec<D>>& gradient_;  // grad C_i, owned and ghosts
  Column<Vec<D>>& shift_;     // dr_i, owned and ghosts
  std::vector<double> completeness_;
  std::vector<Vec<D>> dv_;
  std::vector<double> drho_;  // div dr_i
  std::int64_t surface_ = 0;
  double largest_ = 0;
};

}  // namespace sph
