#pragma once
// Inflow and outflow boundaries by buffer zones (case.proto OpenBoundary). The unit exists
// only in cases with open boundaries; it adds one column, `open_boundary` (0 for the fluid,
// b + 1 for a particle in the buffer of boundary b).
//
// Buffer particles are fluid particles (they take part in density summation, the wall
// condition and every pair loop as neighbours of the fluid, so the fluid near an inlet or
// outlet has full kernel support), but their state is set by the boundary, not integrated:
// their acceleration (and transport-velocity correction) is zero, and
//  - velocity: an INFLOW and a velocity outlet prescribe u = U phi(lane) ramp(t) n; a pressure
//    outlet takes the fluid's normal mass flux next to the outlet, lane by lane (zero normal
//    gradient), divided by the buffer particle's density: rho_b u_b = (rho u.n)_fluid, so
//    the buffer's particles spread out to the outlet density as they leave the fluid; plus
//    (p_fluid - p_out) / (rho_b c), which keeps the outgoing acoustic characteristic and so
//    pulls the fluid's pressure level to the outlet's (after_forces). Buffer particles move
//    along n only;
//  - pressure: where the velocity is prescribed the pressure has zero normal gradient (the
//    fluid's next to the face plus the hydrostatic part rho0 b.(x - x_sample), Adami 2012
//    eq. 27 without the wall's acceleration); a pressure outlet holds `pressure`. The density
//    follows from the EOS (Adami 2012 eq. 28).
// This pairs a Dirichlet condition with a Neumann one at each end (velocity inlet with
// extrapolated pressure, pressure outlet with extrapolated velocity), as in the buffer
// methods of Lastiwka, Basa & Quinlan 2009 (IJNMF 61:709) and Tafuni et al. 2018 (CMAME
// 342:604, "velocity inlet / pressure outlet"); we extrapolate at zeroth order from the
// fluid next to the face (Shepard mean, Fuchs 2021 eq. 13) rather than by Tafuni's
// first-order mirror interpolation, which needs fluid up to 2 buffer lengths away and so
// beyond the ghost layer. A pressure outlet is what anchors the pressure level of a channel;
// with velocity outlets (Fuchs 2021's gas flow: "a parabolic inflow respectively outflow ...
// is prescribed") the inflow and outflow rates must balance.
//
// Particle flux (after each drift): an inflow buffer particle that crosses the inner face
// becomes a fluid particle and a copy re-enters the lane one buffer length upstream (lanes
// are rows spaced dx and the buffer is a whole number of dx long, so the lane stays a
// lattice row: SPHinXsys' emitter recycles particles the same way); a fluid particle that
// crosses an outflow's inner face joins its buffer, and leaves the run at the outer face.
// So does a rigid particle of a freely moving body (a grain carried out by the gas): the
// caller rebuilds the bodies that lost particles (BodyRegrouping, Fuchs 2021 eq. 29), so a
// body leaves through an outlet piece by piece, its remaining part keeping the velocity the
// rigid motion gives it there, and the particles counted through the outlet include its
// particles. Prescribed and fixed bodies are the scene's geometry and never leave.
// Pressure outlets are bidirectional: where the flow turns inwards (a vortex leaving, or a
// pressure drop that draws fluid in through the outlet), buffer particles that cross the inner
// face back become fluid, and a lane whose particles move inwards gets a new particle one
// spacing beyond its outermost one once the gap to the far face reaches that spacing
// (dx (rho0 / rho)^(1/d) at the outlet's density), so the buffer stays full instead of
// emptying from its far end. Filling gaps, rather than copying each particle that crosses
// back, creates no mass where a particle crosses the inner face to and fro. The outflow's
// count is net: particles out minus particles in.
// New particles get ids from ParticleLedger (deterministic on any rank count).
//
// The fluid's state next to a face is read at one sample point per lane, r_c inside the
// fluid (so that the buffer's own state does not enter it); the rank owning the point's cell
// sums its neighbours in canonical order and the others contribute zero, so the reduced
// values, hence the buffers, are identical on any rank count.
// Not supported: fluid entering an inflow buffer against the flow (it stays fluid),
// directions that are not along a coordinate axis.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/bodies/rigid_bodies.h"
#include "solver/boundaries/open_boundary_zone.h"
#include "solver/boundaries/particle_ledger.h"
#include "solver/core/cell_grid.h"
#include "solver/core/checkpoint_state.h"
#include "solver/core/neighbor_list.h"
#include "solver/parallel/comm.h"
#include "solver/physics/fluid_table.h"

