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
// At a free surface the background-pressure term of the transport velocity pulls the surface
// particles inwards (their missing neighbours leave sum_j grad W_ij unbalanced), which
// compresses a free-surface flow until it fails. Particles whose kernel support is incomplete,
// sigma_i = V_i W(0) + sum_j V_j W_ij < 0.95 (walls and bodies count as filled), therefore keep
// only the component of a~ tangential to the surface, whose normal is -sum_j V_j grad W_ij:
// the free-surface treatment of particle shifting (Lind, Xu, Stansby, Rogers 2012, sec. 3.2;
// Sun, Colagrossi, Marrone, Zhang 2017, delta+-SPH). Confined flows never see it.
// Wall and rigid neighbours act through the values of the wall condition: pressure (eq. 27),
// density (eq. 28, for the fluid of particle i), the extrapolated no-slip velocity
// (eq. 23) in the viscous term (left out at free-slip walls), and no artificial viscosity
// or artificial stress (Adami 2012 sec. 3.2).
// The terms a case uses are selected at compile time, so the pair loop carries no unused
// work: one instantiation per combination of physical viscosity, artificial viscosity and
// transport velocity.
#include <cmath>
#include <vector>

#include "solver/core/neighbor_list.h"
#include "solver/core/pair_access.h"
#include "solver/physics/fluid_table.h"

