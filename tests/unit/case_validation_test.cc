// Case loading and validation: every error names the field path and the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "case/case_limits.h"
#include "case/estimate.h"
#include "case/load.h"
#include "case/validate.h"
#include "tests/support/field_errors.h"

namespace sph {
namespace {

const char* kBase = R"(
name: "t"
dimension: 2
dx: 0.1
domain { lo { x: 0 y: 0 } hi { x: 2 y: 2 } }
materials { name: "water" density: 1000 eos { sound_speed: 10 } }
fluids { name: "f" material: "water" shape { box { lo { x: 0.5 y: 0.5 } hi { x: 1.5 y: 1.5 } } } }
time { end_time: 1 }
)";

std::vector<FieldError> errors_of(const std::string& extra, ValidationLimits lim = {}) {
  return validate_case(parse_case_text(std::string(kBase) + extra), lim);
}

using testing::has_error;

std::string dump(const std::vector<FieldError>& errs) {
  return join_errors(errs);
}

TEST(CaseValidation, BaseCaseIsValid) {
  const auto errs = errors_of("");
  EXPECT_TRUE(errs.empty()) << dump(errs);
}

TEST(CaseValidation, MalformedTextNamesLineAndColumn) {
  try {
    parse_case_text("dimension: 2\ndx: 0.1\ndomain { lo { x: 0 ");
    FAIL() << "expected CaseLoadError";
  } catch (const CaseLoadError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
}

TEST(CaseValidation, UnknownFieldIsRejected) {
  try {
    parse_case_text("dimension: 2\nviscosity_of_the_moon: 3\n");
    FAIL() << "expected CaseLoadError";
  } catch (const CaseLoadError& e) {
    EXPECT_NE(std::string(e.what()).find("viscosity_of_the_moon"), std::string::npos) << e.what();
  }
}

TEST(CaseValidation, NegativeDx) {
  auto c = parse_case_text(kBase);
  c.set_dx(-0.1);
  const auto errs = validate_case(c);
  EXPECT_TRUE(has_error(errs, "dx", "must be > 0")) << dump(errs);
}

TEST(CaseValidation, DensityDiffusionNeedsContinuityOneFluidAndDeltaInRange) {
  const std::string dd = "fluid_model { density: CONTINUITY density_diffusion { ";
  EXPECT_TRUE(errors_of(dd + "form: FOURTAKAS delta: 0.1 } }").empty());
  EXPECT_TRUE(errors_of(dd + "form: MOLTENI_COLAGROSSI } }").empty());  // delta 0.1
  EXPECT_TRUE(has_error(errors_of(dd + "delta: nan } }"), "fluid_model.density_diffusion.delta",
                        "must be finite"));
  for (const char* bad : {"delta: 0", "delta: -0.1", "delta: 1.5"}) {
    const auto errs = errors_of(dd + bad + " } }");
    EXPECT_TRUE(has_error(errs, "fluid_model.density_diffusion.delta", "must be in (0, 1]"))
        << bad << ": " << dump(errs);
  }
  auto errs = errors_of("fluid_model { density: SUMMATION density_diffusion { } }");
  EXPECT_TRUE(has_error(errs, "fluid_model.density_diffusion",
                        "needs fluid_model.density: "
                        "CONTINUITY"))
      << dump(errs);
  errs = errors_of("fluid_model { density_diffusion { } }");  // unspecified = summation
  EXPECT_TRUE(has_error(errs, "fluid_model.density_diffusion", "CONTINUITY")) << dump(errs);
  errs = errors_of(dd + "} }\nmaterials { name: \"air\" density: 1 eos { sound_speed: 10 } }");
  EXPECT_TRUE(
      has_error(errs, "fluid_model.density_diffusion", "one fluid material; the case has 2"))
      << dump(errs);
}

TEST(CaseValidation, ParticleShiftingCoefficientsAndWhatItRefuses) {
  const std::string ps = "fluid_model { particle_shifting { ";
  EXPECT_TRUE(errors_of(ps + "} }").empty()) << dump(errors_of(ps + "} }"));
  EXPECT_TRUE(errors_of(ps + "coefficient: 6 surface_threshold: 0.9 speed: MAXIMUM } }").empty());
  for (const char* bad : {"coefficient: 0", "coefficient: -1", "coefficient: 11"}) {
    const auto errs = errors_of(ps + bad + " } }");
    EXPECT_TRUE(has_error(errs, "fluid_model.particle_shifting.coefficient", "must be in (0, 10]"))
        << bad << ": " << dump(errs);
  }
  for (const char* bad : {"surface_threshold: 0.5", "surface_threshold: 1.01"}) {
    const auto errs = errors_of(ps + bad + " } }");
    EXPECT_TRUE(
        has_error(errs, "fluid_model.particle_shifting.surface_threshold", "must be in (0.5, 1]"))
        << bad << ": " << dump(errs);
  }
  auto errs = errors_of("fluid_model { transport_velocity: true particle_shifting { } }");
  EXPECT_TRUE(has_error(errs, "fluid_model.particle_shifting",
                        "cannot be combined with fluid_model.transport_velocity"))
      << dump(errs);
  errs = errors_of(ps + "} }\nmaterials { name: \"air\" density: 1 eos { sound_speed: 10 } }");
  EXPECT_TRUE(
      has_error(errs, "fluid_model.particle_shifting", "one fluid material; the case has 2"))
      << dump(errs);
  errs = errors_of(ps +
                   "} }\nopen_boundaries { name: \"out\" kind: OUTFLOW material: \"water\" "
                   "region { lo { x: 1.8 y: 0 } hi { x: 2 y: 2 } } direction { x: 1 } }");
  EXPECT_TRUE(
      has_error(errs, "fluid_model.particle_shifting", "cannot be combined with open_boundaries"))
      << dump(errs);
}

TEST(CaseValidation, RiemannDissipationScopeLimiterAndWhatItRefuses) {
  const std::string rd = "fluid_model { density: CONTINUITY riemann_dissipation { ";
  EXPECT_TRUE(errors_of(rd + "} }").empty()) << dump(errors_of(rd + "} }"));
  EXPECT_TRUE(errors_of(rd + "scope: CONTINUITY_AND_MOMENTUM limiter_eta: 3 } }").empty());
  for (const char* bad : {"limiter_eta: 0", "limiter_eta: -3", "limiter_eta: 2e6"}) {
    const auto errs = errors_of(rd + bad + " } }");
    EXPECT_TRUE(
        has_error(errs, "fluid_model.riemann_dissipation.limiter_eta", "must be in (0, 1e6]"))
        << bad << ": " << dump(errs);
  }
  auto errs = errors_of(rd + "scope: 7 } }");
  EXPECT_TRUE(has_error(errs, "fluid_model.riemann_dissipation.scope",
                        "must be CONTINUITY or CONTINUITY_AND_MOMENTUM"))
      << dump(errs);
  errs = errors_of("fluid_model { riemann_dissipation { } }");  // unspecified = summation
  EXPECT_TRUE(
      has_error(errs, "fluid_model.riemann_dissipation", "needs fluid_model.density: CONTINUITY"))
      << dump(errs);
  errs = errors_of(
      "fluid_model { density: CONTINUITY density_diffusion { } riemann_dissipation { } }");
  EXPECT_TRUE(has_error(errs, "fluid_model.riemann_dissipation",
                        "cannot be combined with fluid_model.density_diffusion"))
      << dump(errs);
  EXPECT_TRUE(errors_of("fluid_model { density: CONTINUITY artificial_viscosity: 0.1 "
                        "riemann_dissipation { scope: CONTINUITY } }")
                  .empty());
  errs = errors_of(
      "fluid_model { density: CONTINUITY artificial_viscosity: 0.1 riemann_dissipation { scope: "
      "CONTINUITY_AND_MOMENTUM } }");
  EXPECT_TRUE(has_error(errs, "fluid_model.riemann_dissipation.scope",
                        "set fluid_model.artificial_viscosity to 0"))
      << dump(errs);
  errs = errors_of(rd + "} }\nmaterials { name: \"air\" density: 1 eos { sound_speed: 10 } }");
  EXPECT_TRUE(
      has_error(errs, "fluid_model.riemann_dissipation", "one fluid material; the case has 2"))
      << dump(errs);
}

TEST(CaseValidation, OutputIntervalBoundsTheSnapshotCount) {
  // end_time 1 / interval 1e-9: a billion snapshot times would be stored before the run.
  EXPECT_TRUE(
      has_error(errors_of("output { interval: 1e-9 }"), "output.interval", "at most 100000"));
  EXPECT_TRUE(errors_of("output { interval: 1e-5 }").empty());
}

TEST(CaseValidation, MissingMaterialIsNamed) {
  const auto errs = errors_of(
      R"(fluids { name: "g" material: "oil" shape { ball { center { x: 1 y: 1 } radius: 0.2 } } })");
  EXPECT_TRUE(has_error(errs, "fluids[1].material", "unknown material 'oil'")) << dump(errs);
}

TEST(CaseValidation, WrongPhaseAndDuplicates) {
  auto errs = errors_of(R"(materials { name: "steel" phase: SOLID density: 7800 }
materials { name: "water" density: 1 eos { sound_speed: 1 } }
fluids { name: "g" material: "steel" shape { ball { center { x: 1 y: 1 } radius: 0.2 } } })");
  EXPECT_TRUE(has_error(errs, "materials[2].name", "duplicate material name 'water'"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "fluids[1].material", "is SOLID, expected FLUID")) << dump(errs);
}

TEST(CaseValidation, EosNeedsExactlyOneScale) {
  const auto errs = errors_of(
      R"(materials { name: "air" density: 1 eos { sound_speed: 3 reference_pressure: 4 } })");
  EXPECT_TRUE(
      has_error(errs, "materials[1].eos", "exactly one of sound_speed and reference_pressure"))
      << dump(errs);
}

TEST(CaseValidation, TwoDimensionalVectorsMustHaveZeroZ) {
  const auto errs = errors_of(R"(gravity { acceleration { y: -1 z: -3 } })");
  EXPECT_TRUE(has_error(errs, "gravity.acceleration.z", "must be 0 in a 2D case")) << dump(errs);
}

TEST(CaseValidation, ShapeChecksNameNestedPaths) {
  const auto errs = errors_of(
      R"(walls { shape { difference { base { box { lo { x: 0 y: 0 } hi { x: 1 y: -1 } } } subtract { ball { radius: -2 } } } } })");
  EXPECT_TRUE(
      has_error(errs, "walls[0].shape.difference.base.box.hi.y", "must be greater than box.lo"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "walls[0].shape.difference.subtract[0].ball.radius", "must be > 0"))
      << dump(errs);
}

TEST(CaseValidation, DimensionSpecificShapes) {
  const auto errs =
      errors_of(R"(walls { shape { cylinder { axis { y: 1 } radius: 1 length: 1 } } })");
  EXPECT_TRUE(has_error(errs, "walls[0].shape.cylinder", "only in 3D cases")) << dump(errs);
}

TEST(CaseValidation, LatentHeatNeedsAnIntervalAndTemperature) {
  auto errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
thermal { }
phase_transitions { solid_material: "s" fluid_material: "water" driver: TEMPERATURE
                    latent_heat: 2e5 })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].latent_heat_interval", "is required"))
      << dump(errs);
  errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
thermal { }
phase_transitions { solid_material: "s" fluid_material: "water" driver: TEMPERATURE
                    latent_heat: -1 latent_heat_interval: 0 })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].latent_heat", "must be > 0")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].latent_heat_interval", "must be > 0"))
      << dump(errs);
  errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
