#pragma once
// Elastic bodies by total Lagrangian SPH (X. Tang's thesis sec. 3, digest sec. 3; P-I sec. 3),
// a unit on the seam (solver/seam/unit.h). Each step, at the positions of the search:
//
//   kForces      reference neighbours of every owned elastic particle (the same body within r_c
//                in the reference configuration, found in the neighbour list; see
//                solver/elastic/total_lagrangian.h for why), the correction matrix B (eq. 3.7),
//                F (eq. 3.10) and dF/dt (P-I eq. 35), the first Piola-Kirchhoff stress P of the
//                body's material (solver/elastic/elastic_law.h, Kelvin-Voigt damping included),
//                P B to the ghosts, then
//                  a_a += (1/m_a) sum_b V0_a V0_b (P_a B_a + P_b B_b) grad0 W_ab   (eqs. 3.8-3.9)
//                         + f_a^fluid / m_a + g
//                with f^fluid the fluid's pressure and viscous force on the particle, which the
//                fluid-solid coupling (thesis sec. 2.5) writes into the column
//                "elastic_fluid_force" before the units of this phase run (the thesis adds the
//                coupling terms of eqs. 3.12-3.13 as they are, but they are forces: divided by
//                m_a here, erratum 3 of the digest), and g gravity (ramped as the fluid's,
//                Adami 2012 eq. 13) unless the body ignores it. The fluid's constant body force
//                does not act on solids; a body's own force field (ElasticBody.body_force_field,
//                solver/elastic/manufactured_torsion.h) does, at every step and sub-step.
//   kConstraints particles of a constraint get a = 0: clamped ones stay where they were put at
//                rest, prescribed ones move as kAfterDrift sets them.
//   kAfterDrift  particles of a constraint with a motion are put at x(t), v(t) of the motion
//                (case/motion.h, as walls are moved: solver/physics/wall_motion.h); clamped ones
//                at their reference position with v = 0.
//
// The kick-drift-kick integrator (solver/integrate/kick_drift_kick.h) advances owned elastic
// particles like fluid ones, which is the thesis' position-based Verlet (P-I eqs. 36-38) in
// kick-drift-kick form; F is not integrated but recomputed from the positions every step
// (eq. 3.10), so it needs no state of its own.
//
// Sub-steps (TimeControl.subcycle_elastic_bodies; thesis sec. 6.1, P-I eqs. 33-38): the fluid's
// kicks and drift leave elastic particles alone, and the unit advances them itself, on their
// own velocity (column "elastic_velocity"), as an impulse multiple-time-step method (r-RESPA,
// Tuckerman, Berne & Martyna 1992): the fluid's force is the slow force, kicked at the ends of
// the fluid's step, the internal forces and gravity the fast ones, sub-stepped in between:
//   kAfterDrift  v += dt/2 f^n / m (the fluid's force of t^n, held in
//                "elastic_held_fluid_force"), then kappa = ceil(dt / dt_s) kick-drift-kick
//                sub-steps of dt / kappa from t^n to t^{n+1} (P-I eqs. 36-38), each with the
//                internal forces at its positions (ghosts refreshed); the fluid is then shown
//                that velocity and its change over the step as the particle's v and a;
//   kForces      v += dt/2 f^{n+1} / m with the fluid's force at t^{n+1}, which is held.
// dt_s is eq. 33 at the end of the previous sub-steps, the same on every rank. The thesis holds
// the fluid's force over the sub-steps and shows the fluid the solid's velocity averaged over
// its step (P-I eq. 34); both went unstable for a stiff plate under water
// (docs/elastic_solids.md).
//
// Quasi-static loading (TimeControl.quasi_static; thesis sec. 3.6, P-III sec. 4, digest sec.
// 6.2; docs/quasi_static.md): the run's step is the outer (load) step; the bodies take the
// sub-step path with no fluid force, and kAfterDrift relaxes them instead of sub-stepping:
// inner kick-drift-kick steps of eq. 33 in which the constraints and gravity first move on to
// the step's end over a short ramp (the load increment), with the relaxation damping
// (solver/elastic/relaxation_damping.h) after each drift and kinetic damping (every velocity
// to zero at a peak of the kinetic energy) after the ramp, until such a peak is below the
// threshold, or the inner steps fill the outer step (the thesis' loop: time advances either
// way). The series
// "elastic/relaxation_steps" and "elastic/unrelaxed_load_steps" count the inner steps and the outer
// steps that ended unrelaxed.
//
// Time step (thesis eq. 33, P-I sec. 3.4):
//   dt <= cfl_factor 0.6 min(sqrt(h / |a|max), h / (|v|max + c_s)),
// with c_s = sqrt(K / rho0) the largest of the bodies' materials and the maxima over the free
// elastic particles (speeds of the constrained ones too) of all ranks: a maximum is exact, so
// the bound is the same on any rank count; with Kelvin-Voigt damping also
//   dt <= cfl_factor 0.125 h^2 rho0 / eta_d (an explicit viscous bound),
// and with hourglass control (solver/elastic/hourglass_control.h, Material.hourglass_control)
//   dt <= cfl_factor 0.6 / omega_hg, omega_hg the frequency it gives the checkerboard mode.
//
// Output: snapshot fields "elastic_displacement_x/_y/_z" (x - X), "von_mises_stress" (of the
// Cauchy stress; plane strain in 2D) and "elastic_strain" (equivalent strain of the
// Green-Lagrange strain), zero on other particles; series "elastic/<body>/displacement" (the
// displacement of the particle nearest each ElasticBody.observation_points entry in the
// reference configuration, ties to the smallest id), "elastic/<body>/kinetic_energy" and
// "elastic/<body>/strain_energy" (sum of V0 Psi(F)), summed exactly (solver/parallel/exact_sum.h)
// so that they are bitwise the same on any rank count.
//
// J2 plasticity (Material.plasticity; solver/elastic/j2_plasticity.h, thesis sec. 5): a body of a
// plastic material gets its Kirchhoff stress tau from the return mapping at the F of the step
// (plane strain in 2D), P = tau F^-T (+ F S_damping), and keeps per particle the persistent
// columns "plastic_metric" ((Cbar^p)^-1) and "equivalent_plastic_strain" (alpha, also a snapshot
// field). The return mapping advances that state once per evaluation of the stresses: once per
// step (kForces), or once per sub-step; a resumed run does not evaluate the forces of the
// checkpointed step again, so the state is advanced exactly as in an uninterrupted run. The
// strain energy series is then the elastic part (eqs. 33-34); the plastic work is not in it.
//
// Constraint forces: with constraints, series "elastic/<body>/constraint_force" (one row of D
// values per constraint, in the order of ElasticBody.constraints) holds the force that the
// constraint exerts on the body's particles it holds, -(internal + fluid + gravity forces on
// them), summed exactly: the reaction force of a prescribed-motion test.
//
// Anisotropic bodies (ElasticBody.anisotropy, ASPH: thesis sec. 3.5, P-II; docs/asph.md): each
// particle of the run keeps its kernel map G (column "elastic_kernel_map", ghosted; I / h for
// isotropic bodies, a plate's map of smoothing lengths ratio h along its surface and h through
// its thickness for anisotropic ones), the reference pairs are those in either particle's
// elliptical support with the symmetrised gradient of P-II eqs. 16-17
// (ReferenceNeighbors::build_anisotropic), and the stress enters the momentum sum as P B^T
// (P-II eq. 32; B is not symmetric for an elliptical kernel). The run's search radius covers the
// longest semi-axis (case/anisotropy.h). The time step stays eq. 33 with the run's h, which is
// the smoothing length through the thickness, the smallest: the thickness direction bounds it.
//
// Porous bodies (Material.porous; thesis sec. 2.3, P-III eqs. 2.17 and 2.21, digest sec. 5.2;
// docs/porous_media.md): the pore fluid of saturation c (the case's concentration column,
// solver/physics/scalar_transport.h) presses with p = C (c - c0), and the mixture's Cauchy stress
// sigma_s - p I enters the momentum sum as P = P_s - J p F^-T (the P-II eq. 7 form). The
// saturation is the particle's own, read where P is, so it needs no ghost.
//
// Guard: a particle whose correction matrix is singular (it lost the reference neighbours that
// span the space: a torn body) or whose F is inverted (det F <= 0) stops the run, naming the
// body, the particle and the place.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "case/anisotropy.h"
#include "case/motion.h"
#include "solver/diagnostics/stability_guards.h"
#include "solver/elastic/elastic_law.h"
#include "solver/elastic/hourglass_control.h"
#include "solver/elastic/j2_plasticity.h"
#include "solver/elastic/manufactured_torsion.h"
#include "solver/elastic/relaxation_damping.h"
#include "solver/elastic/total_lagrangian.h"
#include "solver/parallel/exact_sum.h"
#include "solver/physics/body_force.h"
#include "solver/run/unit_set.h"

