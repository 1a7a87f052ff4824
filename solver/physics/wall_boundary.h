#pragma once
// The generalized wall boundary condition of Adami, Hu, Adams (2012), applied to dummy wall
// particles (and, later, to rigid-body particles, Fuchs 2021 "Boundary and coupling
// conditions"). For each wall particle w with fluid neighbours f:
//   p_w = (sum_f p_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf) / sum_f W_wf     (eq. 27)
//   rho_w from p_w through the EOS of the neighbouring fluid                      (eq. 28)
//   v_w' = 2 v_w - sum_f v_f W_wf / sum_f W_wf   for the viscous (no-slip) term  (eqs. 22-23)
// g is the body force acting on the fluid and a_w the wall's own acceleration, which the
// free-fall experiment (sec. 7.1) shows must not be left out.
// With several fluids around one wall particle, rho_w is stored for the fluid of largest
// kernel weight; FluidForces converts it for a pair with another fluid (eq. 28 "from the
// interacting fluid particle b").
#include <algorithm>
#include <array>
#include <vector>

#include "solver/core/neighbor_list.h"
#include "solver/physics/fluid_table.h"

namespace sph {

template <int D, class K>
class WallBoundary {
 public:
  static constexpr const char* kName = "wall_boundary";
  WallBoundary(ParticleStore<D>& s, const K& kernel, const std::vector<FluidConstants>& fluids)
      : s_(s),
        k_(kernel),
        fluids_(fluids),
        vext_(s.template add<Vec<D>>("wall_noslip_velocity", kName, false)),
        wall_fluid_(s.template add<std::uint16_t>("wall_fluid_material", kName, false)) {
    for (std::size_t m = 0; m < fluids.size(); ++m)
      if (fluids[m].fluid && first_fluid_ < 0) first_fluid_ = static_cast<int>(m);
  }

  Column<Vec<D>>& noslip_velocity() { return vext_; }
  Column<std::uint16_t>& fluid_material() { return wall_fluid_; }

  // body: acceleration acting on the fluid; wall_accel: per-particle wall acceleration or
  // nullptr for walls at rest.
  void run(const NeighborList<D>& nl, const Vec<D>& body, const Column<Vec<D>>* wall_accel) {
    const std::size_t nmat = fluids_.size();
    std::vector<double> weight(nmat, 0.0);
    for (std::size_t w = 0; w < s_.owned(); ++w) {
      if (s_.kind[w] == Kind::kFluid) continue;
      double sw = 0, sp = 0;
      Vec<D> srho = Vec<D>::Zero(), sv = Vec<D>::Zero();
      int mat = -1;
      bool mixed = false;
      const Vec<D> xw = s_.x[w];
      for (const std::uint32_t* fp = nl.begin(w); fp != nl.fluid_end(w); ++fp) {
        const std::uint32_t f = *fp;
        const Vec<D> rwf = xw - s_.x[f];
        const double W = k_.W(rwf.norm());
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
        vext_[w] = s_.v[w];
        continue;
      }
      if (mixed) {
        std::fill(weight.begin(), weight.end(), 0.0);
        for (const std::uint32_t* fp = nl.begin(w); fp != nl.fluid_end(w); ++fp)
          weight[s_.material[*fp]] += k_.W((xw - s_.x[*fp]).norm());
        mat = static_cast<int>(std::max_element(weight.begin(), weight.end()) - weight.begin());
      }
      Vec<D> acc = body;
      if (wall_accel) acc -= (*wall_accel)[w];
      const double pw = (sp + acc.dot(srho)) / sw;
      s_.p[w] = pw;
      s_.rho[w] = fluids_[static_cast<std::size_t>(mat)].density(pw);
      wall_fluid_[w] = static_cast<std::uint16_t>(mat);
      vext_[w] = 2.0 * s_.v[w] - sv / sw;
    }
  }

 private:
  ParticleStore<D>& s_;
  const K& k_;
  const std::vector<FluidConstants>& fluids_;
  Column<Vec<D>>& vext_;
  Column<std::uint16_t>& wall_fluid_;
  int first_fluid_ = -1;
};

}  // namespace sph
