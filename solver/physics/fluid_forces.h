#pragma once
// Acceleration of fluid particles (Fuchs 2021 eqs. 15-16; Adami 2012 eqs. 7-11; Adami, Hu,
// Adams 2013 for the transport-velocity terms):
//   a_i = 1/m_i sum_j (V_i^2 + V_j^2) [ -p~_ij dW/dr e_ij + eta~_ij u_ij/r_ij dW/dr
//                                       + 1/2 (A_i + A_j) . grad W ]  + art. viscosity + b_i
// (for the sign of the artificial viscosity see the pair loop)
//   p~_ij = (rho_j p_i + rho_i p_j)/(rho_i + rho_j),  eta~_ij = 2 eta_i eta_j/(eta_i + eta_j)
//   A = rho u (u~ - u)  (transport velocity only)
// plus the background-pressure acceleration that defines the transport velocity:
//   a~_i = -p_b,i/m_i sum_j (V_i^2 + V_j^2) grad W_ij.
// Wall and rigid neighbours act through the values of the wall condition: pressure (eq. 27),
// density (eq. 28, for the fluid of particle i), the extrapolated no-slip velocity
// (eq. 23) in the viscous term (left out at free-slip walls), and no artificial viscosity
// or artificial stress (Adami 2012 sec. 3.2).
// The terms a case uses are selected at compile time, so the pair loop carries no unused
// work: one instantiation per combination of physical viscosity, artificial viscosity and
// transport velocity.
#include <vector>

#include "solver/core/neighbor_list.h"
#include "solver/physics/fluid_table.h"