namespace sph {

template <int D, class K>
class ElasticSolid final : public Unit<D> {
 public:
  static constexpr const char* kName = "elastic_solid";
  // moment_conditioning (total_lagrangian.h) below which a correction matrix counts as
  // singular: above 0.8 at the corners of lattice blocks, 0 with the reference neighbours all on
  // one line (plane in 3D).
  static constexpr double kMinConditioning = 1e-3;
  // Thesis eq. 33.
  static constexpr double kTimeStepFactor = 0.6;
  // Sub-steps in one fluid step above which the run stops (a solid blowing up).
  static constexpr int kMaxSubsteps = 10000;
  // Quasi-static loading: the constraints' pace over a load step's ramp, as a fraction of the
  // bodies' sound speed, about the strain they impose as they go (docs/quasi_static.md).
  static constexpr double kLoadRampSpeed = 1e-4;

  explicit ElasticSolid(const UnitBuildContext<D>& b);

  const char* name() const override { return kName; }
  PhaseMask phases() const override {
    return constrained_ || solid_v_ ? kConstrainedPhases : phase_bit(StepPhase::kForces);
  }
  void run(StepPhase phase, StepContext<D>& ctx) override;
  // Sub-stepped bodies set no bound on the fluid's step.
  double max_time_step() const override {
    return solid_v_ ? std::numeric_limits<double>::infinity() : max_dt_;
  }
  void save(CheckpointState& state) const override;
  void load(const CheckpointState& state) override;
  std::size_t scratch_bytes() const override {
    return refs_.bytes() + poses_.capacity() * sizeof(MotionPath::Pose) +
           slots_.capacity() * sizeof(std::pair<ParticleId, std::size_t>);
  }
  void declare_output(ResultFile& result) override;
  void sample(ResultFile& result, const StepContext<D>& ctx) override;
  void initialize(std::size_t i, const SceneParticle& p) override;
  std::string check(const StepContext<D>& /*ctx*/) const override { return failure_; }

  // The constants of material k (zero moduli for materials of no elastic body).
  const ElasticConstants& constants(std::size_t k) const { return laws_[k]; }

 private:
  static constexpr PhaseMask kConstrainedPhases =
      sph::phases(StepPhase::kAfterDrift, StepPhase::kForces, StepPhase::kConstraints);
  struct Body {
    std::string name;
    bool gravity = true;
    std::size_t first_constraint = 0;               // into paths_
    std::vector<Vec<D>> points;                     // observation points
    std::vector<ParticleId> observed;               // the particle nearest each point
    std::optional<ManufacturedTorsion<D>> torsion;  // ElasticBody.body_force_field
  };

  void forces(StepContext<D>& ctx);
  // F, dF/dt (from v), P, P B and the output fields of every owned elastic particle, and what
  // the internal forces read of them to the ghosts.
  void stresses(StepContext<D>& ctx, const Vec<D>* v);
  // The internal force on owned particle i (eqs. 3.8-3.9 and the hourglass control), after
  // stresses().
  Vec<D> internal_force_on(const ParticleStore<D>& s, std::size_t i) const;
  // Sub-steps: F, P B and the output fields of the owned particles at their positions now (v:
  // the velocities dF/dt reads), P B to the ghosts, then the internal forces.
  void internal_forces(StepContext<D>& ctx, const Vec<D>* v);
  void hold_fluid_force(StepContext<D>& ctx);
  void substeps(StepContext<D>& ctx);
  // Quasi-static loading: one outer step's load increment and relaxation.
  void relax(StepContext<D>& ctx);
  // The bodies' kinetic energy on the solid's velocities (free particles, exact sum).
  double kinetic_energy(const ParticleStore<D>& s, const Comm& comm) const;
  // The farthest any constrained particle moves between t0 and t1 (all ranks).
  double constraint_travel(const ParticleStore<D>& s, const Comm& comm, double t0, double t1) const;
  // Internal force over mass, gravity g and the body's force field at time t.
  Vec<D> substep_acceleration(const ParticleStore<D>& s, std::size_t i, const Vec<D>& g,
                              double t) const;
  void substep_bound(const ParticleStore<D>& s, const Comm& comm, double t);
  // |E| of particle i's Green strain when its law stiffens with strain (Saint Venant-
  // Kirchhoff), else 0: the sound speed of stable_step grows with it.
  double stiffening_strain(const ParticleStore<D>& s, std::size_t i) const;
  // The solid's stable step from the maxima over its particles (reduced over all ranks).
  double stable_step(const Comm& comm, double a_max, double v_max, double strain_max);
  void place_constrained(ParticleStore<D>& s, Column<Vec<D>>& v, double t);
  void hold_constrained(ParticleStore<D>& s);
  // P of owned particle i of a plastic material at F (the return mapping advances its state),
  // and its von Mises stress into the output column.
  Mat<D> plastic_stress(const ElasticConstants& law, std::uint16_t mat, std::size_t i,
                        const Mat<D>& F, const Mat<D>& dFdt);
  void move_constrained(ParticleStore<D>& s, double t) { place_constrained(s, s.v, t); }
  void find_observed(const ParticleStore<D>& s, const Comm& comm);
  void fail(const ParticleStore<D>& s, std::size_t i, const StepContext<D>& ctx, const char* what);

