#pragma once
// Implementation of Simulation<D, K> (included by simulation.h; instantiated in
// simulation_2d.cc and simulation_3d.cc).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

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
      rc_(K::kSupport * h_),
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
      result_(comm, opt.output_dir) {
  const auto& g = c.guards();
  if (g.has_max_density_deviation()) guards_.max_density_deviation = g.max_density_deviation();
  if (g.has_min_dt_fraction()) guards_.min_dt_fraction = g.min_dt_fraction();
  if (g.has_max_mach()) guards_.max_mach = g.max_mach();
  if (g.has_max_solid_fraction()) guards_.max_solid_fraction = g.max_solid_fraction();
  if (g.has_max_contact_substeps()) guards_.max_contact_substeps = g.max_contact_substeps();
  build_units();
}

template <int D, class K>
Vec<D> Simulation<D, K>::fluid_body_force(double t) const {
  return body_ ? body_->at(t) : Vec<D>::Zero();
}

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
    bool any_slip = false, any_motion = false;
    std::vector<MotionPath> paths;
    for (const auto& w : c_.walls()) {
      any_slip = any_slip || w.free_slip();
      paths.emplace_back(w.motion(), D);
      any_motion = any_motion || !paths.back().is_static();
    }
    if (any_slip) {
      free_slip_ = &s_.template add<std::uint8_t>("wall_free_slip", WallBoundary<D>::kName, true);
    }
    if (any_motion) {
      wall_motion_.emplace(s_, std::move(paths), *wall_index_);
      units_.push_back(WallMotion<D>::kName);
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
      contact_.emplace(s_, *bodies_, k.stiffness(), k.damping(), dx_,
                       !k.has_with_walls() || k.with_walls(), k.friction().coefficient(),
                       k.has_friction() ? k.friction().tangential_stiffness() : 0.0);
      units_.push_back(SpringDashpotContact<D>::kName);
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
  build_transport_units();
  build_phase_transitions();
  build_open_boundaries();
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
  // Series in the result file.
  for (const char* n :
       {"time", "step", "dt", "mass", "kinetic_energy", "potential_energy", "elastic_energy",
        "max_density_deviation", "max_speed", "imbalance", "fluid_particles", "neighbor_searches"})
    result_.add_series(std::string("diagnostics/") + n);
  result_.add_series("diagnostics/momentum", {static_cast<std::uint64_t>(D)});
  result_.add_series("diagnostics/max_density_deviation_at", {static_cast<std::uint64_t>(D)});
  // Bounding box of the fluid (e.g. the surge front of a dam break).
  result_.add_series("diagnostics/fluid_min", {static_cast<std::uint64_t>(D)});
  result_.add_series("diagnostics/fluid_max", {static_cast<std::uint64_t>(D)});
  if (walls_) result_.add_series("diagnostics/max_solid_fraction");
  if (contact_) result_.add_series("diagnostics/min_contact_distance");
  phases_ = std::count_if(fluids_.begin(), fluids_.end(),
                          [](const FluidConstants& fl) { return fl.fluid; }) > 1;
  if (phases_)
    for (const char* n : {"interface_particles", "stray_phase_particles"})
      result_.add_series(std::string("diagnostics/") + n);
  if (bodies_) {
    body_slots_ = phase_ ? phase_->max_bodies() : static_cast<std::size_t>(c_.bodies_size());
    const auto nb = static_cast<std::uint64_t>(body_slots_);
    const std::uint64_t dd = D, aa = RigidBodies<D>::A;
    result_.add_series("bodies/time");
    result_.add_series("bodies/position", {nb, dd});
    result_.add_series("bodies/velocity", {nb, dd});
    result_.add_series("bodies/angular_velocity", {nb, aa});
    result_.add_series("bodies/orientation", {nb, D == 2 ? 1u : 4u});
    result_.add_series("bodies/fluid_force", {nb, dd});
    result_.add_series("bodies/fluid_torque", {nb, aa});
    result_.add_series("bodies/contact_force", {nb, dd});
    result_.add_series("bodies/contact_torque", {nb, aa});
    result_.add_series("bodies/contacts", {nb});
    result_.add_series("bodies/kinetic_energy", {nb});
    result_.add_series("bodies/mass", {nb});
    result_.add_series("bodies/inertia", {nb, aa * aa});  // body frame, about the centre of mass
    // Which body fills each slot (RigidBody::serial; NaN while empty): melting empties slots
    // and later bodies take them.
    result_.add_series("bodies/serial", {nb});
    result_.add_field(bodies_->body_index());
  }
  if (probes_)
    for (const auto& set : probes_->sets()) {
      const auto n = static_cast<std::uint64_t>(set.points.size());
      result_.add_series("probes/" + set.name + "/time");
      result_.add_series("probes/" + set.name + "/pressure", {n});
      result_.add_series("probes/" + set.name + "/density", {n});
      result_.add_series("probes/" + set.name + "/velocity", {n, static_cast<std::uint64_t>(D)});
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
                              wall_index_};
  unit_set_ = UnitSet<D>(make_units<D>(b));
  for (const auto& u : unit_set_.units()) {
    units_.push_back(u->name());
    u->declare_output(result_);
  }
  bound_->add_limit(unit_set_.max_time_step());
}

