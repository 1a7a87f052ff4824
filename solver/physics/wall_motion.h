#pragma once
// Prescribed motion of wall particles: position, velocity and acceleration at time t from
// each wall's MotionPath (exact integrals of the prescribed velocity). The acceleration
// feeds the wall pressure condition (Adami 2012 eq. 27). A unit on the seam: it moves the
// walls to t^{n+1} in StepPhase::kAfterDrift, before the ghosts are sent.
#include <vector>

#include "case/motion.h"
#include "solver/core/particle_store.h"
#include "solver/seam/unit.h"

namespace sph {

template <int D>
class WallMotion final : public Unit<D> {
 public:
  static constexpr const char* kName = "wall_motion";
  // paths[k]: motion of the particles whose wall index is k; `advect`: the transport velocity
  // column, if any, which walls also carry (they are advected with their own velocity).
  WallMotion(ParticleStore<D>& s, std::vector<MotionPath> paths,
             const Column<std::uint16_t>& wall_index, Column<Vec<D>>* advect = nullptr)
      : s_(s),
        paths_(std::move(paths)),
        x0_(s.template add<Vec<D>>("reference_position", kName, true)),
        wall_(wall_index),
        accel_(s.template add<Vec<D>>("wall_acceleration", kName, true)),
        advect_(advect) {
    x0_.set_ghost(false);
    // Persistent: set when the walls move, before particles migrate, and read by the wall
    // condition after; ghosts do not need it.
    accel_.set_ghost(false);
  }

  // Whether any wall of `paths` moves (a case without moving walls builds no unit).
  static bool any_moves(const std::vector<MotionPath>& paths) {
    for (const MotionPath& p : paths)
      if (!p.is_static()) return true;
    return false;
  }
  Column<Vec<D>>& reference_position() { return x0_; }
  const Column<Vec<D>>& acceleration() const { return accel_; }

  const char* name() const override { return kName; }
  PhaseMask phases() const override { return phase_bit(StepPhase::kAfterDrift); }
  void run(StepPhase /*phase*/, StepContext<D>& ctx) override { run(ctx.t, advect_); }
  void initialize(std::size_t i, const SceneParticle& /*p*/) override { x0_[i] = s_.x[i]; }
  std::size_t scratch_bytes() const override {
    return poses_.capacity() * sizeof(MotionPath::Pose);
  }

  // Moves the owned wall particles to time t. `advect` (the transport velocity column, if
  // any) gets the wall velocity too: walls are advected with their own velocity.
  void run(double t, Column<Vec<D>>* advect) {
    // One pose per wall and step: evaluating the motion per particle cost as much as the
    // fluid forces in a shaken tank with a third as many wall particles as fluid ones.
    poses_.resize(paths_.size());
    for (std::size_t k = 0; k < paths_.size(); ++k)
      if (!paths_[k].is_static()) poses_[k] = paths_[k].pose(t);
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      if (s_.kind[i] != Kind::kWall) continue;
      if (paths_[wall_[i]].is_static()) {
        accel_[i] = Vec<D>::Zero();
        continue;
      }
      const MotionPath::Pose& pose = poses_[wall_[i]];
      const Point3 x0 = lift(x0_[i]);
      s_.x[i] = drop(pose.position(x0));
      s_.v[i] = drop(pose.velocity(x0));
      accel_[i] = drop(pose.acceleration(x0));
      if (advect) (*advect)[i] = s_.v[i];
    }
  }

 private:
  static Point3 lift(const Vec<D>& v) {
    Point3 p = Point3::Zero();
    for (int a = 0; a < D; ++a) p[a] = v[a];
    return p;
  }
  static Vec<D> drop(const Point3& p) {
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = p[a];
    return v;
  }
  ParticleStore<D>& s_;
  std::vector<MotionPath> paths_;
  std::vector<MotionPath::Pose> poses_;  // of paths_ at the time of the last run
  Column<Vec<D>>& x0_;
  const Column<std::uint16_t>& wall_;
  Column<Vec<D>>& accel_;
  Column<Vec<D>>* advect_;
};

}  // namespace sph