  std::vector<MaterialParams> mats_;
  std::vector<ElasticConstants> laws_;  // per material
  std::vector<J2Constants> j2_;         // per material, plastic_[k] != 0 only
  std::vector<char> plastic_;           // per material: J2 plasticity on
  std::vector<double> inv_rho0_;        // per material
  // Porous materials only: C and c0 per material (C = 0: none), and the saturation column.
  std::vector<double> swelling_modulus_, reference_saturation_;
  const Column<double>* saturation_ = nullptr;
  std::vector<Body> bodies_;
  std::vector<MotionPath> paths_;  // per constraint, bodies in order
  std::vector<MotionPath::Pose> poses_;
  bool constrained_ = false;
  K kernel_;
  double h_ = 0, cfl_ = 1, sound_speed_ = 0;
  Vec<D> gravity_ = Vec<D>::Zero();
  double gravity_ramp_ = 0;
  double max_dt_ = std::numeric_limits<double>::infinity();
  // Kelvin-Voigt damping is a viscous stress with kinematic viscosity eta_d / rho0: the
  // explicit viscous bound 0.125 h^2 / nu (Morris 1997; the fluid's in Fuchs 2021 eq. 41).
  static constexpr double kDampingStepFactor = 0.125;
  double damping_dt_ = std::numeric_limits<double>::infinity();
  HourglassControl<D> hourglass_;  // solver/elastic/hourglass_control.h
  bool observed_found_ = false;
  std::vector<std::pair<ParticleId, std::size_t>> slots_;  // observed id -> series slot
  std::string failure_;
  // |a|max, |v|max and |E|max of Saint Venant-Kirchhoff particles (reduced in place).
  std::vector<double> maxima_ = std::vector<double>(3);

