#pragma once
// Conduction of heat and diffusion of a concentration in fluid and rigid particles, in the
// form of Cleary & Monaghan (1999) used by Fuchs 2021 eq. (28):
//   c_a dT_a/dt = 1/rho_a sum_b V_b 4 k_a k_b/(k_a + k_b) (T_a - T_b)/r_ab dW/dr_ab,
// and for a concentration (Fuchs 2021 Remark 4) the same with the diffusivity for k and
// c = 1. The harmonic mean of the conductivities keeps the flux continuous across material
// interfaces. Integrated explicitly (Fuchs 2021 eq. 37) with the rates from the field at t^n
// and positions and densities at t^{n+1}.
//
// Walls: a wall with a schedule is a Dirichlet boundary. Its particles carry the mirror value
// T_w = 2 T_D - T~, T~ the Shepard average of the fluid and rigid particles around the wall
// particle (a mirror of the fluid alone lets a solid resting on the wall conduct with the
// mirror of the fluid beside it, not of itself), the way
// Adami 2012 eqs. 22-23 impose a no-slip velocity: the profile then continues linearly
// through the wall and T_D holds at the wall surface (holding the particles at T_D itself
// would make the wall a second medium and the boundary condition only first order). They
// conduct with the wall material's coefficient, or the neighbour's if it has none. A wall
// without a schedule is insulated (no flux: its particles are left out of the sum).
// Materials marked fixed (a concentration held constant, e.g. gastric juice) are sources
// that never change.
//
// The mirror value is second order but not monotone: where a wall particle's support holds
// particles of very different values (hot gas beside a solid resting on a cold wall), T~ is
// far from the value of the particle the wall conducts with, and 2 T_D - T~ drives that
// particle past T_D.
// Each particle a therefore limits the difference it sees to a Dirichlet wall particle w:
//   T_a - T_w  is clamped to lie between 0 and R (T_a - T_D),   R = kMirrorLimit,
// which leaves smooth profiles alone (there T_a - T_w is about (1 + 2 y~/y_a)(T_a - T_D),
// 2 to 4 times T_a - T_D for the first fluid rows with y~ the mean distance of T~'s
// particles from the surface) and makes the wall term pull T_a towards T_D only, never past
// it. With it the update is a convex combination of T_a, its neighbours' values and the
// walls' T_D whenever dt sum_b c_ab (R for wall pairs) <= 1, so values stay within the
// initial and prescribed bounds (a discrete maximum principle) at the steps eq. (41) gives.
//
// Latent heat (Fuchs 2021 Remark 3; Proell, Wall, Meier 2020): the apparent-capacity scheme
// raises c_p by L/dT inside the melting interval [T_lo, T_hi]. Integrated as written, an
// explicit step can jump across a narrow interval and skip the latent heat. The update is
// therefore done on the specific enthalpy h(T) = c_p T + L clamp((T - T_lo)/dT, 0, 1), whose
// derivative is exactly the apparent capacity: h^{n+1} = h(T^n) + dt q, T^{n+1} = h^{-1}(h^{n+1})
// with q the conduction (and source) power per unit mass. Energy sum m h is then conserved
// by the symmetric pair fluxes whatever the step size.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "case/time_function.h"
#include "solver/core/neighbor_list.h"
#include "solver/core/pair_access.h"

namespace sph {

struct DiffusionMaterial {
  double coefficient = 0;  // conductivity kappa or diffusivity D
  double capacity = 1;     // c_p (1 for a concentration)
  double density = 1;      // rho of rigid particles (their density column holds the dummy value)
  bool fixed = false;
  // Latent heat L released/absorbed over [latent_lo, latent_hi] (0: none).
  double latent = 0, latent_lo = 0, latent_hi = 0;

