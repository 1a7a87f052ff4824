// What each effect costs (not a test): one scene, a disk settling in a heated box, run as
// fluid only, + heat conduction, + concentration diffusion, + a rigid body, + contact, + heat
// with bodies and contact, + phase change (the disk melting from its rim), + a drop of a second
// fluid in place of the disk, + surface tension between the two fluids, the fluid with density
// by the continuity equation without and with density diffusion or Riemann dissipation (in the
// continuity equation, and in it and the momentum equation), the box filled to 4/5 with and
// without surface tension on its free surface, the fluid without the transport
// velocity and with particle shifting instead of it, the box's walls growing into the fluid
// around the disk, and for each the time per step by unit and the per-particle storage by unit.
// A unit a scene does not use must show no time and no storage.
//
//   bench_effects [--steps S] [--dx DX] [--pair-kernel compact|table|stream] [--only LABEL_PART]
#include <mpi.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "case/load.h"
#include "solver/core/kernel.h"
#include "solver/run/simulation.h"

namespace {

struct Effects {
  bool heat = false, body = false, contact = false, concentration = false, phase = false;
  bool drop = false, tension = false;  // a drop of a second fluid; surface tension on its rim
  // The box filled to 4/5, so the fluid has a free surface; surface tension on it (no gas).
  bool free_surface = false, free_tension = false;
  bool plate = false;              // an elastic plate standing on the floor, clamped there
  bool continuity = false;         // density by the continuity equation, not summation
  bool density_diffusion = false;  // with its density diffusion (Fourtakas, delta 0.1)
  bool riemann = false;            // with Riemann dissipation (CONTINUITY)
  bool riemann_momentum = false;   // with Riemann dissipation (CONTINUITY_AND_MOMENTUM)
  // The contact model with `contact` (docs/contact.md): the spring-dashpot with a damping,
  // with the damping from a restitution, impulses, Glowinski's repulsion.
  enum class Law {
    kSpringDashpot,
    kSpringDashpotFromE,
    kImpulses,
    kRepulsion
  } law = Law::kSpringDashpot;
  bool no_transport = false;  // without the transport velocity
  bool shifting = false;      // particle shifting (LOCAL, A = 2) instead of it
  bool grow = false;  // the box's walls grow into the fluid at 0.1 m/s (docs/growing_walls.md)
};

std::string scene(double dx, const Effects& e) {
  char head[256];
  std::snprintf(
      head, sizeof head,
      "dimension: 2 dx: %.10g domain { lo { x: -0.003 y: -0.003 } hi { x: 0.053 y: 0.053 } }\n",
      dx);
  std::string t = head;
  const std::string thermal = e.heat ? "heat_capacity: 4000 thermal_conductivity: 0.6 " : "";
  const std::string diffusive = e.concentration ? "diffusivity: 1e-6 " : "";
  t +=
      R"(materials { name: "fluid" density: 1000 eos { sound_speed: 1 } kinematic_viscosity: 1e-5 )" +
      thermal + diffusive + "}\n";
  t += R"(materials { name: "solid" phase: SOLID density: 2000 )";
  if (e.heat) t += "heat_capacity: 500 thermal_conductivity: 20 ";
  t += diffusive + "}\n";
  // The melt of the disk (phase change): a second fluid phase.
  if (e.phase)
    t +=
        R"(materials { name: "melt" density: 2000 eos { sound_speed: 1 } kinematic_viscosity: 1e-5 )" +
        std::string("heat_capacity: 500 thermal_conductivity: 20 }\n");
  // The drop: oil-like, of the same density, where the disk would be but floating mid-box.
  if (e.drop) {
    t +=
        R"(materials { name: "drop" density: 1000 eos { sound_speed: 1 } kinematic_viscosity: 1e-5 })";
    t += R"(
fluids { material: "fluid" shape { difference { base { box { lo { x: 0 y: 0 } hi { x: 0.05 y: 0.05 } } } subtract { ball { center { x: 0.025 y: 0.025 } radius: 0.01 } } } } }
fluids { material: "drop" shape { ball { center { x: 0.025 y: 0.025 } radius: 0.01 } } })";
  } else {
    t += R"(fluids { material: "fluid" shape { box { lo { x: 0 y: 0 } hi { x: 0.05 y: )" +
         std::string(e.free_surface ? "0.04" : "0.05") + " } } } }";
  }
  // Water against oil, about 0.03-0.05 N/m.
  if (e.tension)
    t += R"(
surface_tension { pairs { material_a: "fluid" material_b: "drop" sigma: 0.04 } })";
  // Water against void (docs/surface_tension.md, "Free surfaces").
  if (e.free_tension)
    t += R"(