  ReferenceNeighbors<D> refs_;
  // Anisotropic bodies only (null / empty otherwise): each particle's kernel map G (persistent,
  // ghosted), each body's G (Identity / h for an isotropic one), the kernel of unit h.
  Column<Mat<D>>* kernel_map_ = nullptr;
  std::vector<Mat<D>> body_map_;
  AnisotropicKernel<D, K> anisotropic_kernel_;
  // Builds refs_ over the candidates of the last search (isotropic or anisotropic), once per
  // search.
  void build_references(const StepContext<D>& ctx);
  Column<Vec<D>>& X_;                 // reference position (persistent, ghosted)
  Column<std::uint16_t>& body_;       // elastic body (persistent, ghosted)
  Column<std::int32_t>& constraint_;  // constraint of the body holding it, -1 free
  Column<Vec<D>>& fluid_force_;       // the fluid's force on the particle [N] (scratch)
  Column<Mat<D>>& pb_;                // P B (scratch, ghosted by halo.update)
  // Sub-steps only (null otherwise, all persistent): the solid's own velocity (ghosted), the
  // held fluid force, the internal force of the last sub-step, the acceleration shown to the
  // fluid.
  Column<Vec<D>>* solid_v_ = nullptr;
  Column<Vec<D>>* held_force_ = nullptr;
  Column<Vec<D>>* internal_ = nullptr;
  Column<Vec<D>>* shown_a_ = nullptr;
  double substep_dt_ = std::numeric_limits<double>::infinity();  // eq. 33 at the last sub-step
  // Quasi-static loading only (damping 0 and null otherwise): eta, the kinetic energy threshold,
  // the damped velocities (scratch), inner steps so far and outer steps that ended unrelaxed.
  double relax_damping_ = 0, relax_threshold_ = 0;
  Column<Vec<D>>* damped_v_ = nullptr;
  std::int64_t relax_steps_ = 0, unrelaxed_steps_ = 0;
  Column<Mat<D>>& F_;                // deformation gradient of the last step (scratch)
  Column<double>* displacement_[D];  // x - X per axis (scratch, output)
  Column<double>& von_mises_;        // (scratch, output)
  Column<double>& strain_;           // (scratch, output)
  // J2 plasticity only (null otherwise; persistent, not ghosted): (Cbar^p)^-1 and alpha (output).
  Column<PlasticMetric>* metric_ = nullptr;
  Column<double>* alpha_ = nullptr;
  // Constraints without sub-steps only (null otherwise; persistent, not ghosted): the force the
  // constraint exerts on each particle it holds, kept from kForces for sample().
  Column<Vec<D>>* reaction_ = nullptr;
  std::size_t constraints_ = 0;  // over all bodies
};

template <int D>
inline Vec<D> elastic_vec(const v1::Vec3& v) {
  Vec<D> out;
  out[0] = v.x();
  out[1] = v.y();
  if constexpr (D == 3) out[2] = v.z();
  return out;
}

template <int D, class K>
ElasticSolid<D, K>::ElasticSolid(const UnitBuildContext<D>& b)
    : mats_(b.materials),
      laws_(b.materials.size()),
      j2_(b.materials.size()),
      plastic_(b.materials.size(), 0),
      inv_rho0_(b.materials.size(), 0.0),
      kernel_(b.h),
      h_(b.h),
      cfl_(b.cfl_factor),
      X_(b.particles.template add<Vec<D>>("elastic_reference_position", kName, true)),
      body_(b.particles.template add<std::uint16_t>("elastic_body", kName, true)),
      constraint_(b.particles.template add<std::int32_t>("elastic_constraint", kName, true)),
      fluid_force_(b.particles.template add<Vec<D>>("elastic_fluid_force", kName, false)),
      pb_(b.particles.template add<Mat<D>>("elastic_stress_correction", kName, false)),
      F_(b.particles.template add<Mat<D>>("elastic_deformation_gradient", kName, true)),
      von_mises_(b.particles.template add<double>("von_mises_stress", kName, true)),
      strain_(b.particles.template add<double>("elastic_strain", kName, true)) {
  // Only the owner moves a constrained particle; ghosts need the reference position and body
  // (the reference neighbours of their neighbours) but not the constraint.
  constraint_.set_ghost(false);
  // F and the output fields are recomputed in every kForces, but sampled and written after
  // the step, when a rebalance may have moved the particle to another rank: they travel with
  // it (persistent), though no ghost needs them.
  F_.set_ghost(false);
  von_mises_.set_ghost(false);
  strain_.set_ghost(false);
  static const char* const kAxis[3] = {"elastic_displacement_x", "elastic_displacement_y",
                                       "elastic_displacement_z"};
  for (int a = 0; a < D; ++a) {
    displacement_[a] = &b.particles.template add<double>(kAxis[a], kName, true);
    displacement_[a]->set_ghost(false);
  }
  for (std::size_t k = 0; k < b.materials.size(); ++k) {
    if (b.materials[k].rho0 > 0) inv_rho0_[k] = 1.0 / b.materials[k].rho0;
    swelling_modulus_.push_back(b.materials[k].swelling_modulus);
    reference_saturation_.push_back(b.materials[k].reference_saturation);
  }
  // The diffusion unit, built before this one, owns the column (validation requires it).
  if (std::any_of(swelling_modulus_.begin(), swelling_modulus_.end(),
                  [](double C) { return C != 0.0; }) &&
      b.particles.has("concentration"))
    saturation_ = &b.particles.template get<double>("concentration");
  const v1::Case& c = b.c;
  if (c.time().has_quasi_static()) {
    relax_damping_ = c.time().quasi_static().damping();
    relax_threshold_ = c.time().quasi_static().kinetic_energy_threshold();
    damped_v_ = &b.particles.template add<Vec<D>>("elastic_damped_velocity", kName, false);
    damped_v_->set_ghost(false);
  }
  if (c.time().subcycle_elastic_bodies() || c.time().has_quasi_static()) {
    solid_v_ = &b.particles.template add<Vec<D>>("elastic_velocity", kName, true);
    held_force_ = &b.particles.template add<Vec<D>>("elastic_held_fluid_force", kName, true);
    internal_ = &b.particles.template add<Vec<D>>("elastic_internal_force", kName, true);
    shown_a_ = &b.particles.template add<Vec<D>>("elastic_shown_acceleration", kName, true);
    for (Column<Vec<D>>* col : {held_force_, internal_, shown_a_}) col->set_ghost(false);
  }
  if (c.has_gravity()) {
    gravity_ = elastic_vec<D>(c.gravity().acceleration());
    gravity_ramp_ = c.gravity().damping_time();
  }
  for (int k = 0; k < c.elastic_bodies_size(); ++k) {
    const v1::ElasticBody& e = c.elastic_bodies(k);
    Body body;
    body.name = e.name().empty() ? "body" + std::to_string(k) : e.name();
    body.gravity = !e.ignore_gravity();
    body.first_constraint = paths_.size();
    for (const auto& p : e.observation_points()) body.points.push_back(elastic_vec<D>(p));
    for (const auto& con : e.constraints()) {
      paths_.push_back(con.has_motion() ? MotionPath(con.motion(), D) : MotionPath());
      constrained_ = true;
    }
    bodies_.push_back(std::move(body));
    if (is_anisotropic(e)) {
      // P-II: h2 = h through the thickness, h1 = r h2 along the surface.
      Vec<D> n = Vec<D>::Zero();
      const int axis = thickness_axis(e, D);  // validated: a coordinate axis
      n[axis >= 0 ? axis : D - 1] = 1.0;
      body_map_.push_back(plate_anisotropy_map<D>(e.anisotropy().ratio() * h_, h_, n));
    } else {
      body_map_.push_back(Mat<D>::Identity() / h_);
    }
    const int m = material_index(b.materials, e.material());
    if (m < 0) continue;  // validation names the missing material
    const MaterialParams& mp = b.materials[static_cast<std::size_t>(m)];
    ElasticConstants& law = laws_[static_cast<std::size_t>(m)];
    law = ElasticConstants::from(mp.youngs_modulus, mp.poisson_ratio, mp.rho0,
                                 mp.elastic_law == v1::NEO_HOOKEAN
                                     ? ElasticLawKind::kNeoHookean
                                     : ElasticLawKind::kSaintVenantKirchhoff,
                                 mp.elastic_damping);
    sound_speed_ = std::max(sound_speed_, law.sound_speed);
    if (e.body_force_field().has_manufactured_torsion()) {
      const v1::ManufacturedTorsion& mt = e.body_force_field().manufactured_torsion();
      ManufacturedTorsion<D> field;
      field.center = elastic_vec<D>(mt.center());
      field.inner = mt.inner_radius();
      field.outer = mt.outer_radius();
      field.angle = mt.angle();
      field.ramp = mt.ramp_time();
      field.mu_over_rho0 = law.mu / mp.rho0;
      bodies_.back().torsion = field;
    }
    if (mp.plastic) {
      J2Constants& j2 = j2_[static_cast<std::size_t>(m)];
      j2.bulk = law.bulk;
      j2.shear = law.mu;
      j2.hardening = {mp.yield_stress, mp.saturation_stress, mp.saturation_exponent,
                      mp.linear_hardening};
      plastic_[static_cast<std::size_t>(m)] = 1;
    }
    if (mp.elastic_damping > 0)
      damping_dt_ =
          std::min(damping_dt_, kDampingStepFactor * h_ * h_ * mp.rho0 / mp.elastic_damping);
  }
  if (std::find(plastic_.begin(), plastic_.end(), 1) != plastic_.end()) {
    metric_ = &b.particles.template add<PlasticMetric>("plastic_metric", kName, true);
    alpha_ = &b.particles.template add<double>("equivalent_plastic_strain", kName, true);
    metric_->set_ghost(false);
    alpha_->set_ghost(false);
  }
  constraints_ = paths_.size();
  if (std::any_of(c.elastic_bodies().begin(), c.elastic_bodies().end(),
                  [](const v1::ElasticBody& e) { return is_anisotropic(e); }))
    kernel_map_ = &b.particles.template add<Mat<D>>("elastic_kernel_map", kName, true);
  else
    body_map_.clear();
  if (constrained_ && !solid_v_) {
    reaction_ = &b.particles.template add<Vec<D>>("elastic_constraint_force", kName, true);
    reaction_->set_ghost(false);
    reaction_->set_zero_if_absent(true);  // checkpoints of code before the series
  }
  hourglass_ = HourglassControl<D>(c, b.materials, kernel_, b.dx);
  damping_dt_ = std::min(damping_dt_, kTimeStepFactor * hourglass_.time_scale());
  // The bound at rest, h / c_s: the smallest the step can be without motion, and what the
  // run starts from before the first forces.
  if (sound_speed_ > 0) max_dt_ = cfl_ * kTimeStepFactor * h_ / sound_speed_;
  max_dt_ = std::min(max_dt_, cfl_ * damping_dt_);
}

template <int D, class K>
void ElasticSolid<D, K>::initialize(std::size_t i, const SceneParticle& p) {
  F_[i] = Mat<D>::Identity();
  if (metric_) {
    (*metric_)[i] = PlasticMetric{};
    (*alpha_)[i] = 0;
  }
  if (reaction_) (*reaction_)[i] = Vec<D>::Zero();
  if (solid_v_) {
    for (int a = 0; a < D; ++a) (*solid_v_)[i][a] = p.kind == Kind::kElastic ? p.v[a] : 0.0;
    (*held_force_)[i] = (*internal_)[i] = (*shown_a_)[i] = Vec<D>::Zero();
  }
  if (p.kind != Kind::kElastic) {
    constraint_[i] = -1;
    if (kernel_map_) (*kernel_map_)[i] = Mat<D>::Identity() / h_;
    return;
  }
  for (int a = 0; a < D; ++a) X_[i][a] = p.x[a];
  body_[i] = static_cast<std::uint16_t>(p.elastic);
  if (kernel_map_) (*kernel_map_)[i] = body_map_[static_cast<std::size_t>(p.elastic)];
  constraint_[i] = p.constraint;
}

template <int D, class K>
void ElasticSolid<D, K>::run(StepPhase phase, StepContext<D>& ctx) {
  switch (phase) {
    case StepPhase::kForces:
      if (solid_v_)
        hold_fluid_force(ctx);
      else
        forces(ctx);
      break;
    case StepPhase::kConstraints:
      hold_constrained(ctx.particles);
      break;
    case StepPhase::kAfterDrift:
      if (solid_v_ && ctx.dt > 0 && damped_v_)
        relax(ctx);
      else if (solid_v_ && ctx.dt > 0)
        substeps(ctx);
      else
        move_constrained(ctx.particles, ctx.t);
      break;
    default:
      break;
  }
}

template <int D, class K>
void ElasticSolid<D, K>::fail(const ParticleStore<D>& s, std::size_t i, const StepContext<D>& ctx,
                              const char* what) {
  if (!failure_.empty()) return;
  failure_ = "elastic body " + bodies_[body_[i]].name + ": " + what +
             describe_particle(s, mats_, i, ctx.step, ctx.t);
}

template <int D, class K>
void ElasticSolid<D, K>::build_references(const StepContext<D>& ctx) {
  if (refs_.current(ctx.neighbors)) return;
  if (kernel_map_)
    refs_.build_anisotropic(ctx.particles, ctx.neighbors, X_.data(), body_.data(), inv_rho0_.data(),
                            kernel_map_->data(), anisotropic_kernel_);
  else
    refs_.build(ctx.particles, ctx.neighbors, X_.data(), body_.data(), inv_rho0_.data(), kernel_);
}

template <int D, class K>
void ElasticSolid<D, K>::forces(StepContext<D>& ctx) {
  ParticleStore<D>& s = ctx.particles;
  const std::size_t n = s.owned();
  const Kind* kind = s.kind.data();
  const Vec<D>* v = s.v.data();
  failure_.clear();
  build_references(ctx);
  stresses(ctx, v);
  // Pass 2: the momentum equation, the fluid's force and gravity.
  const Vec<D> g = BodyForce<D>::damping_factor(ctx.t, gravity_ramp_) * gravity_;
  double a_max = 0, v_max = 0, strain_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (kind[i] != Kind::kElastic) continue;
    const double m = s.m[i];
    const Vec<D> force = internal_force_on(s, i) + fluid_force_[i];
    Vec<D> acc = force / m;
    const Body& body = bodies_[body_[i]];
    if (body.gravity) acc += g;
    if (body.torsion) acc += body.torsion->force(X_[i], ctx.t);
    s.a[i] += acc;  // forces accumulate (solver/seam/unit.h)
    if (reaction_ && constraint_[i] >= 0)
      (*reaction_)[i] = bodies_[body_[i]].gravity ? Vec<D>(-force - m * g) : Vec<D>(-force);
    v_max = std::max(v_max, v[i].norm());
    if (constraint_[i] < 0) a_max = std::max(a_max, s.a[i].norm());
    strain_max = std::max(strain_max, stiffening_strain(s, i));
  }
  max_dt_ = stable_step(ctx.comm, a_max, v_max, strain_max);
}

