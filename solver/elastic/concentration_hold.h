#pragma once
// Parts of elastic bodies held at a concentration for a while (ElasticBody.concentration_holds),
// a unit on the seam: the wetted spot under a droplet of the thesis' porous beam and Nafion film
// (sec. 5.5.3-5.5.4, digest sec. 8.13-8.14), where the pores stay saturated at c~ = c for the
// contact time. A particle belongs to the first hold of its body whose region holds its
// reference position (the body does not carry its wetted spot along as it bends), found once at
// the start and kept in the persistent column "concentration_hold" (0: none, k + 1: hold k).
// While start_time <= t < end_time its concentration is set to the hold's value
//   kAfterDrift  at t^{n+1}, before the ghosts are sent, so the step's diffusion sees it;
//   kWallState   again after the diffusion's update (solver/elastic/porous_diffusion.h for
//                porous bodies, solver/physics/scalar_transport.h for others; both built before
//                this unit, so they run first in a phase), which moved it.
// Under quasi-static loading the diffusion runs at kAfterDrift and this unit right after it,
// before the bodies relax (the elastic solid runs after it).
// Outside the window the particles diffuse like the rest of the body; the species mass series
// then grows by what the holds put in.
#include <cstdint>
#include <memory>
#include <vector>

#include "case/estimate.h"
#include "case/geometry.h"
#include "solver/seam/unit.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class ConcentrationHolds final : public Unit<D> {
 public:
  static constexpr const char* kName = "concentration_holds";

  // `values`: the concentration column of the diffusion unit.
  ConcentrationHolds(const v1::Case& c, ParticleStore<D>& s, Column<double>& values)
      : values_(values), hold_(s.template add<std::uint16_t>("concentration_hold", kName, true)) {
    hold_.set_ghost(false);
    const double shell = default_shell_thickness(c);
    for (const auto& e : c.elastic_bodies()) {
      first_.push_back(holds_.size());
      for (const auto& h : e.concentration_holds())
        holds_.push_back({compile_shape(h.region(), D, shell), h.value(), h.start_time(),
                          h.end_time() > 0 ? h.end_time() : kForever});
    }
    first_.push_back(holds_.size());
  }

  static bool wanted(const v1::Case& c) {
    for (const auto& e : c.elastic_bodies())
      if (e.concentration_holds_size() > 0) return true;
    return false;
  }

  const char* name() const override { return kName; }
  PhaseMask phases() const override {
    return sph::phases(StepPhase::kAfterDrift, StepPhase::kWallState);
  }
  void run(StepPhase /*phase*/, StepContext<D>& ctx) override { apply(ctx.particles, ctx.t); }

  // After the diffusion unit's initialize, which gave the particle its initial value.
  void initialize(std::size_t i, const SceneParticle& p) override {
    hold_[i] = 0;
    if (p.kind != Kind::kElastic) return;
    const auto body = static_cast<std::size_t>(p.elastic);
    for (std::size_t k = first_[body]; k < first_[body + 1]; ++k)
      if (holds_[k].region->contains(p.x)) {
        hold_[i] = static_cast<std::uint16_t>(k + 1);
        if (holds_[k].active(0.0)) values_[i] = holds_[k].value;
        return;
      }
  }

 private:
  static constexpr double kForever = 1e300;
  struct Hold {
    std::unique_ptr<Shape> region;
    double value, start, end;
    bool active(double t) const { return start <= t && t < end; }
  };

  void apply(const ParticleStore<D>& s, double t) {
    for (std::size_t i = 0; i < s.owned(); ++i) {
      if (hold_[i] == 0) continue;
      const Hold& h = holds_[hold_[i] - 1u];
      if (h.active(t)) values_[i] = h.value;
    }
  }

  Column<double>& values_;
  Column<std::uint16_t>& hold_;
  std::vector<Hold> holds_;
  std::vector<std::size_t> first_;  // per body, its first hold; one past the last at the end
};

}  // namespace sph