template <int D, class K>
void Simulation<D, K>::build_transport_units() {
  const double factor = c_.time().has_cfl_factor() ? c_.time().cfl_factor() : 1.0;
  std::vector<int> wall_material;
  for (const auto& w : c_.walls())
    wall_material.push_back(w.material().empty() ? -1 : material_index(mats_, w.material()));
  if (c_.has_thermal()) {
    std::vector<DiffusionMaterial> m;
    for (const auto& pm : c_.materials()) {
      DiffusionMaterial dm;
      dm.coefficient = pm.thermal_conductivity();
      dm.capacity = pm.has_heat_capacity() ? pm.heat_capacity() : 1.0;
      dm.density = pm.density();
      // Both materials of a transition with latent heat take it up over the same interval
      // (Fuchs 2021 Remark 3), so a particle's enthalpy does not jump when it changes phase.
      for (const auto& pt : c_.phase_transitions())
        if (pt.has_latent_heat() &&
            (pt.solid_material() == pm.name() || pt.fluid_material() == pm.name())) {
          dm.latent = pt.latent_heat();
          dm.latent_lo = pt.transition_value() - 0.5 * pt.latent_heat_interval();
          dm.latent_hi = pt.transition_value() + 0.5 * pt.latent_heat_interval();
        }
      m.push_back(dm);
      // Conduction bound 0.1 rho c_p h^2 / kappa (Fuchs 2021 eq. 41).
      if (pm.thermal_conductivity() > 0)
        bound_->add_limit(factor * 0.1 * pm.density() * m.back().capacity * h_ * h_ /
                          pm.thermal_conductivity());
    }
    std::vector<std::optional<TimeFunction>> walls;
    for (const auto& w : c_.walls())
      walls.push_back(w.has_temperature()
                          ? std::optional<TimeFunction>(TimeFunction(w.temperature().value()))
                          : std::nullopt);
    heat_.emplace(s_, "temperature", m, walls, wall_material, wall_volume_,
                  c_.thermal().volumetric_heat_source());
    units_.push_back("heat_conduction");
    result_.add_field(heat_->values());
    for (const char* n : {"temperature_min", "temperature_max", "thermal_energy"})
      result_.add_series(std::string("diagnostics/") + n);
  }
  if (c_.has_diffusion()) {
    std::vector<DiffusionMaterial> m;
    for (const auto& pm : c_.materials()) {
      DiffusionMaterial dm;
      dm.coefficient = pm.diffusivity();
      dm.density = pm.density();
      dm.fixed = pm.fixed_concentration();
      m.push_back(dm);
      if (pm.diffusivity() > 0)
        bound_->add_limit(factor * 0.1 * pm.density() * h_ * h_ / pm.diffusivity());
    }
    std::vector<std::optional<TimeFunction>> walls;
    for (const auto& w : c_.walls())
      walls.push_back(w.has_concentration()
                          ? std::optional<TimeFunction>(TimeFunction(w.concentration().value()))
                          : std::nullopt);
    concentration_.emplace(s_, "concentration", m, walls, wall_material, wall_volume_, 0.0);
    units_.push_back("concentration_diffusion");
    result_.add_field(concentration_->values());
    for (const char* n : {"concentration_min", "concentration_max", "species_mass"})
      result_.add_series(std::string("diagnostics/") + n);
  }
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
    rules.push_back(r);
    slots =
        std::max(slots, pt.has_max_bodies() ? static_cast<std::size_t>(pt.max_bodies())
                                            : 2 * static_cast<std::size_t>(c_.bodies_size()) + 64);
  }
  phase_.emplace(s_, std::move(rules), slots, dx_);
  units_.push_back(PhaseTransitions<D>::kName);
  for (const char* n :
       {"melted", "solidified", "active_bodies", "reversals", "shortest_reversal_steps"})
    result_.add_series(std::string("phase/") + n);
}