template <int D, class K>
void ElasticSolid<D, K>::stresses(StepContext<D>& ctx, const Vec<D>* v) {
  ParticleStore<D>& s = ctx.particles;
  const std::size_t n = s.owned();
  const Kind* kind = s.kind.data();
  const std::uint16_t* mat = s.material.data();
  const Vec<D>* X = X_.data();
  const Vec<D>* x = s.x.data();
  // F, dF/dt, P and P B of every owned elastic particle (eqs. 3.7, 3.10, P-I 35).
  for (std::size_t i = 0; i < n; ++i) {
    if (kind[i] != Kind::kElastic) {
      pb_[i] = Mat<D>::Zero();
      von_mises_[i] = strain_[i] = 0;
      for (int a = 0; a < D; ++a) (*displacement_[a])[i] = 0;
      continue;
    }
    const ElasticConstants& law = laws_[mat[i]];
    const ReferenceSums<D> sums = reference_sums<D>(refs_, i, X, x, v);
    for (int a = 0; a < D; ++a) (*displacement_[a])[i] = x[i][a] - X[i][a];
    Mat<D> F = Mat<D>::Identity();
    pb_[i] = Mat<D>::Zero();
    von_mises_[i] = strain_[i] = 0;
    const double conditioning = moment_conditioning<D>(sums.moment);
    if (!(conditioning > kMinConditioning)) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "singular correction matrix (%zu reference neighbours left, conditioning "
                    "%.3g): the body tore",
                    refs_.size(i), conditioning);
      fail(s, i, ctx, buf);
    } else {
      const Mat<D> B = sums.moment.inverse();
      // What the momentum sum multiplies the kernel gradient by: B, or B^T with anisotropic
      // kernels (total_lagrangian.h, internal_force).
      const Mat<D> Bg = kernel_map_ ? Mat<D>(B.transpose()) : B;
      const Mat<D> Fi = sums.position * B;
      const double J = Fi.determinant();
      if (!(J > 0)) {
        char buf[160];
        std::snprintf(
            buf, sizeof buf, "inverted particle (det F = %.3g <= 0%s)", J,
            hourglass_.stiffness(mat[i]) > 0
                ? ""
                : "; if a checkerboard grew into it, Material.hourglass_control 0.1 holds it");
        fail(s, i, ctx, buf);
      } else {
        F = Fi;
        Mat<D> P;
        if (metric_ && plastic_[mat[i]]) {
          P = plastic_stress(law, mat[i], i, F, sums.velocity * B);
        } else {
          const Mat<D> S = second_piola<D>(law, F, sums.velocity * B);
          P = F * S;  // eq. 2.3
          von_mises_[i] = von_mises(cauchy_stress<D>(law, F, S));
        }
        // The pore pressure (P-III eqs. 2.17, 2.21): isotropic, so no von Mises part.
        if (saturation_ && swelling_modulus_[mat[i]] != 0.0) {
          const double p =
              swelling_modulus_[mat[i]] * ((*saturation_)[i] - reference_saturation_[mat[i]]);
          P -= (p * J) * F.inverse().transpose();
        }
        pb_[i] = P * Bg;
        strain_[i] = equivalent_strain<D>(F);
      }
    }
    F_[i] = F;
  }
  // The momentum sum reads P B of the neighbours, the hourglass force their F.
  if (hourglass_.active())
    ctx.halo.update(s, {&pb_, &F_});
  else
    ctx.halo.update(s, {&pb_});
}

template <int D, class K>
Mat<D> ElasticSolid<D, K>::plastic_stress(const ElasticConstants& law, std::uint16_t mat,
                                          std::size_t i, const Mat<D>& F, const Mat<D>& dFdt) {
  const Eigen::Matrix3d F3 = embed_3d<D>(F);
  const J2Result r = j2_return_map(j2_[mat], F3, (*metric_)[i], (*alpha_)[i]);
  // P = tau F^-T; in 2D F^-T is block diagonal (F_zz = 1), so the in-plane block of P is that of
  // tau F^-T.
  Mat<D> P = (r.tau * F3.inverse().transpose()).template topLeftCorner<D, D>();
  Eigen::Matrix3d sigma = r.tau / F3.determinant();
  if (law.damping != 0.0) {
    // Kelvin-Voigt as for the elastic laws: S_d = eta_d dE/dt, P += F S_d.
    const Mat<D> FSd = F * (law.damping * green_lagrange_rate<D>(F, dFdt));
    P += FSd;
    sigma.template topLeftCorner<D, D>() += FSd * F.transpose() / F3.determinant();
  }
  von_mises_[i] = von_mises(sigma);
  return P;
}

template <int D, class K>
void ElasticSolid<D, K>::hold_constrained(ParticleStore<D>& s) {
  for (std::size_t i = 0; i < s.owned(); ++i)
    if (s.kind[i] == Kind::kElastic && constraint_[i] >= 0) s.a[i] = Vec<D>::Zero();
}

