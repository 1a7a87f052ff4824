#pragma once
// The channel of cases/channel_inflow_outflow_2d.textproto run backwards through its left
// boundary (solver/boundaries/open_boundaries.h, bidirectional outflows), shared by the
// validation and rank-consistency tests: the right boundary becomes a velocity outlet that
// draws the parabola's flow out, ramped over `ramp`, and the left one a pressure outlet
// (p = 0, facing -x) through which the fluid comes in.
#include "tests/support/test_cases.h"

namespace sph::test {

// The channel's inflow (its left boundary) made a pressure outlet at `pressure`, facing -x.
inline void make_inlet_a_pressure_outlet(v1::Case& c, double pressure) {
  auto* in = c.mutable_open_boundaries(0);
  in->set_kind(v1::OUTFLOW);
  in->mutable_direction()->set_x(-1);
  in->clear_mean_velocity();
  in->clear_profile();
  in->clear_ramp_time();
  in->set_pressure(pressure);
}

inline v1::Case backflow_channel(double ramp) {
  auto c = load_case("channel_inflow_outflow_2d");
  make_inlet_a_pressure_outlet(c, 0);
  auto* out = c.mutable_open_boundaries(1);
  out->clear_pressure();
  out->set_profile(v1::PARABOLIC);
  out->set_mean_velocity(1.0);
  out->set_ramp_time(ramp);
  return c;
}

}  // namespace sph::test