template <int D, class K>
std::string Simulation<D, K>::apply_phase_transitions() {
  if (!phase_) return {};
  typename PhaseTransitions<D>::Outcome out;
  {
    Timer tm(timer(PhaseTransitions<D>::kName));
    out = phase_->run(s_, nl_, *bodies_, heat_ ? &heat_->values() : nullptr,
                      concentration_ ? &concentration_->values() : nullptr, transport_,
                      fluid_body_force(t_), step_, comm_);
  }
  if (!out.error.empty()) {
    char buf[120];
    std::snprintf(buf, sizeof buf, " at step %lld, t = %.9g", static_cast<long long>(step_), t_);
    return out.error + buf;
  }
  if (out.melted + out.solidified > 0) {  // all ranks: the counts are global
    // Particles changed kind and body after this step's search: the ghosts and the contact
    // candidates are those of before (a melted particle would push its old neighbours as a
    // wall, a merged body would keep contacts within itself), so refresh the ghosts and sort
    // the candidates again by kind (search again, without a skin), and evaluate the rebuilt
    // bodies' contact forces for the next step's first contact kick.
    exchange_and_search(Search::kKindsChanged);
    if (contact_) {
      Timer tc(timer(SpringDashpotContact<D>::kName));
      contact_->refresh(nl_, comm_);
    }
    bodies_->update_accelerations(t_);  // the rebuilt bodies' own forces
  }
  return {};
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
  result_.add_field(open_->zone());
  result_.add_series("open_boundaries/time");
  for (const auto& z : open_->zones()) result_.add_series("open_boundaries/" + z.name());
  const bool outflow = std::any_of(open_->zones().begin(), open_->zones().end(),
                                   [](const OpenBoundaryZone<D>& z) { return !z.inflow(); });
  // Free bodies lose the particles carried out; what remains stays one body.
  if (bodies_ && outflow) leaving_.emplace(BodyRegrouping<D>::whole_bodies(dx_));
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
                      free_slip_, background_, heat_ ? &heat_->values() : nullptr,
                      concentration_ ? &concentration_->values() : nullptr, comm_);
}

template <int D, class K>
void Simulation<D, K>::set_wall_scalars(double t) {
  if (!wall_index_) return;
  if (heat_) heat_->set_wall_values(t, *wall_index_);
  if (concentration_) concentration_->set_wall_values(t, *wall_index_);
}

template <int D, class K>
void Simulation<D, K>::transport_scalars(double dt) {
  if (dt <= 0) return;
  for (ScalarDiffusion<D>* unit :
       {heat_ ? &*heat_ : nullptr, concentration_ ? &*concentration_ : nullptr}) {
    if (!unit) continue;
    Timer tm(
        timer(unit == (heat_ ? &*heat_ : nullptr) ? "heat_conduction" : "concentration_diffusion"));
    if (unit->has_dirichlet_walls()) {
      // The mirror values use this step's fluid values at the new positions.
      unit->extrapolate_walls(nl_, pk_, t_, *wall_index_);
      Timer th(timer("halo_exchange"));
      halo_.update(s_, {&unit->values()});
    }
    unit->run(nl_, pk_, dt, *wall_index_or_empty());
  }
}

// Extremes and content (thermal energy sum m h(T), latent heat included; species mass sum m C)
// of the scalars.
template <int D, class K>
void Simulation<D, K>::sample_scalars() {
  for (int which = 0; which < 2; ++which) {
    ScalarDiffusion<D>* unit =
        which == 0 ? (heat_ ? &*heat_ : nullptr) : (concentration_ ? &*concentration_ : nullptr);
    if (!unit) continue;
    std::vector<double> ext = {-std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity()};
    double content = 0;
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      if (s_.kind[i] == Kind::kWall) continue;
      const double v = unit->values()[i];
      ext[0] = std::max(ext[0], -v);
      ext[1] = std::max(ext[1], v);
      content += s_.m[i] * unit->content(s_.material[i], v);
    }
    comm_.max_inplace(ext);
    content = comm_.sum(content);
    const std::string base = which == 0 ? "diagnostics/temperature_" : "diagnostics/concentration_";
    result_.append_series(base + "min", {-ext[0]});
    result_.append_series(base + "max", {ext[1]});
    result_.append_series(which == 0 ? "diagnostics/thermal_energy" : "diagnostics/species_mass",
                          {content});
  }
}

// Work per particle for load balancing: fluid and rigid particles run every pair loop; a wall
// particle only takes part in neighbour search and, next to fluid, the wall condition. A
// scene is often mostly wall (a 3D tank), so balancing raw counts leaves one rank with all
// the fluid. Integers keep the histogram sums exact.
inline std::int64_t work_weight(Kind k) {
  return k == Kind::kWall ? 1 : 10;
}

template <int D, class K>
void Simulation<D, K>::decompose_by_histogram() {
  std::vector<std::int64_t> counts(static_cast<size_t>(grid_.total()), 0);
  for (std::size_t i = 0; i < s_.owned(); ++i)
    counts[static_cast<size_t>(grid_.linear(grid_.canonical(grid_.coord(s_.x[i]))))] +=
        work_weight(s_.kind[i]);
  comm_.sum_inplace(counts);
  halo_.set_decomposition(Decomposition<D>(grid_, comm_.size(), counts));
}

