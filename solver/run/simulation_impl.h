#pragma once
// Implementation of Simulation<D, K>, included only by simulation_2d.cc and simulation_3d.cc,
// which instantiate it.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "solver/run/simulation.h"

namespace sph {

namespace detail {
template <int D>
Vec<D> to_vec(const v1::Vec3& v) {
  Vec<D> out;
  out[0] = v.x();
  out[1] = v.y();
  if constexpr (D == 3) out[2] = v.z();
  return out;
}
template <int D>
Vec<D> to_vec(const Point3& p) {
  Vec<D> out;
  for (int a = 0; a < D; ++a) out[a] = p[a];
  return out;
}
}  // namespace detail

template <int D, class K>
Simulation<D, K>::Simulation(const v1::Case& c, const Comm& comm, const RunOptions& opt)
    : c_(c),
      comm_(comm),
      opt_(opt),
      mats_(resolve_materials(c)),
      fluids_(make_fluid_table(mats_)),
      dx_(c.dx()),
      h_(smoothing_length(c)),  // h = dx by default (Fuchs 2021 Remark 8)
      // The kernel's support, or the longest semi-axis of an anisotropic elastic body's
      // support (case/anisotropy.h): cells, ghosts and lists then reach its reference
      // neighbours, whose pairs the elastic unit takes from the list (total_lagrangian.h).
      rc_(std::max(K::kSupport * h_, search_radius(c))),
      skin_(neighbor_skin(c)),
      wall_volume_(std::pow(c.dx(), D)),
      kernel_(h_),
      // Cells hold every candidate of a Verlet list within the 3^D around a particle.
      grid_(detail::to_vec<D>(c.domain().lo()), detail::to_vec<D>(c.domain().hi()), rc_ + skin_,
            [&] {
              std::array<bool, D> p{};
              p[0] = c.periodic_x();
              p[1] = c.periodic_y();
              if constexpr (D == 3) p[2] = c.periodic_z();
              return p;
            }()),
      halo_(grid_, comm),
      schedule_(c),
      recorder_(comm, opt) {
  const auto& g = c.guards();
  if (g.has_max_density_deviation()) guards_.max_density_deviation = g.max_density_deviation();
  if (g.has_min_dt_fraction()) guards_.min_dt_fraction = g.min_dt_fraction();
  if (g.has_max_mach()) guards_.max_mach = g.max_mach();
  if (g.has_max_solid_fraction()) guards_.max_solid_fraction = g.max_solid_fraction();
  if (g.has_max_contact_substeps()) guards_.max_contact_substeps = g.max_contact_substeps();
  build_units();
}

template <int D, class K>
RunOutcome Simulation<D, K>::run() {
  RunOutcome out;
  start();
  report_progress(true);
  RunStatus status = RunStatus::kCompleted;
  std::string message;
  const double steady = c_.stop().steady_kinetic_energy();
  while (true) {
    if (schedule_.finished(t_)) break;
    if (c_.time().max_steps() > 0 && step_ >= c_.time().max_steps()) {
      if (!last_step_had_snapshot_) write_snapshot();
      message = "time.max_steps reached";
      break;
    }
    const StepReport e = step();
    if (e.violated) {
      status = RunStatus::kUnstable;
      message = e.diagnosis;
      break;
    }
    // Sampled on schedule and at the end, so the series end where the run does.
    if (t_ >= next_series_ - schedule_.eps() || schedule_.finished(t_)) sample_series();
    last_step_had_snapshot_ = false;
    if (schedule_.snapshot_due(t_, next_output_)) {
      write_snapshot();
      last_step_had_snapshot_ = true;
      next_output_ = schedule_.first_after(t_);
    }
    report_progress(false);
    if (e.interrupt) {
      write_checkpoint_now();
      status = RunStatus::kInterrupted;
      message = "interrupted; checkpoint written";
      break;
    }
    if (e.cancel) {
      if (!last_step_had_snapshot_) write_snapshot();
      status = RunStatus::kCancelled;
      message = "cancelled at a step boundary; last state written";
      break;
    }
    if (e.checkpoint) write_checkpoint_now();
    if (e.out_of_time) {
      if (!last_step_had_snapshot_) write_snapshot();
      message = "stop.max_wall_seconds reached";
      break;
    }
    if (steady > 0 && step_ % 20 == 0) {
      const Vec<D> g = Vec<D>::Zero();
      const ConservationSample<D> cs = conservation(s_, fluids_, g, comm_);
      if (cs.mass > 0 && cs.kinetic / cs.mass < steady) {
        if (!last_step_had_snapshot_) write_snapshot();
        message = "steady state reached (stop.steady_kinetic_energy)";
        break;
      }
    }
  }
  report_progress(true);
  const std::map<std::string, double> bytes =
      recorder_.finish(to_string(status), message, timers_, memory_by_owner(), searches_);
  out.unit_bytes = bytes;
  out.status = status;
  out.message = message;
  out.steps = step_;
  out.time = t_;
  out.wall_seconds = recorder_.wall_seconds();
  out.unit_seconds = timers_;
  out.neighbor_searches = searches_;
  out.last_checkpoint = recorder_.last_checkpoint();
  out.files = {std::filesystem::absolute(recorder_.result().h5_path()).string(),
               std::filesystem::absolute(recorder_.result().xmf_path()).string()};
  return out;
}

template <int D, class K>
void Simulation<D, K>::start() {
  recorder_.start_clock();
  if (opt_.resume_from.empty()) {
    build_scene();
    migrate();
    s_.release_unused();
    global_particles_ = comm_.sum(static_cast<std::int64_t>(s_.owned()));
    if (bodies_) {
      std::vector<Vec<D>> v0;
      std::vector<AngVec<D>> w0;
      for (const auto& b : c_.bodies()) {
        v0.push_back(detail::to_vec<D>(b.initial_velocity()));
        AngVec<D> w;
        if constexpr (D == 2)
          w[0] = b.initial_angular_velocity().z();
        else
          w = Eigen::Vector3d(b.initial_angular_velocity().x(), b.initial_angular_velocity().y(),
                              b.initial_angular_velocity().z());
        w0.push_back(w);
      }
      bodies_->initialize(comm_, dx_, v0, w0);
    }
    prime();
    {
      // Initial transport velocity and series before the first step.
      const GuardScan<D> scan =
          scan_particles<D>(s_, fluids_, mats_, guards_, detail::to_vec<D>(c_.domain().lo()),
                            detail::to_vec<D>(c_.domain().hi()), grid_.periodic, 0, 0.0);
      dt_ = fixed_time_step(c_) > 0
                ? fixed_time_step(c_)
                : std::min(bound_->dt(comm_.max(scan.max_speed), comm_.max(scan.max_acceleration)),
                           unit_set_.max_time_step());
      dt0_ = dt_;
    }
    if (walls_) solid_fraction_ = comm_.max(scan_solid_fraction().max);
    if (contact_) min_contact_distance_ = comm_.min(nl_.min_contact_distance());
    recorder_.result().declare([this] { record_series(); });
    recorder_.result().create(metadata("running"));
    sample_series();
    write_snapshot();
    next_output_ = schedule_.first_after(0.0);
    // After the first sample and snapshot: a rebalance migrates only the persistent columns,
    // and units' other columns (normals, curvature) are written again in the first step.
    maybe_rebalance();
  } else {
    const CheckpointState state = read_checkpoint(comm_, opt_.resume_from, s_);
    try {
      t_ = state_value(state, "time");
      step_ = static_cast<std::int64_t>(state_value(state, "step"));
      dt_ = state_value(state, "dt");
      dt0_ = state_value(state, "dt0");
      next_series_ = state_value(state, "next_series");
      contact_possible_ =
          state.count("contact_possible") && state_value(state, "contact_possible") > 0;
      if (state.count("neighbor_searches"))
        searches_ = static_cast<std::int64_t>(state_value(state, "neighbor_searches"));
      // A unit the checkpoint ran with but the case lacks (or the reverse) would leave its
      // particles to units that do not know them, e.g. rigid particles with no body.
      const auto expect = [&state](bool in_case, const char* key, const char* what) {
        if (in_case != (state.count(key) > 0))
          throw std::runtime_error(std::string("the checkpoint was written for a case ") +
                                   (in_case ? "without " : "with ") + what + "; this case " +
                                   (in_case ? "has them" : "has none"));
      };
      expect(bodies_.has_value(), "bodies.count", "rigid bodies (or phase transitions)");
      expect(open_.has_value(), "open_next_id", "open boundaries");
      if (bodies_) bodies_->load(state);
      if (open_) open_->load(state);
      if (phase_) phase_->load(state);
      if (growth_) growth_->load(state);
      if (contact_) contact_->load(state);  // every rank reads all pairs ...
      for (const auto& u : unit_set_.units()) u->load(state);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("resuming from " + opt_.resume_from + ": " + e.what());
    }
    decompose_by_histogram();
    // The first step's contact drift reads the neighbour list of the checkpointed positions
    // (an uninterrupted run has it from the previous step), and with a skin the first step
    // keeps the candidates of the search before the checkpoint (or searches again) as the
    // uninterrupted run does.
    if (searched_at_ &&
        (state.count("searched_at_skin") == 0 || state_value(state, "searched_at_skin") != skin_)) {
      // A checkpoint of code before the skin, or of another skin (whose candidates may miss
      // pairs this skin's would hold): search afresh here.
      std::copy(s_.x.data(), s_.x.data() + s_.owned(), searched_at_->data());
    }
    exchange_and_search(Search::kAtReference);
    if (contact_) {
      contact_->prune_history();  // ... and keeps those of its particles
      min_contact_distance_ = comm_.min(nl_.min_contact_distance());
    }
    global_particles_ = comm_.sum(static_cast<std::int64_t>(s_.owned()));
    auto meta = metadata("running");
    meta["resumed_from"] = opt_.resume_from;
    recorder_.result().declare([this] { record_series(); });
    recorder_.result().carry_over(opt_.previous_result, t_, meta);
    next_output_ = schedule_.first_after(t_);
    maybe_rebalance();
  }
}

template <int D, class K>
void Simulation<D, K>::prime() {
  if (bodies_) bodies_->place_owned_particles();
  run_phase(StepPhase::kAfterDrift);  // walls moved to t, their prescribed values
  step_dt_ = 0;
  exchange_and_search();
  run_phase(StepPhase::kAfterSearch);
  compute_density_and_pressure(0.0);
  apply_wall_condition();
  compute_forces();
  if (open_) apply_open_boundaries_after_forces();
  run_phase(StepPhase::kConstraints);
  if (bodies_) {
    if (contact_) {
      contact_->drift(nl_, 0.0, 1, t_, comm_);  // evaluates the initial contact forces
      contact_possible_ =
          comm_.min(nl_.min_contact_distance()) < contact_->touch_range() + 0.1 * dx_;
    }
    bodies_->update_accelerations(t_);
  }
}

template <int D, class K>
typename Simulation<D, K>::StepReport Simulation<D, K>::step() {
  // Due since the end of the last step, done now: its series and snapshot have read the
  // units' columns that a migration does not carry (those not persistent).
  if (rebalance_due_) {
    rebalance_due_ = false;
    maybe_rebalance();
  }
  const double dt = schedule_.clip(t_, dt_, next_output_);
  // Checked before the step, so the state that stops the run is still the last good one.
  substeps_ = contact_substeps(dt);  // move_bodies uses it
  if (const int n = substeps_; n > guards_.max_contact_substeps) {
    StepReport rep;
    rep.violated = true;
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "contact too stiff for the time step: k_c = %.4g, d_c = %.4g need %d contact "
                  "sub-steps of %.3e per fluid step of %.3e (guards.max_contact_substeps = "
                  "%lld) at step %lld, t = %.9g",
                  c_.contact().stiffness(), c_.contact().damping(), n, dt / n, dt,
                  static_cast<long long>(guards_.max_contact_substeps),
                  static_cast<long long>(step_), t_);
    rep.diagnosis = buf;
    return rep;
  }
  std::string why = integrate_step(dt);
  if (why.empty()) why = apply_phase_transitions();
  if (!why.empty()) {
    StepReport rep;
    rep.violated = true;
    rep.diagnosis = why;
    return rep;
  }
  const EndOfStep e = end_of_step_checks();
  StepReport rep{e.violated, e.cancel, e.interrupt, e.checkpoint, e.out_of_time, e.diagnosis};
  if (e.violated) return rep;
  if (fixed_time_step(c_) <= 0) {
    // The units' bounds may change from step to step (the elastic solid's, thesis eq. 33).
    dt_ = std::min(bound_->dt(e.max_speed, e.max_acceleration), unit_set_.max_time_step());
    if (dt_ < guards_.min_dt_fraction * dt0_) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "time step collapsed to %.3e (< %.3g x initial %.3e, guards.min_dt_fraction) "
                    "at step %lld, t = %.9g",
                    dt_, guards_.min_dt_fraction, dt0_, static_cast<long long>(step_), t_);
      rep.violated = true;
      rep.diagnosis = buf;
      return rep;
    }
  }
  if (contact_) contact_possible_ = e.min_contact_distance < contact_->touch_range() + 0.1 * dx_;
  if (step_ % kRebalanceEvery == 0) rebalance_due_ = true;
  return rep;
}