template <int D, class K>
void ElasticSolid<D, K>::place_constrained(ParticleStore<D>& s, Column<Vec<D>>& vel, double t) {
  // One pose per constraint and step, as WallMotion does.
  poses_.resize(paths_.size());
  for (std::size_t k = 0; k < paths_.size(); ++k)
    if (!paths_[k].is_static()) poses_[k] = paths_[k].pose(t);
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.kind[i] != Kind::kElastic || constraint_[i] < 0) continue;
    const std::size_t k =
        bodies_[body_[i]].first_constraint + static_cast<std::size_t>(constraint_[i]);
    if (paths_[k].is_static()) {
      s.x[i] = X_[i];
      vel[i] = Vec<D>::Zero();
      continue;
    }
    Point3 X0 = Point3::Zero();
    for (int a = 0; a < D; ++a) X0[a] = X_[i][a];
    const Point3 xt = poses_[k].position(X0), vt = poses_[k].velocity(X0);
    for (int a = 0; a < D; ++a) {
      s.x[i][a] = xt[a];
      vel[i][a] = vt[a];
    }
  }
}

template <int D, class K>
void ElasticSolid<D, K>::find_observed(const ParticleStore<D>& s, const Comm& comm) {
  // The particle nearest each point in the reference configuration: the smallest distance of
  // all ranks, then the smallest id at that distance (both reductions exact).
  slots_.clear();
  std::size_t slot = 0;
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    Body& body = bodies_[k];
    body.observed.assign(body.points.size(), -1);
    for (std::size_t p = 0; p < body.points.size(); ++p, ++slot) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < s.owned(); ++i)
        if (s.kind[i] == Kind::kElastic && body_[i] == k)
          best = std::min(best, (X_[i] - body.points[p]).squaredNorm());
      best = comm.min(best);
      std::int64_t id = std::numeric_limits<std::int64_t>::max();
      for (std::size_t i = 0; i < s.owned(); ++i)
        if (s.kind[i] == Kind::kElastic && body_[i] == k &&
            (X_[i] - body.points[p]).squaredNorm() == best)
          id = std::min<std::int64_t>(id, s.id[i]);
      body.observed[p] = comm.min(id);
      slots_.emplace_back(body.observed[p], slot);
    }
  }
  std::sort(slots_.begin(), slots_.end());
  observed_found_ = true;
}

template <int D, class K>
void ElasticSolid<D, K>::declare_output(ResultFile& result) {
  for (int a = 0; a < D; ++a) result.add_field(*displacement_[a]);
  result.add_field(von_mises_);
  result.add_field(strain_);
  if (alpha_) result.add_field(*alpha_);
}

template <int D, class K>
void ElasticSolid<D, K>::sample(ResultFile& result, const StepContext<D>& ctx) {
  const ParticleStore<D>& s = ctx.particles;
  if (!observed_found_) find_observed(s, ctx.comm);
  // Displacements of the observed particles: each from its owner, zeros from the others.
  std::vector<double> shown(slots_.size() * D, 0.0);
  if (!slots_.empty())
    for (std::size_t i = 0; i < s.owned(); ++i) {
      if (s.kind[i] != Kind::kElastic) continue;
      const auto range = std::equal_range(
          slots_.begin(), slots_.end(), std::pair<ParticleId, std::size_t>(s.id[i], 0),
          [](const auto& l, const auto& r) { return l.first < r.first; });
      for (auto it = range.first; it != range.second; ++it)
        for (int a = 0; a < D; ++a) shown[it->second * D + a] = s.x[i][a] - X_[i][a];
    }
  ctx.comm.sum_inplace(shown);
  // Kinetic and strain energy per body (exact sums: rank-independent bits).
  const std::size_t nb = bodies_.size();
  const std::size_t nr = constraints_ * D;  // constraint forces, after the energies
  const Vec<D> g = BodyForce<D>::damping_factor(ctx.t, gravity_ramp_) * gravity_;
  const std::vector<double> energy = exact_sum(
      2 * nb + nr,
      [&](auto&& emit) {
        for (std::size_t i = 0; i < s.owned(); ++i) {
          if (s.kind[i] != Kind::kElastic) continue;
          const std::uint16_t k = body_[i];
          const double m = s.m[i];
          const Vec<D>& v = solid_v_ ? (*solid_v_)[i] : s.v[i];
          emit(2 * k, 0.5 * m * v.squaredNorm());
          const std::uint16_t mat = s.material[i];
          const double psi = metric_ && plastic_[mat]
                                 ? j2_elastic_energy(j2_[mat], embed_3d<D>(F_[i]), (*metric_)[i])
                                 : strain_energy_density<D>(laws_[mat], F_[i]);
          emit(2 * k + 1, m * inv_rho0_[mat] * psi);
          if (constraint_[i] < 0 || nr == 0) continue;
          Vec<D> held;
          if (reaction_) {
            held = (*reaction_)[i];
          } else {  // sub-steps: the last sub-step's internal force and the held fluid force
            held = -(*internal_)[i] - (*held_force_)[i];
            if (bodies_[k].gravity) held -= m * g;
          }
          const std::size_t row =
              bodies_[k].first_constraint + static_cast<std::size_t>(constraint_[i]);
          for (int a = 0; a < D; ++a) emit(2 * nb + row * D + static_cast<std::size_t>(a), held[a]);
        }
      },
      ctx.comm);
  std::size_t slot = 0;
  for (std::size_t k = 0; k < nb; ++k) {
    const std::string base = "elastic/" + bodies_[k].name + "/";
    const std::size_t np = bodies_[k].points.size();
    if (np > 0)
      result.put(base + "displacement",
                 std::vector<double>(shown.begin() + static_cast<std::ptrdiff_t>(slot * D),
                                     shown.begin() + static_cast<std::ptrdiff_t>((slot + np) * D)),
                 {np, static_cast<std::uint64_t>(D)});
    slot += np;
    result.put(base + "kinetic_energy", energy[2 * k]);
    result.put(base + "strain_energy", energy[2 * k + 1]);
    const std::size_t nc =
        (k + 1 < nb ? bodies_[k + 1].first_constraint : constraints_) - bodies_[k].first_constraint;
    if (nc > 0) {
      const auto first =
          energy.begin() + static_cast<std::ptrdiff_t>(2 * nb + bodies_[k].first_constraint * D);
      result.put(base + "constraint_force",
                 std::vector<double>(first, first + static_cast<std::ptrdiff_t>(nc * D)),
                 {nc, static_cast<std::uint64_t>(D)});
    }
  }
  if (damped_v_) {
    result.put("elastic/relaxation_steps", static_cast<double>(relax_steps_));
    result.put("elastic/unrelaxed_load_steps", static_cast<double>(unrelaxed_steps_));
  }
}

template <int D, class K>
void ElasticSolid<D, K>::save(CheckpointState& state) const {
  if (solid_v_) state["elastic_solid.substep_dt"] = substep_dt_;
  if (damped_v_) {
    state["elastic_solid.relaxation_steps"] = static_cast<double>(relax_steps_);
    state["elastic_solid.unrelaxed_load_steps"] = static_cast<double>(unrelaxed_steps_);
  }
}

template <int D, class K>
void ElasticSolid<D, K>::load(const CheckpointState& state) {
  if (solid_v_) substep_dt_ = state_value(state, "elastic_solid.substep_dt");
  if (damped_v_) {
    relax_steps_ = static_cast<std::int64_t>(state_value(state, "elastic_solid.relaxation_steps"));
    unrelaxed_steps_ =
        static_cast<std::int64_t>(state_value(state, "elastic_solid.unrelaxed_load_steps"));
  }
}

