#pragma once
// The growing-wall test scene (solver/boundaries/wall_growth.h), shared by the validation and
// rank-consistency tests: periodic in x over 0.4, still fluid between a floor growing at
// `speed` and a lid, dx = 0.04; `extra` adds case text (bodies, contact, forces).
#include <string>

namespace sph::test {

inline std::string growing_floor(double speed, double end_time, const std::string& extra = "") {
  return R"(
name: "growing_floor"
dimension: 2
dx: 0.04
domain { lo { x: 0 y: -0.12 } hi { x: 0.4 y: 1.12 } }
periodic_x: true
materials { name: "water" density: 1 eos { kind: LINEAR sound_speed: 10 } dynamic_viscosity: 0.01 }
materials { name: "solid" phase: SOLID density: 1 }
fluids { name: "f" material: "water" shape { box { lo { x: 0 y: 0 } hi { x: 0.4 y: 1 } } } }
walls { name: "floor" shape { box { lo { x: 0 y: -0.12 } hi { x: 0.4 y: 0 } } }
        growth_speed { constant: )" +
         std::to_string(speed) + R"( } }
walls { name: "lid" shape { box { lo { x: 0 y: 1 } hi { x: 0.4 y: 1.12 } } } }
fluid_model { density: SUMMATION }
time { end_time: )" +
         std::to_string(end_time) + R"( }
output { interval: 0 series_interval: 0.01 }
)" + extra;
}

}  // namespace sph::test
