// Solver throughput benchmark (not a test): builds a dam-break scene of about N fluid
// particles in 2D or 3D, runs S steps and prints particle-steps/s, pair interactions/s,
// bytes per particle, the time share of each physics unit and of communication.
// Run under mpirun for the parallel numbers (tests/bench/scaling.sh drives that).
//
//   bench_solver [--dim 2|3] [--particles N] [--steps S] [--kernel quintic|wendland]
//                [--pair-kernel compact|table|stream]   (Case.pair_kernel_storage; default: the
//                case's) [--wall-thickness T]   (the tank's walls T thick: a scene mostly of
//                wall, as thick-walled cases are, for the load balancer)
//                [--balance pairs|kind]   (work per particle from its pairs, the default, or
//                fixed per kind) [--per-rank 1]   (each rank's particles, pairs and busy time)
//                [--independent 1]   (each rank runs its own copy alone: the machine's ceiling)
//                [--output K]   (then K snapshots and K checkpoints, each timed: their share of a
//                run at cases/dambreak_2d's output.interval and sph-worker's checkpoint interval)
//   bench_solver --case FILE [--steps S] [--skip T]   (any case; --skip advances T steps first,
//                                                     e.g. to time bodies in contact)
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "case/estimate.h"
#include "case/load.h"
#include "solver/core/kernel.h"
#include "solver/parallel/load_balance.h"
#include "solver/run/simulation.h"

namespace {

// This process's resident memory (/proc/self/status), bytes: the resident set now, at its
// peak, and the part of it in shared memory (Open MPI's shared-memory transport maps its
// peers' segments, which every process counts again).
struct Resident {
  double now = 0, peak = 0, shared = 0;
};
Resident resident_bytes() {
  Resident r;
  if (std::FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, f)) {
      double kb = 0;
      if (std::sscanf(line, "VmRSS: %lf kB", &kb) == 1) r.now = 1024 * kb;
      if (std::sscanf(line, "VmHWM: %lf kB", &kb) == 1) r.peak = 1024 * kb;
      if (std::sscanf(line, "RssShmem: %lf kB", &kb) == 1) r.shared = 1024 * kb;
    }
    std::fclose(f);
  }
  return r;
}

sph::v1::Vec3 vec(double x, double y, double z) {
  sph::v1::Vec3 v;
  v.set_x(x);
  v.set_y(y);
  v.set_z(z);
  return v;
}

// Adami 2012 dam break (L = H = 1, tank 4 x 2 [x 1 in 3D]), dx chosen for ~n fluid particles.
// wall_thickness > 0: the tank's walls that thick (a scene mostly of wall, for the balancer).
sph::v1::Case dam_break(int dim, double n, bool wendland, double wall_thickness) {
  sph::v1::Case c;
  c.set_name("bench_dambreak");
  c.set_dimension(dim);
  const double depth = dim == 3 ? 1.0 : 0.0;
  const double dx = dim == 2 ? 1.0 / std::sqrt(n) : std::cbrt(depth / n);
  c.set_dx(dx);
  c.set_kernel(wendland ? sph::v1::WENDLAND_C2 : sph::v1::QUINTIC_SPLINE);
  const double pad = 4 * dx + wall_thickness;
  *c.mutable_domain()->mutable_lo() = vec(-pad, -pad, dim == 3 ? -pad : 0);
  *c.mutable_domain()->mutable_hi() = vec(4 + pad, 2 + pad, dim == 3 ? depth + pad : 0);
  auto* m = c.add_materials();
  m->set_name("water");
  m->set_density(1);
  m->mutable_eos()->set_kind(sph::v1::TAIT);
  m->mutable_eos()->set_sound_speed(20);
  auto* f = c.add_fluids();
  f->set_name("column");
  f->set_material("water");
  *f->mutable_shape()->mutable_box()->mutable_lo() = vec(0, 0, 0);
  *f->mutable_shape()->mutable_box()->mutable_hi() = vec(1, 1, depth);
  auto* w = c.add_walls();
  w->set_name("tank");
  w->set_free_slip(true);
  if (wall_thickness > 0) w->mutable_shape()->mutable_shell()->set_thickness(wall_thickness);
  auto* inner = w->mutable_shape()->mutable_shell()->mutable_inner()->mutable_box();
  *inner->mutable_lo() = vec(0, 0, 0);
  *inner->mutable_hi() = vec(4, 2, depth);
  c.mutable_fluid_model()->set_density(sph::v1::CONTINUITY);
  c.mutable_fluid_model()->set_artificial_viscosity(0.1);
  *c.mutable_gravity()->mutable_acceleration() = vec(0, -1, 0);
  c.mutable_time()->set_end_time(100);
  return c;
}