diffusion { }
phase_transitions { solid_material: "s" fluid_material: "water" driver: CONCENTRATION
                    latent_heat: 1 latent_heat_interval: 1 })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].latent_heat", "needs driver TEMPERATURE"))
      << dump(errs);
  errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
thermal { }
phase_transitions { solid_material: "s" fluid_material: "water" driver: TEMPERATURE
                    latent_heat: 2e5 latent_heat_interval: 10 })");
  for (const auto& e : errs) EXPECT_EQ(e.field.find("latent"), std::string::npos) << dump(errs);
}

TEST(CaseValidation, FrictionNeedsATangentialStiffness) {
  auto errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
bodies { name: "b" material: "s" shape { ball { center { x: 1 y: 1 } radius: 0.2 } } }
contact { stiffness: 1 friction { coefficient: 0.3 } })");
  EXPECT_TRUE(has_error(errs, "contact.friction.tangential_stiffness", "must be > 0"))
      << dump(errs);
}

// The base case's fluid sits in [0.5, 1.5]^2 (dx = 0.1, r_c = 0.3); these buffers flank it.
const char* kInlet = R"(open_boundaries { name: "in" kind: INFLOW material: "water"
  region { lo { x: 0.2 y: 0.5 } hi { x: 0.5 y: 1.5 } } direction { x: 1 }
  profile: PARABOLIC mean_velocity: 0.5 ramp_time: 0.1 }
)";
const char* kOutlet = R"(open_boundaries { name: "out" kind: OUTFLOW material: "water"
  region { lo { x: 1.5 y: 0.5 } hi { x: 1.8 y: 1.5 } } direction { x: 1 } pressure: 0 }
)";

TEST(CaseValidation, OpenBoundariesAreAccepted) {
  auto errs = errors_of(std::string(kInlet) + kOutlet);
  EXPECT_TRUE(errs.empty()) << dump(errs);
  // A velocity outlet (Fuchs 2021's gas flow) and a flow along -y.
  errs = errors_of(R"(open_boundaries { name: "out" kind: OUTFLOW material: "water"
  region { lo { x: 0.5 y: 0.2 } hi { x: 1.5 y: 0.5 } } direction { y: -1 }
  profile: UNIFORM mean_velocity: 0.5 start_time: 0.2 })");
  EXPECT_TRUE(errs.empty()) << dump(errs);
}

TEST(CaseValidation, OpenBoundaryNeedsKindMaterialRegionAndDirection) {
  const auto errs = errors_of(R"(open_boundaries { name: "in" })");
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].kind", "is required")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].material", "is required")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].region", "is required")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].direction", "must not be zero")) << dump(errs);
}

TEST(CaseValidation, OpenBoundaryGeometry) {
  // Oblique direction, thinner than r_c, off the lattice, out of the domain.
  auto errs = errors_of(R"(open_boundaries { name: "in" kind: INFLOW material: "water"
  region { lo { x: -0.1 y: 0.5 } hi { x: 0.15 y: 2.5 } } direction { x: 1 y: 1 }
  mean_velocity: 1 })");
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].direction", "along a coordinate axis"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].region.lo.x", "must lie in the domain"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].region.hi.y", "must lie in the domain"))
      << dump(errs);
  errs = errors_of(R"(open_boundaries { name: "in" kind: INFLOW material: "water"
  region { lo { x: 0.25 y: 0.5 } hi { x: 0.45 y: 1.5 } } direction { x: 1 }
  mean_velocity: 1 })");
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].region.hi.x", "at least the kernel support"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].region.lo.x", "lattice cell face")) << dump(errs);
  // Along a periodic axis.
  errs = errors_of(std::string("periodic_x: true\n") + kInlet);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].direction", "periodic")) << dump(errs);
  // Two buffers overlapping, and the same name twice.
  errs = errors_of(std::string(kInlet) + kInlet);
  EXPECT_TRUE(has_error(errs, "open_boundaries[1].region", "overlaps open_boundaries[0]"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[1].name", "duplicate")) << dump(errs);
  // Names become series paths.
  errs = errors_of(R"(open_boundaries { name: "in/1" })");
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].name", "only letters")) << dump(errs);
}

TEST(CaseValidation, OpenBoundaryMaterialAndFlow) {
  // The material must exist and be a fluid; an inflow needs a positive mean velocity.
  auto errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
open_boundaries { name: "in" kind: INFLOW material: "s"
  region { lo { x: 0.2 y: 0.5 } hi { x: 0.5 y: 1.5 } } direction { x: 1 } }
open_boundaries { name: "in2" kind: INFLOW material: "oil" mean_velocity: -1
  region { lo { x: 0.5 y: 1.5 } hi { x: 1.5 y: 1.8 } } direction { y: -1 } })");
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].material", "is SOLID, expected FLUID"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].mean_velocity", "required for an INFLOW"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[1].material", "unknown material 'oil'"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[1].mean_velocity", "must be > 0")) << dump(errs);
  // A pressure outlet has no profile or ramp; an inflow has no outlet pressure.
  errs = errors_of(R"(open_boundaries { name: "out" kind: OUTFLOW material: "water"
  region { lo { x: 1.5 y: 0.5 } hi { x: 1.8 y: 1.5 } } direction { x: 1 }
  profile: PARABOLIC ramp_time: 1 }
open_boundaries { name: "in" kind: INFLOW material: "water" mean_velocity: 1 pressure: 3
  ramp_time: -1 region { lo { x: 0.2 y: 0.5 } hi { x: 0.5 y: 1.5 } } direction { x: 1 } })");
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].profile", "only used with mean_velocity"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[0].ramp_time", "only used with mean_velocity"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[1].pressure", "only used by a pressure outlet"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "open_boundaries[1].ramp_time", "must be >= 0")) << dump(errs);
  // The inflow's temperature needs heat conduction.
  errs = errors_of(std::string(kOutlet) + R"(open_boundaries { name: "in" kind: INFLOW
  material: "water" mean_velocity: 1 temperature: 300
  region { lo { x: 0.2 y: 0.5 } hi { x: 0.5 y: 1.5 } } direction { x: 1 } })");
  EXPECT_TRUE(has_error(errs, "open_boundaries[1].temperature", "heat conduction is not enabled"))
      << dump(errs);
}

TEST(CaseValidation, PhaseTransitionsNeedTheirMaterialsAndDrivingField) {
  auto errs = errors_of(R"(phase_transitions { solid_material: "s" })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].solid_material", "unknown material 's'"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].fluid_material", "is required")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].driver", "is required")) << dump(errs);
  // Phase change without the field that drives it.
  errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
phase_transitions { solid_material: "s" fluid_material: "water" driver: CONCENTRATION
                    transition_value: 0.8 hysteresis: -1 })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].driver", "add a `diffusion { }` block"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].hysteresis", "must be >= 0")) << dump(errs);
  errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
thermal { }
phase_transitions { solid_material: "water" fluid_material: "s" driver: TEMPERATURE
                    join_radius: 0.5 })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].solid_material", "expected SOLID"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].join_radius", "kernel support")) << dump(errs);
  // A join radius of dx links no lattice neighbours: bodies would shatter at the first transition.
  errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
thermal { }
phase_transitions { solid_material: "s" fluid_material: "water" driver: TEMPERATURE
                    join_radius: 0.1 })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].join_radius", "must be larger than dx"))
      << dump(errs);
  // The melt of a scene that starts solid needs its thermal properties before any particle of
  // it exists, and a particle keeps its mass when it changes phase: one density for both.
  errs = errors_of(
      R"(materials { name: "s" phase: SOLID density: 2 heat_capacity: 1 thermal_conductivity: 1 }
materials { name: "melt" density: 3 eos { sound_speed: 1 } }
thermal { }
phase_transitions { solid_material: "s" fluid_material: "melt" driver: TEMPERATURE })");
  EXPECT_TRUE(
      has_error(errs, "materials[2].heat_capacity", "used by phase_transitions[0].fluid_material"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].fluid_material",
                        "density 3 of 'melt' differs from the solid's 2"))
      << dump(errs);
}

