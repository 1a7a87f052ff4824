#pragma once
// Density from the continuity equation (Adami 2012 eq. 6):
//   d rho_a/dt = rho_a sum_b V_b v_ab . grad_a W_ab,
// with V_b = m_b/rho_b for fluid neighbours and the initial volume for wall particles, whose
// velocity is the prescribed wall velocity (Adami 2012 sec. 4). It is integrated as
// Adami 2012 eq. 16, rho^{n+1} = rho^n + dt (d rho/dt)^{n+1/2}: the rate is evaluated at the
// mid-step positions r^{n+1/2} = r^{n+1} - dt/2 v^{n+1/2}, reconstructed per pair from the
// end-of-step positions, so one neighbour search per step suffices.
#include <vector>

#include "solver/core/neighbor_list.h"

namespace sph {

template <int D, class K>
class ContinuityDensity {
 public:
  static constexpr const char* kName = "continuity_density";
  // `advect`: the velocity particles were drifted with (the transport velocity under TVF).
  ContinuityDensity(ParticleStore<D>& s, const K& kernel, double wall_volume,
                    Column<Vec<D>>& advect)
      : s_(s), k_(kernel), wall_volume_(wall_volume), adv_(advect) {}

  void run(const NeighborList<D>& nl, double dt) {
    const std::size_t n = s_.owned();
    rate_.assign(n, 0.0);
    const double rc2 = k_.support_radius() * k_.support_radius();
    for (std::size_t i = 0; i < n; ++i) {
      if (s_.kind[i] != Kind::kFluid) continue;
      const Vec<D> xi = s_.x[i], ui = adv_[i];
      double sum = 0.0;
      for (const std::uint32_t* jp = nl.begin(i); jp != nl.end(i); ++jp) {
        const std::uint32_t j = *jp;
        const Vec<D> uij = ui - adv_[j];
        const Vec<D> rij = (xi - s_.x[j]) - 0.5 * dt * uij;
        const double r2 = rij.squaredNorm();
        if (r2 >= rc2 || r2 == 0.0) continue;
        const double r = std::sqrt(r2);
        const double vol = s_.kind[j] == Kind::kFluid ? s_.m[j] / s_.rho[j] : wall_volume_;
        sum += vol * k_.dW(r) / r * uij.dot(rij);
      }
      rate_[i] = s_.rho[i] * sum;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (s_.kind[i] == Kind::kFluid) s_.rho[i] += dt * rate_[i];
  }

  // Bytes of the per-particle scratch (the rates).
  std::size_t bytes() const { return rate_.capacity() * sizeof(double); }

 private:
  ParticleStore<D>& s_;
  const K& k_;
  double wall_volume_;
  Column<Vec<D>>& adv_;
  std::vector<double> rate_;
};

}  // namespace sph