template <int D, class K>
std::string Simulation<D, K>::integrate_step(double dt) {
  step_dt_ = dt;
  {
    Timer tm(timer("integrate"));
    kick(s_, 0.5 * dt, !subcycled_elastic_);
    if (transport_) set_transport_velocity(s_, *transport_, *background_, 0.5 * dt);
    drift(s_, transport_ ? *transport_ : s_.v, dt, !subcycled_elastic_);
  }
  if (bodies_) {
    bodies_->kick(0.5 * dt, t_);  // Fuchs 2021 eq. 31
    move_bodies(dt);              // eqs. 33-36, contact substeps
  }
  t_ += dt;
  ++step_;
  run_phase(StepPhase::kAfterDrift);  // walls moved to t, their prescribed values
  bool bodies_left = false, converted = false, engulfed = false;
  if (growth_)
    if (std::string why = grow_walls(converted, engulfed); !why.empty()) return why;
  if (open_) {
    {
      Timer tm(timer(OpenBoundaries<D, K>::kName));
      // Inflows refill, outflows delete (fluid, and the parts of bodies carried out).
      if (leaving_) lost_.assign(bodies_->bodies().size(), 0);
      global_particles_ +=
          open_->exchange_particles(t_, transport_, comm_, leaving_ ? &*bodies_ : nullptr, &lost_);
    }
    if (leaving_) {
      bodies_left = std::any_of(lost_.begin(), lost_.end(), [](std::int64_t n) { return n > 0; });
      if (bodies_left)
        if (std::string why = regroup_bodies_that_left(); !why.empty()) return why;
    }
  }
  // Particles that changed kind are listed by their new kind: a fresh search.
  exchange_and_search(converted ? Search::kFresh : Search::kAsNeeded);
  if ((bodies_left || engulfed) && contact_) {
    // As after a phase transition: the rebuilt bodies' contact forces for the next step.
    Timer tc(timer(BodyContact<D>::kName));
    contact_->refresh(nl_, comm_);
  }
  run_phase(StepPhase::kAfterSearch);
  compute_density_and_pressure(dt);
  apply_wall_condition();
  compute_forces();
  if (open_) apply_open_boundaries_after_forces();
  run_phase(StepPhase::kConstraints);
  {
    Timer tm(timer("integrate"));
    kick(s_, 0.5 * dt, !subcycled_elastic_);
    if (bodies_) {
      bodies_->kick(0.5 * dt, t_);  // eq. 39
      bodies_->update_accelerations(t_);
      bodies_->update_owned_velocities();  // eq. 40
    }
  }
  run_phase(StepPhase::kEndOfStep);
  return {};
}