TEST(CaseValidation, MergingBodiesNeedSolidificationAndNoPeriodicFaces) {
  const std::string melt =
      R"(materials { name: "s" phase: SOLID density: 1000 heat_capacity: 1 thermal_conductivity: 1 }
materials { name: "melt" density: 1000 eos { sound_speed: 10 } heat_capacity: 1 thermal_conductivity: 1 }
thermal { }
)";
  auto errs = errors_of(melt + R"(phase_transitions { solid_material: "s" fluid_material: "melt"
                    driver: TEMPERATURE merge_bodies: true })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].merge_bodies", "needs reversible: true"))
      << dump(errs);
  errs = errors_of(melt + R"(periodic_x: true
phase_transitions { solid_material: "s" fluid_material: "melt" driver: TEMPERATURE
                    reversible: true merge_bodies: true })");
  EXPECT_TRUE(has_error(errs, "phase_transitions[0].merge_bodies", "periodic domain"))
      << dump(errs);
  errs = errors_of(melt + R"(phase_transitions { solid_material: "s" fluid_material: "melt"
                    driver: TEMPERATURE reversible: true merge_bodies: true })");
  EXPECT_FALSE(has_error(errs, "phase_transitions[0].merge_bodies", "")) << dump(errs);
}

TEST(CaseValidation, RigidBodiesAndContact) {
  auto errs = errors_of(R"(bodies { name: "disk" })");
  EXPECT_TRUE(has_error(errs, "bodies[0].shape", "is required")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "bodies[0].material", "is required")) << dump(errs);
  errs = errors_of(R"(materials { name: "s" phase: SOLID density: 2 }
bodies { name: "b" material: "water" body_force: BUOYANCY_REDUCED shape { ball { center { x: 1 y: 1 } radius: 0.2 } } }
bodies { name: "b" material: "s" motion_type: PRESCRIBED shape { ball { center { x: 1 y: 1 } radius: 0.2 } } })");
  EXPECT_TRUE(has_error(errs, "bodies[0].material", "is FLUID, expected SOLID")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "bodies[0].buoyancy_fluid", "is required")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "bodies[1].name", "duplicate body name 'b'")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "bodies[1].motion", "a PRESCRIBED body needs a motion"))
      << dump(errs);
  errs = errors_of(R"(contact { stiffness: -1 })");
  EXPECT_TRUE(has_error(errs, "contact.stiffness", "must be > 0")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "contact", "no rigid bodies")) << dump(errs);
}

TEST(CaseValidation, EffectsMustBeEnabledAndComplete) {
  // Configured but not enabled: a validation error naming the field.
  auto errs = errors_of(
      R"(materials { name: "hot" density: 1 eos { sound_speed: 1 } thermal_conductivity: 2 })");
  EXPECT_TRUE(
      has_error(errs, "materials[1].thermal_conductivity", "heat conduction is not enabled"))
      << dump(errs);
  errs = errors_of(
      R"(walls { shape { box { lo { x: 0 y: 0 } hi { x: 2 y: 0.2 } } } concentration { value { constant: 1 } } })");
  EXPECT_TRUE(has_error(errs, "walls[0].concentration", "concentration diffusion is not enabled"))
      << dump(errs);
  // Enabled without what it needs: the material of a fluid region lacks its coefficients.
  errs = errors_of(R"(thermal { initial_temperature: 300 })");
  EXPECT_TRUE(has_error(errs, "materials[0].heat_capacity", "required: heat conduction is enabled"))
      << dump(errs);
  errs = errors_of(R"(diffusion { })");
  EXPECT_TRUE(
      has_error(errs, "materials[0].diffusivity", "required: concentration diffusion is enabled"))
      << dump(errs);
}

TEST(CaseValidation, TransportPressureWithoutTransportVelocity) {
  const auto errs = errors_of(
      R"(materials { name: "air" density: 1 eos { sound_speed: 3 } transport_background_pressure: 2 })");
  EXPECT_TRUE(has_error(errs, "materials[1].transport_background_pressure",
                        "fluid_model.transport_velocity is not enabled"))
      << dump(errs);
}

TEST(CaseValidation, SizeLimitNamesDx) {
  auto c = parse_case_text(kBase);
  const CaseEstimate e = estimate_case(c);
  EXPECT_NEAR(e.fluid_particles, 100, 0.5);  // 10 x 10 lattice points in the 1 x 1 box
  c.set_dx(0.001);                           // 1e6 particles
  const auto errs = validate_case(c, ValidationLimits{1e4});
  EXPECT_TRUE(has_error(errs, "dx",
                        "case too large: estimated 1e6 particles; this server's limit is 10000 "
                        "(--max-particles)"))
      << dump(errs);
}

// The Verlet skin is given in units of dx, refused outside [0, 2] by name; it is 0.3 dx by
// default, 0 with open boundaries, and no wider than leaves each periodic axis two cells of
// r_c + skin.
TEST(CaseValidation, NeighborSkin) {
  EXPECT_TRUE(has_error(errors_of("neighbor_skin: -0.1"), "neighbor_skin",
                        "between 0 and 2 (times dx; got -0.1)"));
  EXPECT_TRUE(has_error(errors_of("neighbor_skin: 2.5"), "neighbor_skin", "between 0 and 2"));
  EXPECT_TRUE(errors_of("neighbor_skin: 0").empty());
  auto c = parse_case_text(kBase);
  EXPECT_NEAR(neighbor_skin(c), 0.03, 1e-15);
  c.set_neighbor_skin(1.5);
  EXPECT_NEAR(neighbor_skin(c), 0.15, 1e-15);
  c.set_neighbor_skin(2);  // r_c + skin = 0.5 would leave the 2 x 2 domain 4 cells: allowed
  EXPECT_NEAR(neighbor_skin(c), 0.2, 1e-15);
  c.mutable_domain()->mutable_hi()->set_y(0.9);  // a narrow axis that is not periodic
  EXPECT_NEAR(neighbor_skin(c), 0.2, 1e-15);
  c.set_periodic_y(true);  // 0.9 / 2 - r_c = 0.15: two cells of r_c + skin along y
  EXPECT_NEAR(neighbor_skin(c), 0.15, 1e-15);
  c.add_open_boundaries();
  EXPECT_EQ(neighbor_skin(c), 0.0);
}

// h = smoothing_length_ratio * dx: the support, the default wall shell, the time step and the
// neighbour count follow h, and ratios outside [1, 4] are refused by name.
TEST(CaseValidation, SmoothingLengthRatio) {
  EXPECT_TRUE(has_error(errors_of("smoothing_length_ratio: 0.5"), "smoothing_length_ratio",
                        "between 1 and 4 (got 0.5)"));
  EXPECT_TRUE(has_error(errors_of("smoothing_length_ratio: 5"), "smoothing_length_ratio",
                        "between 1 and 4"));
  const auto ok = errors_of("smoothing_length_ratio: 2");
  EXPECT_TRUE(ok.empty()) << dump(ok);
  // r_c = 3 h = 0.6: the 2 x 2 domain is wider than two supports at h = dx, not at h = 4 dx.
  EXPECT_TRUE(has_error(errors_of("smoothing_length_ratio: 4"), "domain.hi.x",
                        "narrower than two kernel supports"));

  auto c = parse_case_text(kBase);
  EXPECT_DOUBLE_EQ(smoothing_length(c), 0.1);
  EXPECT_DOUBLE_EQ(default_shell_thickness(c), 0.3);  // three layers for r_c = 3 dx
  const CaseEstimate e1 = estimate_case(c);
  c.set_smoothing_length_ratio(1.5);
  EXPECT_DOUBLE_EQ(smoothing_length(c), 0.15);
  EXPECT_NEAR(kernel_support_radius(c), 0.45, 1e-15);
  EXPECT_NEAR(default_shell_thickness(c), 0.5, 1e-15);  // r_c = 4.5 dx: five layers
  const CaseEstimate e15 = estimate_case(c);
  // The acoustic step 0.25 h / c limits here, so it grows with h.
  EXPECT_NEAR(e15.initial_dt / e1.initial_dt, 1.5, 1e-12) << e1.dt_limited_by;
  EXPECT_GT(e15.bytes, e1.bytes);
}

// A growing wall (solver/boundaries/wall_growth.h): a speed that never goes negative, and
// no motion.
TEST(CaseValidation, GrowingWallSpeedIsNonNegativeAndTheWallStill) {
  const std::string floor =
      "walls { name: \"floor\" shape { box { lo { x: 0.5 y: 0.2 } hi { x: 1.5 y: 0.5 } } } ";
  auto errs = errors_of(floor + "growth_speed { constant: 0.1 end_time: 0.5 } }");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  errs =
      errors_of(floor + "growth_speed { piecewise_linear { times: [0, 1] values: [0, 0.2] } } }");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  errs = errors_of(floor + "growth_speed { constant: -0.1 } }");
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed.constant", "must be >= 0")) << dump(errs);
  errs = errors_of(floor + "growth_speed { constant: inf } }");
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed.constant", "must be finite")) << dump(errs);
  errs = errors_of(floor + "growth_speed { sine { offset: 0.1 amplitude: 0.2 } } }");
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed.sine", "offset must be >= |amplitude|"))
      << dump(errs);
  errs = errors_of(floor +
                   "growth_speed { piecewise_constant { times: [0, 1] values: [0.1, -1] } } }");
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed.piecewise_constant.values[1]", "must be >= 0"))
      << dump(errs);
  errs = errors_of(floor + "growth_speed { start_time: 1 } }");
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed", "needs a speed")) << dump(errs);
  errs =
      errors_of(floor + "growth_speed { constant: 0.1 } motion { velocity_x { constant: 1 } } }");
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed", "a growing wall cannot move")) << dump(errs);
  errs = errors_of(
      R"(walls { name: "dots" shape { points { points { x: 1 y: 0.45 } } } growth_speed { constant: 0.1 } })");
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed", "no surface to grow from")) << dump(errs);
  // Nested: a union of point sets has no surface either; a union with a box has.
  const std::string dots = "shapes { points { points { x: 1 y: 0.45 } } }";
  errs = errors_of(R"(walls { name: "dots" shape { union { )" + dots + " " + dots +
                   R"( } } growth_speed { constant: 0.1 } })");
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed", "no surface to grow from")) << dump(errs);
  errs = errors_of(R"(walls { name: "dots" shape { union { )" + dots +
                   R"( shapes { box { lo { x: 0.9 y: 0.4 } hi { x: 1.1 y: 0.5 } } } } })"
                   R"( growth_speed { constant: 0.1 } })");
  EXPECT_FALSE(has_error(errs, "walls[0].growth_speed", "no surface to grow from")) << dump(errs);
}

