#pragma once
// Walls that grow into the fluid (Reder et al. 2021 sec. 3.7: boundary structures growing at a
// prescribed front velocity, overgrowing the particles that get stuck on them).
//
// Front. A growing wall w advances by s_w(t) = int_0^t v_w(t') dt' (Wall.growth_speed, its
// exact integral) along the normal of its initial shape: a fluid particle whose distance to
// that shape is below s_w(t) becomes a dummy particle of w (Adami 2012) where it stands. The
// lattice puts the k-th fluid layer at (k - 1/2) dx from the wall's surface, so it converts
// when s_w = (k - 1/2) dx, and the grown thickness, dx per layer converted, is s_w rounded
// to the nearest dx: the mean front advances at v_w, without bias (docs/growing_walls.md).
// Distances are the shape's signed distance (case/geometry.h: exact for primitives and
// unions), across periodic boundaries the nearest image's.
//
// Conversion. The particle keeps its id, mass (every particle's mass is unchanged, so fluid
// mass plus grown mass stays the initial mass up to the rounding of the sums), position and
// scalars; its velocity becomes the wall's (zero) and its acceleration zero, so its momentum
// goes into the wall as a wall force's would. The wall condition gives it pressure and
// density from this step on (Adami 2012 eqs. 27-28).
//
// Engulfing. A rigid body is engulfed when the front reaches one of its particles (the same
// distance test): every particle of the body becomes a particle of that wall (the first
// growing wall, in case order, that reached it), and the body, emptied, leaves the body
// table (BodyRegrouping with whole bodies; an empty body is inactive). Its momentum goes into
// the wall with it.
//
// It runs after the drift (r^{n+1}, before the ghosts are built): every decision reads only
// the owned particle's own position, the counts are summed over the ranks and the masses by
// exact sums, so results do not depend on the rank count. The grown distances are functions
// of t alone; the running totals go into the checkpoint.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "case/geometry.h"
#include "case/materials.h"
#include "case/time_function.h"
#include "solver/bodies/body_regrouping.h"
#include "solver/bodies/rigid_bodies.h"
#include "solver/core/checkpoint_state.h"
#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class WallGrowth {
 public:
  static constexpr const char* kName = "wall_growth";

  // The walls of `c` with a growth_speed. `periodic` and `length`: the domain's periodic axes
  // and their lengths (distances are those of the nearest periodic image).
  WallGrowth(const v1::Case& c, const std::vector<MaterialParams>& materials, double dx,
             const std::array<bool, D>& periodic, const Vec<D>& length);

  // Columns the conversion sets besides the core ones (null where the case lacks them).
  struct Columns {
    Column<std::uint16_t>* wall_index = nullptr;
    Column<std::uint8_t>* free_slip = nullptr;
    Column<Vec<D>>* transport = nullptr;   // transport velocity: a wall's is its velocity
    Column<Vec<D>>* background = nullptr;  // background acceleration of the TVF
    Column<Vec<D>>* wall_accel = nullptr;  // "wall_acceleration" (eq. 27 of Adami 2012)
    const Column<std::uint8_t>* open_zone = nullptr;  // buffer particles do not convert
  };
  struct Outcome {
    std::int64_t grown = 0;     // fluid particles converted, all ranks
    std::int64_t engulfed = 0;  // bodies engulfed, all ranks
    std::string error;          // non-empty: the run cannot go on
  };
  // Collective. At time t (after the drift). `bodies` may be null.
  Outcome run(ParticleStore<D>& s, const Columns& cols, RigidBodies<D>* bodies, double t,
              const Comm& comm);

  std::size_t size() const { return walls_.size(); }
  const std::string& name(std::size_t k) const { return walls_[k].name; }
  // s_k(t): how far wall k's front has advanced from its initial surface.
  double front(std::size_t k, double t) const { return walls_[k].speed.integral(t); }
  // Particles and mass each wall has taken from the fluid and from engulfed bodies since
  // t = 0 (all ranks), and the bodies engulfed.
  std::int64_t grown_particles(std::size_t k) const { return walls_[k].particles; }
  double grown_mass(std::size_t k) const { return walls_[k].mass; }
  std::int64_t engulfed_bodies() const { return engulfed_; }
  // The front must not pass more than a fraction of a layer per step (never binding where
  // the speed is well below the speed of sound).
  double max_time_step() const { return max_dt_; }

  void save(CheckpointState& state) const;
  void load(const CheckpointState& state);

 private:
  struct Growing {
    std::uint16_t wall = 0;
    std::uint16_t material = kNoMaterial;
    bool free_slip = false;
    std::string name;
    TimeFunction speed;
    std::unique_ptr<Shape> shape;
    Aabb bounds;
    std::int64_t particles = 0;
    double mass = 0;
  };
  // Distance from x to wall k's initial shape (nearest periodic image).
  double distance(std::size_t k, const Vec<D>& x, double reach) const;

  std::vector<Growing> walls_;
  std::vector<Vec<D>> images_;  // periodic shifts tried, the zero shift first
  std::int64_t engulfed_ = 0;
  double max_dt_;
  double dx_;
};

}  // namespace sph