  // Specific enthalpy (energy per unit mass) at value T; c_p T without latent heat.
  double enthalpy(double T) const {
    double h = capacity * T;
    if (latent > 0) h += latent * std::clamp((T - latent_lo) / (latent_hi - latent_lo), 0.0, 1.0);
    return h;
  }
  // The inverse of enthalpy(): h is strictly increasing and piecewise linear.
  double value_of(double h) const {
    if (latent <= 0) return h / capacity;
    if (h <= capacity * latent_lo) return h / capacity;
    if (h >= capacity * latent_hi + latent) return (h - latent) / capacity;
    const double apparent = capacity + latent / (latent_hi - latent_lo);
    return latent_lo + (h - capacity * latent_lo) / apparent;
  }
};

// The largest ratio (T_a - T_w)/(T_a - T_D) a wall pair may carry (see above).
inline constexpr double kMirrorLimit = 3.0;

template <int D>
class ScalarDiffusion {
 public:
  // `name`: the particle column ("temperature" or "concentration"), owned by the unit
  // `owner`; materials indexed like the particles' material; wall_values[k]: schedule of
  // wall k (absent = insulated).
  ScalarDiffusion(ParticleStore<D>& s, const std::string& name, std::vector<DiffusionMaterial> mats,
                  std::vector<std::optional<TimeFunction>> wall_values,
                  std::vector<int> wall_material, double wall_volume, double source_per_volume,
                  const std::string& owner)
      : s_(s),
        value_(s.template add<double>(name, owner, true)),
        mats_(std::move(mats)),
        walls_(std::move(wall_values)),
        wall_material_(std::move(wall_material)),
        wall_volume_(wall_volume),
        source_(source_per_volume),
        targets_(walls_.size(), 0.0) {
    tabulate_pairs();
  }

  Column<double>& values() { return value_; }
  const Column<double>& values() const { return value_; }
  const std::string& name() const { return value_.name(); }
  // Energy (species mass) per unit mass of a particle of `material` at `value`.
  double content(std::uint16_t material, double value) const {
    return mats_[material].enthalpy(value);
  }

  // Prescribed values of the owned wall particles at time t (before the ghost exchange).
  void set_wall_values(double t, const Column<std::uint16_t>& wall_index) {
    for (std::size_t i = 0; i < s_.owned(); ++i)
      if (s_.kind[i] == Kind::kWall) {
        const auto& f = walls_[wall_index[i]];
        if (f) value_[i] = f->value(t);
      }
  }

  // Mirror values of the owned Dirichlet wall particles at time t from their fluid and rigid
  // neighbours; the caller then refreshes the ghosts of values().
  void extrapolate_walls(const NeighborList<D>& nl, const PairKernel<D>& pk, double t,
                         const Column<std::uint16_t>& wall_index) {
    for (std::size_t k = 0; k < walls_.size(); ++k)
      if (walls_[k]) targets_[k] = walls_[k]->value(t);
    for (std::size_t w = 0; w < s_.owned(); ++w) {
      if (s_.kind[w] != Kind::kWall) continue;
      const auto& f = walls_[wall_index[w]];
      if (!f) continue;
      double sw = 0, sv = 0;
      const double* g_w = pk.weights(nl, w);
      for (const std::uint32_t* bp = nl.begin(w); bp != nl.end(w); ++bp, ++g_w) {
        const double W = *g_w;
        sw += W;
        sv += W * value_[*bp];
      }
      const double target = targets_[wall_index[w]];
      value_[w] = sw > 0 ? 2.0 * target - sv / sw : target;
    }
  }
  bool has_dirichlet_walls() const {
    for (const auto& w : walls_)
      if (w) return true;
    return false;
  }

  // Advances the owned fluid and rigid particles by dt. `wall_index` tells which wall a wall
  // particle belongs to (ghosts included).
  void run(const NeighborList<D>& nl, const PairKernel<D>& pk, double dt,
           const Column<std::uint16_t>& wall_index) {
    if (pk.compact())
      advance<true>(nl, pk, dt, wall_index);
    else
      advance<false>(nl, pk, dt, wall_index);
  }

  // Bytes of the unit's per-particle scratch (the value column is counted with the store).
  std::size_t bytes() const {
    return rate_.capacity() * sizeof(double) + volume_.capacity() * sizeof(double) +
           class_.capacity() * sizeof(std::uint16_t);
  }