surface_tension { pairs { material_a: "fluid" sigma: 0.072 } })";
  t += "\nwalls { shape { shell { inner { box { lo { x: 0 y: 0 } hi { x: 0.05 y: 0.05 } } } } } ";
  if (e.heat) t += "temperature { value { constant: 350 } } ";
  if (e.concentration) t += "concentration { value { constant: 1 } } ";
  if (e.grow) t += "growth_speed { constant: 0.1 } ";
  t += "}\n";
  if (e.body)
    t +=
        R"(bodies { name: "disk" material: "solid" shape { ball { center { x: 0.025 y: 0.006 } radius: 0.005 } } )" +
        std::string(e.phase ? "initial_temperature: 300.55 " : "") + "}\n";
  if (e.contact) {
    switch (e.law) {
      case Effects::Law::kSpringDashpot:
        t += "contact { stiffness: 1e5 damping: 1 }\n";
        break;
      case Effects::Law::kSpringDashpotFromE:
        t += "contact { stiffness: 1e5 restitution: 0.5 }\n";
        break;
      case Effects::Law::kImpulses:
        t += "contact { model: RESTITUTION restitution: 0.5 }\n";
        break;
      case Effects::Law::kRepulsion:
        t += "contact { model: REPULSIVE repulsion { strength: 1 range: 1e-4 } }\n";
        break;
    }
  }
  // A rubber-like plate 2 mm thick and 20 mm tall standing in the water, its lowest 2 mm held:
  // E = 8 kPa gives c_s = 2.2 m/s, so its own step bound (thesis eq. 33) is about the fluid's.
  if (e.plate)
    t +=
        R"(materials { name: "rubber" phase: SOLID density: 1100 youngs_modulus: 8000 poisson_ratio: 0.3 )" +
        std::string(e.heat ? "heat_capacity: 2000 thermal_conductivity: 0.2 " : "") + R"(}
elastic_bodies { name: "plate" material: "rubber" shape { box { lo { x: 0.024 y: 0 } hi { x: 0.026 y: 0.02 } } }
  constraints { region { box { lo { x: 0.02 y: 0 } hi { x: 0.03 y: 0.002 } } } } }
)";
  // With phase change the fluid starts at 302 and the disk at 300.55, just below its melting
  // point of 300.6: the contact temperature of water and this solid (effusivities 1.5e3 and
  // 4.5e3) is 300.92, so the disk melts from its rim inwards through the run (measured: from
  // step 25 on, 196 particles by step 120, in pieces every few steps) and the row measures
  // steps that melt particles and rebuild the body, not only the check.
  if (e.heat)
    t += e.phase ? "thermal { initial_temperature: 302 }\n"
                 : "thermal { initial_temperature: 300 }\n";
  if (e.concentration) t += "diffusion { initial_concentration: 0 }\n";
  if (e.phase)
    t +=
        R"(phase_transitions { solid_material: "solid" fluid_material: "melt" driver: TEMPERATURE transition_value: 300.5 hysteresis: 0.2 reversible: true }
)";
  t += e.continuity
           ? "fluid_model { density: CONTINUITY transport_velocity: true " +
                 std::string(e.density_diffusion
                                 ? "density_diffusion { form: FOURTAKAS delta: 0.1 } "
                                 : "") +
                 std::string(e.riemann ? "riemann_dissipation { scope: CONTINUITY } " : "") +
                 std::string(e.riemann_momentum ? "riemann_dissipation { scope: "
                                                  "CONTINUITY_AND_MOMENTUM } "
                                                : "") +
                 "}\n"
       : e.no_transport || e.shifting
           ? "fluid_model { density: SUMMATION " +
                 std::string(e.shifting ? "particle_shifting { } " : "") + "}\n"
           : "fluid_model { density: SUMMATION transport_velocity: true }\n";
  t += R"(gravity { acceleration { y: -9.81 } }