// A growing wall must keep clear of open-boundary buffers, as far as it grows by the end time.
TEST(CaseValidation, GrowingWallKeepsClearOfOpenBoundaryBuffers) {
  auto c =
      load_case_file(std::string(SPHD_SOURCE_DIR) + "/cases/channel_inflow_outflow_2d.textproto");
  c.mutable_walls(0)->mutable_growth_speed()->set_constant(0.1);
  auto errs = validate_case(c, {});
  EXPECT_TRUE(has_error(errs, "walls[0].growth_speed", "reaches the buffer of open_boundaries[0]"))
      << dump(errs);
  // Growing only between the buffers, 0.1 m/s for 1 s: clear of them.
  c.mutable_walls(0)->mutable_shape()->mutable_box()->mutable_lo()->set_x(0.5);
  c.mutable_walls(0)->mutable_shape()->mutable_box()->mutable_hi()->set_x(1.5);
  c.mutable_time()->set_end_time(1);
  errs = validate_case(c, {});
  EXPECT_FALSE(has_error(errs, "walls[0].growth_speed", "reaches the buffer")) << dump(errs);
}

// A wall must hold particles wherever a first-row fluid particle's kernel support reaches
// into it: lattice distances n dx < r_c, two layers at r_c = 3 dx, five at r_c = 6 dx.
TEST(CaseValidation, WallsMustCoverTheKernelSupport) {
  const auto floor = [](double lo_y) {
    return "walls { name: \"floor\" shape { box { lo { x: 0.5 y: " + std::to_string(lo_y) +
           " } hi { x: 1.5 y: 0.5 } } } }\n";
  };
  auto errs = errors_of(floor(0.3));  // two layers
  EXPECT_TRUE(errs.empty()) << dump(errs);
  errs = errors_of(floor(0.4));  // one layer
  EXPECT_TRUE(has_error(errs, "walls[0].shape",
                        "wall 'floor' is 1 particle layer thick along -y next to the fluid "
                        "particle at (0.55, 0.55) (and 9 more places): the kernel support "
                        "reaches past it into empty space; r_c = 0.3 needs 2 layers (0.2 thick)"))
      << dump(errs);
  // h = 2 dx: five layers; 0.2 no longer does, 0.5 does.
  errs = errors_of("smoothing_length_ratio: 2\n" + floor(0.3));
  EXPECT_TRUE(has_error(errs, "walls[0].shape", "is 2 particle layers thick")) << dump(errs);
  errs = errors_of("smoothing_length_ratio: 2\n" + floor(0.0));
  EXPECT_TRUE(errs.empty()) << dump(errs);
  // A one-layer wall across the fluid: fluid on both sides would interact through it.
  errs = errors_of(
      R"(walls { name: "baffle" shape { box { lo { x: 1.0 y: 0.5 } hi { x: 1.1 y: 1.5 } } } })");
  EXPECT_TRUE(has_error(errs, "walls[0].shape", "with fluid behind it at (1.15,")) << dump(errs);
  // A shell without thickness gets enough layers at any ratio; the domain must hold them (a
  // shell clipped by the domain is thin again).
  const std::string shell =
      R"(walls { name: "tank" shape { shell { inner { box { lo { x: 0.5 y: 0.5 } hi { x: 1.5 y: 1.5 } } } } } })";
  // r_c = 0.75 at h = 2.5 dx: the shell's eight layers are cut to five by the domain, seven
  // are needed.
  errs = errors_of("smoothing_length_ratio: 2.5\n" + shell);
  EXPECT_TRUE(has_error(errs, "walls[0].shape", "wall 'tank' is 5 particle layers thick"))
      << dump(errs);
  errs = errors_of("smoothing_length_ratio: 1.5\n" + shell);
  EXPECT_TRUE(errs.empty()) << dump(errs);
}

TEST(CaseValidation, EmptyPlacementIsAnError) {
  auto c = parse_case_text(kBase);
  c.mutable_fluids(0)->mutable_shape()->mutable_box()->mutable_lo()->set_x(5);
  c.mutable_fluids(0)->mutable_shape()->mutable_box()->mutable_hi()->set_x(6);
  const auto errs = validate_case(c);
  EXPECT_TRUE(has_error(errs, "fluids[0].shape",
                        "fluid 'f' places no particles: it has no lattice points (dx = 0.1) "
                        "inside the domain (x in [0, 2], y in [0, 2]); the shape spans x in [5, "
                        "6], y in [0.5, 1.5]"))
      << dump(errs);
}

TEST(CaseValidation, TimeFunctionTables) {
  const auto errs = errors_of(
      R"(walls { shape { box { lo { x: 0 y: 0 } hi { x: 2 y: 0.2 } } } motion { velocity_x { piecewise_linear { times: 0 times: 0 values: 1 } } } })");
  EXPECT_TRUE(has_error(errs, "walls[0].motion.velocity_x.piecewise_linear.values",
                        "as many values as times"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "walls[0].motion.velocity_x.piecewise_linear.times[1]",
                        "strictly increasing"))
      << dump(errs);
}

// Every case file under cases/, cases/studies/ and tests/*/cases/ (the seed scenes, the
// stability suite's, the convergence studies' and the service tests' cases): a shipped case
// that no longer validates fails here, not in a user's hands.
TEST(CaseValidation, EveryShippedCaseIsValid) {
  int checked = 0;
  std::vector<std::string> dirs = {"/cases", "/cases/studies"};
  for (const auto& e : std::filesystem::directory_iterator(std::string(SPHD_SOURCE_DIR) + "/tests"))
    if (std::filesystem::is_directory(e.path() / "cases"))
      dirs.push_back("/tests/" + e.path().filename().string() + "/cases");
  for (const auto& dir : dirs) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(std::string(SPHD_SOURCE_DIR) + dir))
      if (e.path().extension() == ".textproto") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      const auto errs = validate_case(load_case_file(f.string()));
      EXPECT_TRUE(errs.empty()) << f.filename() << ": " << dump(errs);
      ++checked;
    }
  }
  EXPECT_GE(checked, 42);
}

// surface_tension { } (case/validate_surface_tension.cc): coefficients, materials, pairs and
// contact angles are each named with the limit they break.
const char* kTwoFluids = R"(materials { name: "oil" density: 900 eos { sound_speed: 10 } }
materials { name: "air" density: 1 eos { sound_speed: 10 } }
materials { name: "steel" phase: SOLID density: 7800 }
)";

TEST(CaseValidation, SurfaceTensionPairs) {
  const std::string m = kTwoFluids;
  auto errs = errors_of(m + R"(surface_tension {
    pairs { material_a: "water" material_b: "oil" sigma: 0.03 } })");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  // No material_b: water against void, which needs the continuity density.
  errs = errors_of(m + R"(surface_tension { pairs { material_a: "water" sigma: 0.072 } })");
  EXPECT_TRUE(has_error(errs, "fluid_model.density", "CONTINUITY")) << dump(errs);
  errs = errors_of(
      m +
      R"(fluid_model { density: CONTINUITY } surface_tension { pairs { material_a: "water" sigma: 0.072 } })");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  errs = errors_of(m + R"(fluid_model { density: CONTINUITY } surface_tension {
    pairs { material_a: "water" sigma: 0.072 } pairs { material_a: "water" sigma: 0.05 } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.pairs[1].material_a", "duplicate free surface"))
      << dump(errs);
  errs = errors_of(
      m + R"(surface_tension { pairs { material_a: "water" material_b: "oil" sigma: -1 } })");
  EXPECT_TRUE(
      has_error(errs, "surface_tension.pairs[0].sigma", "must be > 0 and finite [N/m]; got -1"))
      << dump(errs);
  errs = errors_of(
      m + R"(surface_tension { pairs { material_a: "water" material_b: "oil" sigma: 0 } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.pairs[0].sigma", "got 0")) << dump(errs);
  errs = errors_of(
      m + R"(surface_tension { pairs { material_a: "mercury" material_b: "oil" sigma: 0.4 } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.pairs[0].material_a", "unknown material 'mercury'"))
      << dump(errs);
  errs = errors_of(
      m + R"(surface_tension { pairs { material_a: "water" material_b: "steel" sigma: 1 } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.pairs[0].material_b",
                        "material 'steel' is SOLID; surface tension acts between FLUID materials"))
      << dump(errs);
  errs = errors_of(
      m + R"(surface_tension { pairs { material_a: "water" material_b: "water" sigma: 1 } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.pairs[0].material_b", "must differ from material_a"))
      << dump(errs);
  errs = errors_of(m + R"(surface_tension {
    pairs { material_a: "water" material_b: "oil" sigma: 1 }
    pairs { material_a: "oil" material_b: "water" sigma: 2 } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.pairs[1].material_b",
                        "duplicate pair 'oil' - 'water' (already surface_tension.pairs[0])"))
      << dump(errs);
  errs = errors_of(m + R"(surface_tension { pairs { material_b: "oil" sigma: 1 } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.pairs[0].material_a", "is required")) << dump(errs);
  errs = errors_of("surface_tension { }");
  EXPECT_TRUE(has_error(errs, "surface_tension.pairs", "give at least one pair")) << dump(errs);
}

