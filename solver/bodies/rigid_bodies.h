#pragma once
// The rigid-body unit: bodies as clusters of particles (Fuchs 2021), their mass properties,
// the reduction of particle forces to body forces and torques, and the motion of bodies and of
// their particles.
//
// Time integration (Fuchs 2021 eqs. 31-40) as a two-level r-RESPA splitting (Tuckerman,
// Berne, Martyna 1992): the slow forces (fluid coupling and body force) kick the bodies by
// dt/2 at the start and end of each fluid step, and the drift over dt is split into substeps
// short enough for the stiff contact springs (0.22 sqrt(m_r/k_c), eq. 41), each a
// kick-drift-kick with the contact force alone. Without contact the drift is a single step
// and the scheme is exactly Fuchs' kick-drift-kick. Only the bodies pay for the contact time
// step; the fluid keeps its own. The fluid force is held at its value from the start of the
// step during the substeps, which is the splitting error r-RESPA accepts (second order,
// symplectic for conservative forces).
#include <map>
#include <vector>

#include "solver/bodies/rigid_body.h"
#include "solver/core/checkpoint_state.h"
#include "solver/core/neighbor_list.h"
#include "solver/core/particle_store.h"
#include "solver/parallel/exact_sum.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class RigidBodies {
 public:
  static constexpr const char* kName = "rigid_bodies";
  static constexpr int A = D == 2 ? 1 : 3;  // angular components

  RigidBodies(ParticleStore<D>& s, const v1::Case& c, const std::vector<double>& solid_density,
              const std::vector<double>& fluid_density_of_body);

  std::vector<RigidBody<D>>& bodies() { return bodies_; }
  const std::vector<RigidBody<D>>& bodies() const { return bodies_; }
  // The case's bodies hold the first slots; later ones were made by phase transitions.
  std::size_t case_bodies() const { return case_bodies_; }
  // The serial number for the next body a phase transition makes (RigidBody::serial).
  std::int64_t next_serial() { return bodies_made_++; }
  Column<std::int32_t>& body_index() { return body_; }
  const Column<std::int32_t>& body_index() const { return body_; }
  Column<Vec<D>>& offset() { return offset_; }
  Column<Vec<D>>& particle_acceleration() { return accel_; }
  Column<Vec<D>>& fluid_force() { return fluid_force_; }
  // sum_i of the viscous factor times r_ir over each rigid particle's fluid neighbours, written
  // with fluid_force (solver/physics/fluid_forces.h): the lever of the spin damping.
  Column<Vec<D>>& spin_lever() { return spin_lever_; }

  // Mass, centre of mass and inertia from the particles (eqs. 20-23 with Remark 13); sets the
  // body-frame offsets of the owned rigid particles. Collective.
  void initialize(const Comm& comm, double dx, const std::vector<Vec<D>>& initial_velocity,
                  const std::vector<AngVec<D>>& initial_omega);

  // Body force per unit mass on body k at time t (gravity ramped like the fluid's).
  void set_gravity(const Vec<D>& g, double damping_time) {
    g_ = g;
    t_damp_ = damping_time;
  }

  // Slow kick (fluid force + body force) of the free bodies by h; the fluid torque's spin
  // damping is taken at the end of the kick (backward Euler).
  void kick(double h, double t);
  // Drift by dt (no contact) and move prescribed bodies to time t + dt.
  void drift(double dt, double t_end);
  // Positions, velocities (eq. 36/40) and accelerations of the owned rigid particles from the
  // body states.
  void place_owned_particles();
  // Velocities of the owned rigid particles from the body states (eq. 40).
  void update_owned_velocities();
  // Sums the per-particle fluid forces (eq. 19) of the owned rigid particles into body forces
  // and torques (eqs. 24-26), and their spin levers into each body's spin damping. Collective;
  // identical on every rank for any decomposition.
  void reduce_fluid_forces(const Comm& comm);
  // Accelerations for the wall condition of the next step (a = F/m + b, alpha = I^-1 (M - w x L)).
  void update_accelerations(double t);

  double total_mass() const;

  // Own moment of inertia per unit mass of a rigid particle (Fuchs 2021 Remark 13): a disk of
  // radius dx/sqrt(pi) in 2D, a sphere of radius (3/(4 pi))^(1/3) dx in 3D.
  static double self_inertia_per_mass(double dx);

  // Checkpoint state (everything the integrator needs besides the particle columns).
  void save(CheckpointState& state) const;
  void load(const CheckpointState& state);

 private:
  friend class RigidBodiesTest;
  Vec<D> body_force(const RigidBody<D>& b, double t) const;
  // Orientation and angular velocity of a body with prescribed rotation at time t.
  static void set_prescribed_rotation(RigidBody<D>& b, double t);

  ParticleStore<D>& s_;
  std::vector<RigidBody<D>> bodies_;
  std::size_t case_bodies_ = 0;
  std::int64_t bodies_made_ = 0;
  Column<std::int32_t>& body_;
  Column<Vec<D>>& offset_;       // position relative to the centre of mass, body frame
  Column<Vec<D>>& accel_;        // particle acceleration (wall condition, Adami eq. 27)
  Column<Vec<D>>& fluid_force_;  // force from the fluid on each rigid particle (eq. 19)
  Column<Vec<D>>& spin_lever_;   // see spin_lever()
  Vec<D> g_ = Vec<D>::Zero();
  double t_damp_ = 0;
};

}  // namespace sph