template <int D, class K>
double Simulation<D, K>::initial_scalar(const SceneParticle& p, bool temperature) const {
  const double fallback =
      temperature ? c_.thermal().initial_temperature() : c_.diffusion().initial_concentration();
  switch (p.kind) {
    case Kind::kFluid: {
      if (p.open >= 0) {
        const auto& o = c_.open_boundaries(p.open);
        if (temperature && o.has_temperature()) return o.temperature();
        if (!temperature && o.has_concentration()) return o.concentration();
        return fallback;
      }
      const auto& r = c_.fluids(p.region);
      if (temperature && r.has_initial_temperature()) return r.initial_temperature();
      if (!temperature && r.has_initial_concentration()) return r.initial_concentration();
      return fallback;
    }
    case Kind::kRigid: {
      const auto& b = c_.bodies(p.body);
      if (temperature && b.has_initial_temperature()) return b.initial_temperature();
      if (!temperature && b.has_initial_concentration()) return b.initial_concentration();
      return fallback;
    }
    case Kind::kWall: {
      const auto& w = c_.walls(p.wall);
      if (temperature && w.has_temperature())
        return TimeFunction(w.temperature().value()).value(0.0);
      if (!temperature && w.has_concentration())
        return TimeFunction(w.concentration().value()).value(0.0);
      return fallback;
    }
  }
  return fallback;
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
    if (wall_motion_) {
      wall_motion_->reference_position()[i] = s_.x[i];
    }
    if (wall_index_) (*wall_index_)[i] = p.wall;
    if (heat_) heat_->values()[i] = initial_scalar(p, true);
    if (concentration_) concentration_->values()[i] = initial_scalar(p, false);
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
void Simulation<D, K>::exchange_and_search(Search mode) {
  // Counted: searches that every rank count makes alike (not a rebalance's or a resume's).
  const bool counted = mode != Search::kAtReference;
  if (skin_ == 0) mode = Search::kFresh;  // the lists of the positions now are all there is
  bool refreshed = false;
  if (mode == Search::kKindsChanged) {
    {
      Timer tm(timer("halo_exchange"));
      halo_.refresh_ghosts(s_);
    }
    Timer tm(timer("neighbor_search"));
    const ContactQuery q = contact_query();
    nl_.reclassify_candidates(s_, contact_ ? &q : nullptr, skin_);
    refreshed = true;  // refined below
  }
  if (mode == Search::kAsNeeded) {
    Timer tm(timer("neighbor_search"));
    mode = moved_half_the_skin() ? Search::kFresh : Search::kAsNeeded;
  }
  if (mode == Search::kFresh) {
    {
      Timer tm(timer("halo_exchange"));
      migrate();
      // Keep owned particles in cell order so neighbours are close in memory.
      if (step_ - reordered_at_ >= 25) {
        s_.reorder_owned(owned_cell_order(s_, grid_, halo_.my_box()));
        reordered_at_ = step_;
      }
      if (searched_at_) std::copy(s_.x.data(), s_.x.data() + s_.owned(), searched_at_->data());
      halo_.build_ghosts(s_);
    }
    if (counted) ++searches_;
    search_candidates();
  } else if (mode == Search::kAtReference) {
    // Ghosts and candidates as the last search made them: everything placed by the positions
    // it searched at, then the positions now refreshed on the ghosts.
    auto swap_positions = [&] {
      for (std::size_t i = 0; i < s_.owned(); ++i) std::swap(s_.x[i], (*searched_at_)[i]);
    };
    {
      Timer tm(timer("halo_exchange"));
      swap_positions();
      migrate();
      halo_.build_ghosts(s_);
    }
    search_candidates();
    Timer tm(timer("halo_exchange"));
    swap_positions();
    halo_.refresh_ghosts(s_);
  } else if (!refreshed) {
    Timer tm(timer("halo_exchange"));
    halo_.refresh_ghosts(s_);
  }
  if (skin_ > 0) {
    Timer tm(timer("neighbor_search"));
    nl_.refine(s_, rc_, contact_ ? contact_->candidate_range() : 0.0,
               pk_.squared_distances_for(nl_));
  }
  Timer tm(timer("pair_kernel"));
  if (skin_ > 0)
    pk_.prepare_refined(s_, nl_, kernel_);
  else
    pk_.prepare(s_, nl_, kernel_);
}

template <int D, class K>
ContactQuery Simulation<D, K>::contact_query() const {
  if (!contact_) return {};
  return ContactQuery{bodies_->body_index().data(), contact_->candidate_range(),
                      contact_->with_walls()};
}

// The lists (without a skin) or the Verlet candidates of the positions in s_.x.
template <int D, class K>
void Simulation<D, K>::search_candidates() {
  Timer tm(timer("neighbor_search"));
  const ContactQuery q = contact_query();
  const ContactQuery* query = contact_ ? &q : nullptr;
  if (skin_ > 0)
    nl_.build_candidates(s_, grid_, halo_.ghost_box(), rc_, skin_, query, rigid_all());
  else
    nl_.build(s_, grid_, halo_.ghost_box(), rc_, query, rigid_all());
}

template <int D, class K>
bool Simulation<D, K>::moved_half_the_skin() {
  double largest = 0;
  for (std::size_t i = 0; i < s_.owned(); ++i) {
    Vec<D> d = s_.x[i] - (*searched_at_)[i];
    for (int a = 0; a < D; ++a) {
      // A wall moved by a prescribed motion (or a body placed from its centre) may be whole
      // periods from where it was searched; its ghosts were sent as images of that place.
      if (!grid_.periodic[a] || !(std::abs(d[a]) > 0.5 * grid_.length[a])) continue;
      const double shift = std::round(d[a] / grid_.length[a]) * grid_.length[a];
      s_.x[i][a] -= shift;
      d[a] -= shift;
    }
    largest = std::max(largest, d.squaredNorm());
  }
  return comm_.max(largest) >= 0.25 * skin_ * skin_;
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
    forces_->run_coupling(s_, nl_, kernel_, in);
    bodies_->reduce_fluid_forces(comm_);
  }
}