TEST(CaseValidation, SurfaceTensionContactAngles) {
  const std::string m =
      std::string(kTwoFluids) +
      R"(walls { name: "floor" shape { box { lo { x: 0 y: 0 } hi { x: 2 y: 0.4 } } } }
)";
  auto errs =
      errors_of(m + R"(surface_tension { pairs { material_a: "water" material_b: "oil" sigma: 0.03 }
    walls { wall: "floor" contact_angle: 60 material: "water" } })");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  for (const char* angle : {"0", "180", "-30", "200"}) {
    errs = errors_of(
        m +
        "surface_tension { pairs { material_a: \"water\" material_b: \"oil\" sigma: 0.072 } "
        "walls { wall: \"floor\" contact_angle: " +
        angle + " material: \"water\" } }");
    EXPECT_TRUE(has_error(errs, "surface_tension.walls[0].contact_angle",
                          std::string("must be in (0, 180) degrees; got ") + angle))
        << dump(errs);
  }
  errs =
      errors_of(m + R"(surface_tension { pairs { material_a: "water" material_b: "oil" sigma: 0.03 }
    walls { wall: "roof" contact_angle: 60 material: "water" }
    walls { wall: "floor" contact_angle: 60 material: "air" }
    walls { wall: "floor" contact_angle: 70 material: "water" }
    walls { contact_angle: 70 material: "water" } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.walls[0].wall", "unknown wall 'roof'"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "surface_tension.walls[1].material",
                        "material 'air' has no surface tension (it is in no pair)"))
      << dump(errs);
  EXPECT_TRUE(
      has_error(errs, "surface_tension.walls[2].wall",
                "duplicate contact angle for wall 'floor' (already surface_tension.walls[1])"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "surface_tension.walls[3].wall", "is required")) << dump(errs);
  // At a free surface (a pair without material_b): walls within the validated 60 to 105
  // degrees, no angles at rigid bodies.
  const std::string free = "fluid_model { density: CONTINUITY } ";
  errs = errors_of(m + free + R"(surface_tension { pairs { material_a: "water" sigma: 0.072 }
    walls { wall: "floor" contact_angle: 60 material: "water" } })");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  errs = errors_of(m + free + R"(surface_tension { pairs { material_a: "water" sigma: 0.072 }
    walls { wall: "floor" contact_angle: 105 material: "water" } })");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  for (const char* angle : {"120", "45"}) {
    errs = errors_of(m + free +
                     "surface_tension { pairs { material_a: \"water\" sigma: 0.072 } walls { "
                     "wall: \"floor\" contact_angle: " +
                     angle + " material: \"water\" } }");
    EXPECT_TRUE(has_error(errs, "surface_tension.walls[0].contact_angle",
                          std::string("material 'water' has a free surface: its contact angle "
                                      "must be in [60, 105] degrees (the range validated at a "
                                      "free surface); got ") +
                              angle))
        << dump(errs);
  }
  errs = errors_of(m + free + R"(surface_tension { pairs { material_a: "water" sigma: 0.072 }
    bodies { solid_material: "steel" contact_angle: 60 material: "water" } })");
  EXPECT_TRUE(has_error(errs, "surface_tension.bodies[0].material",
                        "contact angles at rigid bodies are not supported at a free surface"))
      << dump(errs);
}

// Contact angles at rigid bodies, by their SOLID material (surface_tension.bodies).
TEST(CaseValidation, SurfaceTensionContactAnglesAtBodies) {
  const std::string m = kTwoFluids;  // with the SOLID "steel"
  const std::string pair = R"(pairs { material_a: "water" material_b: "oil" sigma: 0.03 } )";
  auto errs =
      errors_of(m + "surface_tension { " + pair +
                R"(bodies { solid_material: "steel" contact_angle: 30 material: "water" } })");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  errs = errors_of(m + "surface_tension { " + pair +
                   R"(bodies { solid_material: "water" contact_angle: 30 material: "water" }
    bodies { solid_material: "iron" contact_angle: 30 material: "water" }
    bodies { solid_material: "steel" contact_angle: 180 material: "water" }
    bodies { solid_material: "steel" contact_angle: 30 material: "steel" }
    bodies { contact_angle: 30 material: "water" } })");
  EXPECT_TRUE(
      has_error(errs, "surface_tension.bodies[0].solid_material", "material 'water' is not SOLID"))
      << dump(errs);
  EXPECT_TRUE(
      has_error(errs, "surface_tension.bodies[1].solid_material", "unknown material 'iron'"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "surface_tension.bodies[2].contact_angle",
                        "must be in (0, 180) degrees; got 180"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "surface_tension.bodies[3].solid_material",
                        "duplicate contact angle for material 'steel' (already "
                        "surface_tension.bodies[2])"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "surface_tension.bodies[3].material", "material 'steel' is SOLID"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "surface_tension.bodies[4].solid_material", "is required"))
      << dump(errs);
  std::string many = m + "surface_tension { " + pair;
  for (int i = 0; i <= kMaxMaterials; ++i)
    many += R"(bodies { solid_material: "steel" contact_angle: 30 material: "water" } )";
  errs = errors_of(many + "}");
  EXPECT_TRUE(has_error(errs, "surface_tension.bodies",
                        "has " + std::to_string(kMaxMaterials + 1) + " entries; at most " +
                            std::to_string(kMaxMaterials)))
      << dump(errs);
  EXPECT_EQ(errs.size(), 1u) << dump(errs);
}

// Elastic bodies (case/validate/elastic_bodies.cc). The base case's fluid fills [0.5, 1.5]^2;
// the plate lies above it, clamped at its left end.
const char* kRubber =
    R"(materials { name: "rubber" phase: SOLID density: 1000 youngs_modulus: 1.4e6 poisson_ratio: 0.4 }
)";
const char* kPlate = R"(elastic_bodies { name: "plate" material: "rubber"
  shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
  constraints { region { box { lo { x: 0.2 y: 1.6 } hi { x: 0.4 y: 1.8 } } } } }
)";
// No fluid: the oscillating plate of thesis digest sec. 8.4 in a 2 x 2 domain.
const char* kNoFluid = R"(
name: "plate"
dimension: 2
dx: 0.1
domain { lo { x: 0 y: 0 } hi { x: 2 y: 2 } }
time { end_time: 1 }
)";

std::vector<FieldError> plate_errors(const std::string& extra) {
  return errors_of(std::string(kRubber) + extra);
}

TEST(CaseValidation, ElasticBodiesAreAccepted) {
  auto errs = plate_errors(kPlate);
  EXPECT_TRUE(errs.empty()) << dump(errs);
  // Without fluid, clamped, with the beam's first bending mode, observed at its tip.
  errs = validate_case(parse_case_text(std::string(kNoFluid) + kRubber + R"(
elastic_bodies { name: "plate" material: "rubber"
  shape { box { lo { x: 0.2 y: 0.9 } hi { x: 1.6 y: 1.1 } } }
  constraints { region { box { lo { x: 0.2 y: 0.9 } hi { x: 0.4 y: 1.1 } } } }
  initial_velocity_field { beam_mode { root { x: 0.4 y: 1 } axis { x: 1 } direction { y: 1 }
                                       length: 1.2 tip_velocity: 0.05 } }
  observation_points { x: 1.55 y: 1 } })"));
  EXPECT_TRUE(errs.empty()) << dump(errs);
  // Free in a fluid, with a field a fluid could take as well, held by a moving clamp.
  errs = plate_errors(R"(elastic_bodies { name: "flap" material: "rubber"
  shape { box { lo { x: 0.8 y: 0.8 } hi { x: 1.2 y: 1.2 } } }
  initial_velocity_field { linear { gradient_x { y: 0.1 } } } }
elastic_bodies { name: "vortex" material: "rubber"
  shape { ball { center { x: 0.3 y: 0.3 } radius: 0.15 } }
  initial_velocity_field { taylor_green { wavelength: 1 amplitude: 0.1 } }
  constraints { region { ball { center { x: 0.3 y: 0.3 } radius: 0.08 } }
                motion { velocity_x { constant: 0.1 } } } })");
  EXPECT_TRUE(errs.empty()) << dump(errs);
}

TEST(CaseValidation, BackflowStabilizationOnPressureOutletsOnly) {
  const std::string outlet = R"(open_boundaries { name: "out" kind: OUTFLOW material: "water"
  region { lo { x: 1.5 y: 0.5 } hi { x: 1.8 y: 1.5 } } direction { x: 1 } )";
  EXPECT_TRUE(errors_of(outlet + "backflow_stabilization: 1 }").empty())
      << dump(errors_of(outlet + "backflow_stabilization: 1 }"));
  EXPECT_TRUE(has_error(errors_of(outlet + "backflow_stabilization: 1.5 }"),
                        "open_boundaries[0].backflow_stabilization",
                        "must be in [0, 1] (got 1.5)"));
  EXPECT_TRUE(has_error(errors_of(outlet + "mean_velocity: 1 backflow_stabilization: 1 }"),
                        "open_boundaries[0].backflow_stabilization",
                        "only used by a pressure outlet"));
}

