#pragma once
// One simulation run: builds the scene and the physics units a case calls for, then advances
// it with kick-drift-kick steps until the end time. Templated on dimension and kernel so the
// pair loops inline the kernel.
//
// The step is written down once, with its equations, in solver/seam/step_phase.h: the built-in
// stages (neighbour search, density and EOS, the wall condition, fluid forces, rigid bodies
// and contact, growing walls, open boundaries, phase transitions) run in that order, and the
// units on the seam (solver/seam/unit.h; heat, species, surface tension, ...) run at the
// phases they name.
// Each unit appears only if the case needs it; unit_seconds() reports what ran and its time.
// The implementation is split by concern:
//   simulation_impl.h         run, start, step, integrate_step: the step loop;
//   simulation_wiring_impl.h  the case wired into units and particles (unit_set.cc: seam units);
//   simulation_search_impl.h  migration, ghosts, neighbour lists, load balancing;
//   simulation_series_impl.h  every result series; run_recorder.h writes the files.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "case/anisotropy.h"
#include "case/estimate.h"
#include "case/materials.h"
#include "case/motion.h"
#include "solver/bodies/body_regrouping.h"
#include "solver/bodies/phase_transitions.h"
#include "solver/bodies/restitution_contact.h"
#include "solver/bodies/restitution_damping.h"
#include "solver/bodies/rigid_bodies.h"
#include "solver/bodies/spring_dashpot_contact.h"
#include "solver/boundaries/open_boundaries.h"
#include "solver/boundaries/wall_growth.h"
#include "solver/core/kernel.h"
#include "solver/core/neighbor_list.h"
#include "solver/core/pair_kernel.h"
#include "solver/core/particle_store.h"
#include "solver/diagnostics/conservation.h"
#include "solver/diagnostics/phase_mixing.h"
#include "solver/diagnostics/probes.h"
#include "solver/diagnostics/solid_fraction.h"
#include "solver/diagnostics/stability_guards.h"
#include "solver/integrate/kick_drift_kick.h"
#include "solver/integrate/time_step.h"
#include "solver/io/checkpoint.h"
#include "solver/io/result_file.h"
#include "solver/parallel/halo.h"
#include "solver/parallel/load_balance.h"
#include "solver/physics/body_force.h"
#include "solver/physics/continuity_density.h"
#include "solver/physics/density_summation.h"
#include "solver/physics/equation_of_state.h"
#include "solver/physics/fluid_forces.h"
#include "solver/physics/fluid_table.h"
#include "solver/physics/wall_boundary.h"
#include "solver/run/code_version.h"
#include "solver/run/output_schedule.h"
#include "solver/run/run_case.h"
#include "solver/run/run_recorder.h"
#include "solver/run/unit_set.h"
#include "solver/scene/scene_builder.h"

namespace sph {

template <int D, class K>
class Simulation {
 public:
  Simulation(const v1::Case& c, const Comm& comm, const RunOptions& opt);
  RunOutcome run();

  // Access for tests and benchmarks.
  ParticleStore<D>& particles() { return s_; }
  const std::map<std::string, double>& unit_seconds() const { return timers_; }
  // Fresh neighbour searches so far (with a Verlet skin, fewer than the steps).
  std::int64_t neighbor_searches() const { return searches_; }
  // Builds (or resumes) the run; then step() advances one checked step: the time step for
  // the next step is set, the decomposition rebalanced and memory reordered as needed.
  void start();
  struct StepReport {
    bool violated = false, cancel = false, interrupt = false, checkpoint = false,
         out_of_time = false;
    std::string diagnosis;
  };
  StepReport step();
  double time() const { return t_; }
  std::int64_t steps() const { return step_; }
  double dt() const { return dt_; }
  std::size_t pairs() const { return nl_.pairs(); }
  const NeighborList<D>& neighbor_list() const { return nl_; }
  std::map<std::string, std::size_t> memory_by_owner() const;
  // Seconds spent in MPI communication (halo exchanges and step reductions).
  double communication_seconds() {
    comm_seconds_ += halo_.take_comm_seconds();
    return comm_seconds_;
  }
  double imbalance() const { return imbalance_; }
  // The result file's snapshot of the state now, and a checkpoint (returns its path): what
  // run() writes at output times and checkpoint times (collective).
  void write_snapshot();
  std::string write_checkpoint_now();
  std::int64_t rebalances() const { return rebalances_; }  // since this process started
  std::int64_t global_particles() const { return global_particles_; }
  // Particles melted and solidified since the start (all ranks; 0 without phase transitions).
  std::int64_t particles_melted() const { return phase_ ? phase_->melted_total() : 0; }
  std::int64_t particles_solidified() const { return phase_ ? phase_->solidified_total() : 0; }