namespace sph {

template <int D, class K>
class OpenBoundaries {
 public:
  static constexpr const char* kName = "open_boundaries";

  OpenBoundaries(ParticleStore<D>& s, const K& kernel, std::vector<OpenBoundaryZone<D>> zones,
                 const std::vector<FluidConstants>& fluids, double wall_volume)
      : s_(s),
        k_(kernel),
        zones_(std::move(zones)),
        fluids_(fluids),
        wall_volume_(wall_volume),
        zone_(s.template add<std::uint8_t>("open_boundary", kName, true)),
        through_(zones_.size(), 0),
        tally_(zones_.size(), 0) {
    std::size_t lanes = 0;
    for (const auto& z : zones_) {
      lane_offset_.push_back(lanes);
      lanes += z.lane_count();
    }
    lane_value_.assign(lanes, 0.0);
    lane_pressure_.assign(lanes, 0.0);
    lane_sums_.assign(4 * lanes, 0.0);
    for (const auto& z : zones_)
      if (!z.inflow() && !z.prescribed()) lane_far_.assign(lanes, 0.0);
  }

  // 0: fluid; b + 1: in the buffer of boundary b.
  Column<std::uint8_t>& zone() { return zone_; }
  const std::vector<OpenBoundaryZone<D>>& zones() const { return zones_; }
  ParticleLedger<D>& ledger() { return ledger_; }
  // Particles that entered the fluid through each inflow / left the run through each outflow
  // (net of those that came back in through it).
  const std::vector<std::int64_t>& through() const { return through_; }

  // Prescribed velocities at time t (inflows, velocity outlets), and the transport velocity
  // when given: a buffer particle moves with its prescribed velocity, so its transport
  // velocity is that velocity too (else its neighbours see an artificial stress
  // rho u (u~ - u) from a stale u~, Adami, Hu, Adams 2013).
  void set_prescribed_velocities(double t, Column<Vec<D>>* transport) {
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      const std::uint8_t z = zone_[i];
      if (z == 0 || s_.kind[i] != Kind::kFluid) continue;
      const OpenBoundaryZone<D>& b = zones_[z - 1u];
      if (!b.prescribed()) continue;
      s_.v[i] = b.speed(b.lane_of(s_.x[i]), t) * b.normal();
      if (transport) (*transport)[i] = s_.v[i];
    }
  }

