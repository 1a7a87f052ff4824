#pragma once
// Simulation<D, K>: the case wired into units and particles. Which units a case builds, the
// columns they add, their time-step bounds, the fields they write, the scene's particles
// with their initial values, and what each unit's storage costs. A new unit on the seam is
// wired in solver/run/unit_set.cc instead (build_seam_units).
// Included only by simulation_impl.h.

namespace sph {

template <int D, class K>
void Simulation<D, K>::build_units() {
  const auto& fm = c_.fluid_model();
  units_.push_back("halo_exchange");
  units_.push_back("neighbor_search");
  if (skin_ > 0) {
    searched_at_ = &s_.template add<Vec<D>>("searched_at", "neighbor_search", true);
    searched_at_->set_ghost(false);
    // Checkpoints of code before the skin lack it; start() then searches afresh.
    searched_at_->set_zero_if_absent(true);
  }
  units_.push_back("pair_kernel");
  if (fm.density() == v1::CONTINUITY) {
    units_.push_back(ContinuityDensity<D, K>::kName);
  } else {
    summation_.emplace(s_, kernel_);
    units_.push_back(DensitySummation<D, K>::kName);
  }
  units_.push_back("equation_of_state");
  const bool tvf = fm.transport_velocity();
  if (tvf) {
    transport_ = &s_.template add<Vec<D>>("transport_velocity", "transport_velocity", true);
    background_ = &s_.template add<Vec<D>>("background_acceleration", "transport_velocity", true);
    background_->set_ghost(false);
    units_.push_back("transport_velocity");
  }
  if (fm.density() == v1::CONTINUITY)
    continuity_.emplace(s_, kernel_, wall_volume_, tvf ? *transport_ : s_.v);
  if (c_.walls_size() > 0) {
    wall_index_ = &s_.template add<std::uint16_t>("wall_index", "walls", true);
    walls_.emplace(s_, fluids_);
    units_.push_back(WallBoundary<D>::kName);
    bool any_slip = false;
    for (const auto& w : c_.walls()) any_slip = any_slip || w.free_slip();
    if (any_slip) {
      free_slip_ = &s_.template add<std::uint8_t>("wall_free_slip", WallBoundary<D>::kName, true);
    }
  }
  if (c_.bodies_size() > 0 || c_.phase_transitions_size() > 0) {
    std::vector<double> rho_s, rho_f;
    for (const auto& b : c_.bodies()) {
      rho_s.push_back(mats_[static_cast<size_t>(material_index(mats_, b.material()))].rho0);
      const int f = b.buoyancy_fluid().empty() ? -1 : material_index(mats_, b.buoyancy_fluid());
      rho_f.push_back(f < 0 ? 0.0 : mats_[static_cast<size_t>(f)].rho0);
      const double m = rho_s.back() * wall_volume_;
      min_rigid_mass_ = min_rigid_mass_ == 0 ? m : std::min(min_rigid_mass_, m);
    }
    // Particles that solidify keep their fluid mass.
    for (const auto& pt : c_.phase_transitions()) {
      const double m = mats_[static_cast<size_t>(material_index(mats_, pt.fluid_material()))].rho0 *
                       wall_volume_;
      min_rigid_mass_ = min_rigid_mass_ == 0 ? m : std::min(min_rigid_mass_, m);
    }
    bodies_.emplace(s_, c_, rho_s, rho_f);
    if (c_.has_gravity())
      bodies_->set_gravity(detail::to_vec<D>(c_.gravity().acceleration()),
                           c_.gravity().damping_time());
    units_.push_back(RigidBodies<D>::kName);
    units_.push_back("rigid_coupling");
    if (!walls_) {  // rigid particles use the wall condition too
      walls_.emplace(s_, fluids_);
      units_.push_back(WallBoundary<D>::kName);
    }
    if (c_.has_contact()) {
      const auto& k = c_.contact();
      const bool walls = !k.has_with_walls() || k.with_walls();
      if (k.model() == v1::RESTITUTION) {
        contact_ = std::make_unique<RestitutionContact<D>>(
            s_, *bodies_, k.restitution(), k.friction().coefficient(), dx_, walls, wall_index_);
      } else {
        ParticleContactLaw law;
        law.stiffness = k.stiffness();
        law.damping = k.damping();
        if (k.model() == v1::REPULSIVE) {
          law.repulsion_strength = k.repulsion().strength();
          law.repulsion_range = k.repulsion().range();
        } else if (k.has_restitution()) {
          law.damping_ratio = damping_ratio_for_restitution(k.restitution());
        }
        law.friction = k.friction().coefficient();
        law.tangential_stiffness = k.has_friction() ? k.friction().tangential_stiffness() : 0.0;
        contact_ = std::make_unique<SpringDashpotContact<D>>(s_, *bodies_, law, dx_, walls);
      }
      units_.push_back(BodyContact<D>::kName);
    }
  }
  if (c_.elastic_bodies_size() > 0) {
    units_.push_back("elastic_coupling");
    if (!walls_) {  // elastic particles are moving walls to the fluid (thesis sec. 2.5)
      walls_.emplace(s_, fluids_);
      units_.push_back(WallBoundary<D>::kName);
    }
  }
  bool viscous = false;
  double c_max = 0, nu_max = 0;
  for (const auto& f : fluids_) {
    if (!f.fluid) continue;
    viscous = viscous || f.eta > 0;
    c_max = std::max(c_max, f.c);
  }
  for (const auto& m : mats_)
    if (m.fluid) nu_max = std::max(nu_max, m.nu());
  const double alpha = fm.artificial_viscosity();
  // Artificial viscosity as an equivalent kinematic viscosity (Adami 2012 eq. 12).
  nu_max = std::max(nu_max, alpha * h_ * c_max / (2.0 * (D + 2)));
  forces_.emplace(viscous, alpha > 0, tvf);
  units_.push_back(std::string(FluidForces<D, K>::kName) + "[pressure" +
                   (viscous ? "+viscous" : "") + (alpha > 0 ? "+artificial_viscosity" : "") +
                   (tvf ? "+transport_velocity" : "") + "]");
  Vec<D> g = Vec<D>::Zero();
  double t_damp = 0;
  fluid_gravity_ =
      !c_.has_gravity() || !c_.gravity().has_apply_to_fluid() || c_.gravity().apply_to_fluid();
  if (c_.has_gravity() && fluid_gravity_) {
    g = detail::to_vec<D>(c_.gravity().acceleration());
    t_damp = c_.gravity().damping_time();
  }
  const Vec<D> f = detail::to_vec<D>(c_.body_force());
  if (!g.isZero() || !f.isZero()) {
    body_.emplace(g, t_damp, f);
    units_.push_back("body_force");
  }
  const double factor = c_.time().has_cfl_factor() ? c_.time().cfl_factor() : 1.0;
  bound_.emplace(h_, factor, c_max, nu_max, body_ ? body_->max_magnitude() : 0.0);
  build_phase_transitions();
  build_open_boundaries();
  build_wall_growth();
  build_seam_units();
  if (c_.probes_size() > 0) {
    std::vector<ProbeSet<D>> sets;
    for (const auto& p : c_.probes()) {
      ProbeSet<D> set;
      set.name = p.name();
      const Vec<D> a = detail::to_vec<D>(p.position()), b = detail::to_vec<D>(p.line_end());
      const int n = std::max(1, p.count());
      for (int k = 0; k < n; ++k)
        set.points.push_back(n == 1 ? a : Vec<D>(a + (b - a) * (double(k) / (n - 1))));
      sets.push_back(std::move(set));
    }
    probes_.emplace(std::move(sets), kernel_);
    units_.push_back(Probes<D, K>::kName);
  }
  phases_ = std::count_if(fluids_.begin(), fluids_.end(),
                          [](const FluidConstants& fl) { return fl.fluid; }) > 1;
  if (bodies_) {
    body_slots_ = phase_ ? phase_->max_bodies() : static_cast<std::size_t>(c_.bodies_size());
    recorder_.result().add_field(bodies_->body_index());
  }
}

template <int D, class K>
void Simulation<D, K>::build_seam_units() {
  const UnitBuildContext<D> b{c_,
                              mats_,
                              fluids_,
                              s_,
                              dx_,
                              h_,
                              wall_volume_,
                              kernel_.W(0.0),
                              c_.time().has_cfl_factor() ? c_.time().cfl_factor() : 1.0,
                              wall_index_,
                              body_ ? &*body_ : nullptr};
  unit_set_ = UnitSet<D>(make_units<D>(b));
  for (const auto& u : unit_set_.units()) {
    units_.push_back(u->name());
    u->declare_output(recorder_.result());
  }
  bound_->add_limit(unit_set_.max_time_step());
  // Written by the fluid-solid coupling, read by the elastic unit (solver/elastic/).
  if (s_.has("elastic_fluid_force"))
    elastic_force_ = &s_.template get<Vec<D>>("elastic_fluid_force");
  subcycled_elastic_ = c_.elastic_bodies_size() > 0 &&
                       (c_.time().subcycle_elastic_bodies() || c_.time().has_quasi_static());
  if (s_.has("temperature")) temperature_ = &s_.template get<double>("temperature");
  if (s_.has("concentration")) concentration_ = &s_.template get<double>("concentration");
}

template <int D, class K>
void Simulation<D, K>::build_phase_transitions() {
  if (c_.phase_transitions_size() == 0) return;
  std::vector<PhaseRule> rules;
  std::size_t slots = 0;
  for (const auto& pt : c_.phase_transitions()) {
    PhaseRule r;
    r.solid = static_cast<std::uint16_t>(material_index(mats_, pt.solid_material()));
    r.fluid = static_cast<std::uint16_t>(material_index(mats_, pt.fluid_material()));
    r.fluid_rho0 = mats_[r.fluid].rho0;
    r.temperature = pt.driver() == v1::TEMPERATURE;
    // The hysteresis band is centred on the transition value: no flicker inside it.
    r.melt_above = pt.transition_value() + 0.5 * pt.hysteresis();
    r.freeze_below = pt.transition_value() - 0.5 * pt.hysteresis();
    r.reversible = pt.reversible();
    r.join_radius = pt.has_join_radius() ? pt.join_radius() : 1.5 * dx_;
    r.merge_bodies = pt.merge_bodies();
    rules.push_back(r);
    slots =
        std::max(slots, pt.has_max_bodies() ? static_cast<std::size_t>(pt.max_bodies())
                                            : 2 * static_cast<std::size_t>(c_.bodies_size()) + 64);
  }
  phase_.emplace(s_, std::move(rules), slots, dx_);
  units_.push_back(PhaseTransitions<D>::kName);
}

template <int D, class K>
void Simulation<D, K>::build_wall_growth() {
  const auto& walls = c_.walls();
  if (std::none_of(walls.begin(), walls.end(),
                   [](const v1::Wall& w) { return w.has_growth_speed(); }))
    return;
  growth_.emplace(c_, mats_, dx_, grid_.periodic, grid_.length);
  bound_->add_limit(growth_->max_time_step());
  units_.push_back(WallGrowth<D>::kName);
}

template <int D, class K>
void Simulation<D, K>::build_open_boundaries() {
  if (c_.open_boundaries_size() == 0) return;
  std::vector<OpenBoundaryZone<D>> zones;
  for (int b = 0; b < c_.open_boundaries_size(); ++b) {
    const int m = material_index(mats_, c_.open_boundaries(b).material());
    zones.emplace_back(c_, b, static_cast<std::uint16_t>(m), mats_[static_cast<size_t>(m)].rho0);
  }
  open_.emplace(s_, kernel_, std::move(zones), fluids_, wall_volume_);
  units_.push_back(OpenBoundaries<D, K>::kName);
  recorder_.result().add_field(open_->zone());
  const bool outflow = std::any_of(open_->zones().begin(), open_->zones().end(),
                                   [](const OpenBoundaryZone<D>& z) { return !z.inflow(); });
  // Free bodies lose the particles carried out; what remains stays one body.
  if (bodies_ && outflow) leaving_.emplace(BodyRegrouping<D>::whole_bodies(dx_));
}

template <int D, class K>
void Simulation<D, K>::build_scene() {
  SceneBuilder scene(c_, mats_);
  // Pass 1: every rank counts the particles per cell of the whole scene (no communication:
  // the generation is deterministic), and all compute the same decomposition.
  std::vector<std::int64_t> counts(static_cast<size_t>(grid_.total()), 0);
  scene.for_each([&](const SceneParticle& p) {
    counts[static_cast<size_t>(
        grid_.linear(grid_.canonical(grid_.coord(detail::to_vec<D>(p.x)))))] += work_weight(p.kind);
  });
  halo_.set_decomposition(Decomposition<D>(grid_, comm_.size(), counts));
  // Pass 2: keep the particles of this rank's cells; ids are global generation indices.
  const CellBox<D> mine = halo_.my_box();
  ParticleId next_id = 0;
  std::vector<SceneParticle> kept;
  std::vector<ParticleId> ids;
  scene.for_each([&](const SceneParticle& p) {
    const ParticleId id = next_id++;
    if (!mine.contains(grid_.canonical(grid_.coord(detail::to_vec<D>(p.x))))) return;
    kept.push_back(p);
    ids.push_back(id);
  });
  global_particles_ = next_id;
  s_.resize(kept.size(), kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const SceneParticle& p = kept[i];
    s_.x[i] = detail::to_vec<D>(p.x);
    s_.v[i] = detail::to_vec<D>(p.v);
    s_.a[i] = Vec<D>::Zero();
    s_.rho[i] = p.rho;
    s_.p[i] = 0;
    s_.m[i] = p.mass;
    s_.kind[i] = p.kind;
    s_.material[i] = p.material;
    s_.id[i] = ids[i];
    if (transport_) (*transport_)[i] = s_.v[i];
    if (background_) (*background_)[i] = Vec<D>::Zero();
    if (wall_index_) (*wall_index_)[i] = p.wall;
    for (const auto& u : unit_set_.units()) u->initialize(i, p);
    if (free_slip_)
      (*free_slip_)[i] = p.kind == Kind::kWall && c_.walls(p.wall).free_slip() ? 1 : 0;
    if (bodies_) bodies_->body_index()[i] = p.body;
    if (open_) open_->zone()[i] = p.open >= 0 ? static_cast<std::uint8_t>(p.open + 1) : 0;
  }
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (s_.kind[i] == Kind::kFluid) s_.p[i] = fluids_[s_.material[i]].pressure(s_.rho[i]);
  if (open_) {
    open_->ledger().set_next_id(next_id);
    open_->set_prescribed_velocities(t_, transport_);
  }
}

template <int D, class K>
std::map<std::string, std::size_t> Simulation<D, K>::memory_by_owner() const {
  auto m = s_.memory_by_owner();
  m["neighbor_search"] += nl_.bytes();
  m["pair_kernel"] += pk_.bytes();
  // Units' scratch arrays (their columns are counted with the store).
  if (forces_) m[FluidForces<D, K>::kName] += forces_->bytes();
  if (continuity_) m[ContinuityDensity<D, K>::kName] += continuity_->bytes();
  for (const auto& u : unit_set_.units()) m[u->name()] += u->scratch_bytes();
  return m;
}

}  // namespace sph