// Writes `k` snapshots, then `k` checkpoints, as run() does at output and checkpoint times,
// and prints each one's time (slowest rank) and its share of a run: a snapshot every
// output.interval of simulated time (cases/dambreak_2d's 0.1 s, at this case's dt) and a
// checkpoint every 300 s of wall time (sph-worker's --checkpoint-interval default).
template <int D, class K>
void time_outputs(sph::Simulation<D, K>& sim, int k, double ms_per_step, bool print,
                  MPI_Comm comm) {
  auto timed = [&](auto&& write) {
    std::vector<double> t;
    for (int i = 0; i < k; ++i) {
      MPI_Barrier(comm);
      const double t0 = MPI_Wtime();
      write();
      MPI_Barrier(comm);
      t.push_back(MPI_Wtime() - t0);
    }
    std::sort(t.begin(), t.end());
    return t;
  };
  const std::vector<double> snap = timed([&] { sim.write_snapshot(); });
  std::string path;
  const std::vector<double> ckpt = timed([&] { path = sim.write_checkpoint_now(); });
  if (!print) return;
  const double interval = 0.1, ckpt_every = 300;
  const double steps_per_interval = interval / sim.dt();
  const double run_s = steps_per_interval * ms_per_step * 1e-3;
  const auto mb = [](const std::string& p) {
    std::error_code ec;
    const auto n = std::filesystem::file_size(p, ec);
    return ec ? 0.0 : static_cast<double>(n) / (1 << 20);
  };
  std::printf(
      "  snapshot           %10.3f s (median of %d; %.3f-%.3f); every %.2g s of simulated time "
      "(%.0f steps of dt = %.3g, %.1f s): %.2f %% of the run\n",
      snap[snap.size() / 2], k, snap.front(), snap.back(), interval, steps_per_interval, sim.dt(),
      run_s, 100 * snap[snap.size() / 2] / (run_s + snap[snap.size() / 2]));
  std::printf(
      "  checkpoint         %10.3f s (median of %d; %.3f-%.3f), %.1f MiB; every %.0f s of wall "
      "time: %.2f %% of the run\n",
      ckpt[ckpt.size() / 2], k, ckpt.front(), ckpt.back(), mb(path), ckpt_every,
      100 * ckpt[ckpt.size() / 2] / ckpt_every);
  std::fflush(stdout);
}