 private:
  class Timer {
   public:
    explicit Timer(double& acc) : acc_(acc), t0_(MPI_Wtime()) {}
    ~Timer() { acc_ += MPI_Wtime() - t0_; }

   private:
    double& acc_;
    double t0_;
  };
  double& timer(const char* name) { return timers_[name]; }

  void build_scene();
  void build_units();
  // By the work of the owned particles per kind (before the lists of a resumed run exist).
  void decompose_by_histogram();
  void prime();
  // How exchange_and_search() finds the neighbours:
  //  - kFresh: particles to their owners, ghosts and lists anew at the positions now;
  //  - kAsNeeded: with a Verlet skin, the ghosts refreshed and the lists refined from the
  //    candidates while no particle has moved half the skin since the last search; else kFresh;
  //  - kAtReference: ghosts and candidates anew at the positions of the last search, lists
  //    refined at the positions now: after a resume or a rebalance, which must not change
  //    which pairs are listed or their order (an uninterrupted run on any rank count keeps
  //    the candidates it has);
  //  - kKindsChanged: after a phase transition, with a Verlet skin, the same ghosts refreshed
  //    (kinds and bodies included) and the candidates sorted again by the kinds now, lists
  //    refined; without a skin, kFresh (melting and freezing happen over many steps, and a
  //    fresh search at each would cost as much as the steps without them).
  enum class Search { kFresh, kAsNeeded, kAtReference, kKindsChanged };
  void exchange_and_search(Search mode = Search::kFresh);
  // Whether some particle has moved half the skin since the last search (collective). First
  // brings positions that a prescribed motion carried whole periods away back to within a
  // period of where they were searched.
  bool moved_half_the_skin();
  void search_candidates();
  ContactQuery contact_query() const;  // of the bodies now (empty without contact)
  void compute_density_and_pressure(double dt);
  void apply_wall_condition();  // the wall values (when there are walls), then kWallState
  void apply_wall_values();
  void compute_forces();  // a^{n+1} cleared, the fluid forces, then the kForces units
  void compute_fluid_forces();
  void move_bodies(double dt);
  void migrate();
  // Rigid particles need all their neighbours when they conduct or diffuse.
  bool rigid_all() const { return temperature_ || concentration_; }
  void sample_bodies();
  std::string integrate_step(double dt);  // non-empty: why the run cannot go on
  // Contact sub-steps the coming step of length dt needs (1 when bodies cannot touch); step()
  // keeps it in substeps_ for move_bodies.
  int contact_substeps(double dt) const;
  int substeps_ = 1;
  // The largest solid fraction of a fluid particle's support on this rank (the guard's scan).
  SolidFractionScan scan_solid_fraction();
  struct EndOfStep {
    double max_speed = 0, max_acceleration = 0, max_density_dev = 0, min_contact_distance = 0;
    bool violated = false, cancel = false, interrupt = false, checkpoint = false,
         out_of_time = false;
    std::string diagnosis;
  };
  // One reduction per step carries the time-step input and every stop/checkpoint decision.
  EndOfStep end_of_step_checks();
  void sample_series();  // record_series() and the next sample time
  void record_series();
  void report_progress(bool force);
  std::map<std::string, std::string> metadata(const std::string& status) const;
  Vec<D> fluid_body_force(double t) const;
  void maybe_rebalance();

  const v1::Case& c_;
  Comm comm_;
  RunOptions opt_;
  std::vector<MaterialParams> mats_;
  std::vector<FluidConstants> fluids_;
  double dx_, h_, rc_;
  double skin_;  // Verlet skin of the neighbour search (0: searched every step)
  double wall_volume_;
  K kernel_;
  CellGrid<D> grid_;
  Halo<D> halo_;
  ParticleStore<D> s_;
  NeighborList<D> nl_;
  PairKernel<D> pk_{pair_kernel_storage(c_) == v1::PAIR_KERNEL_STREAM
                        ? PairKernel<D>::Storage::kStream
                    : pair_kernel_storage(c_) == v1::PAIR_KERNEL_TABLE
                        ? PairKernel<D>::Storage::kTable
                        : PairKernel<D>::Storage::kCompact};  // the kernel of nl_'s pairs
  GuardSettings guards_;
  OutputSchedule schedule_;
  RunRecorder recorder_;  // result file, checkpoints, progress, metadata