template <int D, class K>
void Simulation<D, K>::compute_density_and_pressure(double dt) {
  if (summation_) {
    Timer tm(timer(DensitySummation<D, K>::kName));
    summation_->run(nl_, pk_);
  } else if (continuity_ && dt > 0) {
    Timer tm(timer(ContinuityDensity<D, K>::kName));
    continuity_->run(nl_, dt);
  }
  {
    Timer tm(timer("equation_of_state"));
    apply_equation_of_state(s_, fluids_);
  }
  {
    Timer tm(timer("halo_exchange"));
    halo_.update(s_, {&s_.rho, &s_.p});
  }
  if (open_) set_open_boundary_pressure();
  run_phase(StepPhase::kDensity);
}

template <int D, class K>
void Simulation<D, K>::apply_wall_condition() {
  if (walls_) apply_wall_values();
  run_phase(StepPhase::kWallState);
}

template <int D, class K>
void Simulation<D, K>::apply_wall_values() {
  {
    Timer tm(timer(WallBoundary<D>::kName));
    walls_->run(
        nl_, pk_, fluid_body_force(t_),
        s_.has("wall_acceleration") ? &s_.template get<Vec<D>>("wall_acceleration") : nullptr);
  }
  Timer tm(timer("halo_exchange"));
  if (walls_->second_pressure())
    halo_.update(s_, {&s_.rho, &s_.p, &walls_->noslip_velocity(), &walls_->fluid_material(),
                      walls_->second_pressure(), walls_->second_fluid_material()});
  else
    halo_.update(s_, {&s_.rho, &s_.p, &walls_->noslip_velocity(), &walls_->fluid_material()});
}

