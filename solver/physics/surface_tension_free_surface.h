#pragma once
// Surface tension at a free surface: a fluid against void (a pair of surface_tension with no
// material_b), for SurfaceTension<D> (solver/physics/surface_tension.h).
//
// The colour function of one phase next to void is 1 on its particles and 0 where there are
// none. A10's colour gradient (Adami, Hu, Adams 2010, J. Comput. Phys. 229, 5011)
//   grad c_i = 1/V_i sum_j (V_i^2 + V_j^2) c~_ij grad W_ij
// over a void that has no particles keeps only the present neighbours, each with c~ = 1 (the
// density-weighted colour of A10 at an infinite density ratio, the heavy side taking the whole
// jump), so
//   grad c_i = 1/V_i sum_{j present} (V_i^2 + V_j^2) grad W_ij,
// walls and rigid particles counted as present (the solid is not void). It points into the
// phase. Next to a solid the normal is not turned to the contact angle as between two fluids:
// the contact-line force of SurfaceTension<D>::contact_line_force pulls the line to it
// (Huber et al. 2016): with turned normals the liquid alone takes the force of the bend that a
// second fluid shares, and the drop does not settle at the angle (docs/surface_tension.md).
// This is the same sum, with the same weights, as the pressure term of the momentum equation
// (Adami 2012, solver/physics/fluid_forces.h) at a uniform pressure p:
//   -1/m_i sum_j (V_i^2 + V_j^2) p grad W_ij = -(p / rho_i) grad c_i,
// so the continuum surface force kappa sigma grad c_i / rho_i and the pressure p = sigma kappa
// cancel particle by particle: a drop at rest with the interface's curvature everywhere is in
// equilibrium at the Laplace pressure sigma / R (2D) against the free surface's p = 0, not only
// on average. Across a planar surface the sum's magnitude is 2 w1(z), w1 the kernel integrated
// over the plane at depth z, which integrates over the particles (depths dx/2, 3 dx/2, ...) to
// 2 int_0^inf w1 = 1: the whole jump of c sits on the liquid's side.
//
// In the bulk of a disordered liquid the sum is lattice noise, not an exact zero as between two
// fluids (where only pairs across the interface contribute), and a normal from noise has a
// noise curvature. The void's share of the kernel support, 1 - (V_i W(0) + sum_j V_j W_ij)
// (the kernel's integral is 1), tells the surface from the bulk: the void's term is taken only
// where it exceeds kFreeSurfaceMinVoidShare. The curvature is then the divergence of the unit
// normals over the neighbours that have one (the tensor form tr(N M^-1) of the two-phase unit,
// exact for a linear field on the one-sided band), mapped onto the interface as there, the
// particle's depth d from its own phase's share of the support with the void counted.
//
// Capillary waves on a free surface have omega^2 = sigma k^3 / rho, those between two fluids
// sigma k^3 / (rho_a + rho_b): the two-fluid bound of Brackbill 1992 with the mean density
// (rho_a + rho_b) / 2 resolves the shortest wave, k = pi / h; at a free surface the same
// frequency comes with rho / 2 in its place.
#include <cmath>
#include <numbers>

namespace sph {

// The void's term of a particle is weighted by its void share s of the kernel support:
// 0 up to kFreeSurfaceVoidShareFrom, 1 from kFreeSurfaceVoidShareFull, linear between.
inline constexpr double kFreeSurfaceVoidShareFrom = 0.002;
inline constexpr double kFreeSurfaceVoidShareFull = 0.01;

inline double free_surface_weight(double void_share) {
  if (!(void_share > kFreeSurfaceVoidShareFrom)) return 0.0;
  if (void_share >= kFreeSurfaceVoidShareFull) return 1.0;
  return (void_share - kFreeSurfaceVoidShareFrom) /
         (kFreeSurfaceVoidShareFull - kFreeSurfaceVoidShareFrom);
}

// 0.25 sqrt(rho_mean h^3 / (2 pi sigma)) with rho_mean = rho / 2 (capillary waves against
// void; Brackbill 1992 and A10 for two fluids), without the CFL factor.
inline double free_surface_capillary_step(double rho, double h, double sigma) {
  return 0.25 * std::sqrt(0.5 * rho * h * h * h / (2.0 * std::numbers::pi * sigma));
}

}  // namespace sph
