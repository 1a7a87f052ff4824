#pragma once
// Diffusion of the pore fluid's saturation through porous elastic bodies (Material.porous;
// thesis sec. 2.3 and eqs. 3.16-3.17, P-III sec. 3.2, digest sec. 5.2; docs/porous_media.md), a
// unit on the seam. The thesis discretises Fick's law in two passes with the kernel-corrected
// gradient of total Lagrangian SPH, the flux first and then its divergence; here in the
// reference configuration, with the operators of the elastic solid (total_lagrangian.h):
//
//   grad c_a = B_a^T sum_b V0_b (c_b - c_a) grad0 W_ab                (as F_a, eq. 3.10)
//   f_a      = B_a^T D_a grad c_a                                     (the flux, eq. 3.17)
//   dc_a/dt  = sum_b V0_b (f_a + f_b) . grad0 W_ab                    (as eqs. 3.8-3.9; eq. 3.16)
//              + 2 kMismatch D_ab sum_b V0_b e_ab (-1/r dW/dr)
//   e_ab     = (c_b - c_a) - (grad c_a + grad c_b)/2 . (X_b - X_a)
//
// with D = Material.diffusivity / rho0 [m^2/s] (the case's diffusivity is rho D) and D_ab the
// harmonic mean of the pair's. The corrected gradient is exact for any linear field, and the
// divergence of a body's flux sums to zero (antisymmetric pairs), so a body's free surfaces are
// closed to the fluid (the thesis' "no outflow") and its fluid is conserved to round-off, the
// way its surfaces are traction-free in the momentum equation. The Cleary-Monaghan Laplacian the
// fluids use (solver/physics/scalar_diffusion.h) has neither: near a free surface its kernel
// sum misses the particles beyond it, and a strip four particles thick diffused 27% too slowly
// along its length (docs/porous_media.md). The two-pass form alone leaves the checkerboard of c
// undamped (its corrected gradient is zero), as total Lagrangian elasticity leaves its
// hourglass mode; the last term damps it, a diffusion of the mismatch e_ab, which is zero for
// any quadratic field (the trapezoid rule) and so leaves the scheme's accuracy alone
// (Ganzenmueller 2015's hourglass control, for a scalar).
//
// Explicit: the rates from c^n, the update c^{n+1} = c^n + dt rate, in the phase where the
// case's other diffusion runs (solver/physics/scalar_transport.h: kWallState, or kAfterDrift
// under quasi-static loading, before the relaxation). Porous particles are left out of that
// unit's pairs. Bound: dt <= cfl_factor 0.1 h^2 / D (Fuchs 2021 eq. 41 for a diffusivity).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "solver/elastic/total_lagrangian.h"
#include "solver/seam/unit.h"

namespace sph {

template <int D, class K>
class PorousDiffusion final : public Unit<D> {
 public:
  static constexpr const char* kName = "porous_diffusion";
  // The weight of the mismatch diffusion, relative to the diffusivity.
  static constexpr double kMismatch = 1.0;

  // `values`: the concentration column of the diffusion unit; built after the elastic solid,
  // whose reference positions and bodies it reads.
  PorousDiffusion(const v1::Case& c, const std::vector<MaterialParams>& materials,
                  ParticleStore<D>& s, double h, double cfl_factor, Column<double>& values)
      : values_(values),
        X_(s.template get<Vec<D>>("elastic_reference_position")),
        body_(s.template get<std::uint16_t>("elastic_body")),
        grad_(s.template add<Vec<D>>("porous_gradient", kName, false)),
        flux_(s.template add<Vec<D>>("porous_flux", kName, false)),
        kernel_(h),
        update_after_drift_(c.time().has_quasi_static()) {
    for (const MaterialParams& m : materials) {
      const bool porous = m.porous && m.rho0 > 0;
      const double d = porous ? m.diffusivity / m.rho0 : 0.0;
      diffusivity_.push_back(d);
      porous_.push_back(porous ? 1 : 0);
      inv_rho0_.push_back(m.rho0 > 0 ? 1.0 / m.rho0 : 0.0);
      if (d > 0) max_dt_ = std::min(max_dt_, cfl_factor * 0.1 * h * h / d);
    }
  }