template <int D, class K>
void Simulation<D, K>::compute_forces() {
  {
    // Forces accumulate: a^{n+1} starts at zero and every force unit adds to it.
    Timer tm(timer("integrate"));
    std::fill(s_.a.data(), s_.a.data() + s_.owned(), Vec<D>::Zero());
  }
  compute_fluid_forces();
  run_phase(StepPhase::kForces);
}

template <int D, class K>
void Simulation<D, K>::compute_fluid_forces() {
  Timer tm(timer("fluid_forces"));
  FluidForceInputs<D> in;
  in.fluids = &fluids_;
  in.pairs = &pk_;
  in.body = fluid_body_force(t_);
  in.wall_volume = wall_volume_;
  in.h = h_;
  in.alpha = c_.fluid_model().artificial_viscosity();
  if (walls_) {
    in.noslip = &walls_->noslip_velocity();
    in.wall_fluid = &walls_->fluid_material();
    in.wall_p2 = walls_->second_pressure();
    in.wall_fluid2 = walls_->second_fluid_material();
  }
  in.free_slip = free_slip_;
  in.transport = transport_;
  in.background = background_;
  forces_->run(s_, nl_, kernel_, in);
  if (bodies_) {
    Timer tc(timer("rigid_coupling"));
    in.rigid_force = &bodies_->fluid_force();
    in.rigid_lever = &bodies_->spin_lever();
    forces_->run_coupling(s_, nl_, kernel_, in);
    bodies_->reduce_fluid_forces(comm_);
    in.rigid_force = nullptr;
  }
  if (elastic_force_) {
    Timer tc(timer("elastic_coupling"));
    in.elastic_force = elastic_force_;
    forces_->run_coupling(s_, nl_, kernel_, in);
  }
}

