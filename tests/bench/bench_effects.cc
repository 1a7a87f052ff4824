// What each effect costs (not a test): one scene, a disk settling in a heated box, run as
// fluid only, + heat conduction, + a rigid body, + contact, + all, and for each the time per
// step by unit and the per-particle storage by unit. A unit a scene does not use must show
// no time and no storage.
//
//   bench_effects [--steps S] [--dx DX]
#include <mpi.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "case/load.h"
#include "solver/core/kernel.h"
#include "solver/run/simulation.h"

namespace {

std::string scene(double dx, bool heat, bool body, bool contact) {
  char head[256];
  std::snprintf(
      head, sizeof head,
      "dimension: 2 dx: %.10g domain { lo { x: -0.003 y: -0.003 } hi { x: 0.053 y: 0.053 } }\n",
      dx);
  std::string t = head;
  t +=
      R"(materials { name: "fluid" density: 1000 eos { sound_speed: 1 } kinematic_viscosity: 1e-5 )";
  if (heat) t += "heat_capacity: 4000 thermal_conductivity: 0.6 ";
  t += "}\n";
  t += R"(materials { name: "solid" phase: SOLID density: 2000 )";
  if (heat) t += "heat_capacity: 500 thermal_conductivity: 20 ";
  t += "}\n";
  t += R"(fluids { material: "fluid" shape { box { lo { x: 0 y: 0 } hi { x: 0.05 y: 0.05 } } } })";
  t += "\nwalls { shape { shell { inner { box { lo { x: 0 y: 0 } hi { x: 0.05 y: 0.05 } } } } } ";
  if (heat) t += "temperature { value { constant: 350 } } ";
  t += "}\n";
  if (body)
    t +=
        R"(bodies { name: "disk" material: "solid" shape { ball { center { x: 0.025 y: 0.006 } radius: 0.005 } } }
)";
  if (contact) t += "contact { stiffness: 1e5 damping: 1 }\n";
  if (heat) t += "thermal { initial_temperature: 300 }\n";
  t += R"(fluid_model { density: SUMMATION transport_velocity: true }
gravity { acceleration { y: -9.81 } }
time { end_time: 1e9 }
output { series_interval: 1e9 })";
  return t;
}

void run(const std::string& label, const sph::v1::Case& c, int steps, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  sph::RunOptions o;
  o.output_dir =
      (std::filesystem::temp_directory_path() / ("sphd-effects-" + std::to_string(::getpid())))
          .string();
  o.output_dir = sph::Comm(comm).broadcast(o.output_dir);
  o.quiet = true;
  sph::Simulation<2, sph::QuinticSpline<2>> sim(c, sph::Comm(comm), o);
  sim.start();
  for (int k = 0; k < 20; ++k) sim.step();
  const auto before = sim.unit_seconds();
  const double t0 = MPI_Wtime();
  for (int k = 0; k < steps; ++k) sim.step();
  const double wall = MPI_Wtime() - t0;
  if (rank != 0) return;
  const double n = static_cast<double>(sim.global_particles());
  std::printf("%-22s %8.3f ms/step  ", label.c_str(), 1e3 * wall / steps);
  for (const auto& [unit, sec] : sim.unit_seconds()) {
    const auto it = before.find(unit);
    const double d = sec - (it == before.end() ? 0.0 : it->second);
    if (d > 1e-4 * wall) std::printf(" %s %.3f", unit.c_str(), 1e3 * d / steps);
  }
  std::printf("\n%-22s %8.0f bytes/particle ", "", [&] {
    double b = 0;
    for (const auto& [u, x] : sim.memory_by_owner()) b += static_cast<double>(x);
    return b / n;
  }());
  for (const auto& [unit, b] : sim.memory_by_owner())
    std::printf(" %s %.0f", unit.c_str(), static_cast<double>(b) / n);
  std::printf("\n");
  std::fflush(stdout);
  std::filesystem::remove_all(o.output_dir);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int steps = 200;
  double dx = 2.5e-4;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--steps") steps = std::stoi(argv[i + 1]);
    if (a == "--dx") dx = std::stod(argv[i + 1]);
  }
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    std::printf(
        "bench_effects: disk in a box, dx = %g, %d steps; per unit: ms per step; storage: bytes "
        "per particle\n",
        dx, steps);
  const struct {
    const char* label;
    bool heat, body, contact;
  } variants[] = {{"fluid only", false, false, false},
                  {"+ heat", true, false, false},
                  {"+ rigid body", false, true, false},
                  {"+ body + contact", false, true, true},
                  {"+ heat + body + contact", true, true, true}};
  for (const auto& v : variants)
    run(v.label, sph::parse_case_text(scene(dx, v.heat, v.body, v.contact)), steps, MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}
