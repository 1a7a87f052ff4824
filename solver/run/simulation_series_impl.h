#pragma once
// Simulation<D, K>: what a run records. Every series of the result file is named once, in
// record_series() and the functions it calls (and in the seam units' sample()); snapshots,
// checkpoints, progress and metadata go through the RunRecorder.
// Included only by simulation_impl.h.

namespace sph {

template <int D, class K>
void Simulation<D, K>::sample_series() {
  record_series();
  next_series_ = t_ + schedule_.series_interval();
}

// Every series of the result file, named here (or in a unit's sample()) and nowhere else:
// start() runs this once in ResultFile::declare to declare them.
template <int D, class K>
void Simulation<D, K>::record_series() {
  Timer tm(timer("diagnostics"));
  const Vec<D> g = fluid_gravity_ && c_.has_gravity()
                       ? detail::to_vec<D>(c_.gravity().acceleration())
                       : Vec<D>::Zero();
  const ConservationSample<D> cs = conservation(s_, fluids_, g, comm_);
  // One reduction for the extremes: [dev, vmax, -min_0.., max_0..].
  std::vector<double> ext(2 + 2 * D, -std::numeric_limits<double>::infinity());
  ext[0] = ext[1] = 0.0;
  std::size_t worst = s_.owned();  // the owned fluid particle of the largest deviation
  for (std::size_t i = 0; i < s_.owned(); ++i) {
    if (s_.kind[i] != Kind::kFluid) continue;
    const double dev_i = std::abs(s_.rho[i] * fluids_[s_.material[i]].inv_rho0 - 1.0);
    if (worst == s_.owned() || dev_i > ext[0] || (dev_i == ext[0] && s_.id[i] < s_.id[worst]))
      worst = i;
    ext[0] = std::max(ext[0], dev_i);
    ext[1] = std::max(ext[1], s_.v[i].norm());
    for (int a = 0; a < D; ++a) {
      ext[2 + static_cast<size_t>(a)] = std::max(ext[2 + static_cast<size_t>(a)], -s_.x[i][a]);
      ext[2 + D + static_cast<size_t>(a)] =
          std::max(ext[2 + D + static_cast<size_t>(a)], s_.x[i][a]);
    }
  }
  const double local_dev = ext[0];
  comm_.max_inplace(ext);
  const double dev = ext[0], vmax = ext[1];
  // Where the largest deviation sits (a particle squeezed in a closing gap, the start of a
  // blow-up); ties go to the smallest global id, so the answer is the same for any rank count.
  const double inf = std::numeric_limits<double>::infinity();
  const double my_id =
      worst < s_.owned() && local_dev == dev ? static_cast<double>(s_.id[worst]) : inf;
  const double worst_id = comm_.min(my_id);
  std::vector<double> worst_at(D, -inf);
  if (my_id == worst_id && my_id < inf)
    for (int a = 0; a < D; ++a) worst_at[static_cast<size_t>(a)] = s_.x[worst][a];
  comm_.max_inplace(worst_at);
  if (worst_id == inf) worst_at.assign(D, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> fmin(D), fmax(D);
  for (int a = 0; a < D; ++a) {
    fmin[static_cast<size_t>(a)] = -ext[2 + static_cast<size_t>(a)];
    fmax[static_cast<size_t>(a)] = ext[2 + D + static_cast<size_t>(a)];
  }
  const std::vector<std::uint64_t> dd = {static_cast<std::uint64_t>(D)};
  // Bounding box of the fluid (e.g. the surge front of a dam break).
  recorder_.result().put("diagnostics/fluid_min", fmin, dd);
  recorder_.result().put("diagnostics/fluid_max", fmax, dd);
  auto put = [&](const char* n, double v) {
    recorder_.result().put(std::string("diagnostics/") + n, v);
  };
  put("time", t_);
  put("step", static_cast<double>(step_));
  put("dt", dt_);
  put("mass", cs.mass);
  put("kinetic_energy", cs.kinetic);
  put("potential_energy", cs.potential);
  put("elastic_energy", cs.elastic);
  put("max_density_deviation", dev);
  recorder_.result().put("diagnostics/max_density_deviation_at", worst_at, dd);
  put("max_speed", vmax);
  put("imbalance", imbalance_);
  put("fluid_particles", cs.fluid_particles);
  put("neighbor_searches", static_cast<double>(searches_));
  if (walls_) put("max_solid_fraction", solid_fraction_);
  if (contact_) put("min_contact_distance", min_contact_distance_);
  if (phases_) {
    const PhaseMixingScan mix = phase_mixing<D>(s_, nl_, pk_, kernel_.W(0.0), wall_volume_);
    put("interface_particles",
        static_cast<double>(comm_.sum(static_cast<std::int64_t>(mix.interface))));
    put("stray_phase_particles",
        static_cast<double>(comm_.sum(static_cast<std::int64_t>(mix.stray))));
  }
  recorder_.result().put("diagnostics/momentum",
                         std::vector<double>(cs.momentum.data(), cs.momentum.data() + D), dd);
  if (bodies_) sample_bodies();
  if (growth_) {
    recorder_.result().put("wall_growth/time", t_);
    for (std::size_t k = 0; k < growth_->size(); ++k) {
      const std::string base = "wall_growth/" + growth_->name(k) + "/";
      recorder_.result().put(base + "front", growth_->front(k, t_));
      recorder_.result().put(base + "particles", static_cast<double>(growth_->grown_particles(k)));
      recorder_.result().put(base + "mass", growth_->grown_mass(k));
    }
    recorder_.result().put("wall_growth/engulfed_bodies",
                           static_cast<double>(growth_->engulfed_bodies()));
  }
  if (open_) {
    recorder_.result().put("open_boundaries/time", t_);
    for (std::size_t b = 0; b < open_->zones().size(); ++b)
      recorder_.result().put("open_boundaries/" + open_->zones()[b].name(),
                             static_cast<double>(open_->through()[b]));
  }
  if (!unit_set_.empty()) {
    const StepContext<D> ctx = context(dt_);
    for (const auto& u : unit_set_.units()) u->sample(recorder_.result(), ctx);
  }
  if (probes_) {
    Timer tp(timer(Probes<D, K>::kName));
    const auto values = probes_->sample(s_, nl_, grid_, halo_.my_box(), comm_);
    for (std::size_t k = 0; k < probes_->sets().size(); ++k) {
      const std::string base = "probes/" + probes_->sets()[k].name + "/";
      std::vector<double> pr, rh, ve;
      const auto& v = values[k];
      for (std::size_t p = 0; p < probes_->sets()[k].points.size(); ++p) {
        const std::size_t o = p * Probes<D, K>::kValues;
        pr.push_back(v[o]);
        rh.push_back(v[o + 1]);
        for (int a = 0; a < D; ++a) ve.push_back(v[o + 2 + static_cast<size_t>(a)]);
      }
      const auto n = static_cast<std::uint64_t>(probes_->sets()[k].points.size());
      recorder_.result().put(base + "time", t_);
      recorder_.result().put(base + "pressure", pr, {n});
      recorder_.result().put(base + "density", rh, {n});
      recorder_.result().put(base + "velocity", ve, {n, static_cast<std::uint64_t>(D)});
    }
  }
}

template <int D, class K>
void Simulation<D, K>::sample_bodies() {
  std::vector<double> pos, vel, w, q, ff, ft, cf, ct, n, ke, mass, inertia, serial;
  // Fixed width: slots of bodies not born yet (phase transitions) or gone are NaN.
  std::vector<RigidBody<D>> padded;
  const std::vector<RigidBody<D>>* list = &bodies_->bodies();
  if (phase_ || leaving_ || growth_) {
    padded = bodies_->bodies();
    RigidBody<D> none;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    none.mass = none.body_force_factor = nan;
    none.com.setConstant(nan);
    none.velocity.setConstant(nan);
    none.omega.setConstant(nan);
    none.inertia_body.setConstant(nan);
    for (RigidBody<D>& b : padded)
      if (!b.active()) b = none;
    padded.resize(body_slots_, none);
    list = &padded;
  }
  for (const RigidBody<D>& b : *list) {
    for (int a = 0; a < D; ++a) {
      pos.push_back(b.com[a]);
      vel.push_back(b.velocity[a]);
      ff.push_back(b.fluid_force[a]);
      cf.push_back(b.contact_force[a]);
    }
    for (int a = 0; a < RigidBodies<D>::A; ++a) {
      w.push_back(b.omega[a]);
      ft.push_back(b.fluid_torque[a]);
      ct.push_back(b.contact_torque[a]);
    }
    if constexpr (D == 2)
      q.push_back(b.orientation.angle);
    else
      for (int a = 0; a < 4; ++a) q.push_back(b.orientation.q.coeffs()[a]);  // x, y, z, w
    n.push_back(static_cast<double>(b.contacts));
    ke.push_back(b.kinetic_energy());
    mass.push_back(b.mass);
    serial.push_back(b.active() || (!phase_ && !leaving_ && !growth_)
                         ? static_cast<double>(b.serial)
                         : std::numeric_limits<double>::quiet_NaN());
    for (int p = 0; p < RigidBodies<D>::A; ++p)
      for (int r = 0; r < RigidBodies<D>::A; ++r) inertia.push_back(b.inertia_body(p, r));
  }
  const auto nb = static_cast<std::uint64_t>(list->size());
  const std::uint64_t dd = D, aa = RigidBodies<D>::A;
  recorder_.result().put("bodies/time", t_);
  recorder_.result().put("bodies/position", pos, {nb, dd});
  recorder_.result().put("bodies/velocity", vel, {nb, dd});
  recorder_.result().put("bodies/angular_velocity", w, {nb, aa});
  recorder_.result().put("bodies/orientation", q, {nb, D == 2 ? 1u : 4u});
  recorder_.result().put("bodies/fluid_force", ff, {nb, dd});
  recorder_.result().put("bodies/fluid_torque", ft, {nb, aa});
  recorder_.result().put("bodies/contact_force", cf, {nb, dd});
  recorder_.result().put("bodies/contact_torque", ct, {nb, aa});
  recorder_.result().put("bodies/contacts", n, {nb});
  recorder_.result().put("bodies/kinetic_energy", ke, {nb});
  recorder_.result().put("bodies/mass", mass, {nb});
  // Which body fills each slot (RigidBody::serial; NaN while empty): melting empties slots
  // and later bodies take them.
  recorder_.result().put("bodies/serial", serial, {nb});
  recorder_.result().put("bodies/inertia", inertia,
                         {nb, aa * aa});  // body frame, about the centre of mass
  if (phase_) {
    std::int64_t active = 0;
    for (const RigidBody<D>& b : bodies_->bodies()) active += b.active() ? 1 : 0;
    recorder_.result().put("phase/melted", static_cast<double>(phase_->melted_total()));
    recorder_.result().put("phase/solidified", static_cast<double>(phase_->solidified_total()));
    recorder_.result().put("phase/active_bodies", static_cast<double>(active));
    recorder_.result().put("phase/reversals", static_cast<double>(phase_->reversals_total()));
    recorder_.result().put("phase/shortest_reversal_steps",
                           static_cast<double>(phase_->shortest_reversal()));
    recorder_.result().put("phase/merged_bodies", static_cast<double>(phase_->merged_total()));
  }
}

template <int D, class K>
void Simulation<D, K>::write_snapshot() {
  Timer tm(timer("output"));
  recorder_.write_snapshot(s_, t_, step_);
}

template <int D, class K>
std::string Simulation<D, K>::write_checkpoint_now() {
  Timer tm(timer("output"));
  CheckpointState state = {{"time", t_},
                           {"step", static_cast<double>(step_)},
                           {"dt", dt_},
                           {"dt0", dt0_},
                           {"next_series", next_series_},
                           {"contact_possible", contact_possible_ ? 1.0 : 0.0}};
  // The particles carry the positions searched at, and a resume lists the candidates within
  // this skin of them.
  if (searched_at_) state["searched_at_skin"] = skin_;
  state["neighbor_searches"] = static_cast<double>(searches_);
  if (bodies_) bodies_->save(state);
  if (contact_) contact_->save(state, comm_);
  if (open_) open_->save(state);
  if (phase_) phase_->save(state);
  if (growth_) growth_->save(state);
  for (const auto& u : unit_set_.units()) u->save(state);
  return recorder_.write_checkpoint(s_, state, step_, t_);
}

template <int D, class K>
void Simulation<D, K>::report_progress(bool force) {
  Progress p;
  p.step = step_;
  p.time = t_;
  p.end_time = schedule_.end_time();
  p.dt = dt_;
  p.particles = global_particles_;
  p.ranks = comm_.size();
  p.imbalance = imbalance_;
  recorder_.report_progress(p, force);
}

template <int D, class K>
std::map<std::string, std::string> Simulation<D, K>::metadata(const std::string& status) const {
  auto m = recorder_.metadata(opt_.case_text.empty() ? c_.DebugString() : std::string(), D, dx_, h_,
                              skin_, K::kSupport == 3.0 ? "quintic_spline" : "wendland_c2", units_);
  // The storage the case chose or was given by default (case/estimate.h pair_kernel_storage()).
  const v1::PairKernelStorage storage = pair_kernel_storage(c_);
  m["pair_kernel_storage"] = storage == v1::PAIR_KERNEL_STREAM  ? "stream"
                             : storage == v1::PAIR_KERNEL_TABLE ? "table"
                                                                : "compact";
  if (bodies_) {
    std::string names;
    for (const auto& b : bodies_->bodies()) names += (names.empty() ? "" : ",") + b.name;
    m["body_names"] = names;
  }
  m["status"] = status;
  return m;
}

}  // namespace sph