time { end_time: 1e9 }
output { series_interval: 1e9 })";
  return t;
}

// Steps run before the timed ones (first neighbour searches, allocations).
constexpr int kWarmUpSteps = 20;

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
  for (int k = 0; k < kWarmUpSteps; ++k) sim.step();
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
  if (sim.particles_melted() + sim.particles_solidified() > 0)
    std::printf(" (%lld particles melted, %lld solidified in all %d steps)",
                static_cast<long long>(sim.particles_melted()),
                static_cast<long long>(sim.particles_solidified()), kWarmUpSteps + steps);
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
  std::string pair_kernel = "table";
  std::string only;  // run only the variants whose label contains it
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--steps") steps = std::stoi(argv[i + 1]);
    if (a == "--dx") dx = std::stod(argv[i + 1]);
    if (a == "--pair-kernel") pair_kernel = argv[i + 1];
    if (a == "--only") only = argv[i + 1];
  }
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    std::printf(
        "bench_effects: disk in a box, dx = %g, %d steps, pair kernel %s; per unit: ms per step; "
        "storage: bytes per particle\n",
        dx, steps, pair_kernel.c_str());
  const struct {
    const char* label;
    Effects effects;
  } variants[] = {
      {"fluid only", {}},
      {"+ heat", {.heat = true}},
      {"+ concentration", {.concentration = true}},
      {"+ rigid body", {.body = true}},
      {"+ body + contact", {.body = true, .contact = true}},
      {"+ body + contact, damping from restitution",
       {.body = true, .contact = true, .law = Effects::Law::kSpringDashpotFromE}},
      {"+ body + contact by impulses",
       {.body = true, .contact = true, .law = Effects::Law::kImpulses}},
      {"+ body + repulsive contact",
       {.body = true, .contact = true, .law = Effects::Law::kRepulsion}},
      {"+ heat + body + contact", {.heat = true, .body = true, .contact = true}},
      {"+ heat + phase change", {.heat = true, .body = true, .contact = true, .phase = true}},
      {"+ a drop of a second fluid", {.drop = true}},
      {"+ drop + surface tension", {.drop = true, .tension = true}},
      {"+ elastic plate", {.plate = true}},
      {"+ heat + elastic plate (thermal FSI)", {.heat = true, .plate = true}},
      {"continuity density", {.continuity = true}},
      {"continuity + density diffusion", {.continuity = true, .density_diffusion = true}},
      {"continuity + Riemann dissipation", {.continuity = true, .riemann = true}},
      {"continuity + Riemann dissipation (momentum)",
       {.continuity = true, .riemann_momentum = true}},
      {"continuity, free surface", {.free_surface = true, .continuity = true}},
      {"continuity, free surface + surface tension",
       {.free_surface = true, .free_tension = true, .continuity = true}},
      {"shifting: no transport velocity", {.no_transport = true}},
      {"shifting: on", {.shifting = true}},
      {"+ rigid body + growing walls", {.body = true, .grow = true}},
  };
  for (const auto& v : variants) {
    if (!only.empty() && std::string(v.label).find(only) == std::string::npos) continue;
    sph::v1::Case c = sph::parse_case_text(scene(dx, v.effects));
    if (pair_kernel == "stream") c.set_pair_kernel_storage(sph::v1::PAIR_KERNEL_STREAM);
    if (pair_kernel == "table") c.set_pair_kernel_storage(sph::v1::PAIR_KERNEL_TABLE);
    if (pair_kernel == "compact") c.set_pair_kernel_storage(sph::v1::PAIR_KERNEL_COMPACT);
    run(v.label, c, steps, MPI_COMM_WORLD);
  }
  MPI_Finalize();
  return 0;
}