namespace sph {

template <int D>
struct FluidForceInputs {
  const std::vector<FluidConstants>* fluids = nullptr;
  Vec<D> body = Vec<D>::Zero();             // body force per unit mass on fluid particles
  double wall_volume = 0;                    // reference volume of a dummy particle (dx^d)
  double h = 0;                              // smoothing length
  double alpha = 0;                          // artificial viscosity (Adami 2012 eq. 11)
  const Column<Vec<D>>* noslip = nullptr;    // wall no-slip velocity (eq. 23)
  const Column<std::uint16_t>* wall_fluid = nullptr;  // fluid whose EOS gave rho_w
  const Column<std::uint8_t>* free_slip = nullptr;    // per wall particle, or nullptr
  Column<Vec<D>>* transport = nullptr;       // u~ (TVF)
  Column<Vec<D>>* background = nullptr;      // a~ (TVF)
};

template <int D, class K, bool kViscous, bool kArtVisc, bool kTransport>
void compute_fluid_forces(ParticleStore<D>& s, const NeighborList<D>& nl, const K& k,
                          const FluidForceInputs<D>& in) {
  const auto& fl = *in.fluids;
  const double eps_h2 = 0.01 * in.h * in.h;  // Adami 2012 eq. 11, epsilon = 0.01
  const Vec<D>* x = s.x.data();
  const Vec<D>* v = s.v.data();
  const double* rho = s.rho.data();
  const double* p = s.p.data();
  const double* m = s.m.data();
  const Kind* kind = s.kind.data();
  const std::uint16_t* mat = s.material.data();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (kind[i] != Kind::kFluid) continue;
    const FluidConstants& fi = fl[mat[i]];
    const Vec<D> xi = x[i], vi = v[i];
    const double mi = m[i], rhoi = rho[i], pi = p[i];
    const double Vi = mi / rhoi, Vi2 = Vi * Vi;
    Vec<D> acc = Vec<D>::Zero();  // times m_i
    Vec<D> acc_av = Vec<D>::Zero();
    Vec<D> acc_bg = Vec<D>::Zero();
    Vec<D> dui = Vec<D>::Zero();
    if constexpr (kTransport) dui = (*in.transport)[i] - vi;
    for (const std::uint32_t* jp = nl.begin(i); jp != nl.end(i); ++jp) {
      const std::uint32_t j = *jp;
      const Vec<D> rij = xi - x[j];
      const double r = rij.norm();
      if (r == 0.0) continue;
      const double dwdr = k.dW(r);
      const Vec<D> gradW = (dwdr / r) * rij;
      if (kind[j] == Kind::kFluid) {
        const double rhoj = rho[j], Vj = m[j] / rhoj;
        const double s2 = Vi2 + Vj * Vj;
        const double pt = (rhoj * pi + rhoi * p[j]) / (rhoi + rhoj);
        acc -= (s2 * pt) * gradW;
        if constexpr (kViscous) {
          const double ej = fl[mat[j]].eta, es = fi.eta + ej;
          if (es > 0) acc += (s2 * 2.0 * fi.eta * ej / es * dwdr / r) * (vi - v[j]);
        }
        if constexpr (kTransport) {
          acc_bg -= s2 * gradW;
          const Vec<D> duj = (*in.transport)[j] - v[j];
          // 1/2 (A_i + A_j) . grad W with A = rho u (u~ - u)^T.
          acc += (0.5 * s2) * (rhoi * dui.dot(gradW) * vi + rhoj * duj.dot(gradW) * v[j]);
        }
        if constexpr (kArtVisc) {
          // Adami 2012 eq. 11 as printed has a leading minus; with grad_a W_ab = W' e_ab that
          // accelerates approaching particles towards each other. The dissipative sign is
          // Monaghan's (Pi_ab = -alpha h c v_ab.r_ab / (rho (r^2 + eps h^2)), a -= m_b Pi_ab
          // grad W), applied to every pair as the paper does.
          const double vr = (vi - v[j]).dot(rij);
          const double cbar = 0.5 * (fi.c + fl[mat[j]].c), rhobar = 0.5 * (rhoi + rhoj);
          acc_av += (m[j] * in.alpha * in.h * cbar * vr / (rhobar * (r * r + eps_h2))) * gradW;
        }
      } else {
        // Dummy particle: density from its pressure through this fluid's EOS (eq. 28).
        const double rhoj = (*in.wall_fluid)[j] == mat[i] ? rho[j] : fi.density(p[j]);
        const double Vj = in.wall_volume * fi.rho0 / rhoj;
        const double s2 = Vi2 + Vj * Vj;
        const double pt = (rhoj * pi + rhoi * p[j]) / (rhoi + rhoj);
        acc -= (s2 * pt) * gradW;
        if constexpr (kViscous) {
          if (!(in.free_slip && (*in.free_slip)[j]))
            acc += (s2 * fi.eta * dwdr / r) * (vi - (*in.noslip)[j]);
        }
        if constexpr (kTransport) {
          acc_bg -= s2 * gradW;
          acc += (0.5 * s2 * rhoi * dui.dot(gradW)) * vi;
        }
      }
    }
    s.a[i] = acc / mi + acc_av + in.body;
    if constexpr (kTransport) (*in.background)[i] = (fi.pb / mi) * acc_bg;
  }
}

// Runtime selection of the instantiation a case needs.
template <int D, class K>
class FluidForces {
 public:
  static constexpr const char* kName = "fluid_forces";
  FluidForces(bool viscous, bool art_visc, bool transport) {
    fn_ = pick<false, false, false>(viscous, art_visc, transport);
  }
  void run(ParticleStore<D>& s, const NeighborList<D>& nl, const K& k,
           const FluidForceInputs<D>& in) const {
    fn_(s, nl, k, in);
  }

 private:
  using Fn = void (*)(ParticleStore<D>&, const NeighborList<D>&, const K&, const FluidForceInputs<D>&);
  template <bool V, bool A, bool T>
  static Fn pick(bool v, bool a, bool t) {
    if (v) return pick2<true, A, T>(a, t);
    return pick2<false, A, T>(a, t);
  }
  template <bool V, bool A, bool T>
  static Fn pick2(bool a, bool t) {
    if (a) return pick3<V, true, T>(t);
    return pick3<V, false, T>(t);
  }
  template <bool V, bool A, bool T>
  static Fn pick3(bool t) {
    if (t) return &compute_fluid_forces<D, K, V, A, true>;
    return &compute_fluid_forces<D, K, V, A, false>;
  }
  Fn fn_;
};

}  // namespace sph
