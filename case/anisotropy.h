#pragma once
// Anisotropic resolution of elastic bodies (ASPH; X. Tang's thesis sec. 3.5, P-II; docs/asph.md):
// what the case's ElasticBody.anisotropy means for the particle lattice, the kernel's smoothing
// lengths and the neighbour search. Shared by validation, estimates, the scene builder and the
// solver.
#include "case/lattice.h"
#include "sph/v1/case.pb.h"

namespace sph {

// Largest anisotropic ratio a case may ask for (the neighbour search's cells grow with it).
inline constexpr double kMaxAnisotropyRatio = 16;

// Whether the body is resolved anisotropically (its anisotropy block is present).
bool is_anisotropic(const v1::ElasticBody& b);
// The axis (0, 1, 2) of the body's thickness direction, -1 when it is not a coordinate axis.
int thickness_axis(const v1::ElasticBody& b, int dim);
// The lattice of the body's particles: spacing dx along the thickness axis, ratio dx along the
// others, from the case's lattice origin; the case's lattice for an isotropic body.
LatticeSpec elastic_lattice_spec(const v1::Case& c, const v1::ElasticBody& b);
// The volume of one particle of the body: dx^D times ratio^(D-1).
double elastic_particle_volume(const v1::Case& c, const v1::ElasticBody& b);
// The radius the neighbour search must cover: the kernel's support r_c, or, larger, the longest
// semi-axis of an anisotropic body's support (kappa ratio h).
double search_radius(const v1::Case& c);

}  // namespace sph