template <int D, class K>
void Simulation<D, K>::move_bodies(double dt) {
  Timer tm(timer(RigidBodies<D>::kName));
  if (contact_) {
    Timer tc(timer(BodyContact<D>::kName));
    // Substep only when bodies may touch during this step; otherwise one drift.
    contact_->drift(nl_, dt, substeps_, t_ + dt, comm_);
  } else {
    bodies_->drift(dt, t_ + dt);
  }
  bodies_->place_owned_particles();
}

template <int D, class K>
int Simulation<D, K>::contact_substeps(double dt) const {
  if (!contact_ || !contact_possible_) return 1;
  const double factor = c_.time().has_cfl_factor() ? c_.time().cfl_factor() : 1.0;
  const double n = std::ceil(dt / (factor * contact_->time_step(min_rigid_mass_)));
  return n > 2e9 ? std::numeric_limits<int>::max() : std::max(1, static_cast<int>(n));
}

template <int D, class K>
std::string Simulation<D, K>::apply_phase_transitions() {
  if (!phase_) return {};
  typename PhaseTransitions<D>::Outcome out;
  {
    Timer tm(timer(PhaseTransitions<D>::kName));
    out = phase_->run(s_, nl_, *bodies_, temperature_, concentration_, transport_,
                      fluid_body_force(t_), step_, comm_);
  }
  if (!out.error.empty()) {
    char buf[120];
    std::snprintf(buf, sizeof buf, " at step %lld, t = %.9g", static_cast<long long>(step_), t_);
    return out.error + buf;
  }
  if (out.melted + out.solidified + out.touching > 0) {  // all ranks: the counts are global
    // Particles changed kind and body after this step's search: the ghosts and the contact
    // candidates are those of before (a melted particle would push its old neighbours as a
    // wall, a merged body would keep contacts within itself), so refresh the ghosts and sort
    // the candidates again by kind (search again, without a skin), and evaluate the rebuilt
    // bodies' contact forces for the next step's first contact kick.
    exchange_and_search(Search::kKindsChanged);
    if (contact_) {
      Timer tc(timer(BodyContact<D>::kName));
      contact_->refresh(nl_, comm_);
    }
    bodies_->update_accelerations(t_);  // the rebuilt bodies' own forces
  }
  return {};
}

