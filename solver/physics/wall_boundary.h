#pragma once
// The generalized wall boundary condition of Adami, Hu, Adams (2012), applied to dummy wall
// particles, rigid-body particles (Fuchs 2021 "Boundary and coupling conditions") and the
// particles of elastic bodies (thesis sec. 2.5). For each wall particle w with fluid
// neighbours f:
//   p_w = (sum_f p_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf) / sum_f W_wf     (eq. 27)
//   rho_w from p_w through the EOS of the neighbouring fluid                      (eq. 28)
//   v_w' = 2 v_w - sum_f v_f W_wf / sum_f W_wf   for the viscous (no-slip) term  (eqs. 22-23)
// g is the body force acting on the fluid and a_w the wall's own acceleration, which the
// free-fall experiment (sec. 7.1) shows must not be left out.
// With several fluids around one wall particle, each of the two fluids of largest kernel
// weight gets its own p_w from its own particles only: every phase sees the wall as in the
// single-phase condition. Extrapolating the mixture instead hands a light phase the heavy
// phase's hydrostatic term rho_heavy g r, and a pressure error of rho_heavy g dx accelerates
// light particles by rho_heavy/rho_light times more than heavy ones (docs/effects.md, "Design
// measurements"). rho_w is stored for the
// majority fluid; FluidForces converts a p_w for a pair with another fluid (eq. 28 "from the
// interacting fluid particle b"). A third fluid at one wall particle uses the majority's p_w.
#include <algorithm>
#include <array>
#include <vector>

#include "solver/core/neighbor_list.h"
#include "solver/core/pair_kernel.h"
#include "solver/physics/fluid_table.h"

namespace sph {

template <int D>
class WallBoundary {
 public:
  static constexpr const char* kName = "wall_boundary";
  WallBoundary(ParticleStore<D>& s, const std::vector<FluidConstants>& fluids)
      : s_(s),
        fluids_(fluids),
        vext_(s.template add<Vec<D>>("wall_noslip_velocity", kName, false)),
        wall_fluid_(s.template add<std::uint16_t>("wall_fluid_material", kName, false)) {
    int n_fluids = 0;
    for (std::size_t m = 0; m < fluids.size(); ++m)
      if (fluids[m].fluid) {
        if (first_fluid_ < 0) first_fluid_ = static_cast<int>(m);
        ++n_fluids;
      }
    if (n_fluids > 1) {
      p2_ = &s.template add<double>("wall_pressure_second_fluid", kName, false);
      fluid2_ = &s.template add<std::uint16_t>("wall_second_fluid_material", kName, false);
    }
    msw_.assign(fluids.size(), 0.0);
    msp_.assign(fluids.size(), 0.0);
    msrho_.assign(fluids.size(), Vec<D>::Zero());
  }

  Column<Vec<D>>& noslip_velocity() { return vext_; }
  Column<std::uint16_t>& fluid_material() { return wall_fluid_; }
  // The second fluid's wall pressure and its material (null with a single fluid).
  Column<double>* second_pressure() { return p2_; }
  Column<std::uint16_t>* second_fluid_material() { return fluid2_; }