  // Whether the case has a porous material (with `diffusion { }`, which validation requires).
  static bool wanted(const std::vector<MaterialParams>& materials) {
    return std::any_of(materials.begin(), materials.end(),
                       [](const MaterialParams& m) { return m.porous; });
  }

  const char* name() const override { return kName; }
  PhaseMask phases() const override {
    return phase_bit(update_after_drift_ ? StepPhase::kAfterDrift : StepPhase::kWallState);
  }
  double max_time_step() const override { return max_dt_; }
  std::size_t scratch_bytes() const override {
    return refs_.bytes() + rate_.capacity() * sizeof(double);
  }

  void run(StepPhase /*phase*/, StepContext<D>& ctx) override {
    if (ctx.dt <= 0) return;  // priming
    ParticleStore<D>& s = ctx.particles;
    if (!refs_.current(ctx.neighbors))
      refs_.build(s, ctx.neighbors, X_.data(), body_.data(), inv_rho0_.data(), kernel_);
    const std::size_t n = s.owned();
    const Vec<D>* X = X_.data();
    const double* c = values_.data();
    // Pass 1: the corrected gradient and the flux of every owned porous particle.
    for (std::size_t a = 0; a < n; ++a) {
      grad_[a] = flux_[a] = Vec<D>::Zero();
      if (!porous(s, a)) continue;
      Mat<D> M = Mat<D>::Zero();
      Vec<D> sum = Vec<D>::Zero();
      for (const auto* p = refs_.begin(a); p != refs_.end(a); ++p) {
        M.noalias() += (X[p->j] - X[a]) * p->g.transpose();
        sum += (c[p->j] - c[a]) * p->g;
      }
      // A singular M (a torn body) stops the run in the elastic solid's guard; no flux here.
      if (!(moment_conditioning<D>(M) > 0)) continue;
      const Mat<D> Bt = M.inverse().transpose();
      grad_[a] = Bt * sum;
      flux_[a] = Bt * (diffusivity_[s.material[a]] * grad_[a]);
    }
    ctx.halo.update(s, {&grad_, &flux_});
    // Pass 2: the divergence of the flux and the mismatch diffusion, then the update.
    rate_.assign(n, 0.0);
    for (std::size_t a = 0; a < n; ++a) {
      if (!porous(s, a)) continue;
      const double Da = diffusivity_[s.material[a]];
      double rate = 0;
      for (const auto* p = refs_.begin(a); p != refs_.end(a); ++p) {
        const std::uint32_t b = p->j;
        const Vec<D> Xba = X[b] - X[a];
        rate += (flux_[a] + flux_[b]).dot(p->g);
        const double Db = diffusivity_[s.material[b]];
        if (Da + Db <= 0) continue;
        const double mismatch = (c[b] - c[a]) - 0.5 * (grad_[a] + grad_[b]).dot(Xba);
        // V0_b (-1/r dW/dr) = g . X_ba / |X_ba|^2 (g = V0_b grad0 W_ab, eq. 3.6).
        rate += 2 * kMismatch * (2 * Da * Db / (Da + Db)) * mismatch * p->g.dot(Xba) /
                Xba.squaredNorm();
      }
      rate_[a] = rate;
    }
    for (std::size_t a = 0; a < n; ++a)
      if (rate_[a] != 0.0) values_[a] += ctx.dt * rate_[a];
  }

 private:
  bool porous(const ParticleStore<D>& s, std::size_t a) const {
    return s.kind[a] == Kind::kElastic && porous_[s.material[a]];
  }

  Column<double>& values_;
  Column<Vec<D>>& X_;
  Column<std::uint16_t>& body_;
  Column<Vec<D>>& grad_;  // grad c (scratch, ghosted)
  Column<Vec<D>>& flux_;  // B^T D grad c (scratch, ghosted)
  K kernel_;
  bool update_after_drift_;
  std::vector<double> diffusivity_, inv_rho0_;  // per material: D [m^2/s], 1 / rho0
  std::vector<char> porous_;                    // per material
  double max_dt_ = std::numeric_limits<double>::infinity();
  ReferenceNeighbors<D> refs_;
  std::vector<double> rate_;
};

}  // namespace sph