namespace sph {

template <int D>
struct FluidForceInputs {
  const std::vector<FluidConstants>* fluids = nullptr;
  const PairKernel<D>* pairs = nullptr;               // kernel values of the list's pairs
  Vec<D> body = Vec<D>::Zero();                       // body force per unit mass on fluid particles
  double wall_volume = 0;                             // reference volume of a dummy particle (dx^d)
  double h = 0;                                       // smoothing length
  double alpha = 0;                                   // artificial viscosity (Adami 2012 eq. 11)
  const Column<Vec<D>>* noslip = nullptr;             // wall no-slip velocity (eq. 23)
  const Column<std::uint16_t>* wall_fluid = nullptr;  // fluid whose EOS gave rho_w
  const Column<double>* wall_p2 = nullptr;            // p_w of a second fluid (or null)
  const Column<std::uint16_t>* wall_fluid2 = nullptr;  // that fluid
  const Column<std::uint8_t>* free_slip = nullptr;     // per wall particle, or nullptr
  Column<Vec<D>>* transport = nullptr;                 // u~ (TVF)
  Column<Vec<D>>* background = nullptr;                // a~ (TVF)
  Column<Vec<D>>* rigid_force = nullptr;    // fluid force on each rigid particle (output)
  Column<Vec<D>>* elastic_force = nullptr;  // fluid force on each elastic particle (output)
  Column<Vec<D>>* rigid_lever = nullptr;    // spin lever of each rigid particle (output)
  // Filled by FluidForces::run: V_j = m_j / rho_j of every particle (owned and ghosts) and
  // 2 eta_a eta_b / (eta_a + eta_b) for each pair of fluid materials (row a, column b), so
  // the pair loop divides only where the pair itself needs it.
  const double* volume = nullptr;
  const double* eta_pair = nullptr;
};

// What fluid particle i receives from dummy (wall or rigid) particle j, times m_i: pressure
// with the dummy's density from i's EOS (Adami 2012 eq. 28), viscosity with the no-slip
// velocity (eq. 23) unless the wall is free-slip, and the artificial stress of the transport-
// velocity formulation with A_j = 0. One function serves the fluid's force and the reaction
// on a rigid particle (Fuchs 2021 eq. 19, f_ri = -m_i a_ir), so the two are equal and opposite.
template <int D, bool kViscous, bool kTransport>
struct DummyPair {
  const FluidConstants& fi;
  double rhoi, pi, Vi2;
  Vec<D> vi, dui;
  // s2 returns V_i^2 + V_j^2 (the transport-velocity background term needs it too).
  Vec<D> operator()(const Vec<D>& gradW, double dwdr, double r, double pj, double rhoj_stored,
                    bool same_fluid, const Vec<D>& noslip_j, bool free_slip_j, double wall_volume,
                    double& s2) const {
    const double rhoj = same_fluid ? rhoj_stored : fi.density(pj);
    const double Vj = wall_volume * fi.rho0 / rhoj;
    s2 = Vi2 + Vj * Vj;
    const double pt = (rhoj * pi + rhoi * pj) / (rhoi + rhoj);
    Vec<D> acc = -(s2 * pt) * gradW;
    if constexpr (kViscous) {
      if (!free_slip_j) acc += (s2 * fi.eta * dwdr / r) * (vi - noslip_j);
    }
    if constexpr (kTransport) acc += (0.5 * s2 * rhoi * dui.dot(gradW)) * vi;
    return acc;
  }
};

// Kernel support completeness below which a particle is in the free-surface zone.
inline constexpr double kFreeSurfaceCompleteness = 0.95;

// The pressure dummy j presents to fluid material m (WallBoundary: one p_w per fluid at a wall
// where two fluids meet) and whether its stored density belongs to that fluid.
template <int D>
inline double dummy_pressure(const FluidForceInputs<D>& in, const double* p, std::uint32_t j,
                             std::uint16_t m, bool& same_fluid) {
  same_fluid = (*in.wall_fluid)[j] == m;
  if (!same_fluid && in.wall_fluid2 && (*in.wall_fluid2)[j] == m) return (*in.wall_p2)[j];
  return p[j];
}

template <int D, class K, bool kViscous, bool kArtVisc, bool kTransport, bool kCompact>
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
  const double* V = in.volume;
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (kind[i] != Kind::kFluid) continue;
    const FluidConstants& fi = fl[mat[i]];
    const double* eta_i = in.eta_pair + mat[i] * fl.size();
    const Vec<D> xi = x[i], vi = v[i];
    const double mi = m[i], rhoi = rho[i], pi = p[i];
    const double Vi = mi / rhoi, Vi2 = Vi * Vi;
    Vec<D> acc = Vec<D>::Zero();  // times m_i
    Vec<D> acc_av = Vec<D>::Zero();
    Vec<D> acc_bg = Vec<D>::Zero();
    Vec<D> grad_sum = Vec<D>::Zero();  // sum_j V_j grad W_ij (free-surface normal)
    double sigma = 0;                  // kernel support completeness
    if constexpr (kTransport) sigma = Vi * k.W(0.0);
    Vec<D> dui = Vec<D>::Zero();
    if constexpr (kTransport) dui = (*in.transport)[i] - vi;
    const DummyPair<D, kViscous, kTransport> dummy{fi, rhoi, pi, Vi2, vi, dui};
    const auto g = pairs_of<kCompact>(*in.pairs, nl, i);
    // Fluid neighbours, then the dummies (the list keeps them apart: no test per pair).
    const std::uint32_t* const begin = nl.begin(i);
    const std::uint32_t* const fluid_end = nl.fluid_end(i);
    for (const std::uint32_t* jp = begin; jp != fluid_end; ++jp) {
      const auto e = static_cast<std::size_t>(jp - begin);
      const std::uint32_t j = *jp;
      const Vec<D> rij = xi - x[j];
      if (g.coincident(e, rij)) continue;
      const double dwdr_r = g.dwdr_r(e);
      const Vec<D> gradW = dwdr_r * rij;
      const double rhoj = rho[j], Vj = V[j];
      const double s2 = Vi2 + Vj * Vj;
      const double pt = (rhoj * pi + rhoi * p[j]) / (rhoi + rhoj);
      acc -= (s2 * pt) * gradW;
      if constexpr (kViscous) {
        const double eta_ij = eta_i[mat[j]];
        if (eta_ij > 0) acc += (s2 * eta_ij * dwdr_r) * (vi - v[j]);
      }
      if constexpr (kTransport) {
        acc_bg -= s2 * gradW;
        sigma += Vj * g.W(e);
        grad_sum += Vj * gradW;
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
        acc_av += (m[j] * in.alpha * in.h * cbar * vr / (rhobar * (g.r2(e, rij) + eps_h2))) * gradW;
      }
    }
    for (const std::uint32_t* jp = fluid_end; jp != nl.end(i); ++jp) {
      const auto e = static_cast<std::size_t>(jp - begin);
      const std::uint32_t j = *jp;
      const Vec<D> rij = xi - x[j];
      if (g.coincident(e, rij)) continue;
      const Vec<D> gradW = g.dwdr_r(e) * rij;
      double s2 = 0;
      bool same = false;
      const double pj = dummy_pressure(in, p, j, mat[i], same);
      acc += dummy(gradW, g.dummy_dwdr(e), g.dummy_r(e), pj, rho[j], same, (*in.noslip)[j],
                   in.free_slip && (*in.free_slip)[j], in.wall_volume, s2);
      if constexpr (kTransport) {
        acc_bg -= s2 * gradW;
        sigma += in.wall_volume * g.W(e);
        grad_sum += in.wall_volume * gradW;
      }
    }
    s.a[i] += acc / mi + acc_av + in.body;  // forces accumulate (solver/seam/unit.h)
    if constexpr (kTransport) {
      Vec<D> bg = (fi.pb / mi) * acc_bg;
      const double g2 = grad_sum.squaredNorm();
      if (sigma < kFreeSurfaceCompleteness && g2 > 0) bg -= (bg.dot(grad_sum) / g2) * grad_sum;
      (*in.background)[i] = bg;
    }
  }
}