  // body: acceleration acting on the fluid; wall_accel: per-particle wall acceleration or
  // nullptr for walls at rest.
  void run(const NeighborList<D>& nl, const PairKernel<D>& pk, const Vec<D>& body,
           const Column<Vec<D>>* wall_accel) {
    // A scene of bodies and walls without any fluid material (contact only) has no fluid for
    // the condition to serve, and no fluid whose reference density a lone wall could take.
    if (first_fluid_ < 0) return;
    for (std::size_t w = 0; w < s_.owned(); ++w) {
      if (s_.kind[w] == Kind::kFluid) continue;
      double sw = 0, sp = 0;
      Vec<D> srho = Vec<D>::Zero(), sv = Vec<D>::Zero();
      int mat = -1;
      bool mixed = false;
      const Vec<D> xw = s_.x[w];
      const double* const pair_w = pk.weights(nl, w);
      const double* g_w = pair_w;
      for (const std::uint32_t* fp = nl.begin(w); fp != nl.fluid_end(w); ++fp, ++g_w) {
        const std::uint32_t f = *fp;
        const Vec<D> rwf = xw - s_.x[f];
        const double W = *g_w;
        sw += W;
        sp += s_.p[f] * W;
        srho += (s_.rho[f] * W) * rwf;
        sv += W * s_.v[f];
        const int mf = s_.material[f];
        if (mat < 0)
          mat = mf;
        else if (mf != mat)
          mixed = true;
      }
      if (sw <= 0.0) {
        s_.p[w] = 0.0;
        s_.rho[w] = fluids_[static_cast<std::size_t>(first_fluid_)].rho0;
        wall_fluid_[w] = static_cast<std::uint16_t>(first_fluid_);
        if (p2_) (*fluid2_)[w] = static_cast<std::uint16_t>(first_fluid_);
        vext_[w] = s_.v[w];
        continue;
      }
      Vec<D> acc = body;
      // An elastic particle's own acceleration is its a^n (the fluid sees the structure as a
      // moving wall, Zhang, Rezavand, Hu 2021; thesis eq. 3.14).
      if (s_.kind[w] == Kind::kElastic)
        acc -= s_.a[w];
      else if (wall_accel)
        acc -= (*wall_accel)[w];
      vext_[w] = 2.0 * s_.v[w] - sv / sw;
      if (!mixed) {
        const double pw = (sp + acc.dot(srho)) / sw;
        s_.p[w] = pw;
        s_.rho[w] = fluids_[static_cast<std::size_t>(mat)].density(pw);
        wall_fluid_[w] = static_cast<std::uint16_t>(mat);
        if (p2_) (*fluid2_)[w] = static_cast<std::uint16_t>(mat);
        continue;
      }
      // Per fluid: eq. 27 over that fluid's particles only (the same pairs: pair_w still
      // holds them, no of() or weights() call came between).
      const double* g2_w = pair_w;
      for (const std::uint32_t* fp = nl.begin(w); fp != nl.fluid_end(w); ++fp, ++g2_w) {
        const std::uint32_t f = *fp;
        const std::size_t mf = s_.material[f];
        const Vec<D> rwf = xw - s_.x[f];
        const double W = *g2_w;
        msw_[mf] += W;
        msp_[mf] += s_.p[f] * W;
        msrho_[mf] += (s_.rho[f] * W) * rwf;
      }
      std::size_t first = 0, second = 0;
      double w1 = -1, w2 = -1;
      for (std::size_t m = 0; m < msw_.size(); ++m) {
        if (msw_[m] > w1) {
          second = first;
          w2 = w1;
          first = m;
          w1 = msw_[m];
        } else if (msw_[m] > w2) {
          second = m;
          w2 = msw_[m];
        }
      }
      const double p1 = (msp_[first] + acc.dot(msrho_[first])) / msw_[first];
      s_.p[w] = p1;
      s_.rho[w] = fluids_[first].density(p1);
      wall_fluid_[w] = static_cast<std::uint16_t>(first);
      // A second fluid whose particles all sit at the edge of the support (W rounded to 0)
      // has no pressure to extrapolate: the first's stands for it.
      const std::size_t other = w2 > 0.0 ? second : first;
      (*p2_)[w] = other == first ? p1 : (msp_[other] + acc.dot(msrho_[other])) / msw_[other];
      (*fluid2_)[w] = static_cast<std::uint16_t>(other);
      for (std::size_t m = 0; m < msw_.size(); ++m) {
        msw_[m] = msp_[m] = 0.0;
        msrho_[m].setZero();
      }
    }
  }

 private:
  ParticleStore<D>& s_;
  const std::vector<FluidConstants>& fluids_;
  Column<Vec<D>>& vext_;
  Column<std::uint16_t>& wall_fluid_;
  Column<double>* p2_ = nullptr;
  Column<std::uint16_t>* fluid2_ = nullptr;
  int first_fluid_ = -1;
  // Per-material sums of one wall particle (reset after use).
  std::vector<double> msw_, msp_;
  std::vector<Vec<D>> msrho_;
};

}  // namespace sph