template <int D, class K>
void ElasticSolid<D, K>::internal_forces(StepContext<D>& ctx, const Vec<D>* v) {
  ParticleStore<D>& s = ctx.particles;
  stresses(ctx, v);
  for (std::size_t i = 0; i < s.owned(); ++i)
    if (s.kind[i] == Kind::kElastic) (*internal_)[i] = internal_force_on(s, i);
}

template <int D, class K>
Vec<D> ElasticSolid<D, K>::internal_force_on(const ParticleStore<D>& s, std::size_t i) const {
  const std::uint16_t* mat = s.material.data();
  const double V0 = s.m[i] * inv_rho0_[mat[i]];
  Vec<D> f = internal_force<D>(refs_, i, pb_.data(), V0);  // eqs. 3.8-3.9
  if (hourglass_.active())
    f += hourglass_.force(refs_, i, X_.data(), s.x.data(), F_.data(), s.m.data(), mat,
                          inv_rho0_.data(), kernel_);
  return f;
}

template <int D, class K>
Vec<D> ElasticSolid<D, K>::substep_acceleration(const ParticleStore<D>& s, std::size_t i,
                                                const Vec<D>& g, double t) const {
  Vec<D> acc = (*internal_)[i] / s.m[i];
  const Body& body = bodies_[body_[i]];
  if (body.gravity) acc += g;
  if (body.torsion) acc += body.torsion->force(X_[i], t);
  return acc;
}

template <int D, class K>
void ElasticSolid<D, K>::hold_fluid_force(StepContext<D>& ctx) {
  ParticleStore<D>& s = ctx.particles;
  const std::size_t n = s.owned();
  // The closing half kick of the fluid's force of t^{n+1} (the outer kick of r-RESPA).
  Column<Vec<D>>& vs = *solid_v_;
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != Kind::kElastic) continue;
    (*held_force_)[i] = fluid_force_[i];
    if (constraint_[i] < 0) vs[i] += (0.5 * ctx.dt / s.m[i]) * fluid_force_[i];
  }
  if (ctx.dt == 0) {
    // The run is primed: the internal forces the first sub-step starts from, and its bound.
    failure_.clear();
    build_references(ctx);
    internal_forces(ctx, solid_v_->data());
    substep_bound(s, ctx.comm, ctx.t);
  }
  // The acceleration the fluid sees until the next sub-steps (the wall condition reads a).
  for (std::size_t i = 0; i < n; ++i)
    if (s.kind[i] == Kind::kElastic) s.a[i] += (*shown_a_)[i];
}

template <int D, class K>
void ElasticSolid<D, K>::substeps(StepContext<D>& ctx) {
  ParticleStore<D>& s = ctx.particles;
  const std::size_t n = s.owned();
  const Kind* kind = s.kind.data();
  Column<Vec<D>>& vs = *solid_v_;
  failure_.clear();
  const double dt = ctx.dt, t0 = ctx.t - dt;
  const double ratio = dt / substep_dt_;
  if (!(ratio <= kMaxSubsteps)) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "elastic bodies need %.3g sub-steps of %.3e in a fluid step of %.3e (more "
                  "than %d) at step %lld, t = %.9g",
                  ratio, substep_dt_, dt, kMaxSubsteps, static_cast<long long>(ctx.step), ctx.t);
    failure_ = buf;
    return;
  }
  const int kappa = std::max(1, static_cast<int>(std::ceil(ratio)));
  const double ds = dt / kappa;
  build_references(ctx);
  // The opening half kick of the fluid's force of t^n, then kick-drift-kick sub-steps (P-I
  // eqs. 36-38) of the internal forces and gravity.
  for (std::size_t i = 0; i < n; ++i) {
    if (kind[i] != Kind::kElastic) continue;
    if (constraint_[i] < 0) vs[i] += (0.5 * dt / s.m[i]) * (*held_force_)[i];
  }
  for (int k = 0; k < kappa; ++k) {
    const double ta = t0 + k * ds, tb = k + 1 == kappa ? ctx.t : t0 + (k + 1) * ds;
    const Vec<D> ga = BodyForce<D>::damping_factor(ta, gravity_ramp_) * gravity_;
    for (std::size_t i = 0; i < n; ++i) {
      if (kind[i] != Kind::kElastic || constraint_[i] >= 0) continue;
      vs[i] += 0.5 * ds * substep_acceleration(s, i, ga, ta);
      s.x[i] += ds * vs[i];
    }
    place_constrained(s, vs, tb);
    ctx.halo.update(s, {&s.x, &vs});
    internal_forces(ctx, vs.data());
    const Vec<D> gb = BodyForce<D>::damping_factor(tb, gravity_ramp_) * gravity_;
    for (std::size_t i = 0; i < n; ++i)
      if (kind[i] == Kind::kElastic && constraint_[i] < 0)
        vs[i] += 0.5 * ds * substep_acceleration(s, i, gb, tb);
  }
  // What the fluid sees until the next sub-steps: the solid's velocity now, before the closing
  // half kick of the fluid's force (the fluid's own velocities are likewise half-kicked when its
  // forces are evaluated), and its change over the step as the acceleration. Not the thesis'
  // velocity averaged over the step (P-I eq. 34): with it a stiff plate under water went
  // unstable (docs/elastic_solids.md).
  const double inv_dt = 1.0 / dt;
  for (std::size_t i = 0; i < n; ++i) {
    if (kind[i] != Kind::kElastic) continue;
    (*shown_a_)[i] = (vs[i] - s.v[i]) * inv_dt;
    s.v[i] = vs[i];
    s.a[i] = (*shown_a_)[i];
  }
  substep_bound(s, ctx.comm, ctx.t);
}

template <int D, class K>
double ElasticSolid<D, K>::kinetic_energy(const ParticleStore<D>& s, const Comm& comm) const {
  const Column<Vec<D>>& vs = *solid_v_;
  return exact_sum(
      1,
      [&](auto&& emit) {
        for (std::size_t i = 0; i < s.owned(); ++i)
          if (s.kind[i] == Kind::kElastic && constraint_[i] < 0)
            emit(0, 0.5 * s.m[i] * vs[i].squaredNorm());
      },
      comm)[0];
}

template <int D, class K>
double ElasticSolid<D, K>::constraint_travel(const ParticleStore<D>& s, const Comm& comm, double t0,
                                             double t1) const {
  double travel = 0;
  for (std::size_t k = 0; k < paths_.size(); ++k) {
    if (paths_[k].is_static()) continue;
    const auto p0 = paths_[k].pose(t0), p1 = paths_[k].pose(t1);
    for (std::size_t i = 0; i < s.owned(); ++i) {
      if (s.kind[i] != Kind::kElastic || constraint_[i] < 0 ||
          bodies_[body_[i]].first_constraint + static_cast<std::size_t>(constraint_[i]) != k)
        continue;
      Point3 X0 = Point3::Zero();
      for (int a = 0; a < D; ++a) X0[a] = X_[i][a];
      travel = std::max(travel, (p1.position(X0) - p0.position(X0)).norm());
    }
  }
  return comm.max(travel);
}