// The force on each owned rigid particle from its fluid neighbours (Fuchs 2021 eq. 19):
// f_r = -sum_i m_i a_ir with a_ir exactly the term fluid particle i receives from r. The same
// for the particles of elastic bodies (thesis eqs. 3.12-3.13 with F^{F} = -F^{S}): forces
// equal and opposite by construction. Each kind is written only where its column is given.
// A turning rigid body also takes the part of the viscous stress the fluid's term leaves out.
// The viscous term (Morris 1997, Adami 2012 eq. 8) discretises mu lap(u), which is the
// divergence of the stress mu (grad u + grad u^T) only because div u = 0 in the fluid: a
// pair's force along v_i - v_r ~ (grad u) r_ir carries the flux mu (grad u) n across the wall,
// not the traction mu (grad u + grad u^T) n. On a no-slip rigid wall grad u^T n equals that of
// the body's rigid motion (its tangential derivatives and, by continuity, d u_n / dn are the
// wall's), -omega x n, so the pair's missing part is -(V_i^2 + V_r^2) eta W'_ir / r_ir times
// omega x r_ir. Summed over a particle's fluid neighbours that is omega x g, with the lever
// g = sum_i (V_i^2 + V_r^2) eta W'_ir / r_ir r_ir written to in.rigid_lever. RigidBodies adds
// the torque of omega x g to the body (its spin damping), not its force: over a wetted surface
// the part adds no force (omega x n integrates to zero over a closed surface), and leaving its
// discrete remainder out keeps the momentum of fluid and bodies exact. Over a fully wetted
// body the torque is -2 mu V omega (V the body's volume), the third of the torque a turning
// cylinder lacked in circular Couette flow (tests/validation/reports/magnus.md). The fluid
// keeps mu lap(u): its own motion was right. Elastic bodies do not take this part: their
// wall's spin varies along it (the solid's own velocity gradient would give it).
template <int D, class K, bool kViscous, bool kArtVisc, bool kTransport>
void compute_solid_coupling(ParticleStore<D>& s, const NeighborList<D>& nl, const K& /*kernel*/,
                            const FluidForceInputs<D>& in) {
  const auto& fl = *in.fluids;
  for (std::size_t r = 0; r < s.owned(); ++r) {
    Column<Vec<D>>* const out = s.kind[r] == Kind::kRigid     ? in.rigid_force
                                : s.kind[r] == Kind::kElastic ? in.elastic_force
                                                              : nullptr;
    if (!out) continue;
    Column<Vec<D>>& force = *out;
    Vec<D> f = Vec<D>::Zero();
    const bool rigid = out == in.rigid_force;
    Vec<D> lever = Vec<D>::Zero();
    const PairValues g = in.pairs->of(nl, r);
    const double *g_r = g.r, *g_dw = g.dw;
    for (const std::uint32_t* ip = nl.begin(r); ip != nl.fluid_end(r); ++ip, ++g_r, ++g_dw) {
      const std::uint32_t i = *ip;  // a fluid particle
      const Vec<D> rij = s.x[i] - s.x[r];
      const double dist = *g_r;
      if (dist == 0.0) continue;
      const double dwdr = *g_dw;
      const Vec<D> gradW = (dwdr / dist) * rij;
      const FluidConstants& fi = fl[s.material[i]];
      const double Vi = s.m[i] / s.rho[i];
      Vec<D> dui = Vec<D>::Zero();
      if constexpr (kTransport) dui = (*in.transport)[i] - s.v[i];
      const DummyPair<D, kViscous, kTransport> dummy{fi, s.rho[i], s.p[i], Vi * Vi, s.v[i], dui};
      double s2 = 0;
      bool same = false;
      const double pr =
          dummy_pressure(in, s.p.data(), static_cast<std::uint32_t>(r), s.material[i], same);
      f -= dummy(gradW, dwdr, dist, pr, s.rho[r], same, (*in.noslip)[r], false, in.wall_volume, s2);
      if constexpr (kViscous) {
        if (rigid) lever += (s2 * fi.eta * dwdr / dist) * rij;
      }
    }
    if (rigid && in.rigid_lever) (*in.rigid_lever)[r] = lever;
    force[r] = f;
  }
}