template <int D, class K>
std::string Simulation<D, K>::grow_walls(bool& converted, bool& engulfed) {
  Timer tm(timer(WallGrowth<D>::kName));
  typename WallGrowth<D>::Columns cols;
  cols.wall_index = wall_index_;
  cols.free_slip = free_slip_;
  cols.transport = transport_;
  cols.background = background_;
  if (s_.has("wall_acceleration")) cols.wall_accel = &s_.template get<Vec<D>>("wall_acceleration");
  if (open_) cols.open_zone = &open_->zone();
  const auto out = growth_->run(s_, cols, bodies_ ? &*bodies_ : nullptr, t_, comm_);
  converted = out.grown + out.engulfed > 0;
  engulfed = out.engulfed > 0;
  if (!out.error.empty()) {
    char buf[120];
    std::snprintf(buf, sizeof buf, " at step %lld, t = %.9g", static_cast<long long>(step_), t_);
    return out.error + buf;
  }
  return {};
}

// `lost_` (summed over the ranks) names the bodies that lost particles at an outlet.
template <int D, class K>
std::string Simulation<D, K>::regroup_bodies_that_left() {
  Timer tm(timer(RigidBodies<D>::kName));
  std::string error = leaving_->run(s_, *bodies_, lost_, comm_);
  if (!error.empty()) {
    char buf[120];
    std::snprintf(buf, sizeof buf, " at step %lld, t = %.9g", static_cast<long long>(step_), t_);
    return error + buf;
  }
  return {};
}

// Buffer pressures from the fluid's, then the ghosts' copies.
template <int D, class K>
void Simulation<D, K>::set_open_boundary_pressure() {
  {
    Timer tm(timer(OpenBoundaries<D, K>::kName));
    open_->set_pressure(nl_, grid_, halo_.my_box(), fluid_body_force(t_), comm_);
  }
  Timer tm(timer("halo_exchange"));
  halo_.update(s_, {&s_.rho, &s_.p});
}

