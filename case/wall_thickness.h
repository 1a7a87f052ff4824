#pragma once
// Walls thick enough for the kernel: a fluid particle next to a wall must find wall particles
// wherever its kernel support reaches into the wall, or its density sum and pressure gradient
// miss that part of the support (Adami 2012 sec. 3: the dummy layers extend to the kernel's
// support radius). Shells without a thickness get enough layers; boxes, differences and other
// shapes are whatever the case makes them, so this check walks, from every fluid lattice point
// that touches a wall, along each coordinate axis into the wall and counts the wall layers up
// to the support radius r_c. Too few layers followed by empty space is a thin wall; followed by
// fluid, the fluids on the two sides would interact through the wall.
//
// Walls slanted against the axes are checked along the axes, where they look thicker than
// they are: the check is lenient there, never stricter than the true thickness.
#include <vector>

#include "case/validate.h"
#include "sph/v1/case.pb.h"

namespace sph {

// One error per wall that is too thin somewhere (field "walls[k].shape"). Expects a case whose
// shapes are valid. It tags every lattice cell of the domain (two bytes each) by every region
// that covers it, so a case that needs more work than kWallCheckWork (case/case_limits.h) is
// not checked: no errors.
std::vector<FieldError> check_wall_thickness(const v1::Case& c);

}  // namespace sph