template <int D, class K>
void ElasticSolid<D, K>::relax(StepContext<D>& ctx) {
  ParticleStore<D>& s = ctx.particles;
  const std::size_t n = s.owned();
  const Kind* kind = s.kind.data();
  Column<Vec<D>>& vs = *solid_v_;
  failure_.clear();
  build_references(ctx);
  // The slow process of the outer step (thesis sec. 6.2): the constraints move to where they are
  // at its end, gravity to its value there. Not in one jump: a constrained particle that jumps
  // by d strains its neighbours by about d / dx at once, which can yield a plastic material
  // there at every load step (docs/quasi_static.md). The load
  // follows its path over the ramp time d_max / (kLoadRampSpeed c_s) of inner time instead (at
  // most the outer step), which strains the body by about kLoadRampSpeed as it goes.
  const double t0 = ctx.t - ctx.dt;
  const double ramp =
      std::min(ctx.dt, constraint_travel(s, ctx.comm, t0, ctx.t) / (kLoadRampSpeed * sound_speed_));
  const auto load_time = [&](double tau) {
    return tau >= ramp ? ctx.t : t0 + ctx.dt * (tau / ramp);
  };
  // Constrained particles where the load is at inner time tau, moving at the ramp's pace during
  // it and at rest after.
  const auto hold_constraints = [&](double tau) {
    place_constrained(s, vs, load_time(tau));
    const double pace = tau < ramp ? ctx.dt / ramp : 0.0;
    for (std::size_t i = 0; i < n; ++i)
      if (kind[i] == Kind::kElastic && constraint_[i] >= 0) vs[i] *= pace;
  };
  hold_constraints(0);
  ctx.halo.update(s, {&s.x, &vs});
  internal_forces(ctx, vs.data());
  substep_bound(s, ctx.comm, ctx.t);
  const bool viscous = std::any_of(laws_.begin(), laws_.end(),
                                   [](const ElasticConstants& l) { return l.damping != 0.0; });
  // The inner loop: kick-drift-kick steps of eq. 33 (P-I eqs. 36-38) with the damping after the
  // drift, until, after the ramp, a peak of the kinetic energy is below the threshold, or the
  // inner steps fill the outer step.
  double tau = 0, previous = 0;
  bool relaxed = false;
  while (tau < ctx.dt && !relaxed) {
    const double ds = std::min(substep_dt_, ctx.dt - tau);
    double tl = load_time(tau);
    Vec<D> g = BodyForce<D>::damping_factor(tl, gravity_ramp_) * gravity_;
    for (std::size_t i = 0; i < n; ++i) {
      if (kind[i] != Kind::kElastic || constraint_[i] >= 0) continue;
      vs[i] += 0.5 * ds * substep_acceleration(s, i, g, tl);
      s.x[i] += ds * vs[i];
    }
    tau += ds;
    hold_constraints(tau);
    ctx.halo.update(s, {&s.x, &vs});
    relaxation_damping<D>(refs_, n, kind, constraint_.data(), X_.data(), s.m.data(),
                          s.material.data(), inv_rho0_.data(), relax_damping_ * ds, vs.data(),
                          damped_v_->data());
    for (std::size_t i = 0; i < n; ++i) vs[i] = (*damped_v_)[i];
    // Kelvin-Voigt damping reads the neighbours' dF/dt: their damped velocities.
    if (viscous) ctx.halo.update(s, {&vs});
    internal_forces(ctx, vs.data());
    tl = load_time(tau);
    g = BodyForce<D>::damping_factor(tl, gravity_ramp_) * gravity_;
    for (std::size_t i = 0; i < n; ++i)
      if (kind[i] == Kind::kElastic && constraint_[i] < 0)
        vs[i] += 0.5 * ds * substep_acceleration(s, i, g, tl);
    ++relax_steps_;
    const bool loaded = tau >= ramp;
    double energy = kinetic_energy(s, ctx.comm);
    // (<=: a body the load step leaves at rest has zero kinetic energy twice, a peak at zero.)
    if (loaded && energy <= previous) {
      // Past a peak of the kinetic energy: kinetic damping (Cundall 1976), every velocity to
      // zero. The viscous damping alone leaves the body's lowest mode underdamped (implicitly
      // it saturates at about h^2 lap v a step, whatever eta), and a criterion on the kinetic
      // energy alone would end the loop at a turning point, where all of the energy is strain
      // energy; at a peak, the kinetic energy is the strain energy still to be released. The
      // loop ends at a peak below the threshold.
      relaxed = previous < relax_threshold_;
      for (std::size_t i = 0; i < n; ++i)
        if (kind[i] == Kind::kElastic && constraint_[i] < 0) vs[i] = Vec<D>::Zero();
      energy = 0;
    }
    // The energy of the ramp's last step counts: the motion the ramp leaves is stopped as soon
    // as the body slows down after it, not carried to a later peak.
    previous = energy;
    substep_bound(s, ctx.comm, ctx.t);
    if (!failure_.empty()) return;
  }
  if (!relaxed) ++unrelaxed_steps_;
  for (std::size_t i = 0; i < n; ++i) {
    if (kind[i] != Kind::kElastic) continue;
    (*shown_a_)[i] = Vec<D>::Zero();
    s.v[i] = vs[i];
    s.a[i] = Vec<D>::Zero();
  }
}

template <int D, class K>
void ElasticSolid<D, K>::substep_bound(const ParticleStore<D>& s, const Comm& comm, double t) {
  const Vec<D> g = BodyForce<D>::damping_factor(t, gravity_ramp_) * gravity_;
  double a_max = 0, v_max = 0, strain_max = 0;
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.kind[i] != Kind::kElastic) continue;
    v_max = std::max(v_max, (*solid_v_)[i].norm());
    if (constraint_[i] < 0)
      a_max =
          std::max(a_max, (substep_acceleration(s, i, g, t) + (*held_force_)[i] / s.m[i]).norm());
    strain_max = std::max(strain_max, stiffening_strain(s, i));
  }
  substep_dt_ = stable_step(comm, a_max, v_max, strain_max);
}

template <int D, class K>
double ElasticSolid<D, K>::stiffening_strain(const ParticleStore<D>& s, std::size_t i) const {
  if (laws_[s.material[i]].law != ElasticLawKind::kSaintVenantKirchhoff) return 0;
  return 0.5 * (F_[i].transpose() * F_[i] - Mat<D>::Identity()).norm();
}

template <int D, class K>
double ElasticSolid<D, K>::stable_step(const Comm& comm, double a_max, double v_max,
                                       double strain_max) {
  // Thesis eq. 33 with the maxima of all ranks (exact, so the same on any rank count) and the
  // sound speed of the stretched material: the tangent of Saint Venant-Kirchhoff, dP/dF = S +
  // F (lambda tr dE + 2 mu dE), grows by about 1 + 3 |E| (|E| >= its largest principal
  // strain). With the sound speed at rest, a block swollen by 8% (|E| = 0.12) never relaxed at
  // cfl_factor above 0.9: its corners kept oscillating (docs/porous_media.md).
  maxima_[0] = a_max;
  maxima_[1] = v_max;
  maxima_[2] = strain_max;
  comm.max_inplace(maxima_);
  double dt = h_ / (maxima_[1] + sound_speed_ * std::sqrt(1 + 3 * maxima_[2]));
  if (maxima_[0] > 0) dt = std::min(dt, std::sqrt(h_ / maxima_[0]));
  return std::min(cfl_ * kTimeStepFactor * dt, cfl_ * damping_dt_);
}

}  // namespace sph