// Returns this run's ms per step; prints the report if `print` (on the comm's rank 0).
template <int D, class K>
double bench(const sph::v1::Case& c, int steps, int skip, bool balance_by_kind, bool per_rank,
             int outputs, bool print, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  sph::RunOptions o;
  o.output_dir =
      (std::filesystem::temp_directory_path() / ("sphd-bench-" + std::to_string(::getpid())))
          .string();
  o.output_dir = sph::Comm(comm).broadcast(o.output_dir);  // rank 0's pid names the directory
  o.quiet = true;
  o.balance_by_kind = balance_by_kind;
  const Resident before = resident_bytes();  // MPI, libraries: not the solver's
  sph::Simulation<D, K> sim(c, sph::Comm(comm), o);
  const double t_setup = MPI_Wtime();
  sim.start();
  const double setup = MPI_Wtime() - t_setup;
  for (int k = 0; k < 5 + skip; ++k) sim.step();  // warm-up: first neighbour lists, page faults
  const auto units0 = sim.unit_seconds();
  const double comm0 = sim.communication_seconds();
  const std::int64_t rebalances0 = sim.rebalances();
  MPI_Barrier(comm);
  const double t0 = MPI_Wtime();
  for (int k = 0; k < steps; ++k) {
    const auto r = sim.step();
    if (r.violated) {
      if (rank == 0) std::printf("run became unstable: %s\n", r.diagnosis.c_str());
      break;
    }
  }
  MPI_Barrier(comm);
  const double wall = MPI_Wtime() - t0;
  const double comm_s = sim.communication_seconds() - comm0;
  double pairs = static_cast<double>(sim.pairs());
  MPI_Allreduce(MPI_IN_PLACE, &pairs, 1, MPI_DOUBLE, MPI_SUM, comm);
  double bytes = 0;
  auto by_owner = sim.memory_by_owner();
  for (auto& [owner, b] : by_owner) {
    double v = static_cast<double>(b);
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, comm);
    b = static_cast<std::size_t>(v);
    bytes += v;
  }
  // What the solver holds in memory, counted by the operating system rather than by the
  // columns' capacities: this process's resident set now and at its peak (the scene's
  // construction included) less what it held before the simulation was built, over all ranks.
  const Resident after = resident_bytes();
  double resident[3] = {after.now - before.now, after.peak - before.now,
                        after.shared - before.shared};
  MPI_Allreduce(MPI_IN_PLACE, resident, 3, MPI_DOUBLE, MPI_SUM, comm);
  double comm_max = comm_s;
  MPI_Allreduce(MPI_IN_PLACE, &comm_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  // Busy time: the step less halo exchange and reductions (and the waits in them). Its
  // largest over its mean is the imbalance of the work as it ran, not as the work model
  // counts it.
  double busy_max = wall - comm_s, busy_sum = wall - comm_s;
  MPI_Allreduce(MPI_IN_PLACE, &busy_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &busy_sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  // Every rank's busy time and unit times, to see where the slowest rank's time goes.
  std::vector<double> mine;
  for (const auto& [name, sec] : sim.unit_seconds()) {
    const auto it = units0.find(name);
    mine.push_back(sec - (it == units0.end() ? 0.0 : it->second));
  }
  // Lists of every owned particle (as after any full step; a case whose last step ended
  // otherwise gets no per-rank pairs and no work model).
  const bool listed = sim.neighbor_list().listed() == sim.particles().owned();
  if (per_rank && listed) {
    // Each rank's particles and pairs by kind, beside its busy time: is a slow rank one with
    // more work than the model counts, or a slower core?
    double pairs_by_kind[2] = {0, 0}, count_by_kind[2] = {0, 0};
    for (std::size_t i = 0; i < sim.particles().owned(); ++i) {
      const int k = sim.particles().kind[i] == sph::Kind::kWall ? 1 : 0;
      pairs_by_kind[k] +=
          static_cast<double>(sim.neighbor_list().end(i) - sim.neighbor_list().begin(i));
      count_by_kind[k] += 1;
    }
    std::printf(
        "  rank %2d: fluid-like %.0f (%.0f pairs), wall %.0f (%.0f pairs), ghosts %zu, busy "
        "%.2f ms/step\n",
        rank, count_by_kind[0], pairs_by_kind[0], count_by_kind[1], pairs_by_kind[1],
        sim.particles().size() - sim.particles().owned(), 1e3 * (wall - comm_s) / steps);
    std::fflush(stdout);
  }
  mine.push_back(wall - comm_s);
  int len = static_cast<int>(mine.size()), len_min = len, len_max = len;
  MPI_Allreduce(&len, &len_min, 1, MPI_INT, MPI_MIN, comm);
  MPI_Allreduce(&len, &len_max, 1, MPI_INT, MPI_MAX, comm);
  std::vector<double> every(len_min == len_max ? static_cast<std::size_t>(len * size) : 0);
  if (len_min == len_max)
    MPI_Gather(mine.data(), len, MPI_DOUBLE, every.data(), len, MPI_DOUBLE, 0, comm);
  const double n = static_cast<double>(sim.global_particles());
  double nf = 0;
  for (std::size_t i = 0; i < sim.particles().owned(); ++i)
    nf += sim.particles().kind[i] == sph::Kind::kFluid ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &nf, 1, MPI_DOUBLE, MPI_SUM, comm);
  // The load balancer's work model (solver/parallel/load_balance.h) summed by kind, to fit its
  // coefficients against measured times.
  double work[2] = {0, 0};  // fluid-like (fluid, rigid, elastic), wall
  for (std::size_t i = 0; listed && i < sim.particles().owned(); ++i)
    work[sim.particles().kind[i] == sph::Kind::kWall ? 1 : 0] +=
        static_cast<double>(sph::pair_work(sim.particles(), sim.neighbor_list(), i));
  MPI_Allreduce(MPI_IN_PLACE, work, 2, MPI_DOUBLE, MPI_SUM, comm);
  if (rank == 0 && print) {
    std::printf(
        "bench_solver case=%s dim=%d kernel=%s pair_kernel=%s ranks=%d particles=%.0f (dx=%.4g) "
        "steps=%d from t=%.4g setup=%.2fs\n",
        c.name().c_str(), D, K::kSupport == 3.0 ? "quintic" : "wendland",
        sph::pair_kernel_storage(c) == sph::v1::PAIR_KERNEL_STREAM  ? "stream"
        : sph::pair_kernel_storage(c) == sph::v1::PAIR_KERNEL_TABLE ? "table"
                                                                    : "compact",
        size, n, c.dx(), steps, sim.time(), setup);
    std::printf("  time/step          %10.3f ms\n", 1e3 * wall / steps);
    std::printf("  particle-steps/s   %10.3e  (%.3e per rank; all particles, walls included)\n",
                n * steps / wall, n * steps / wall / size);
    std::printf("  fluid p-steps/s    %10.3e  (%.3e per rank; %.0f fluid particles)\n",
                nf * steps / wall, nf * steps / wall / size, nf);
    std::printf("  pair interactions  %10.3e /s  (%.1f neighbours per particle)\n",
                pairs * steps / wall, pairs / n);
    std::printf(
        "  work model         %10.4g fluid-like, %.4g wall (quarter pair visits, %.0f wall "
        "particles)\n",
        work[0], work[1], n - nf);
    std::printf("  memory             %10.0f bytes/particle\n", bytes / n);
    for (const auto& [owner, b] : by_owner)
      if (b > 0) std::printf("    %-22s %6.0f B\n", owner.c_str(), static_cast<double>(b) / n);
    std::printf(
        "  resident           %10.0f bytes/particle (peak %.0f; of it in shared memory %.0f: the "
        "processes' resident set less what they held before the scene)\n",
        resident[0] / n, resident[1] / n, resident[2] / n);
    std::printf(
        "  communication      %10.1f %% of step time (rank 0), %.1f %% (rank that waits most)\n",
        100 * comm_s / wall, 100 * comm_max / wall);
    std::printf("  imbalance          %10.3f (work model: largest rank / mean; %lld rebalances)\n",
                sim.imbalance(), static_cast<long long>(sim.rebalances() - rebalances0));
    std::printf(
        "  busy imbalance     %10.3f (measured: largest rank's time outside communication / "
        "mean)\n",
        busy_sum > 0 ? busy_max * size / busy_sum : 1.0);
    if (!every.empty() && size > 1) {
      int slow = 0, fast = 0;
      const auto busy_of = [&](int r) {
        return every[static_cast<std::size_t>(r * len + len - 1)];
      };
      std::printf("  busy per rank      ");
      for (int r = 0; r < size; ++r) {
        std::printf(" %.2f", 1e3 * busy_of(r) / steps);
        if (busy_of(r) > busy_of(slow)) slow = r;
        if (busy_of(r) < busy_of(fast)) fast = r;
      }
      std::printf(" ms/step\n  time per unit, slowest rank %d / fastest rank %d (%% of step):\n",
                  slow, fast);
      int k = 0;
      for (const auto& [name, sec] : sim.unit_seconds()) {
        std::printf("      %-22s %6.1f %6.1f\n", name.c_str(),
                    100 * every[static_cast<std::size_t>(slow * len + k)] / wall,
                    100 * every[static_cast<std::size_t>(fast * len + k)] / wall);
        ++k;
      }
    }
    std::printf("  time per unit (rank 0):\n");
    for (const auto& [name, sec] : sim.unit_seconds()) {
      const auto it = units0.find(name);
      const double d = sec - (it == units0.end() ? 0.0 : it->second);
      std::printf("    %-22s %6.1f %%\n", name.c_str(), 100 * d / wall);
    }
    std::fflush(stdout);
  }
  if (outputs > 0) time_outputs(sim, outputs, 1e3 * wall / steps, rank == 0 && print, comm);
  if (rank == 0) std::filesystem::remove_all(o.output_dir);
  return 1e3 * wall / steps;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int dim = 2, steps = 50, skip = 0;
  std::string case_file;
  double particles = 20000, wall_thickness = 0;
  bool balance_by_kind = false, per_rank = false, independent = false;
  bool wendland = false;
  int outputs = 0;
  std::string pair_kernel;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--dim")
      dim = std::stoi(v);
    else if (a == "--particles")
      particles = std::stod(v);
    else if (a == "--steps")
      steps = std::stoi(v);
    else if (a == "--kernel")
      wendland = v == "wendland";
    else if (a == "--case")
      case_file = v;
    else if (a == "--skip")
      skip = std::stoi(v);
    else if (a == "--pair-kernel")
      pair_kernel = v;
    else if (a == "--wall-thickness")
      wall_thickness = std::stod(v);
    else if (a == "--balance")
      balance_by_kind = v == "kind";
    else if (a == "--per-rank")
      per_rank = v == "1";
    else if (a == "--independent")
      independent = v == "1";
    else if (a == "--output")
      outputs = std::stoi(v);
  }
  sph::v1::Case c = case_file.empty() ? dam_break(dim, particles, wendland, wall_thickness)
                                      : sph::load_case_file(case_file);
  if (!case_file.empty()) {
    dim = c.dimension();
    wendland = c.kernel() == sph::v1::WENDLAND_C2;
    c.mutable_time()->set_end_time(1e30);  // the benchmark decides how long it runs
    c.mutable_time()->set_max_steps(0);
    c.mutable_output()->set_interval(0);
    c.mutable_output()->clear_times();
    c.mutable_output()->set_series_interval(1e29);
  }
  if (pair_kernel == "stream") c.set_pair_kernel_storage(sph::v1::PAIR_KERNEL_STREAM);
  if (pair_kernel == "table") c.set_pair_kernel_storage(sph::v1::PAIR_KERNEL_TABLE);
  if (pair_kernel == "compact") c.set_pair_kernel_storage(sph::v1::PAIR_KERNEL_COMPACT);
  // --independent 1: every rank runs its own copy of the case alone (MPI_COMM_SELF), none
  // waiting for another. Against one copy run alone, this is the machine's ceiling for the
  // solver's speed-up: what the cores give when they all work at once and never communicate.
  int world_rank = 0, world_size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  const MPI_Comm comm = independent ? MPI_COMM_SELF : MPI_COMM_WORLD;
  const bool print = world_rank == 0;
  double ms = 0;
  if (dim == 2) {
    if (wendland)
      ms = bench<2, sph::WendlandC2<2>>(c, steps, skip, balance_by_kind, per_rank, outputs, print,
                                        comm);
    else
      ms = bench<2, sph::QuinticSpline<2>>(c, steps, skip, balance_by_kind, per_rank, outputs,
                                           print, comm);
  } else {
    if (wendland)
      ms = bench<3, sph::WendlandC2<3>>(c, steps, skip, balance_by_kind, per_rank, outputs, print,
                                        comm);
    else
      ms = bench<3, sph::QuinticSpline<3>>(c, steps, skip, balance_by_kind, per_rank, outputs,
                                           print, comm);
  }
  if (independent) {
    std::vector<double> all(static_cast<std::size_t>(world_size));
    MPI_Gather(&ms, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    if (world_rank == 0) {
      double lo = all[0], hi = all[0], sum = 0;
      for (const double v : all) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        sum += v;
      }
      std::printf(
          "  independent copies %10d: ms/step min %.3f mean %.3f max %.3f\n  per copy          ",
          world_size, lo, sum / world_size, hi);
      for (const double v : all) std::printf(" %.2f", v);
      std::printf("\n");
    }
  }
  MPI_Finalize();
  return 0;
}
