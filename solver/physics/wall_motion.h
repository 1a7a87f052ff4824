#pragma once
// Prescribed motion of wall particles: position, velocity and acceleration at time t from
// each wall's MotionPath (exact integrals of the prescribed velocity). The acceleration
// feeds the wall pressure condition (Adami 2012 eq. 27).
#include <vector>

#include "case/motion.h"
#include "solver/core/particle_store.h"

namespace sph {

template <int D>
class WallMotion {
 public:
  static constexpr const char* kName = "wall_motion";
  // paths[k]: motion of the particles whose wall index is k.
  WallMotion(ParticleStore<D>& s, std::vector<MotionPath> paths, Column<std::uint16_t>& wall_index)
      : s_(s),
        paths_(std::move(paths)),
        x0_(s.template add<Vec<D>>("reference_position", kName, true)),
        wall_(wall_index),
        accel_(s.template add<Vec<D>>("wall_acceleration", kName, true)) {
    x0_.set_ghost(false);
    // Persistent: set when the walls move, before particles migrate, and read by the wall
    // condition after; ghosts do not need it.
    accel_.set_ghost(false);
  }

  Column<Vec<D>>& reference_position() { return x0_; }
  const Column<Vec<D>>& acceleration() const { return accel_; }

  // Moves the owned wall particles to time t. `advect` (the transport velocity column, if
  // any) gets the wall velocity too: walls are advected with their own velocity.
  void run(double t, Column<Vec<D>>* advect) {
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      if (s_.kind[i] != Kind::kWall) continue;
      const MotionPath& path = paths_[wall_[i]];
      if (path.is_static()) {
        accel_[i] = Vec<D>::Zero();
        continue;
      }
      const Point3 x0 = lift(x0_[i]);
      s_.x[i] = drop(path.position(x0, t));
      s_.v[i] = drop(path.velocity(x0, t));
      accel_[i] = drop(path.acceleration(x0, t));
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
  Column<Vec<D>>& x0_;
  Column<std::uint16_t>& wall_;
  Column<Vec<D>>& accel_;
};

}  // namespace sph