template <int D, class K>
void Simulation<D, K>::apply_open_boundaries_after_forces() {
  Timer tm(timer(OpenBoundaries<D, K>::kName));
  open_->after_forces(nl_, grid_, halo_.my_box(), walls_ ? &walls_->noslip_velocity() : nullptr,
                      free_slip_, background_, temperature_, concentration_, fluid_body_force(t_),
                      comm_);
}

template <int D, class K>
Vec<D> Simulation<D, K>::fluid_body_force(double t) const {
  return body_ ? body_->at(t) : Vec<D>::Zero();
}

template <int D, class K>
typename Simulation<D, K>::EndOfStep Simulation<D, K>::end_of_step_checks() {
  Timer tm(timer("stability_guards"));
  const auto vmax_dom = detail::to_vec<D>(c_.domain().hi());
  const auto vmin_dom = detail::to_vec<D>(c_.domain().lo());
  GuardScan<D> scan =
      scan_particles<D>(s_, fluids_, mats_, guards_, vmin_dom, vmax_dom, grid_.periodic, step_, t_);
  // The units' own guards (a scalar overflowing past its time-step bound, ...).
  if (scan.violation.empty() && !unit_set_.empty()) {
    const StepContext<D> ctx = context(step_dt_);
    for (const auto& u : unit_set_.units())
      if (scan.violation.empty()) scan.violation = u->check(ctx);
  }
  SolidFractionScan solid;
  if (walls_) {
    solid = scan_solid_fraction();
    if (scan.violation.empty() && solid.max > guards_.max_solid_fraction) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "fluid inside a wall or body: solid fraction %.3f of its kernel support "
                    "exceeds %.3g (guards.max_solid_fraction)",
                    solid.max, guards_.max_solid_fraction);
      scan.violation = buf + describe_particle(s_, mats_, solid.worst, step_, t_);
    }
  }
  std::vector<double> r = {
      scan.max_speed,
      scan.max_acceleration,
      scan.max_density_dev,
      scan.violation.empty() ? 0.0 : 1.0,
      comm_.root() && opt_.cancel_requested && opt_.cancel_requested() ? 1.0 : 0.0,
      opt_.interrupt && opt_.interrupt->load() ? 1.0 : 0.0,
      comm_.root() && recorder_.checkpoint_due(c_.output().checkpoint_wall_interval()) ? 1.0 : 0.0,
      comm_.root() && c_.stop().max_wall_seconds() > 0 &&
              recorder_.wall_seconds() >= c_.stop().max_wall_seconds()
          ? 1.0
          : 0.0,
      -nl_.min_contact_distance(),
      solid.max};
  const double t0 = MPI_Wtime();
  comm_.max_inplace(r);
  comm_seconds_ += MPI_Wtime() - t0;
  EndOfStep e;
  e.max_speed = r[0];
  e.max_acceleration = r[1];
  e.max_density_dev = r[2];
  e.violated = r[3] > 0;
  e.cancel = r[4] > 0;
  e.interrupt = r[5] > 0;
  e.checkpoint = r[6] > 0;
  e.out_of_time = r[7] > 0;
  e.min_contact_distance = -r[8];
  solid_fraction_ = r[9];
  min_contact_distance_ = e.min_contact_distance;
  if (e.violated) e.diagnosis = comm_.first_non_empty(scan.violation);
  return e;
}

template <int D, class K>
SolidFractionScan Simulation<D, K>::scan_solid_fraction() {
  return solid_fraction<D>(s_, nl_, pk_, wall_volume_, wall_index_ ? wall_index_->data() : nullptr,
                           bodies_ ? bodies_->body_index().data() : nullptr);
}

}  // namespace sph

#include "solver/run/simulation_search_impl.h"
#include "solver/run/simulation_series_impl.h"
#include "solver/run/simulation_wiring_impl.h"