TEST(CaseValidation, QuasiStaticFieldsAndLimits) {
  // Quasi-static loading (time.quasi_static): elastic bodies alone, each limit by name.
  v1::Case c = parse_case_text(std::string(kNoFluid) + kRubber + kPlate);
  auto* q = c.mutable_time()->mutable_quasi_static();
  q->set_load_step(0.01);
  q->set_damping(100);
  q->set_kinetic_energy_threshold(1e-6);
  auto errs = validate_case(c);
  EXPECT_TRUE(errs.empty()) << dump(errs);
  const CaseEstimate e = estimate_case(c);
  EXPECT_EQ(e.dt_limited_by, "time.quasi_static.load_step");
  EXPECT_EQ(e.steps, 100);
  // At most load_step / (0.6 h / c_s) inner steps per load step, end_time / that in all.
  const double cs = std::sqrt(1.4e6 / (3 * (1 - 2 * 0.4)) / 1000);
  EXPECT_EQ(e.inner_steps, std::ceil(1.0 / (0.6 * 0.1 / cs)));
  v1::Case bad = c;
  bad.mutable_time()->mutable_quasi_static()->set_load_step(2);
  bad.mutable_time()->mutable_quasi_static()->set_damping(0);
  bad.mutable_time()->mutable_quasi_static()->set_kinetic_energy_threshold(-1);
  bad.mutable_time()->set_fixed_dt(1e-3);
  bad.mutable_time()->set_subcycle_elastic_bodies(true);
  errs = validate_case(bad);
  EXPECT_TRUE(has_error(errs, "time.quasi_static.load_step", "must be at most time.end_time (1)"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "time.quasi_static.damping", "must be > 0")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "time.quasi_static.kinetic_energy_threshold", "must be > 0"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "time.fixed_dt", "must be unset with time.quasi_static"))
      << dump(errs);
  EXPECT_TRUE(
      has_error(errs, "time.subcycle_elastic_bodies", "must be unset with time.quasi_static"))
      << dump(errs);
  // Not with fluid; not without an elastic body.
  v1::Case wet = parse_case_text(std::string(kBase) + kRubber + kPlate);
  *wet.mutable_time()->mutable_quasi_static() = *q;
  EXPECT_TRUE(has_error(validate_case(wet), "time.quasi_static", "the case has fluid"));
  v1::Case empty = parse_case_text(std::string(kBase));
  empty.clear_fluids();
  *empty.mutable_time()->mutable_quasi_static() = *q;
  EXPECT_TRUE(
      has_error(validate_case(empty), "time.quasi_static", "needs at least one elastic body"));
}

TEST(CaseValidation, PorousSolidFieldsAndLimits) {
  // A porous plate (Material.porous) wetted on its right end, relaxed quasi-statically.
  const std::string material = R"(materials { name: "gel" phase: SOLID density: 1000
  youngs_modulus: 1.4e6 poisson_ratio: 0.4 diffusivity: 1e-4
  porous { swelling_modulus: 1e5 reference_saturation: 0.1 } }
)";
  const auto plate = [](const std::string& extra) {
    return R"(elastic_bodies { name: "plate" material: "gel"
  shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
  constraints { region { box { lo { x: 0.2 y: 1.6 } hi { x: 0.4 y: 1.8 } } } } )" +
           extra + "}\n";
  };
  const std::string wet =
      "concentration_holds { region { box { lo { x: 1 y: 1.6 } hi { x: 1.2 y: 1.8 } } } value: 0.5 "
      "end_time: 0.5 } initial_concentration: 0.1";
  const std::string base = std::string(kNoFluid) + material + "diffusion { }\n";
  v1::Case c = parse_case_text(base + plate(wet));
  auto* q = c.mutable_time()->mutable_quasi_static();
  q->set_load_step(0.1);
  q->set_damping(100);
  q->set_kinetic_energy_threshold(1e-6);
  auto errs = validate_case(c);
  EXPECT_TRUE(errs.empty()) << dump(errs);
  // The load step against the explicit diffusion bound 0.1 rho h^2 / D (h = dx = 0.1).
  v1::Case slow = c;
  slow.mutable_materials(0)->set_diffusivity(100);
  errs = validate_case(slow);
  EXPECT_TRUE(has_error(errs, "time.quasi_static.load_step",
                        "must be at most 0.01 s: the explicit diffusion step of material 'gel'"))
      << dump(errs);
  // Each field by name.
  v1::Case bad = c;
  bad.mutable_materials(0)->mutable_porous()->set_swelling_modulus(-1);
  bad.mutable_materials(0)->mutable_porous()->set_reference_saturation(1.5);
  auto* h = bad.mutable_elastic_bodies(0)->mutable_concentration_holds(0);
  h->set_start_time(-1);
  h->mutable_region()->mutable_box()->mutable_lo()->set_x(1.5);
  h->mutable_region()->mutable_box()->mutable_hi()->set_x(1.7);
  errs = validate_case(bad);
  EXPECT_TRUE(has_error(errs, "materials[0].porous.swelling_modulus", "must be >= 0 (got -1)"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[0].porous.reference_saturation", "must be in [0, 1]"))
      << dump(errs);
  const std::string hf = "elastic_bodies[0].concentration_holds[0].";
  EXPECT_TRUE(has_error(errs, hf + "start_time", "must be >= 0 [s] (got -1)")) << dump(errs);
  EXPECT_TRUE(has_error(errs, hf + "region", "does not overlap the body's shape")) << dump(errs);
  v1::Case thin = c;
  thin.mutable_elastic_bodies(0)->mutable_anisotropy()->set_ratio(2);
  EXPECT_TRUE(has_error(validate_case(thin), "elastic_bodies[0].anisotropy",
                        "must be resolved isotropically"));
  // Non-finite numbers are refused with every other number of the case.
  v1::Case nan = c;
  nan.mutable_elastic_bodies(0)->mutable_concentration_holds(0)->set_value(std::nan(""));
  EXPECT_TRUE(has_error(validate_case(nan), hf + "value", "every number must be finite"));
  v1::Case late = c;
  late.mutable_elastic_bodies(0)->mutable_concentration_holds(0)->set_start_time(0.6);
  EXPECT_TRUE(has_error(validate_case(late), hf + "end_time", "must be > start_time (0.6 s)"));
  // Without the diffusion block; on a fluid; on a material no elastic body uses.
  v1::Case dry = c;
  dry.clear_diffusion();
  errs = validate_case(dry);
  EXPECT_TRUE(has_error(errs, "materials[0].porous", "needs concentration diffusion"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].concentration_holds",
                        "concentration diffusion is not enabled"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].initial_concentration",
                        "concentration diffusion is not enabled"))
      << dump(errs);
  EXPECT_TRUE(has_error(errors_of(R"(materials { name: "oil" density: 900 eos { sound_speed: 10 }
  porous { swelling_modulus: 1 } })"),
                        "materials[1].porous", "set on a FLUID material"));
  v1::Case unused = parse_case_text(base + R"(materials { name: "stone" phase: SOLID density: 2000
  youngs_modulus: 1e9 poisson_ratio: 0.2 diffusivity: 0 porous { swelling_modulus: 1 } }
)" + plate(""));
  EXPECT_TRUE(has_error(validate_case(unused), "materials[1].porous", "which no elastic body uses"))
      << dump(validate_case(unused));
}

TEST(CaseValidation, ManufacturedTorsionFieldsAndLimits) {
  // ElasticBody.body_force_field.manufactured_torsion: a neo-Hookean ring in 2D, each limit by
  // name.
  const std::string plate = R"(elastic_bodies { name: "plate" material: "rubber"
  shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
  constraints { region { box { lo { x: 0.2 y: 1.6 } hi { x: 0.4 y: 1.8 } } } }
  body_force_field { manufactured_torsion { inner_radius: 0 outer_radius: 0 angle: 2
                                            ramp_time: 0 } } }
)";
  const auto errs = validate_case(parse_case_text(std::string(kNoFluid) + kRubber + plate));
  const std::string f = "elastic_bodies[0].body_force_field.manufactured_torsion";
  EXPECT_TRUE(has_error(errs, f, "must have elastic_law NEO_HOOKEAN")) << dump(errs);
  EXPECT_TRUE(has_error(errs, f + ".inner_radius", "must be > 0 [m]")) << dump(errs);
  EXPECT_TRUE(has_error(errs, f + ".outer_radius", "must be > inner_radius (0); got 0"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, f + ".angle", "must be in (0, pi/2] [rad]; got 2")) << dump(errs);
  EXPECT_TRUE(has_error(errs, f + ".ramp_time", "must be > 0 [s]")) << dump(errs);
}

TEST(CaseValidation, ElasticMaterialConstants) {
  // On a FLUID material each elastic field is refused by name.
  auto errs = errors_of(R"(materials { name: "oil" density: 900 eos { sound_speed: 10 }
  youngs_modulus: 1e6 poisson_ratio: 0.3 elastic_law: NEO_HOOKEAN elastic_damping: 1
  hourglass_control: 0.1 })");
  for (const char* field :
       {"youngs_modulus", "poisson_ratio", "elastic_law", "elastic_damping", "hourglass_control"})
    EXPECT_TRUE(has_error(errs, std::string("materials[1].") + field, "set on a FLUID material"))
        << field << ": " << dump(errs);
  // Ranges on a SOLID material.
  errs = errors_of(R"(materials { name: "gel" phase: SOLID density: 1000 youngs_modulus: 0
  poisson_ratio: 0.5 elastic_damping: -1 })");
  EXPECT_TRUE(has_error(errs, "materials[1].youngs_modulus", "must be > 0 [Pa] (got 0)"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[1].poisson_ratio",
                        "must be in [0, 0.5) (got 0.5); 0.5 is incompressible"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[1].poisson_ratio", "explicit total Lagrangian SPH"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[1].elastic_damping", "must be >= 0 (got -1)"))
      << dump(errs);
  // Hourglass control: alpha in [0, 10] (not finite: refused before, by the case's bounds).
  const auto with_alpha = [&](const char* alpha) {
    return errors_of(std::string(R"(materials { name: "gel" phase: SOLID density: 1000
  youngs_modulus: 1e6 poisson_ratio: 0.3 hourglass_control: )") +
                     alpha + " }");
  };
  for (const char* alpha : {"-0.1", "11"})
    EXPECT_TRUE(has_error(with_alpha(alpha), "materials[1].hourglass_control",
                          std::string("must be in [0, 10] (got ") + alpha + ")"))
        << alpha << ": " << dump(with_alpha(alpha));
  for (const char* alpha : {"inf", "nan"})
    EXPECT_TRUE(has_error(with_alpha(alpha), "materials[1].hourglass_control", "must be finite"))
        << alpha << ": " << dump(with_alpha(alpha));
  for (const char* alpha : {"0", "0.1", "10"})
    for (const auto& e : with_alpha(alpha))
      EXPECT_EQ(e.field.find("hourglass_control"), std::string::npos) << alpha << ": " << e.message;
  errs = errors_of(
      R"(materials { name: "gel" phase: SOLID density: 1000 youngs_modulus: 1e6 poisson_ratio: -0.1 })");
  EXPECT_TRUE(has_error(errs, "materials[1].poisson_ratio", "must be in [0, 0.5) (got -0.1)"))
      << dump(errs);
  // A law outside the enum (a newer client's value, or a number in binary).
  auto c = parse_case_text(std::string(kBase) + kRubber + kPlate);
  c.mutable_materials(1)->set_elastic_law(static_cast<v1::ElasticLaw>(7));
  errs = validate_case(c);
  EXPECT_TRUE(has_error(errs, "materials[1].elastic_law", "unknown value 7")) << dump(errs);
  // The body's material: known, SOLID, with both constants.
  errs = errors_of(R"(materials { name: "steel" phase: SOLID density: 7800 }
elastic_bodies { name: "a" material: "steel" shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } } }
elastic_bodies { name: "b" material: "water" shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } } }
elastic_bodies { name: "c" material: "lead" shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } } }
elastic_bodies { name: "d" shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } } })");
  EXPECT_TRUE(has_error(errs, "materials[1].youngs_modulus",
                        "required: material 'steel' is used by elastic_bodies[0].material"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[1].poisson_ratio", "required")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[1].material", "is FLUID, expected SOLID"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[2].material", "unknown material 'lead'"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[3].material", "is required")) << dump(errs);
}