// Particles to their owners, with the contact history that belongs to them.
template <int D, class K>
void Simulation<D, K>::migrate() {
  halo_.migrate(s_);
  if (contact_) contact_->migrate_history(halo_);
}

template <int D, class K>
void Simulation<D, K>::move_bodies(double dt) {
  Timer tm(timer(RigidBodies<D>::kName));
  if (contact_) {
    Timer tc(timer(SpringDashpotContact<D>::kName));
    // Substep only when bodies may touch during this step; otherwise one drift.
    contact_->drift(nl_, dt, substeps_, t_ + dt, comm_);
  } else {
    bodies_->drift(dt, t_ + dt);
  }
  bodies_->place_owned_particles();
}

template <int D, class K>
void Simulation<D, K>::prime() {
  if (wall_motion_) {
    Timer tm(timer(WallMotion<D>::kName));
    wall_motion_->run(t_, transport_);
  }
  if (bodies_) bodies_->place_owned_particles();
  set_wall_scalars(t_);
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
      contact_possible_ = comm_.min(nl_.min_contact_distance()) < 1.1 * dx_;
    }
    bodies_->update_accelerations(t_);
  }
}

template <int D, class K>
std::string Simulation<D, K>::integrate_step(double dt) {
  step_dt_ = dt;
  {
    Timer tm(timer("integrate"));
    kick(s_, 0.5 * dt);
    if (transport_) set_transport_velocity(s_, *transport_, *background_, 0.5 * dt);
    drift(s_, transport_ ? *transport_ : s_.v, dt);
  }
  if (bodies_) {
    bodies_->kick(0.5 * dt, t_);  // Fuchs 2021 eq. 31
    move_bodies(dt);              // eqs. 33-36, contact substeps
  }
  t_ += dt;
  ++step_;
  if (wall_motion_) {
    Timer tm(timer(WallMotion<D>::kName));
    wall_motion_->run(t_, transport_);
  }
  set_wall_scalars(t_);
  bool bodies_left = false;
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
  exchange_and_search(Search::kAsNeeded);
  if (bodies_left && contact_) {
    // As after a phase transition: the rebuilt bodies' contact forces for the next step.
    Timer tc(timer(SpringDashpotContact<D>::kName));
    contact_->refresh(nl_, comm_);
  }
  run_phase(StepPhase::kAfterSearch);
  compute_density_and_pressure(dt);
  apply_wall_condition();
  transport_scalars(dt);  // Fuchs 2021 eq. 37: rates from T^n at r^{n+1}, rho^{n+1}
  compute_forces();
  if (open_) apply_open_boundaries_after_forces();
  run_phase(StepPhase::kConstraints);
  {
    Timer tm(timer("integrate"));
    kick(s_, 0.5 * dt);
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
bool Simulation<D, K>::checkpoint_due() const {
  const double every = c_.output().checkpoint_wall_interval();
  return (opt_.checkpoint_requested && opt_.checkpoint_requested()) ||
         (every > 0 && MPI_Wtime() - last_checkpoint_wall_ >= every);
}

template <int D, class K>
typename Simulation<D, K>::EndOfStep Simulation<D, K>::end_of_step_checks() {
  Timer tm(timer("stability_guards"));
  const auto vmax_dom = detail::to_vec<D>(c_.domain().hi());
  const auto vmin_dom = detail::to_vec<D>(c_.domain().lo());
  GuardScan<D> scan =
      scan_particles<D>(s_, fluids_, mats_, guards_, vmin_dom, vmax_dom, grid_.periodic, step_, t_);
  // Temperature and concentration are state too: an explicit diffusion step past its bound
  // (Fuchs 2021 eq. 41) overflows them while the flow is still sound.
  for (ScalarDiffusion<D>* unit :
       {heat_ ? &*heat_ : nullptr, concentration_ ? &*concentration_ : nullptr}) {
    if (!unit || !scan.violation.empty()) continue;
    for (std::size_t i = 0; i < s_.owned(); ++i)
      if (s_.kind[i] != Kind::kWall && !std::isfinite(unit->values()[i])) {
        scan.violation = "non-finite " + unit->name() + describe_particle(s_, mats_, i, step_, t_);
        break;
      }
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
      comm_.root() && checkpoint_due() ? 1.0 : 0.0,
      comm_.root() && c_.stop().max_wall_seconds() > 0 &&
              MPI_Wtime() - wall_start_ >= c_.stop().max_wall_seconds()
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
void Simulation<D, K>::sample_series() {
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
  result_.append_series("diagnostics/fluid_min", fmin);
  result_.append_series("diagnostics/fluid_max", fmax);
  auto put = [&](const char* n, double v) {
    result_.append_series(std::string("diagnostics/") + n, {v});
  };
  put("time", t_);
  put("step", static_cast<double>(step_));
  put("dt", dt_);
  put("mass", cs.mass);
  put("kinetic_energy", cs.kinetic);
  put("potential_energy", cs.potential);
  put("elastic_energy", cs.elastic);
  put("max_density_deviation", dev);
  result_.append_series("diagnostics/max_density_deviation_at", worst_at);
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
  result_.append_series("diagnostics/momentum",
                        std::vector<double>(cs.momentum.data(), cs.momentum.data() + D));
  if (bodies_) sample_bodies();
  if (open_) {
    result_.append_series("open_boundaries/time", {t_});
    for (std::size_t b = 0; b < open_->zones().size(); ++b)
      result_.append_series("open_boundaries/" + open_->zones()[b].name(),
                            {static_cast<double>(open_->through()[b])});
  }
  sample_scalars();
  if (!unit_set_.empty()) {
    const StepContext<D> ctx = context(dt_);
    for (const auto& u : unit_set_.units()) u->sample(result_, ctx);
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
      result_.append_series(base + "time", {t_});
      result_.append_series(base + "pressure", pr);
      result_.append_series(base + "density", rh);
      result_.append_series(base + "velocity", ve);
    }
  }
  next_series_ = t_ + schedule_.series_interval();
}

template <int D, class K>
void Simulation<D, K>::sample_bodies() {
  std::vector<double> pos, vel, w, q, ff, ft, cf, ct, n, ke, mass, inertia, serial;
  // Fixed width: slots of bodies not born yet (phase transitions) or gone are NaN.
  std::vector<RigidBody<D>> padded;
  const std::vector<RigidBody<D>>* list = &bodies_->bodies();
  if (phase_ || leaving_) {
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
    serial.push_back(b.active() || (!phase_ && !leaving_)
                         ? static_cast<double>(b.serial)
                         : std::numeric_limits<double>::quiet_NaN());
    for (int p = 0; p < RigidBodies<D>::A; ++p)
      for (int r = 0; r < RigidBodies<D>::A; ++r) inertia.push_back(b.inertia_body(p, r));
  }
  result_.append_series("bodies/time", {t_});
  result_.append_series("bodies/position", pos);
  result_.append_series("bodies/velocity", vel);
  result_.append_series("bodies/angular_velocity", w);
  result_.append_series("bodies/orientation", q);
  result_.append_series("bodies/fluid_force", ff);
  result_.append_series("bodies/fluid_torque", ft);
  result_.append_series("bodies/contact_force", cf);
  result_.append_series("bodies/contact_torque", ct);
  result_.append_series("bodies/contacts", n);
  result_.append_series("bodies/kinetic_energy", ke);
  result_.append_series("bodies/mass", mass);
  result_.append_series("bodies/serial", serial);
  result_.append_series("bodies/inertia", inertia);
  if (phase_) {
    std::int64_t active = 0;
    for (const RigidBody<D>& b : bodies_->bodies()) active += b.active() ? 1 : 0;
    result_.append_series("phase/melted", {static_cast<double>(phase_->melted_total())});
    result_.append_series("phase/solidified", {static_cast<double>(phase_->solidified_total())});
    result_.append_series("phase/active_bodies", {static_cast<double>(active)});
    result_.append_series("phase/reversals", {static_cast<double>(phase_->reversals_total())});
    result_.append_series("phase/shortest_reversal_steps",
                          {static_cast<double>(phase_->shortest_reversal())});
  }
}

template <int D, class K>
void Simulation<D, K>::write_snapshot() {
  Timer tm(timer("output"));
  result_.write_snapshot(s_, t_, step_);
}

template <int D, class K>
std::string Simulation<D, K>::write_checkpoint_now() {
  Timer tm(timer("output"));
  result_.flush();  // the result file holds every sample up to the checkpoint
  char name[64];
  std::snprintf(name, sizeof name, "ckpt_%012lld.h5", static_cast<long long>(step_));
  const std::string path = opt_.output_dir + "/checkpoints/" + name;
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
  for (const auto& u : unit_set_.units()) u->save(state);
  write_checkpoint(comm_, path, s_, state);
  if (comm_.root()) {
    if (opt_.prune_checkpoints) {  // keep the two newest
      std::vector<std::filesystem::path> all;
      for (const auto& e : std::filesystem::directory_iterator(opt_.output_dir + "/checkpoints"))
        if (e.path().extension() == ".h5") all.push_back(e.path());
      std::sort(all.begin(), all.end());
      for (std::size_t k = 0; k + 2 < all.size(); ++k) std::filesystem::remove(all[k]);
    }
    if (opt_.on_checkpoint) opt_.on_checkpoint(path, step_, t_);
  }
  last_checkpoint_ = path;
  last_checkpoint_wall_ = MPI_Wtime();
  return path;
}

template <int D, class K>
void Simulation<D, K>::report_progress(bool force) {
  if (!comm_.root()) return;
  const double now = MPI_Wtime();
  if (!force && now - last_progress_wall_ < opt_.progress_interval_seconds) return;
  Progress p;
  p.step = step_;
  p.time = t_;
  p.end_time = schedule_.end_time();
  p.dt = dt_;
  p.particles = global_particles_;
  p.ranks = comm_.size();
  p.imbalance = imbalance_;
  p.wall_seconds = now - wall_start_;
  const double dwall = now - (last_progress_wall_ < 0 ? wall_start_ : last_progress_wall_);
  if (last_progress_wall_ > -1e299 && dwall > 0) {
    p.particle_steps_per_second = static_cast<double>(step_ - last_progress_step_) *
                                  static_cast<double>(global_particles_) / dwall;
    const double rate = (t_ - last_progress_time_) / dwall;
    if (rate > 0) p.eta_seconds = (schedule_.end_time() - t_) / rate;
  }
  last_progress_wall_ = now;
  last_progress_step_ = step_;
  last_progress_time_ = t_;
  if (!opt_.quiet) {
    std::printf(
        "step %8lld  t %-11.5g / %-9.4g  dt %-10.3e  N %-9lld  %9.3e particle-steps/s  imbalance "
        "%.2f  ETA %s\n",
        static_cast<long long>(p.step), p.time, p.end_time, p.dt,
        static_cast<long long>(p.particles), p.particle_steps_per_second, p.imbalance,
        p.eta_seconds < 0
            ? "-"
            : (std::to_string(static_cast<long long>(p.eta_seconds + 0.5)) + " s").c_str());
    std::fflush(stdout);
  }
  if (opt_.on_progress) opt_.on_progress(p);
}

template <int D, class K>
std::map<std::string, std::string> Simulation<D, K>::metadata(const std::string& status) const {
  std::map<std::string, std::string> m = opt_.metadata;
  m["case_text"] = opt_.case_text.empty() ? c_.DebugString() : opt_.case_text;
  m["code_version"] = code_version();
  m["ranks"] = std::to_string(comm_.size());
  m["dimension"] = std::to_string(D);
  // The shortest text that reads back as the value (to_string would print 2.5e-6 as 0.000003).
  for (const auto& [key, value] :
       {std::pair<const char*, double>{"dx", dx_}, {"h", h_}, {"neighbor_skin", skin_}}) {
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, value).ptr;
    m[key] = std::string(buf, end);
  }
  m["kernel"] = K::kSupport == 3.0 ? "quintic_spline" : "wendland_c2";
  std::string units;
  for (const auto& u : units_) units += (units.empty() ? "" : ",") + u;
  m["active_units"] = units;
  if (bodies_) {
    std::string names;
    for (const auto& b : bodies_->bodies()) names += (names.empty() ? "" : ",") + b.name;
    m["body_names"] = names;
  }
  m["status"] = status;
  return m;
}

template <int D, class K>
void Simulation<D, K>::maybe_rebalance() {
  // Imbalance = largest rank's work / mean work (work_weight per particle).
  auto imbalance = [&] {
    std::int64_t local = 0;
    for (std::size_t i = 0; i < s_.owned(); ++i) local += work_weight(s_.kind[i]);
    const std::int64_t total = comm_.sum(local), max = comm_.max(local);
    return total > 0 ? static_cast<double>(max) * comm_.size() / static_cast<double>(total) : 1.0;
  };
  imbalance_ = imbalance();
  if (comm_.size() > 1 && imbalance_ > 1.05) {
    {
      Timer tm(timer("halo_exchange"));
      s_.drop_ghosts();
      decompose_by_histogram();
    }
    // Migration reorders the owned rows and the ghosts change: the next step's contact drift
    // and the probes read the neighbour list before that step searches again. The pairs and
    // their order stay those of the last search, whatever the decomposition.
    exchange_and_search(Search::kAtReference);
    imbalance_ = imbalance();
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
  for (const ScalarDiffusion<D>* unit :
       {heat_ ? &*heat_ : nullptr, concentration_ ? &*concentration_ : nullptr})
    if (unit) m[unit->values().owner()] += unit->bytes();
  for (const auto& u : unit_set_.units()) m[u->name()] += u->scratch_bytes();
  return m;
}

template <int D, class K>
void Simulation<D, K>::start() {
  wall_start_ = MPI_Wtime();
  last_checkpoint_wall_ = wall_start_;
  if (opt_.resume_from.empty()) {
    build_scene();
    migrate();
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
      dt_ = c_.time().fixed_dt() > 0
                ? c_.time().fixed_dt()
                : bound_->dt(comm_.max(scan.max_speed), comm_.max(scan.max_acceleration));
      dt0_ = dt_;
    }
    if (walls_) solid_fraction_ = comm_.max(scan_solid_fraction().max);
    if (contact_) min_contact_distance_ = comm_.min(nl_.min_contact_distance());
    result_.create(metadata("running"));
    maybe_rebalance();
    sample_series();
    write_snapshot();
    next_output_ = schedule_.first_after(0.0);
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
    result_.carry_over(opt_.previous_result, t_, meta);
    next_output_ = schedule_.first_after(t_);
    maybe_rebalance();
  }
}

template <int D, class K>
SolidFractionScan Simulation<D, K>::scan_solid_fraction() {
  return solid_fraction<D>(s_, nl_, pk_, wall_volume_, wall_index_ ? wall_index_->data() : nullptr,
                           bodies_ ? bodies_->body_index().data() : nullptr);
}

template <int D, class K>
int Simulation<D, K>::contact_substeps(double dt) const {
  if (!contact_ || !contact_possible_) return 1;
  const double factor = c_.time().has_cfl_factor() ? c_.time().cfl_factor() : 1.0;
  const double n = std::ceil(dt / (factor * contact_->time_step(min_rigid_mass_)));
  return n > 2e9 ? std::numeric_limits<int>::max() : std::max(1, static_cast<int>(n));
}

template <int D, class K>
typename Simulation<D, K>::StepReport Simulation<D, K>::step() {
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
  if (c_.time().fixed_dt() <= 0) {
    dt_ = bound_->dt(e.max_speed, e.max_acceleration);
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
  if (contact_) contact_possible_ = e.min_contact_distance < 1.1 * dx_;
  if (step_ % 20 == 0) maybe_rebalance();
  return rep;
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
  const char* st = status == RunStatus::kCompleted     ? "completed"
                   : status == RunStatus::kCancelled   ? "cancelled"
                   : status == RunStatus::kInterrupted ? "interrupted"
                                                       : "unstable";
  auto meta = std::map<std::string, std::string>{{"status", st}, {"message", message}};
  // What each unit cost: time (rank 0) and storage (all ranks), for "only the effects a scene
  // calls for".
  std::map<std::string, double> bytes;
  {
    const auto local = memory_by_owner();
    std::vector<double> v;
    for (const auto& [k, b] : local) v.push_back(static_cast<double>(b));
    comm_.sum_inplace(v);  // every rank has the same units, so the same keys in the same order
    std::size_t i = 0;
    for (const auto& [k, b] : local) bytes[k] = v[i++];
  }
  std::string times, mem;
  for (const auto& [k, sec] : timers_)
    times += (times.empty() ? "" : ",") + k + "=" + std::to_string(sec);
  for (const auto& [k, b] : bytes)
    mem += (mem.empty() ? "" : ",") + k + "=" + std::to_string(static_cast<long long>(b));
  meta["unit_seconds"] = times;
  meta["unit_bytes"] = mem;
  meta["neighbor_searches"] = std::to_string(searches_);
  result_.flush();
  result_.set_meta(meta);
  out.unit_bytes = bytes;
  out.status = status;
  out.message = message;
  out.steps = step_;
  out.time = t_;
  out.wall_seconds = MPI_Wtime() - wall_start_;
  out.unit_seconds = timers_;
  out.neighbor_searches = searches_;
  out.last_checkpoint = last_checkpoint_;
  out.files = {std::filesystem::absolute(result_.h5_path()).string(),
               std::filesystem::absolute(result_.xmf_path()).string()};
  return out;
}

}  // namespace sph