  // After the drift, at the new time t: particles cross faces, inflow buffers refill,
  // outflows delete, prescribed velocities (and transport velocities, when given) are
  // updated. With `bodies`, rigid particles of free bodies past an outflow's outer face are
  // deleted too and `lost[k]` (sized to the bodies, zero on entry) counts those of body k
  // over all ranks. Collective. Returns the change of the global particle count.
  std::int64_t exchange_particles(double t, Column<Vec<D>>* transport, const Comm& comm,
                                  const RigidBodies<D>* bodies = nullptr,
                                  std::vector<std::int64_t>* lost = nullptr) {
    parents_.clear();
    parent_zone_.clear();
    parent_shift_.clear();
    doomed_.clear();
    std::fill(tally_.begin(), tally_.end(), 0);
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      if (s_.kind[i] != Kind::kFluid) {  // e.g. solidified in a buffer
        if (bodies && s_.kind[i] == Kind::kRigid)
          leave_if_out(i, *bodies, *lost);
        else
          zone_[i] = 0;
        continue;
      }
      std::uint8_t z = zone_[i];
      const Vec<D>& x = s_.x[i];
      if (z == 0) {
        z = zone_[i] = outflow_buffer_at(x);
        if (z == 0) continue;
      }
      const OpenBoundaryZone<D>& o = zones_[z - 1u];
      const double xi = o.xi(x);
      if (o.inflow()) {
        if (xi > o.inner_xi()) {  // into the fluid; a copy refills the lane
          zone_[i] = 0;
          parents_.push_back(static_cast<std::uint32_t>(i));
          parent_zone_.push_back(z);
          parent_shift_.push_back(-o.length());  // one buffer length upstream
          ++tally_[z - 1u];
        }
      } else if (xi >= o.outer_xi()) {  // out of the run
        doomed_.push_back(static_cast<std::uint32_t>(i));
        ++tally_[z - 1u];
      } else if (xi <= o.inner_xi()) {  // back into the fluid
        zone_[i] = 0;
      }
    }
    fill_far_ends(comm);
    // The bodies' counts ride in the ledger's one collective behind the zones' tallies.
    if (lost) tally_.insert(tally_.end(), lost->begin(), lost->end());
    const auto totals = ledger_.apply(s_, parents_, doomed_, tally_, comm);
    if (lost) {
      std::copy(tally_.begin() + static_cast<std::ptrdiff_t>(zones_.size()), tally_.end(),
                lost->begin());
      tally_.resize(zones_.size());
    }
    for (std::size_t k = 0; k < parents_.size(); ++k) {
      const std::size_t i = totals.first_new + k;
      const std::uint8_t z = parent_zone_[k];
      zone_[i] = z;
      s_.x[i] += parent_shift_[k] * zones_[z - 1u].normal();
    }
    for (std::size_t b = 0; b < zones_.size(); ++b) through_[b] += tally_[b];
    set_prescribed_velocities(t, transport);
    return totals.created - totals.deleted;
  }

  // After the fluid's density and pressure (ghosts updated): the buffers' pressure and
  // density. `body`: the body force on the fluid. Collective; the caller refreshes the
  // ghosts' rho and p afterwards.
  void set_pressure(const NeighborList<D>& nl, const CellGrid<D>& grid, const CellBox<D>& mine,
                    const Vec<D>& body, const Comm& comm) {
    sample(nl, grid, mine, comm, true, nullptr, nullptr);
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      const std::uint8_t z = zone_[i];
      if (z == 0 || s_.kind[i] != Kind::kFluid) continue;
      const OpenBoundaryZone<D>& o = zones_[z - 1u];
      double p = o.outlet_pressure();
      if (o.prescribed()) {
        const std::size_t lane = o.lane_of(s_.x[i]);
        p = lane_value_[lane_offset_[z - 1u] + lane] +
            o.rho0() * body.dot(s_.x[i] - o.sample_point(lane));
      }
      s_.p[i] = p;
      s_.rho[i] = fluids_[s_.material[i]].density(p);
    }
  }

  // After the forces: buffer particles get no acceleration and no transport correction;
  // pressure outlets take the fluid's normal mass flux next to their face (no-slip dummy particles
  // enter the mean with their extrapolated velocity, Adami 2012 eq. 23, so lanes next to a
  // wall are not biased towards the faster fluid inside); inflow buffers hold the inflow's
  // temperature and concentration. Collective.
  void after_forces(const NeighborList<D>& nl, const CellGrid<D>& grid, const CellBox<D>& mine,
                    const Column<Vec<D>>* noslip, const Column<std::uint8_t>* free_slip,
                    Column<Vec<D>>* background, Column<double>* temperature,
                    Column<double>* concentration, const Vec<D>& body, const Comm& comm) {
    sample(nl, grid, mine, comm, false, noslip, free_slip);
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      const std::uint8_t z = zone_[i];
      if (z == 0 || s_.kind[i] != Kind::kFluid) continue;
      const OpenBoundaryZone<D>& o = zones_[z - 1u];
      s_.a[i] = Vec<D>::Zero();
      if (background) (*background)[i] = Vec<D>::Zero();
      if (!o.prescribed()) {
        // The lane's mass flux at the outlet density, plus the outgoing characteristic's
        // velocity jump (p_f - p_out) / (rho c): the acoustic Riemann invariant
        // u_n + p / (rho c) carried out of the fluid is kept, so a fluid above the outlet
        // pressure drains faster and one below it draws fluid in (a non-reflecting
        // pressure condition, Thompson 1987 J. Comput. Phys. 68:1 in its 1D acoustic form),
        // instead of any pressure level being steady. p_f is the fluid's at the sample point
        // plus the hydrostatic part rho0 b.(x - x_sample).
        const std::size_t lane = o.lane_of(s_.x[i]), l = lane_offset_[z - 1u] + lane;
        const double p_f = lane_pressure_[l] + o.rho0() * body.dot(s_.x[i] - o.sample_point(lane));
        const double rho_c = s_.rho[i] * fluids_[s_.material[i]].c;
        // Backflow stabilisation (Braack & Mucha 2014): a lane flowing in aims at the static
        // pressure of fluid entering from rest at the outlet's pressure.
        const double u_n = lane_value_[l] / s_.rho[i], u_in = std::min(u_n, 0.0);
        const double p_target =
            o.outlet_pressure() - o.backflow_stabilization() * 0.5 * s_.rho[i] * u_in * u_in;
        s_.v[i] = (u_n + (p_f - p_target) / rho_c) * o.normal();
      }
      if (o.inflow()) {
        if (temperature) (*temperature)[i] = o.temperature();
        if (concentration) (*concentration)[i] = o.concentration();
      }
    }
  }

  void save(CheckpointState& state) const {
    ledger_.save(state, "open_next_id");
    state["open_zones"] = static_cast<double>(zones_.size());
    for (std::size_t b = 0; b < zones_.size(); ++b)
      state["open_through_" + std::to_string(b)] = static_cast<double>(through_[b]);
  }
  void load(const CheckpointState& state) {
    if (const auto it = state.find("open_zones");
        it != state.end() && static_cast<std::size_t>(it->second) != zones_.size())
      throw std::runtime_error("the checkpoint was written for a case with " +
                               std::to_string(static_cast<long long>(it->second)) +
                               " open boundary zones; this case has " +
                               std::to_string(zones_.size()));
    ledger_.load(state, "open_next_id");
    for (std::size_t b = 0; b < zones_.size(); ++b)
      through_[b] =
          static_cast<std::int64_t>(state_value(state, "open_through_" + std::to_string(b)));
  }

 private:
  // b + 1 for the outflow whose buffer holds x (a particle not yet in a buffer got there
  // through the inner face: what lies beyond the far face is not the outflow's), else 0.
  std::uint8_t outflow_buffer_at(const Vec<D>& x) const {
    for (std::size_t b = 0; b < zones_.size(); ++b) {
      const OpenBoundaryZone<D>& o = zones_[b];
      if (!o.inflow() && o.xi(x) > o.inner_xi() && o.xi(x) < o.outer_xi() && o.across(x))
        return static_cast<std::uint8_t>(b + 1);
    }
    return 0;
  }

  // Backflow through pressure outlets: in each lane whose outermost buffer particle moves
  // inwards, that particle spawns a new one a spacing further out once the gap to the far face
  // has reached the spacing. The outermost particle of a lane is found over all ranks (one
  // max-reduction); every particle at the maximum spawns, so which ones do does not depend on
  // the decomposition. The sign of the flow is read from the particle's velocity (the lane's
  // flux set it), which the checkpoint carries. Collective when the case has a pressure outlet.
  void fill_far_ends(const Comm& comm) {
    if (lane_far_.empty()) return;  // no pressure outlet
    const auto in_pressure_outlet = [&](std::size_t i) {
      const std::uint8_t z = zone_[i];
      return z != 0 && s_.kind[i] == Kind::kFluid && !zones_[z - 1u].inflow() &&
             !zones_[z - 1u].prescribed();
    };
    std::fill(lane_far_.begin(), lane_far_.end(), std::numeric_limits<double>::lowest());
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      if (!in_pressure_outlet(i)) continue;
      const OpenBoundaryZone<D>& o = zones_[zone_[i] - 1u];
      double& far = lane_far_[lane_offset_[zone_[i] - 1u] + o.lane_of(s_.x[i])];
      far = std::max(far, o.xi(s_.x[i]));
    }
    comm.max_inplace(lane_far_);
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      if (!in_pressure_outlet(i)) continue;
      const std::uint8_t z = zone_[i];
      const OpenBoundaryZone<D>& o = zones_[z - 1u];
      const double xi = o.xi(s_.x[i]);
      if (xi != lane_far_[lane_offset_[z - 1u] + o.lane_of(s_.x[i])] ||
          s_.v[i].dot(o.normal()) >= 0.0)
        continue;
      const double spacing = o.dx() * std::pow(o.rho0() / s_.rho[i], 1.0 / static_cast<double>(D));
      if (o.outer_xi() - xi < spacing) continue;
      parents_.push_back(static_cast<std::uint32_t>(i));
      parent_zone_.push_back(z);
      parent_shift_.push_back(spacing);
      --tally_[z - 1u];
    }
  }

  // A rigid particle of a free body follows the fluid's rule: it enters an outflow buffer
  // through the inner face and leaves the run at the far face. (A body beyond the far face
  // that never came through the buffer is not the outflow's, as for the fluid.)
  void leave_if_out(std::size_t i, const RigidBodies<D>& bodies, std::vector<std::int64_t>& lost) {
    const std::int32_t k = bodies.body_index()[i];
    std::uint8_t z = zone_[i];
    if (k < 0 || bodies.bodies()[static_cast<std::size_t>(k)].motion != BodyMotion::kFree ||
        (z != 0 && zones_[z - 1u].inflow())) {  // e.g. frozen in an inflow buffer
      zone_[i] = 0;
      return;
    }
    const Vec<D>& x = s_.x[i];
    if (z == 0) {
      z = zone_[i] = outflow_buffer_at(x);
      if (z == 0) return;
    }
    const OpenBoundaryZone<D>& o = zones_[z - 1u];
    if (o.xi(x) >= o.outer_xi()) {
      doomed_.push_back(static_cast<std::uint32_t>(i));
      ++tally_[z - 1u];
      ++lost[static_cast<std::size_t>(k)];
    } else if (o.xi(x) <= o.inner_xi()) {
      zone_[i] = 0;
    }
  }

  // Shepard means at the lanes' sample points over the fluid (not buffer) particles: the
  // pressure for zones with a prescribed velocity (`pressure`), else the normal mass flux.
  void sample(const NeighborList<D>& nl, const CellGrid<D>& grid, const CellBox<D>& mine,
              const Comm& comm, bool pressure, const Column<Vec<D>>* noslip,
              const Column<std::uint8_t>* free_slip) {
    bool any = false;
    std::fill(lane_sums_.begin(), lane_sums_.end(), 0.0);
    for (std::size_t b = 0; b < zones_.size(); ++b) {
      const OpenBoundaryZone<D>& o = zones_[b];
      if (o.prescribed() != pressure) continue;
      any = true;
      const Vec<D> n = o.normal();
      for (std::size_t lane = 0; lane < o.lane_count(); ++lane) {
        const Vec<D>& xp = o.sample_point(lane);
        const ICoord<D> c = grid.coord(xp);
        bool inside = true;
        for (int a = 0; a < D; ++a) inside = inside && c[a] >= 0 && c[a] < grid.n[a];
        if (!inside || !mine.contains(c)) continue;
        double sv = 0, sw = 0, sp = 0, spw = 0;
        nl.for_each_near(c, [&](std::uint32_t j) {
          const double w = k_.W((xp - s_.x[j]).norm());
          if (w == 0.0) return;
          if (s_.kind[j] == Kind::kFluid) {
            if (zone_[j] != 0) return;
            const double vw = s_.m[j] / s_.rho[j] * w;
            sv += vw * (pressure ? s_.p[j] : s_.rho[j] * s_.v[j].dot(n));
            sw += vw;
            sp += vw * s_.p[j];
            spw += vw;
          } else if (!pressure && noslip && !(free_slip && (*free_slip)[j])) {
            const double vw = wall_volume_ * w;
            sv += vw * s_.rho[j] * (*noslip)[j].dot(n);
            sw += vw;
          }
        });
        const std::size_t k = 4 * (lane_offset_[b] + lane);
        lane_sums_[k] = sv;
        lane_sums_[k + 1] = sw;
        lane_sums_[k + 2] = sp;
        lane_sums_[k + 3] = spw;
      }
    }
    if (!any) return;
    // One rank contributes to each lane, the others add zeros: exact.
    comm.sum_inplace(lane_sums_);
    for (std::size_t b = 0; b < zones_.size(); ++b) {
      if (zones_[b].prescribed() != pressure) continue;
      for (std::size_t l = lane_offset_[b]; l < lane_offset_[b] + zones_[b].lane_count(); ++l) {
        const double* sums = &lane_sums_[4 * l];
        lane_value_[l] = sums[1] > 0 ? sums[0] / sums[1] : 0.0;
        lane_pressure_[l] = sums[3] > 0 ? sums[2] / sums[3] : zones_[b].outlet_pressure();
      }
    }
  }

  ParticleStore<D>& s_;
  const K& k_;
  std::vector<OpenBoundaryZone<D>> zones_;
  const std::vector<FluidConstants>& fluids_;
  double wall_volume_;
  Column<std::uint8_t>& zone_;
  ParticleLedger<D> ledger_;
  std::vector<std::int64_t> through_, tally_;
  std::vector<std::size_t> lane_offset_;
  std::vector<double> lane_value_, lane_pressure_, lane_sums_;
  // xi of each pressure-outlet lane's outermost particle (empty without a pressure outlet)
  std::vector<double> lane_far_;
  std::vector<std::uint32_t> parents_, doomed_;
  std::vector<std::uint8_t> parent_zone_;
  std::vector<double> parent_shift_;  // along n, from the parent to its copy
};

}  // namespace sph