TEST(CaseValidation, PlasticityFieldsAndLimits) {
  // J2 plasticity (Material.plasticity): refused on a FLUID material, each limit by name.
  auto errs = errors_of(R"(materials { name: "oil" density: 900 eos { sound_speed: 10 }
  plasticity { yield_stress: 1e6 } })");
  EXPECT_TRUE(has_error(errs, "materials[1].plasticity", "set on a FLUID material")) << dump(errs);
  errs = errors_of(R"(materials { name: "steel" phase: SOLID density: 7850 youngs_modulus: 2e11
  poisson_ratio: 0.29 elastic_law: SAINT_VENANT_KIRCHHOFF plasticity { yield_stress: 0
  saturation_stress: -1 saturation_exponent: -2 linear_hardening: -3 } })");
  EXPECT_TRUE(has_error(errs, "materials[1].plasticity.yield_stress", "must be > 0 [Pa] (got 0)"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[1].plasticity.saturation_stress",
                        "must be >= yield_stress (0 Pa) or 0 for none (got -1)"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[1].plasticity.saturation_exponent", "must be >= 0"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[1].plasticity.linear_hardening", "must be >= 0"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[1].elastic_law", "SAINT_VENANT_KIRCHHOFF with plasticity"))
      << dump(errs);
  // Not finite: refused before, by the case's bounds, by name.
  errs = errors_of(R"(materials { name: "steel" phase: SOLID density: 7850 youngs_modulus: 2e11
  poisson_ratio: 0.29 plasticity { yield_stress: 4.5e8 linear_hardening: nan } })");
  EXPECT_TRUE(has_error(errs, "materials[1].plasticity.linear_hardening", "must be finite"))
      << dump(errs);
  errs = errors_of(R"(materials { name: "steel" phase: SOLID density: 7850 youngs_modulus: 2e11
  poisson_ratio: 0.29 plasticity { yield_stress: 4.5e8 saturation_stress: 4e8 } })");
  EXPECT_TRUE(has_error(errs, "materials[1].plasticity.saturation_stress",
                        "must be >= yield_stress (4.5e+08 Pa) or 0 for none (got 4e+08)"))
      << dump(errs);
  // Table 5.1 of the thesis passes.
  errs = errors_of(R"(materials { name: "steel" phase: SOLID density: 7850 youngs_modulus: 2.069e11
  poisson_ratio: 0.29 elastic_law: NEO_HOOKEAN plasticity { yield_stress: 4.5e8
  saturation_stress: 7.15e8 saturation_exponent: 16.93 linear_hardening: 1.2924e8 } })");
  for (const auto& e : errs)
    EXPECT_EQ(e.field.find("materials[1]"), std::string::npos) << e.field << ": " << e.message;
}

TEST(CaseValidation, ElasticBodyNamesAndShape) {
  auto errs = plate_errors(std::string(kPlate) + kPlate);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[1].name", "duplicate elastic body name 'plate'"))
      << dump(errs);
  errs = plate_errors(
      std::string(R"(walls { name: "plate" shape { box { lo { x: 0 y: 0 } hi { x: 2 y: 0.2 } } } }
bodies { name: "disk" material: "rubber" shape { ball { center { x: 1 y: 1 } radius: 0.2 } } }
elastic_bodies { name: "disk" material: "rubber" shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } } }
elastic_bodies { name: "a/b" material: "rubber" shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } } }
elastic_bodies { material: "rubber" shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
                 observation_points { x: 1 y: 1.7 } }
)") + kPlate);
  EXPECT_TRUE(
      has_error(errs, "elastic_bodies[0].name", "'disk' is already the name of a rigid body"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[1].name", "only letters, digits")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[2].name", "is required with observation_points"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[3].name", "'plate' is already the name of walls[0]"))
      << dump(errs);
  // The shape: required, valid, and at least half inside the domain.
  errs = plate_errors(R"(elastic_bodies { name: "p" material: "rubber" }
elastic_bodies { name: "q" material: "rubber" shape { ball { center { x: 1 y: 1 } radius: -1 } } })");
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].shape", "is required")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[1].shape.ball.radius", "must be > 0")) << dump(errs);
  errs = plate_errors(R"(elastic_bodies { name: "p" material: "rubber"
  shape { box { lo { x: 1.5 y: 1.6 } hi { x: 3.5 y: 1.8 } } } })");
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].shape",
                        "elastic body 'p' lies mostly outside the domain (x in [0, 2], y in [0, "
                        "2]): 10 of its 40 lattice points are inside"))
      << dump(errs);
}

TEST(CaseValidation, ElasticBodyConstraints) {
  // Each constraint's region: present, with an interior, valid, with a valid motion.
  auto errs = plate_errors(R"(elastic_bodies { name: "p" material: "rubber"
  shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
  constraints { }
  constraints { region { points { points { x: 0.25 y: 1.65 } } } }
  constraints { region { box { lo { x: 0.4 y: 1.6 } hi { x: 0.2 y: 1.8 } } } }
  constraints { region { box { lo { x: 0.2 y: 1.6 } hi { x: 0.4 y: 1.8 } } }
                motion { velocity_x { piecewise_linear { times: 0 times: 1 values: 1 } } } } })");
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].constraints[0].region", "is required"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].constraints[1].region.points",
                        "a constraint region needs an interior"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].constraints[2].region.box.hi.x",
                        "must be greater than box.lo"))
      << dump(errs);
  EXPECT_TRUE(
      has_error(errs, "elastic_bodies[0].constraints[3].motion.velocity_x.piecewise_linear.values",
                "as many values as times"))
      << dump(errs);
  // A region beside the body, and one inside a wall that takes the body's points there.
  errs = plate_errors(
      R"(walls { name: "clamp" shape { box { lo { x: 0 y: 1.5 } hi { x: 0.4 y: 1.9 } } } }
elastic_bodies { name: "p" material: "rubber"
  shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
  constraints { region { box { lo { x: 0.2 y: 1.6 } hi { x: 0.4 y: 1.8 } } } }
  constraints { region { box { lo { x: 1.3 y: 1.6 } hi { x: 1.5 y: 1.8 } } } }
  constraints { region { box { lo { x: 0.4 y: 1.6 } hi { x: 0.5 y: 1.8 } } } } })");
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].constraints[0].region",
                        "holds no particle of the body: no lattice point of elastic body 'p' "
                        "inside the domain and outside the walls and bodies before it lies in "
                        "the region"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].constraints[1].region",
                        "(the body spans x in [0.2, 1.2], y in [1.6, 1.8], the region x in [1.3, "
                        "1.5], y in [1.6, 1.8])"))
      << dump(errs);
  EXPECT_FALSE(has_error(errs, "elastic_bodies[0].constraints[2].region", "")) << dump(errs);
  // A point-set body: its own points are tested.
  errs = plate_errors(R"(elastic_bodies { name: "p" material: "rubber"
  shape { points { points { x: 0.25 y: 1.65 } points { x: 0.35 y: 1.65 } } }
  constraints { region { box { lo { x: 0.3 y: 1.6 } hi { x: 0.4 y: 1.7 } } } }
  constraints { region { box { lo { x: 0.5 y: 1.6 } hi { x: 0.6 y: 1.7 } } } } })");
  EXPECT_FALSE(has_error(errs, "elastic_bodies[0].constraints[0].region", "")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].constraints[1].region",
                        "holds no particle of the body: no point of elastic body 'p'"))
      << dump(errs);
  // Issue #36: neither a constraint nor a fluid.
  errs = validate_case(
      parse_case_text(std::string(kNoFluid) + kRubber + R"(gravity { acceleration { y: -9.81 } }
elastic_bodies { name: "p" material: "rubber" shape { box { lo { x: 0.2 y: 0.9 } hi { x: 1.6 y: 1.1 } } } })"));
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].constraints",
                        "this body has no constraint and the case no fluid region"))
      << dump(errs);
}