  // Units (present only when the case needs them).
  std::optional<DensitySummation<D, K>> summation_;
  std::optional<ContinuityDensity<D, K>> continuity_;
  std::optional<WallBoundary<D>> walls_;
  std::optional<Probes<D, K>> probes_;
  std::optional<FluidForces<D, K>> forces_;
  std::optional<BodyForce<D>> body_;
  std::optional<RigidBodies<D>> bodies_;
  // Columns of the heat conduction and species diffusion units (solver/physics/
  // scalar_transport.h), which phase transitions and open boundaries read and set.
  Column<double>* temperature_ = nullptr;
  Column<Vec<D>>* elastic_force_ = nullptr;  // fluid force on elastic particles (coupling)
  // Elastic particles move in the elastic solid's own sub-steps, not in the fluid's kicks
  // and drift (TimeControl.subcycle_elastic_bodies).
  bool subcycled_elastic_ = false;
  Column<double>* concentration_ = nullptr;
  Column<std::uint16_t>* wall_index_ = nullptr;
  std::unique_ptr<BodyContact<D>> contact_;   // the case's contact model
  std::optional<PhaseTransitions<D>> phase_;  // Fuchs 2021 eq. 29
  std::size_t body_slots_ = 0;                // width of the body series in the result
  void build_phase_transitions();
  std::string apply_phase_transitions();  // non-empty: why the run cannot go on
  bool contact_possible_ = false;         // a contact candidate nearer than dx (+ margin): substep
  double min_rigid_mass_ = 0;
  Column<Vec<D>>* transport_ = nullptr;   // u~ (transport-velocity formulation)
  Column<Vec<D>>* background_ = nullptr;  // a~
  Column<std::uint8_t>* free_slip_ = nullptr;
  std::vector<std::string> units_;
  UnitSet<D> unit_set_;  // the units on the seam (solver/seam/unit.h), wired in unit_set.cc
  void build_seam_units();
  StepContext<D> context(double dt) {
    return StepContext<D>{s_, nl_, pk_, halo_, comm_, t_, dt, step_};
  }
  double step_dt_ = 0;  // length of the step being taken (0 while priming)
  void run_phase(StepPhase phase) {
    if (unit_set_.empty()) return;
    StepContext<D> ctx = context(step_dt_);
    unit_set_.run(phase, ctx, timers_);
  }
  std::optional<TimeStepBound> bound_;
  bool fluid_gravity_ = true;

  // Inflow/outflow buffers (solver/boundaries/open_boundaries.h).
  std::optional<OpenBoundaries<D, K>> open_;
  // Free bodies leaving through an outflow: what remains of them is rebuilt (eq. 29).
  std::optional<BodyRegrouping<D>> leaving_;
  std::vector<std::int64_t> lost_;  // per body: particles that left this step
  std::string regroup_bodies_that_left();
  void build_open_boundaries();
  void set_open_boundary_pressure();
  void apply_open_boundaries_after_forces();

  // Walls growing into the fluid (solver/boundaries/wall_growth.h).
  std::optional<WallGrowth<D>> growth_;
  void build_wall_growth();
  // After the drift: converts what the fronts passed. `converted`: some particle changed kind
  // (all ranks alike); `engulfed`: some body was engulfed. Non-empty: why the run cannot go on.
  std::string grow_walls(bool& converted, bool& engulfed);

  // Run state (what a checkpoint stores besides the particles).
  double t_ = 0, dt_ = 0, dt0_ = 0, next_series_ = 0;
  std::int64_t step_ = 0;
  std::size_t next_output_ = 0;

  // Bookkeeping.
  std::map<std::string, double> timers_;
  double imbalance_ = 1;
  bool rebalance_due_ = false;  // checked at the start of the next step
  std::int64_t rebalances_ = 0;
  std::int64_t global_particles_ = 0;
  bool last_step_had_snapshot_ = false;
  double comm_seconds_ = 0;
  double solid_fraction_ = 0;  // largest fluid solid fraction after the last step
  bool phases_ = false;        // two or more fluid materials: the interface is watched
  double min_contact_distance_ = std::numeric_limits<double>::infinity();
  // Positions of the owned particles at the last search (with a skin; persistent, so a resume
  // lists the same candidates).
  Column<Vec<D>>* searched_at_ = nullptr;
  std::int64_t searches_ = 0;        // fresh searches since t = 0 (not a rebalance's or resume's)
  std::int64_t reordered_at_ = -25;  // step of the last memory reordering
};

// Instantiated in simulation_2d.cc and simulation_3d.cc, the only files that include
// simulation_impl.h.
extern template class Simulation<2, QuinticSpline<2>>;
extern template class Simulation<2, WendlandC2<2>>;
extern template class Simulation<3, QuinticSpline<3>>;
extern template class Simulation<3, WendlandC2<3>>;

}  // namespace sph