 private:
  // The pass of run() for one form of the pair values.
  template <bool kCompact>
  void advance(const NeighborList<D>& nl, const PairKernel<D>& pk, double dt,
               const Column<std::uint16_t>& wall_index) {
    gather(wall_index);
    const std::size_t n = s_.owned(), nm = mats_.size(), nc = nm + walls_.size();
    const double* value = value_.data();
    const std::uint16_t* cls = class_.data();
    const double* vol = volume_.data();
    rate_.assign(n, 0.0);
    for (std::size_t a = 0; a < n; ++a) {
      const Kind ka = s_.kind[a];
      if (ka == Kind::kWall) continue;
      const std::size_t mat_a = s_.material[a];
      const DiffusionMaterial& ma = mats_[mat_a];
      if (ma.fixed) continue;
      const double rho_a = ka == Kind::kFluid ? s_.rho[a] : ma.density;
      const double* coef = pair_coefficient_.data() + mat_a * nc;
      const double va = value[a];
      double sum = 0;
      const auto g = pairs_of<kCompact>(pk, nl, a);
      // The fluid neighbours come first and are never walls.
      const std::uint32_t* const begin = nl.begin(a);
      const std::uint32_t* const fluid_end = nl.fluid_end(a);
      for (const std::uint32_t* bp = begin; bp != fluid_end; ++bp) {
        const auto e = static_cast<std::size_t>(bp - begin);
        const std::uint32_t b = *bp;
        const double c = coef[cls[b]];  // 0 for non-conducting pairs
        if (c == 0.0 || g.coincident(e)) continue;
        sum += g.over_r_times_dwdr(vol[b] * c * (va - value[b]), e);
      }
      for (const std::uint32_t* bp = fluid_end; bp != nl.end(a); ++bp) {
        const auto e = static_cast<std::size_t>(bp - begin);
        const std::uint32_t b = *bp;
        const std::uint16_t cb = cls[b];
        const double c = coef[cb];  // 0 for insulated walls and non-conducting pairs
        if (c == 0.0) continue;
        double diff = va - value[b];
        if (cb >= nm) {
          const double towards = kMirrorLimit * (va - targets_[cb - nm]);
          diff = std::clamp(diff, std::min(0.0, towards), std::max(0.0, towards));
        }
        if (g.coincident(e)) continue;
        sum += g.over_r_times_dwdr(vol[b] * c * diff, e);
      }
      rate_[a] = (sum + source_) / rho_a;  // power per unit mass
    }
    for (std::size_t a = 0; a < n; ++a) {
      if (rate_[a] == 0.0) continue;
      const DiffusionMaterial& ma = mats_[s_.material[a]];
      value_[a] = ma.latent > 0 ? ma.value_of(ma.enthalpy(value_[a]) + dt * rate_[a])
                                : value_[a] + dt * rate_[a] / ma.capacity;
    }
  }

  ParticleStore<D>& s_;
  Column<double>& value_;
  std::vector<DiffusionMaterial> mats_;
  std::vector<std::optional<TimeFunction>> walls_;
  std::vector<int> wall_material_;
  double wall_volume_, source_;
  // The per-particle inputs of the pair loop, gathered once per step for owned particles and
  // ghosts, so the loop does no table lookup or division per neighbour beyond the kernel:
  //   class_[b]  the material of a fluid or rigid particle, nm + k for a particle of wall k;
  //   volume_[b] V_b (m/rho for fluid, m/rho_material for rigid, the dummy volume for walls).
  void gather(const Column<std::uint16_t>& wall_index) {
    const std::size_t n = s_.size(), nm = mats_.size();
    class_.resize(n);
    volume_.resize(n);
    for (std::size_t b = 0; b < n; ++b) {
      switch (s_.kind[b]) {
        case Kind::kWall:
          class_[b] = static_cast<std::uint16_t>(nm + wall_index[b]);
          volume_[b] = wall_volume_;
          break;
        case Kind::kFluid:
          class_[b] = s_.material[b];
          volume_[b] = s_.m[b] / s_.rho[b];
          break;
        default:
          class_[b] = s_.material[b];
          volume_[b] = s_.m[b] / mats_[s_.material[b]].density;
      }
    }
  }

  // 4 k_a k_b/(k_a + k_b) (Fuchs 2021 eq. 28) for material a (row) and class b (column); a
  // wall conducts with its material's coefficient, or with a's when it has none, and an
  // insulated wall not at all.
  void tabulate_pairs() {
    const std::size_t nm = mats_.size(), nc = nm + walls_.size();
    pair_coefficient_.assign(nm * nc, 0.0);
    for (std::size_t a = 0; a < nm; ++a) {
      const double ka = mats_[a].coefficient;
      for (std::size_t cb = 0; cb < nc; ++cb) {
        double kb;
        if (cb < nm) {
          kb = mats_[cb].coefficient;
        } else {
          const std::size_t w = cb - nm;
          if (!walls_[w]) continue;
          kb = wall_material_[w] >= 0
                   ? mats_[static_cast<std::size_t>(wall_material_[w])].coefficient
                   : ka;
        }
        if (ka + kb > 0) pair_coefficient_[a * nc + cb] = 4.0 * ka * kb / (ka + kb);
      }
    }
  }

  std::vector<double> targets_;  // T_D of each Dirichlet wall at the current step
  std::vector<double> pair_coefficient_;
  std::vector<double> rate_, volume_;
  std::vector<std::uint16_t> class_;
};

}  // namespace sph