TEST(CaseValidation, ElasticBodyInitialStateAndObservation) {
  // The beam mode: elastic bodies only, with a length, an axis and a direction across it.
  auto errs = errors_of(R"(fluids { name: "g" material: "water"
  shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
  initial_velocity_field { beam_mode { axis { x: 1 } direction { y: 1 } length: 1 } } })");
  EXPECT_TRUE(has_error(errs, "fluids[1].initial_velocity_field.beam_mode", "elastic bodies only"))
      << dump(errs);
  const std::string body = R"(elastic_bodies { name: "p" material: "rubber"
  shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
  constraints { region { box { lo { x: 0.2 y: 1.6 } hi { x: 0.4 y: 1.8 } } } }
  initial_velocity_field { beam_mode { )";
  errs = plate_errors(body + "direction { y: 1 } length: 0 } } }");
  const std::string g = "elastic_bodies[0].initial_velocity_field.beam_mode.";
  EXPECT_TRUE(has_error(errs, g + "axis", "must not be zero")) << dump(errs);
  EXPECT_TRUE(has_error(errs, g + "length", "must be > 0 (the free length L [m]) (got 0)"))
      << dump(errs);
  errs = plate_errors(body + "axis { x: 1 } length: 1 } } }");
  EXPECT_TRUE(has_error(errs, g + "direction", "must not be zero")) << dump(errs);
  errs = plate_errors(body + "axis { x: 1 } direction { x: -2 } length: 1 } } }");
  EXPECT_TRUE(has_error(errs, g + "direction", "must not be parallel to axis")) << dump(errs);
  errs = plate_errors(body + "axis { x: 1 z: 1 } direction { y: 1 } length: 1 } } }");
  EXPECT_TRUE(has_error(errs, g + "axis.z", "must be 0 in a 2D case")) << dump(errs);
  // Temperature with heat conduction only, and then positive; gravity to ignore.
  const std::string plain = R"(elastic_bodies { name: "p" material: "rubber"
  shape { box { lo { x: 0.2 y: 1.6 } hi { x: 1.2 y: 1.8 } } }
  constraints { region { box { lo { x: 0.2 y: 1.6 } hi { x: 0.4 y: 1.8 } } } } )";
  errs = plate_errors(plain + "initial_temperature: 300 ignore_gravity: true }");
  EXPECT_TRUE(
      has_error(errs, "elastic_bodies[0].initial_temperature", "heat conduction is not enabled"))
      << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].ignore_gravity", "the case has no gravity"))
      << dump(errs);
  errs = errors_of(
      R"(materials { name: "rubber" phase: SOLID density: 1000 youngs_modulus: 1.4e6 poisson_ratio: 0.4 heat_capacity: 1 thermal_conductivity: 1 }
thermal { initial_temperature: 300 }
)" + plain +
      "initial_temperature: -5 }");
  // Any finite temperature, as for fluids and rigid bodies.
  EXPECT_FALSE(has_error(errs, "elastic_bodies[0].initial_temperature", "")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "materials[0].heat_capacity", "used by fluids[0].material"))
      << dump(errs);
  // Observation points inside the domain.
  errs = plate_errors(plain +
                      "observation_points { x: 1 y: 1.7 } observation_points { x: 2.5 y: 1 } }");
  EXPECT_FALSE(has_error(errs, "elastic_bodies[0].observation_points[0]", "")) << dump(errs);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].observation_points[1]",
                        "lies outside the domain (x in [0, 2], y in [0, 2])"))
      << dump(errs);
}

// Anisotropic resolution (ASPH, docs/asph.md): the ratio, the thickness direction, whole layers
// of dx through the thickness, and what is not coupled yet, each named; the estimate counts the
// stretched lattice and the isotropic equivalent.
TEST(CaseValidation, ElasticAnisotropy) {
  const std::string body = R"(elastic_bodies { name: "plate" material: "rubber"
  shape { box { lo { x: 0 y: 0.9 } hi { x: 1.6 y: 1.1 } } }
  constraints { region { box { lo { x: 0 y: 0.9 } hi { x: 0.4 y: 1.1 } } } }
  anisotropy { )";
  auto errors = [&](const std::string& aniso, const std::string& extra = "") {
    return validate_case(
        parse_case_text(std::string(kNoFluid) + kRubber + extra + body + aniso + " } }"));
  };
  auto errs = errors("ratio: 4");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  errs = errors("ratio: 2 thickness_direction { y: -1 }");
  EXPECT_TRUE(errs.empty()) << dump(errs);
  EXPECT_TRUE(has_error(errors("ratio: nan"), "elastic_bodies[0].anisotropy.ratio", "finite"));
  for (const char* bad : {"ratio: 0.5", "ratio: 0", "", "ratio: 17"}) {
    errs = errors(bad);
    EXPECT_TRUE(has_error(errs, "elastic_bodies[0].anisotropy.ratio", "must be in [1, 16]"))
        << bad << ": " << dump(errs);
  }
  errs = errors("ratio: 2 thickness_direction { x: 1 y: 1 }");
  EXPECT_TRUE(
      has_error(errs, "elastic_bodies[0].anisotropy.thickness_direction", "a coordinate axis"))
      << dump(errs);
  errs = errors("ratio: 2 thickness_direction { z: 1 }");
  EXPECT_TRUE(
      has_error(errs, "elastic_bodies[0].anisotropy.thickness_direction", "a coordinate axis"))
      << dump(errs);
  // Along x the plate is 1.6 thick: 16 layers, fine; 0.25 thick along y is 2.5 layers.
  errs = errors("ratio: 2 thickness_direction { x: 1 }");
  EXPECT_FALSE(has_error(errs, "elastic_bodies[0].anisotropy.thickness_direction", ""))
      << dump(errs);
  EXPECT_FALSE(has_error(errs, "elastic_bodies[0].shape", "")) << dump(errs);
  auto c = parse_case_text(std::string(kNoFluid) + kRubber + body + "ratio: 2 } }");
  c.mutable_elastic_bodies(0)->mutable_shape()->mutable_box()->mutable_hi()->set_y(1.15);
  errs = validate_case(c);
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].shape", "not a whole number of dx = 0.1 (2.5"))
      << dump(errs);
  // A broken shape is reported by the shape's checks; the anisotropy's does not compile it.
  c = parse_case_text(std::string(kNoFluid) + kRubber + body + "ratio: 2 } }");
  c.mutable_elastic_bodies(0)->mutable_shape()->mutable_box()->mutable_hi()->set_y(0.55);
  errs = validate_case(c);
  EXPECT_FALSE(errs.empty());
  EXPECT_FALSE(has_error(errs, "elastic_bodies[0].shape", "whole number")) << dump(errs);
  // Not yet coupled: fluid, heat, hourglass control.
  errs = validate_case(parse_case_text(std::string(kBase) + kRubber + body + "ratio: 2 } }"));
  EXPECT_TRUE(has_error(errs, "elastic_bodies[0].anisotropy", "cannot be coupled with fluid"))
      << dump(errs);
  c = parse_case_text(std::string(kNoFluid) + kRubber + body + "ratio: 2 } }");
  c.mutable_materials(0)->set_hourglass_control(0.1);
  errs = validate_case(c);
  EXPECT_TRUE(has_error(errs, "materials[0].hourglass_control", "not supported with anisotropic"))
      << dump(errs);
  // Estimate: 1.6 / (4 dx) = 4 columns x 2 rows, isotropically 16 x 2.
  c = parse_case_text(std::string(kNoFluid) + kRubber + body + "ratio: 4 } }");
  const CaseEstimate e = estimate_case(c);
  std::printf("anisotropic plate r = 4: %.0f particles, isotropic %.0f\n", e.elastic_particles,
              e.elastic_isotropic_particles);
  EXPECT_EQ(e.elastic_particles, 8);
  EXPECT_EQ(e.elastic_isotropic_particles, 32);
}

// Elastic particles are counted like rigid ones (they take the lattice points of the fluid
// they overlap), and the solid's step 0.6 h / c_s (thesis eq. 33 at rest) joins the fluid's.
TEST(CaseValidation, ElasticBodyEstimate) {
  auto c = parse_case_text(std::string(kBase) + kRubber + kPlate);
  CaseEstimate e = estimate_case(c);
  EXPECT_NEAR(e.elastic_particles, 20, 0.5);  // 10 x 2 lattice points in the 1 x 0.2 plate
  EXPECT_NEAR(e.fluid_particles, 100, 0.5);
  EXPECT_NEAR(e.total(), 120, 0.5);
  // K = E / (3 (1 - 2 nu)) = 1.4e6 / 0.6; c_s = sqrt(K / 1000) = 48.30 m/s; the fluid's
  // 0.25 h / c = 2.5e-3 s is larger.
  const double cs = std::sqrt(1.4e6 / 0.6 / 1000);
  std::printf("elastic step %.6e s (expected 0.6 h / c_s = %.6e s), limited by %s\n", e.initial_dt,
              0.6 * 0.1 / cs, e.dt_limited_by.c_str());
  EXPECT_NEAR(e.initial_dt, 0.6 * 0.1 / cs, 1e-15);
  EXPECT_EQ(e.dt_limited_by, "elastic 0.6 h/c_s");
  EXPECT_NEAR(e.steps, std::ceil(1.0 / e.initial_dt), 0.5);
  // A stiff body moved into the fluid: its points leave it.
  c.mutable_elastic_bodies(0)->mutable_shape()->mutable_box()->mutable_lo()->set_y(1.3);
  c.mutable_elastic_bodies(0)->mutable_shape()->mutable_box()->mutable_hi()->set_y(1.5);
  e = estimate_case(c);
  EXPECT_NEAR(e.elastic_particles, 20, 0.5);
  EXPECT_NEAR(e.fluid_particles, 100 - 14, 0.5);  // x in [0.5, 1.2], two rows
  // A soft material leaves the fluid's acoustic step in charge.
  c.mutable_materials(1)->set_youngs_modulus(1e3);
  e = estimate_case(c);
  EXPECT_EQ(e.dt_limited_by, "acoustic CFL 0.25 h/c");
  EXPECT_NEAR(e.initial_dt, 2.5e-3, 1e-15);
}

}  // namespace
}  // namespace sph