// Runtime selection of the instantiation a case needs.
template <int D, class K>
class FluidForces {
 public:
  static constexpr const char* kName = "fluid_forces";
  FluidForces(bool viscous, bool art_visc, bool transport) {
    fn_ = pick<false, false, false, false>(viscous, art_visc, transport);
    fn_compact_ = pick<false, false, false, true>(viscous, art_visc, transport);
    coupling_ = pick_coupling(viscous, transport);
  }
  void run(ParticleStore<D>& s, const NeighborList<D>& nl, const K& k,
           const FluidForceInputs<D>& in) {
    const auto& fl = *in.fluids;
    const std::size_t n = s.size(), nf = fl.size();
    volume_.resize(n);
    for (std::size_t j = 0; j < n; ++j) volume_[j] = s.m[j] / s.rho[j];
    eta_pair_.assign(nf * nf, 0.0);
    for (std::size_t a = 0; a < nf; ++a)
      for (std::size_t b = 0; b < nf; ++b) {
        const double es = fl[a].eta + fl[b].eta;
        if (es > 0) eta_pair_[a * nf + b] = 2.0 * fl[a].eta * fl[b].eta / es;
      }
    FluidForceInputs<D> with = in;
    with.volume = volume_.data();
    with.eta_pair = eta_pair_.data();
    (in.pairs->compact() ? fn_compact_ : fn_)(s, nl, k, with);
  }
  // Bytes of the per-particle scratch (V_j).
  std::size_t bytes() const { return volume_.capacity() * sizeof(double); }
  // The reaction forces on rigid and elastic particles (in.rigid_force, in.elastic_force).
  void run_coupling(ParticleStore<D>& s, const NeighborList<D>& nl, const K& k,
                    const FluidForceInputs<D>& in) const {
    coupling_(s, nl, k, in);
  }

 private:
  using Fn = void (*)(ParticleStore<D>&, const NeighborList<D>&, const K&,
                      const FluidForceInputs<D>&);
  template <bool V, bool A, bool T, bool C>
  static Fn pick(bool v, bool a, bool t) {
    if (v) return pick2<true, A, T, C>(a, t);
    return pick2<false, A, T, C>(a, t);
  }
  template <bool V, bool A, bool T, bool C>
  static Fn pick2(bool a, bool t) {
    if (a) return pick3<V, true, T, C>(t);
    return pick3<V, false, T, C>(t);
  }
  template <bool V, bool A, bool T, bool C>
  static Fn pick3(bool t) {
    if (t) return &compute_fluid_forces<D, K, V, A, true, C>;
    return &compute_fluid_forces<D, K, V, A, false, C>;
  }
  static Fn pick_coupling(bool v, bool t) {
    if (v)
      return t ? &compute_solid_coupling<D, K, true, false, true>
               : &compute_solid_coupling<D, K, true, false, false>;
    return t ? &compute_solid_coupling<D, K, false, false, true>
             : &compute_solid_coupling<D, K, false, false, false>;
  }
  Fn fn_, fn_compact_, coupling_;
  std::vector<double> volume_, eta_pair_;
};

}  // namespace sph
